// A set of output files written all or nothing (output_set.hpp).
#include "emoface/retarget/output_set.hpp"

#include <algorithm>
#include <filesystem>
#include <set>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"

namespace emoface::retarget {

namespace fs = std::filesystem;

OutputSet::OutputSet(std::string directory) : directory_(std::move(directory)) {
  if (directory_.empty()) throw InvalidInput("OutputSet: empty directory");
}

void OutputSet::add_writer(const std::string& relative_path,
                           std::function<void(const std::string&)> write) {
  const fs::path p(relative_path);
  const fs::path n = p.lexically_normal();
  if (relative_path.empty() || p.is_absolute() || p.has_root_name() || p.has_root_directory() ||
      n.empty() || *n.begin() == ".." || n == "." || !n.has_filename())
    throw InvalidInput("OutputSet: '" + relative_path +
                       "' is not a path inside the output directory");
  for (const auto& e : entries_) {
    if (e.path == n.generic_string())
      throw InvalidInput("OutputSet: '" + relative_path + "' given twice");
  }
  entries_.push_back({n.generic_string(), std::move(write)});
}

void OutputSet::add(const std::string& relative_path, std::string bytes) {
  add_writer(relative_path, [bytes = std::move(bytes)](const std::string& path) {
    core::write_file_atomic(path, bytes);
  });
}

void OutputSet::commit() {
  const fs::path dir(directory_);
  std::vector<fs::path> created_dirs;  // by this commit, outermost first
  std::vector<fs::path> temporary, renamed;
  auto make_dirs = [&](const fs::path& d) {
    std::vector<fs::path> chain;
    for (fs::path p = d; !p.empty() && !fs::exists(p); p = p.parent_path()) {
      chain.push_back(p);
      if (p == p.parent_path()) break;
    }
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      std::error_code ec;
      if (fs::create_directory(*it, ec)) {
        created_dirs.push_back(*it);
      } else if (ec) {
        throw IoError("cannot create directory '" + it->string() + "': " + ec.message());
      }
    }
  };
  try {
    make_dirs(dir);
    std::vector<fs::path> finals;
    for (const auto& e : entries_) {
      const fs::path final_path = dir / fs::path(e.path);
      make_dirs(final_path.parent_path());
      const fs::path tmp =
          final_path.parent_path() /
          (final_path.stem().string() + ".part-emoface" + final_path.extension().string());
      temporary.push_back(tmp);
      e.write(tmp.string());
      if (!fs::is_regular_file(tmp)) throw IoError("cannot write '" + final_path.string() + "'");
      finals.push_back(final_path);
    }
    for (std::size_t i = 0; i < finals.size(); ++i) {
      std::error_code ec;
      fs::rename(temporary[i], finals[i], ec);
      if (ec) throw IoError("cannot write '" + finals[i].string() + "': " + ec.message());
      renamed.push_back(finals[i]);
    }
  } catch (...) {
    std::error_code ec;
    for (const auto& p : temporary) fs::remove(p, ec);
    for (const auto& p : renamed) fs::remove(p, ec);
    for (auto it = created_dirs.rbegin(); it != created_dirs.rend(); ++it)
      fs::remove(*it, ec);  // only if empty
    throw;
  }
}

}  // namespace emoface::retarget
