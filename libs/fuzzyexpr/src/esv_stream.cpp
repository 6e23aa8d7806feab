#include "emoface/fuzzyexpr/esv_stream.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>

#include "emoface/core/csv.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/core/shard.hpp"

namespace emoface::fuzzyexpr {

namespace {
constexpr std::array<std::string_view, 3> kFormatNames = {"csv", "ndjson", "json"};

bool ends_with(std::string_view s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

std::string printable(std::string_view s) {
  std::string out;
  for (char c : s.substr(0, 40)) out += (static_cast<unsigned char>(c) < 0x20) ? '?' : c;
  if (s.size() > 40) out += "...";
  return out;
}

void append_json_string(std::string& out, std::string_view s) {
  out += '"';
  for (char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
          out += buf;
        } else {
          out += c;
        }
    }
  }
  out += '"';
}
}  // namespace

std::string_view to_string(StreamFormat f) noexcept { return kFormatNames[static_cast<int>(f)]; }

std::optional<StreamFormat> stream_format_from_string(std::string_view s) noexcept {
  for (std::size_t i = 0; i < kFormatNames.size(); ++i)
    if (kFormatNames[i] == s) return static_cast<StreamFormat>(i);
  return std::nullopt;
}

std::optional<StreamFormat> stream_format_from_path(std::string_view path) noexcept {
  if (ends_with(path, ".csv")) return StreamFormat::Csv;
  if (ends_with(path, ".ndjson") || ends_with(path, ".jsonl")) return StreamFormat::Ndjson;
  if (ends_with(path, ".json")) return StreamFormat::Json;
  return std::nullopt;
}

void EsvReaderOptions::validate() const {
  if (format == StreamFormat::Json)
    throw InvalidInput("ESV input must be CSV or NDJSON (one record per line), not JSON");
  if (max_line_bytes < 64) throw InvalidInput("EsvReaderOptions.max_line_bytes must be >= 64");
}

// ---------------------------------------------------------------------------------------------------

struct EsvReader::Impl {
  std::istream& in;
  std::string name;
  EsvReaderOptions options;
  std::vector<char> buf = std::vector<char>(std::size_t{1} << 16);
  std::size_t pos = 0, end = 0;
  bool eof = false;
  std::size_t line_no = 0;
  std::size_t records = 0;
  std::string line;
  // CSV layout
  std::size_t n_fields = 0;
  std::array<std::size_t, kEmotionCount> emotion_field{};
  std::vector<std::size_t> extra_fields;
  std::vector<std::string> extra_names;
  std::vector<std::string> fields;      // scratch for quoted lines
  std::vector<std::string_view> views;  // the fields of the current line

  Impl(std::istream& s, std::string n, EsvReaderOptions o)
      : in(s), name(std::move(n)), options(o) {}

  [[noreturn]] void fail(std::size_t column, const std::string& message) const {
    throw FormatError(SourceLocation{name, "", line_no, column}, message);
  }

  // Reads the next physical line into `line` (without "\n" / "\r\n"). Returns false at the end.
  // A line longer than max_line_bytes is consumed entirely, then reported.
  bool read_line() {
    line.clear();
    bool too_long = false, got_any = false;
    while (true) {
      if (pos == end) {
        if (eof) break;
        in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
        end = static_cast<std::size_t>(in.gcount());
        pos = 0;
        if (end == 0) {
          eof = true;
          if (in.bad()) throw IoError(name + ": read error");
          break;
        }
      }
      got_any = true;
      const char* start = buf.data() + pos;
      const void* nl = std::memchr(start, '\n', end - pos);
      const std::size_t len = nl ? static_cast<std::size_t>(static_cast<const char*>(nl) - start) : end - pos;
      if (!too_long) {
        if (line.size() + len > options.max_line_bytes + 1)  // +1: a trailing '\r'
          too_long = true;
        else
          line.append(start, len);
      }
      pos += len;
      if (nl) {
        ++pos;
        break;
      }
    }
    if (!got_any) return false;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (too_long || line.size() > options.max_line_bytes)
      fail(0, "line is longer than " + std::to_string(options.max_line_bytes) + " bytes");
    if (line_no == 1) {
      if (line.size() >= 2 && ((line[0] == '\xFF' && line[1] == '\xFE') || (line[0] == '\xFE' && line[1] == '\xFF')))
        fail(1, "UTF-16 input is not supported: convert the file to UTF-8");
      if (line.compare(0, 3, "\xEF\xBB\xBF") == 0) line.erase(0, 3);
    }
    std::size_t bad = 0;
    if (!core::is_valid_utf8(line, &bad)) fail(bad + 1, "invalid UTF-8 (byte " + std::to_string(bad + 1) + ")");
    return true;
  }

