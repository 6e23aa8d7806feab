#include "emoface/muscles/io.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>

#include "emoface/core/csv.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/core/json_reader.hpp"
#include "emoface/core/text.hpp"
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

// One CSV field as a number (core::parse_number: locale-free, finite, whole field).
double csv_number(const core::CsvTable& table, std::size_t row, std::size_t column) {
  const std::string& field = table.field(row, column);
  if (field.empty()) table.fail(row, column, "empty field");
  auto v = core::parse_number(field);
  if (!v) table.fail(row, column, "not a finite number: '" + field + "'");
  return *v;
}

// A frame's "time" member, if any.
void read_time(const core::JsonValue& obj, ParameterFrame& f) {
  if (auto t = obj.find("time")) f.time = t->number();
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
    Json doc = core::parse_json(text, source);
    if (doc.is_object() && doc.contains("format")) {
      // The envelope "emoface.params": core::JsonReader applies the unknown-field rule.
      const core::JsonReader reader(core::ParsedJson{std::move(doc)}, source, "params", {1, 0});
      const core::JsonValue root = reader.root();
      root.only_keys({"fps", "frames"});
      double fps = options.fps;
      if (auto v = root.find("fps")) {
        fps = v->number();
        if (!(fps > 0.0 && fps <= 1000.0)) v->fail("fps must be a number in (0, 1000]");
      }
      const std::vector<core::JsonValue> items = root.at("frames").items();
      for (std::size_t i = 0; i < items.size(); ++i) {
        const core::JsonValue& item = items[i];
        item.only_keys({"time", "parameters"});
        ParameterFrame f = new_frame();
        f.time = static_cast<double>(i) / fps;
        read_time(item, f);
        fill_named(item.at("parameters").json(), f, source, 0, item.pointer() + "/parameters",
                   options);
        frames.push_back(std::move(f));
      }
    } else {
      ParameterFrame f = new_frame();
      fill_named(doc, f, source, 0, "", options);
      frames.push_back(std::move(f));
    }
    return frames;
  }
  if (format == FrameFormat::Ndjson) {
    for (const core::Line& line : core::Lines(text)) {
      if (core::trim(line.text).empty()) continue;
      Json obj = [&]() {
        try {
          return core::parse_json(line.text, source);
        } catch (const FormatError& e) {
          fail_at(source, line.number, e.where().column, e.message());
        }
      }();
      if (core::is_stream_header(obj)) continue;  // the stream's version stamp
      ParameterFrame f = new_frame();
      try {
        const core::JsonReader record(core::ParsedJson{std::move(obj)}, source, true);
        const core::JsonValue root = record.root();
        root.expect_object();
        read_time(root, f);
        if (root.has("parameters")) {
          fill_named(root.at("parameters").json(), f, source, line.number, "/parameters", options);
        } else {
          Json flat = root.json();
          flat.erase("time");
          fill_named(flat, f, source, line.number, "", options);
        }
      } catch (const FormatError& e) {
        if (e.where().line != 0) throw;
        fail_ptr(source, line.number, e.where().json_pointer, e.message());  // add the line
      }
      frames.push_back(std::move(f));
    }
    return frames;
  }
  const core::CsvTable table = core::CsvTable::parse(text, source);
  std::vector<long> column_index;  // -1 ignore, -2 time, else parameter index
  for (std::size_t c = 0; c < table.header().size(); ++c) {
    const std::string& name = table.header()[c];
    if (name == "time") {
      column_index.push_back(-2);
      continue;
    }
    try {
      column_index.push_back(static_cast<long>(parameter_index(name)));
    } catch (const InvalidInput& e) {
      if (!options.ignore_unknown_columns && !metadata_columns().count(name))
        fail_at(source, table.header_line(), c + 1, e.what());
      column_index.push_back(-1);
    }
  }
  for (std::size_t r = 0; r < table.size(); ++r) {
    ParameterFrame f = new_frame();
    for (std::size_t c = 0; c < column_index.size(); ++c) {
      if (column_index[c] == -1) continue;
      const double v = csv_number(table, r, c);
      if (column_index[c] == -2)
        f.time = v;
      else
        f.values[static_cast<std::size_t>(column_index[c])] = v;
    }
    try {
      validate_parameter_vector(f.values);
    } catch (const InvalidInput& e) {
      table.fail(r, SIZE_MAX, e.what());
    }
    frames.push_back(std::move(f));
  }
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
