#include "emoface/muscles/io.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>

#include <nlohmann/json.hpp>

#include "emoface/core/csv.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/muscles/parameters.hpp"

namespace emoface::muscles {
namespace {

using Json = nlohmann::ordered_json;

const std::set<std::string>& metadata_columns() {
  static const std::set<std::string> names = {"id", "frame", "index", "label", "name", "sadness", "happiness",
                                              "anger", "fear", "disgust", "surprise"};
  return names;
}

[[noreturn]] void fail_at(const std::string& source, std::size_t line, std::size_t column, const std::string& msg) {
  SourceLocation where;
  where.file = source;
  where.line = line;
  where.column = column;
  throw FormatError(where, msg);
}
[[noreturn]] void fail_ptr(const std::string& source, std::size_t line, const std::string& pointer, const std::string& msg) {
  SourceLocation where;
  where.file = source;
  where.line = line;
  where.json_pointer = pointer;
  throw FormatError(where, msg);
}

// Parses {name: value} into a frame; line = 0 for whole documents.
void fill_named(const Json& obj, ParameterFrame& frame, const std::string& source, std::size_t line,
                const std::string& base, const FrameReadOptions& options) {
  if (!obj.is_object()) fail_ptr(source, line, base, "expected an object of parameter name -> value");
  for (auto it = obj.begin(); it != obj.end(); ++it) {
    const std::string ptr = base + "/" + core::json_pointer_token(it.key());
    std::size_t index = 0;
    try {
      index = parameter_index(it.key());
    } catch (const InvalidInput& e) {
      if (options.ignore_unknown_columns || metadata_columns().count(it.key())) continue;
      fail_ptr(source, line, ptr, e.what());
    }
    if (!it.value().is_number()) fail_ptr(source, line, ptr, "expected a number");
    frame.values[index] = it.value().get<double>();
  }
  try {
    validate_parameter_vector(frame.values);
  } catch (const InvalidInput& e) {
    fail_ptr(source, line, base, e.what());
  }
}

double parse_number(const std::string& field, const std::string& source, std::size_t line, std::size_t column) {
  if (field.empty()) fail_at(source, line, column, "empty field");
  std::size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(field, &used);
  } catch (const std::exception&) {
    fail_at(source, line, column, "not a number: '" + field + "'");
  }
  if (used != field.size()) fail_at(source, line, column, "not a number: '" + field + "'");
  if (!std::isfinite(v)) fail_at(source, line, column, "not a finite number: '" + field + "'");
  return v;
}

}  // namespace

std::string to_string(FrameFormat format) {
  switch (format) {
    case FrameFormat::Csv: return "csv";
    case FrameFormat::Ndjson: return "ndjson";
    case FrameFormat::Json: return "json";
  }
  return "csv";
}
FrameFormat frame_format_from_string(std::string_view name) {
  if (name == "csv") return FrameFormat::Csv;
  if (name == "ndjson") return FrameFormat::Ndjson;
  if (name == "json") return FrameFormat::Json;
  throw InvalidInput("unknown frame format '" + std::string(name) + "' (csv, ndjson or json)");
}
FrameFormat frame_format_from_path(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".csv") return FrameFormat::Csv;
  if (ext == ".ndjson" || ext == ".jsonl") return FrameFormat::Ndjson;
  if (ext == ".json") return FrameFormat::Json;
  throw InvalidInput(path + ": cannot tell the frame format from the extension (.csv, .ndjson, .json)");
}

void FrameReadOptions::validate() const {
  if (!(fps > 0.0 && fps <= 1000.0)) throw InvalidInput("FrameReadOptions: fps must be in (0, 1000]");
}