  void read_header() {
    bool got = read_line();
    while (got && core::is_csv_comment(line)) got = read_line();  // e.g. the "# emoface x.y.z" stamp
    if (!got) {
      line_no = std::max<std::size_t>(line_no, 1);
      fail(0, "empty input: expected a CSV header naming the six emotions");
    }
    std::string why;
    if (std::size_t col = core::split_csv_line(line, fields, &why)) fail(col, "malformed header: " + why);
    n_fields = fields.size();
    emotion_field.fill(SIZE_MAX);
    std::vector<std::string> lower_names;
    for (std::size_t i = 0; i < n_fields; ++i) {
      const std::string_view raw = trim(fields[i]);
      if (raw.empty()) fail(i + 1, "empty column name in header");
      std::string lower(raw);
      std::transform(lower.begin(), lower.end(), lower.begin(),
                     [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
      if (std::find(lower_names.begin(), lower_names.end(), lower) != lower_names.end())
        fail(i + 1, "duplicated column \"" + std::string(raw) + "\"");
      lower_names.push_back(lower);
      if (auto e = emotion_from_string(raw)) {
        emotion_field[index(*e)] = i;
      } else {
        extra_fields.push_back(i);
        extra_names.emplace_back(raw);
      }
    }
    std::string missing;
    for (std::size_t e = 0; e < kEmotionCount; ++e)
      if (emotion_field[e] == SIZE_MAX) missing += (missing.empty() ? "" : ", ") + std::string(to_string(emotion_at(e)));
    if (!missing.empty()) fail(0, "header lacks emotion column(s): " + missing);
  }

  double number(std::string_view text, std::size_t column, std::string_view field) const {
    std::string_view t = trim(text);
    if (t.empty()) fail(column, "empty value for " + std::string(field));
    if (t.front() == '+') t.remove_prefix(1);
    double v = 0.0;
    auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (ec == std::errc::result_out_of_range) fail(column, std::string(field) + ": number out of range: \"" + printable(text) + "\"");
    if (ec != std::errc() || ptr != t.data() + t.size())
      fail(column, std::string(field) + ": not a number: \"" + printable(text) + "\"");
    return check(v, column, field);
  }

  double check(double v, std::size_t column, std::string_view field) const {
    if (!std::isfinite(v)) fail(column, std::string(field) + ": not a finite number");
    if (v < 0.0 || v > 1.0) {
      if (!options.clamp)
        fail(column, std::string(field) + ": intensity " + std::to_string(v) +
                         " is outside [0, 1] (use --clamp to clamp)");
      v = std::clamp(v, 0.0, 1.0);
    }
    return v;
  }

  void parse_csv(EsvRecord& r) {
    views.clear();
    if (line.find('"') == std::string::npos) {
      // Fast path: no quotes, split on commas without copying.
      std::string_view rest = line;
      while (true) {
        const std::size_t comma = rest.find(',');
        views.push_back(rest.substr(0, comma));
        if (comma == std::string_view::npos) break;
        rest.remove_prefix(comma + 1);
      }
    } else {
      std::string why;
      if (std::size_t col = core::split_csv_line(line, fields, &why)) fail(col, "malformed CSV: " + why);
      views.assign(fields.begin(), fields.end());
    }
    const std::size_t n = views.size();
    const std::string_view* f = views.data();
    if (n != n_fields)
      fail(std::min(n, n_fields) + 1, "expected " + std::to_string(n_fields) + " fields, got " + std::to_string(n));
    for (std::size_t e = 0; e < kEmotionCount; ++e) {
      const std::size_t c = emotion_field[e];
      r.esv[e] = number(f[c], c + 1, to_string(emotion_at(e)));
    }
    r.extra.resize(extra_fields.size());
    for (std::size_t k = 0; k < extra_fields.size(); ++k) r.extra[k].assign(f[extra_fields[k]]);
  }

  void parse_ndjson(EsvRecord& r) {
    using Json = nlohmann::json;
    std::array<bool, kEmotionCount> seen{};
    std::vector<std::string> keys;
    std::string dup;
    Json doc;
    try {
      doc = Json::parse(line, [&](int depth, Json::parse_event_t event, Json& parsed) {
        if (event == Json::parse_event_t::key && depth == 1) {
          std::string k = parsed.get<std::string>();
          std::string lower = k;
          std::transform(lower.begin(), lower.end(), lower.begin(),
                         [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
          if (std::find(keys.begin(), keys.end(), lower) != keys.end() && dup.empty()) dup = k;
          keys.push_back(lower);
        }
        return true;
      });
    } catch (const Json::parse_error& e) {
      std::string msg = e.what();
      auto colon = msg.find(": ");
      fail(e.byte, "invalid JSON: " + (colon == std::string::npos ? msg : msg.substr(colon + 2)));
    } catch (const Json::exception& e) {  // e.g. number overflow (1e999): no position reported
      std::string msg = e.what();
      auto bracket = msg.find("] ");
      fail(0, "invalid JSON: " + (bracket == std::string::npos ? msg : msg.substr(bracket + 2)));
    }
    if (!doc.is_object()) fail(1, "expected a JSON object with the six emotion fields");
    if (!dup.empty()) fail(0, "duplicated field \"" + dup + "\"");
    r.extra_json.clear();
    for (auto it = doc.begin(); it != doc.end(); ++it) {
      if (auto e = emotion_from_string(it.key())) {
        if (!it->is_number())
          fail(0, "field \"" + it.key() + "\": expected a number, got " + std::string(it->type_name()));
        r.esv[index(*e)] = check(it->get<double>(), 0, it.key());
        seen[index(*e)] = true;
      } else {
        if (!r.extra_json.empty()) r.extra_json += ',';
        append_json_string(r.extra_json, it.key());
        r.extra_json += ':';
        r.extra_json += it->dump();
      }
    }
    std::string missing;
    for (std::size_t e = 0; e < kEmotionCount; ++e)
      if (!seen[e]) missing += (missing.empty() ? "" : ", ") + std::string(to_string(emotion_at(e)));
    if (!missing.empty()) fail(0, "missing emotion field(s): " + missing);
  }
};

EsvReader::EsvReader(std::istream& in, std::string name, EsvReaderOptions options)
    : impl_(std::make_unique<Impl>(in, std::move(name), options)) {
  options.validate();
  if (options.format == StreamFormat::Csv) impl_->read_header();
}

EsvReader::~EsvReader() = default;

bool EsvReader::next(EsvRecord& record) {
  Impl& m = *impl_;
  if (!m.read_line()) return false;
  // Stream headers ({"format": "emoface.…", …}: the first line of our NDJSON, repeated in concatenated
  // shards) are skipped.
  while (m.options.format == StreamFormat::Ndjson && m.line.find("\"format\"") != std::string::npos) {
    const auto doc = nlohmann::json::parse(m.line, nullptr, false);
    if (doc.is_discarded() || !core::is_stream_header(doc)) break;
    if (!m.read_line()) return false;
  }
  record.line = m.line_no;
  record.index = m.records++;
  if (m.line.empty()) m.fail(0, "empty line");
  if (m.options.format == StreamFormat::Csv)
    m.parse_csv(record);
  else
    m.parse_ndjson(record);
  return true;
}

const std::vector<std::string>& EsvReader::extra_columns() const noexcept { return impl_->extra_names; }

// ---------------------------------------------------------------------------------------------------

void FmcvWriterOptions::validate() const {
  if (precision < 1 || precision > 17) throw InvalidInput("FmcvWriterOptions.precision must be in 1..17");
  if (mapped_columns.empty() != !map)
    throw InvalidInput("FmcvWriterOptions: mapped_columns and map go together");
}

FmcvWriter::FmcvWriter(FmcvWriterOptions options, std::vector<std::string> extra_columns)
    : options_(options), extra_(std::move(extra_columns)) {
  options_.validate();
  zero_ = "0." + std::string(static_cast<std::size_t>(options_.precision), '0');
  if (options_.map) {
    names_ = options_.mapped_columns;
    mapped_.assign(names_.size(), 0.0);
  } else if (options_.sides)
    for (auto n : side_parameter_names()) names_.emplace_back(n);
  else
    for (std::size_t m = 0; m < kMuscleCount; ++m) names_.emplace_back(to_string(muscle_at(m)));
  for (const auto& e : extra_)
    if (std::find(names_.begin(), names_.end(), e) != names_.end())
      throw InvalidInput("passed-through column \"" + e + "\" clashes with an output parameter name");
}

std::string FmcvWriter::begin() const {
  std::string out;
  if (options_.format == StreamFormat::Ndjson) out = core::ndjson_header("fmcv", {1, 0});
  if (options_.format == StreamFormat::Csv) {
    out = core::csv_stamp();
    bool first = true;
    for (const auto& e : extra_) {
      if (!first) out += ',';
      core::append_csv_field(out, e);
      first = false;
    }
    for (const auto& n : names_) {
      if (!first) out += ',';
      out += n;
      first = false;
    }
    out += '\n';
  } else if (options_.format == StreamFormat::Json) {
    auto env = core::make_envelope("fmcv", {1, 0});
    nlohmann::json names = names_;
    out = env.dump();
    out.pop_back();  // reopen the object
    out += ",\"parameters\":" + names.dump() + ",\"rows\":[";
  }
  return out;
}

void FmcvWriter::append(std::string& out, const EsvRecord& record, const Fmcv& fmcv) {
  double fixed_values[kSideParameterCount];
  double* values = fixed_values;
  std::size_t n = 0;
  if (options_.map) {
    options_.map(expand_to_sides(fmcv), mapped_.data());
    values = mapped_.data();
    n = mapped_.size();
  } else if (options_.sides) {
    const auto s = expand_to_sides(fmcv);
    std::copy(s.begin(), s.end(), fixed_values);
    n = kSideParameterCount;
  } else {
    std::copy(fmcv.begin(), fmcv.end(), fixed_values);
    n = kMuscleCount;
  }
  char buf[40];
  // Most muscles are at rest: "0.000…" is written without formatting (same bytes as to_chars).
  auto num = [&](double v) {
    if (v == 0.0) {
      out += zero_;
      return;
    }
    auto res = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, options_.precision);
    out.append(buf, res.ptr);
  };
  if (options_.format == StreamFormat::Csv) {
    bool first = true;
    for (const auto& e : record.extra) {
      if (!first) out += ',';
      core::append_csv_field(out, e);
      first = false;
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (!first) out += ',';
      num(values[i]);
      first = false;
    }
    out += '\n';
    return;
  }
  if (options_.format == StreamFormat::Json && rows_ > 0) out += ',';
  out += '{';
  bool first = true;
  if (!record.extra_json.empty()) {
    out += record.extra_json;
    first = false;
  }
  for (std::size_t k = 0; k < record.extra.size() && k < extra_.size(); ++k) {
    if (!first) out += ',';
    append_json_string(out, extra_[k]);
    out += ':';
    append_json_string(out, record.extra[k]);
    first = false;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!first) out += ',';
    out += '"';
    out += names_[i];
    out += "\":";
    num(values[i]);
    first = false;
  }
  out += '}';
  if (options_.format == StreamFormat::Ndjson) out += '\n';
  ++rows_;
}

std::string FmcvWriter::end() const {
  return options_.format == StreamFormat::Json ? std::string("]}\n") : std::string();
}

// ---------------------------------------------------------------------------------------------------

void BatchOptions::validate() const {
  if (shard_count == 0 || shard_index >= shard_count)
    throw InvalidInput("BatchOptions: shard must satisfy 0 <= index < count");
  if (shard_count > 1 && total_records == kUnknownTotal)
    throw InvalidInput("BatchOptions: contiguous shards need total_records (count_records)");
}

std::size_t count_records(EsvReader& reader) {
  std::size_t n = 0;
  EsvRecord record;
  while (true) {
    try {
      if (!reader.next(record)) break;
    } catch (const FormatError&) {
    }
    ++n;
  }
  return n;
}

BatchReport convert_stream(EsvReader& reader, FmcvWriter& writer, const Engine& engine,
                           const BatchOptions& options,
                           const std::function<void(std::string_view)>& sink,
                           const std::function<void(const EsvRecord&, const Selection&, const Fmcv&)>& observer) {
  options.validate();
  BatchReport report;
  std::string out = writer.begin();
  const core::Shard shard{options.shard_index, options.shard_count};
  const std::size_t total = options.shard_count > 1 ? options.total_records : 0;
  auto mine = [&](std::size_t idx) { return options.shard_count == 1 || shard.owns(idx, total); };
  EsvRecord record;
  const bool want_selection = static_cast<bool>(observer);
  while (true) {
    try {
      if (!reader.next(record)) break;
    } catch (const FormatError& e) {
      const std::size_t idx = report.records_read++;
      if (!mine(idx)) continue;  // another shard's problem
      if (options.on_error == OnError::Stop) throw;
      ++report.records_skipped;
      if (report.errors.size() < options.max_kept_errors) report.errors.emplace_back(e.what());
      continue;
    }
    ++report.records_read;
    if (!mine(record.index)) continue;
    const Fmcv fmcv = engine.convert(record.esv, record.index);
    writer.append(out, record, fmcv);
    ++report.records_written;
    if (want_selection) observer(record, engine.select(record.esv, record.index), fmcv);
    if (out.size() >= (std::size_t{1} << 18)) {
      sink(out);
      out.clear();
    }
  }
  out += writer.end();
  sink(out);
  return report;
}

std::string describe(const Esv& esv, const Selection& s, const Fmcv& fmcv, std::size_t top_muscles) {
  char buf[64];
  auto pct = [&](Emotion e) {
    std::snprintf(buf, sizeof buf, " %.2f", esv[index(e)]);
    return std::string(to_string(e)) + buf;
  };
  std::string out;
  if (std::all_of(esv.begin(), esv.end(), [](double v) { return v == 0.0; })) {
    out = "neutral";
  } else if (s.mode == ExpressionMode::Single) {
    out = "single " + pct(s.first);
  } else {
    out = "blend " + pct(s.first) + " + " + pct(s.second);
    if (!s.pair_has_rules) out += " (no blend rules: " + std::string(to_string(s.first)) + " alone)";
  }
  std::array<std::size_t, kMuscleCount> order;
  for (std::size_t i = 0; i < kMuscleCount; ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return fmcv[a] > fmcv[b]; });
  out += " |";
  std::size_t shown = 0;
  for (std::size_t i = 0; i < kMuscleCount && shown < top_muscles; ++i) {
    if (fmcv[order[i]] <= 0.0) break;
    std::snprintf(buf, sizeof buf, " %.2f", fmcv[order[i]]);
    out += (shown ? ", " : " ") + std::string(to_string(muscle_at(order[i]))) + buf;
    ++shown;
  }
  if (shown == 0) out += " no muscle contracted";
  return out;
}

}  // namespace emoface::fuzzyexpr
