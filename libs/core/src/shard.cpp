#include "emoface/core/shard.hpp"

#include <cstdlib>
#include <optional>

#include "emoface/core/csv.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/core/text.hpp"

namespace emoface::core {

std::pair<std::size_t, std::size_t> Shard::block(std::size_t total) const noexcept {
  // index · total fits: both are bounded by the number of items a process can hold.
  const auto first =
      static_cast<std::size_t>(static_cast<unsigned long long>(index) * total / count);
  const auto last =
      static_cast<std::size_t>(static_cast<unsigned long long>(index + 1) * total / count);
  return {first, last};
}

bool Shard::owns(std::size_t item, std::size_t total) const noexcept {
  const auto [first, last] = block(total);
  return item >= first && item < last;
}

Shard parse_shard(std::string_view text, const std::function<const char*(const char*)>& getenv) {
  auto env = [&](const char* name) -> const char* {
    return getenv ? getenv(name) : std::getenv(name);
  };
  auto size_of = [](std::string_view s) -> std::optional<std::size_t> {
    if (s.empty() || s.size() > 18) return std::nullopt;
    for (char c : s)
      if (c < '0' || c > '9') return std::nullopt;
    auto v = parse_integer(s);
    if (!v || *v < 0) return std::nullopt;
    return static_cast<std::size_t>(*v);
  };
  if (text == "auto") {
    const char* id = env("SLURM_ARRAY_TASK_ID");
    const char* count = env("SLURM_ARRAY_TASK_COUNT");
    const char* min = env("SLURM_ARRAY_TASK_MIN");
    if (!id || !count)
      throw InvalidInput(
          "--shard auto: SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT are not set (run it as a "
          "task of a Slurm job array, or give --shard i/N)");
    const auto i = size_of(id), n = size_of(count), lo = size_of(min ? min : "0");
    if (!i || !n || !lo || *n == 0 || *i < *lo || *i - *lo >= *n)
      throw InvalidInput(std::string("--shard auto: SLURM_ARRAY_TASK_ID=") + id +
                         ", SLURM_ARRAY_TASK_MIN=" + (min ? min : "(unset)") +
                         ", SLURM_ARRAY_TASK_COUNT=" + count +
                         " do not give 0 <= ID - MIN < COUNT (use a contiguous array, e.g. "
                         "--array=0-7)");
    return Shard{*i - *lo, *n};
  }
  const auto slash = text.find('/');
  const auto i = slash == std::string_view::npos ? std::nullopt : size_of(text.substr(0, slash));
  const auto n = slash == std::string_view::npos ? std::nullopt : size_of(text.substr(slash + 1));
  if (!i || !n || *n == 0 || *i >= *n)
    throw InvalidInput("--shard: expected i/N with 0 <= i < N, or auto, got \"" +
                       std::string(text) + "\"");
  return Shard{*i, *n};
}

namespace {

bool is_stamp(std::string_view line) {
  if (is_csv_comment(line)) return true;
  if (line.empty() || line.front() != '{') return false;
  const auto j = nlohmann::json::parse(line, nullptr, false);
  return !j.is_discarded() && is_stream_header(j);
}

// Offset of the first line of `text` after its leading stamp lines; the line itself in `first`.
std::size_t skip_stamps(const std::string& text, std::string_view& first) {
  for (const Line& line : Lines(text)) {
    if (is_stamp(line.text)) continue;
    first = line.text;
    return static_cast<std::size_t>(line.text.data() - text.data());
  }
  first = {};
  return text.size();
}

}  // namespace

std::string merge_shard_outputs(const std::vector<std::string>& parts) {
  if (parts.empty()) return {};
  std::string out = parts.front();
  std::string_view header;
  skip_stamps(parts.front(), header);
  const bool csv = !header.empty() && header.front() != '{';
  for (std::size_t p = 1; p < parts.size(); ++p) {
    std::string_view first;
    std::size_t at = skip_stamps(parts[p], first);
    if (csv && at < parts[p].size()) {
      if (first != header)
        throw InvalidInput("merge_shard_outputs: part " + std::to_string(p) +
                           " has another CSV header than part 0");
      at = parts[p].find('\n', at);
      at = at == std::string::npos ? parts[p].size() : at + 1;
    }
    if (!out.empty() && out.back() != '\n' && at < parts[p].size()) out += '\n';
    out.append(parts[p], at, std::string::npos);
  }
  return out;
}

}  // namespace emoface::core