std::vector<ParameterFrame> parse_parameter_frames(std::string_view text, FrameFormat format, const std::string& source,
                                                   const FrameReadOptions& options) {
  options.validate();
  std::vector<ParameterFrame> frames;
  auto new_frame = [&]() {
    ParameterFrame f;
    f.values.assign(kParameterCount, 0.0);
    f.time = static_cast<double>(frames.size()) / options.fps;
    return f;
  };
  if (format == FrameFormat::Json) {
    const Json doc = core::parse_json(text, source);
    if (doc.is_object() && doc.contains("format")) {
      core::check_envelope(doc, "params", {1, 0}, source);
      double fps = options.fps;
      if (doc.contains("fps")) {
        if (!doc["fps"].is_number() || !(doc["fps"].get<double>() > 0.0) || doc["fps"].get<double>() > 1000.0) fail_ptr(source, 0, "/fps", "fps must be a number in (0, 1000]");
        fps = doc["fps"].get<double>();
      }
      if (!doc.contains("frames") || !doc["frames"].is_array()) fail_ptr(source, 0, "/frames", "expected an array of frames");
      const auto& arr = doc["frames"];
      for (std::size_t i = 0; i < arr.size(); ++i) {
        const std::string p = "/frames/" + std::to_string(i);
        ParameterFrame f = new_frame();
        f.time = static_cast<double>(i) / fps;
        if (!arr[i].is_object() || !arr[i].contains("parameters")) fail_ptr(source, 0, p, "expected {\"time\": t, \"parameters\": {...}}");
        if (arr[i].contains("time")) {
          if (!arr[i]["time"].is_number() || !std::isfinite(arr[i]["time"].get<double>())) fail_ptr(source, 0, p + "/time", "expected a finite number");
          f.time = arr[i]["time"].get<double>();
        }
        fill_named(arr[i]["parameters"], f, source, 0, p + "/parameters", options);
        frames.push_back(std::move(f));
      }
    } else {
      ParameterFrame f = new_frame();
      fill_named(doc, f, source, 0, "", options);
      frames.push_back(std::move(f));
    }
    return frames;
  }
  // Line-oriented formats.
  std::size_t line_no = 0, pos = 0;
  std::vector<std::string> header;
  std::vector<long> column_index;  // -1 ignore, -2 time, else parameter index
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.find_first_not_of(" \t") == std::string_view::npos) continue;
    if (format == FrameFormat::Csv && header.empty() && core::is_csv_comment(line)) continue;  // "# emoface x.y.z"
    if (format == FrameFormat::Ndjson) {
      const Json obj = [&]() {
        try {
          return core::parse_json(line, source);
        } catch (const FormatError& e) {
          fail_at(source, line_no, e.where().column, e.message());
        }
      }();
      if (core::is_stream_header(obj)) continue;  // {"format": "emoface.…", …}: the stream's version stamp
      ParameterFrame f = new_frame();
      if (obj.is_object() && obj.contains("parameters")) {
        if (obj.contains("time")) {
          if (!obj["time"].is_number() || !std::isfinite(obj["time"].get<double>())) fail_ptr(source, line_no, "/time", "expected a finite number");
          f.time = obj["time"].get<double>();
        }
        fill_named(obj["parameters"], f, source, line_no, "/parameters", options);
      } else {
        Json flat = obj;
        if (flat.is_object() && flat.contains("time")) {
          if (!flat["time"].is_number() || !std::isfinite(flat["time"].get<double>())) fail_ptr(source, line_no, "/time", "expected a finite number");
          f.time = flat["time"].get<double>();
          flat.erase("time");
        }
        fill_named(flat, f, source, line_no, "", options);
      }
      frames.push_back(std::move(f));
      continue;
    }
    std::vector<std::string> fields;
    std::string error;
    if (const auto col = core::split_csv_line(line, fields, &error)) fail_at(source, line_no, col, error);
    if (header.empty()) {
      header = fields;
      std::set<std::string> seen;
      for (std::size_t c = 0; c < fields.size(); ++c) {
        const std::string& name = fields[c];
        if (!seen.insert(name).second) fail_at(source, line_no, c + 1, "duplicate column '" + name + "'");
        if (name == "time") {
          column_index.push_back(-2);
          continue;
        }
        try {
          column_index.push_back(static_cast<long>(parameter_index(name)));
        } catch (const InvalidInput& e) {
          if (!options.ignore_unknown_columns && !metadata_columns().count(name)) fail_at(source, line_no, c + 1, e.what());
          column_index.push_back(-1);
        }
      }
      continue;
    }
    if (fields.size() != header.size()) {
      fail_at(source, line_no, 0, "expected " + std::to_string(header.size()) + " fields, got " + std::to_string(fields.size()));
    }
    ParameterFrame f = new_frame();
    for (std::size_t c = 0; c < fields.size(); ++c) {
      if (column_index[c] == -1) continue;
      const double v = parse_number(fields[c], source, line_no, c + 1);
      if (column_index[c] == -2) {
        f.time = v;
      } else {
        f.values[static_cast<std::size_t>(column_index[c])] = v;
      }
    }
    try {
      validate_parameter_vector(f.values);
    } catch (const InvalidInput& e) {
      fail_at(source, line_no, 0, e.what());
    }
    frames.push_back(std::move(f));
  }
  if (format == FrameFormat::Csv && header.empty()) fail_at(source, 1, 0, "missing CSV header");
  return frames;
}

std::vector<ParameterFrame> read_parameter_frames(const std::string& path, const FrameReadOptions& options) {
  return parse_parameter_frames(core::read_file(path), frame_format_from_path(path), path, options);
}

std::string format_parameter_frames_csv(const std::vector<ParameterFrame>& frames) {
  std::string out = core::csv_stamp() + "time";
  for (const auto& n : parameter_names()) out += "," + n;
  out += "\n";
  char buf[32];
  for (const auto& f : frames) {
    if (f.values.size() != kParameterCount) throw InvalidInput("format_parameter_frames_csv: frame with wrong size");
    std::snprintf(buf, sizeof buf, "%.17g", f.time);
    out += buf;
    for (double v : f.values) {
      std::snprintf(buf, sizeof buf, ",%.17g", v);
      out += buf;
    }
    out += "\n";
  }
  return out;
}

std::string format_parameter_frames_json(const std::vector<ParameterFrame>& frames, double fps) {
  Json doc = core::make_envelope("params", {1, 0});
  doc["fps"] = fps;
  Json arr = Json::array();
  for (const auto& f : frames) {
    if (f.values.size() != kParameterCount) throw InvalidInput("format_parameter_frames_json: frame with wrong size");
    Json j;
    j["time"] = f.time;
    Json p = Json::object();
    for (std::size_t i = 0; i < kParameterCount; ++i) p[parameter_names()[i]] = f.values[i];
    j["parameters"] = p;
    arr.push_back(j);
  }
  doc["frames"] = arr;
  return doc.dump(1) + "\n";
}

}  // namespace emoface::muscles
