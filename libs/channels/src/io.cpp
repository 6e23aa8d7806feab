#include "emoface/channels/io.hpp"

#include <cmath>
#include <cstdio>
#include <set>

#include "emoface/core/csv.hpp"
#include "emoface/core/io.hpp"
#include "emoface/core/json_reader.hpp"
#include "emoface/core/text.hpp"

namespace emoface::channels {

namespace {

using Json = nlohmann::ordered_json;
using core::JsonValue;

Dominance parse_dominance(const JsonValue& j) {
  j.only_keys({"alpha", "theta_anticipatory", "theta_carryover", "c", "peak_offset"});
  Dominance d;
  d.alpha = j.number_or("alpha", d.alpha);
  d.theta_anticipatory = j.number_or("theta_anticipatory", d.theta_anticipatory);
  d.theta_carryover = j.number_or("theta_carryover", d.theta_carryover);
  d.c = j.number_or("c", d.c);
  d.peak_offset = j.number_or("peak_offset", d.peak_offset);
  try {
    d.validate();
  } catch (const InvalidInput& e) {
    j.fail(e.what());
  }
  return d;
}

Json dominance_json(const Dominance& d) {
  return Json{{"alpha", d.alpha}, {"theta_anticipatory", d.theta_anticipatory},
              {"theta_carryover", d.theta_carryover}, {"c", d.c}, {"peak_offset", d.peak_offset}};
}

}  // namespace

// The readers below go through core::JsonReader: located errors and the unknown-field rule of
// docs/formats.md (unknown fields are errors in files of this or an older minor version).
VisemeSet parse_visemes(std::string_view text, const std::string& file) {
  const core::JsonReader reader(text, file, "channels.visemes", {1, 0});
  const JsonValue doc = reader.root();
  doc.only_keys({"silence", "visemes", "phonemes"});
  VisemeSet set;
  set.silence = doc.string_or("silence", set.silence);
  for (const JsonValue& v : doc.at("visemes").items()) {
    v.only_keys({"name", "dominance", "targets", "per_parameter", "note"});
    Viseme vis;
    vis.name = v.at("name").string();
    if (auto d = v.find("dominance")) vis.dominance = parse_dominance(*d);
    if (auto targets = v.find("targets"))
      for (const auto& [k, t] : targets->members()) vis.targets.push_back({k, t.number()});
    if (auto pp = v.find("per_parameter"))
      for (const auto& [k, d] : pp->members()) vis.per_parameter[k] = parse_dominance(d);
    set.visemes.push_back(std::move(vis));
  }
  if (auto ph = doc.find("phonemes"))
    for (const auto& [k, v] : ph->members()) set.phoneme_to_viseme[k] = v.string();
  try {
    set.validate();
  } catch (const InvalidInput& e) {
    doc.at("visemes").fail(e.what());
  }
  return set;
}

std::string format_visemes(const VisemeSet& set) {
  set.validate();
  Json doc = core::make_envelope("channels.visemes", {1, 0});
  doc["silence"] = set.silence;
  Json vs = Json::array();
  for (const Viseme& v : set.visemes) {
    Json j{{"name", v.name}};
    Json t = Json::object();
    for (const Target& tg : v.targets) t[tg.parameter] = tg.value;
    j["targets"] = t;
    j["dominance"] = dominance_json(v.dominance);
    if (!v.per_parameter.empty()) {
      Json pp = Json::object();
      for (const auto& [k, d] : v.per_parameter) pp[k] = dominance_json(d);
      j["per_parameter"] = pp;
    }
    vs.push_back(j);
  }
  doc["visemes"] = vs;
  Json ph = Json::object();
  for (const auto& [k, v] : set.phoneme_to_viseme) ph[k] = v;
  doc["phonemes"] = ph;
  return doc.dump(1) + "\n";
}

VisemeSet read_visemes(const std::string& path) { return parse_visemes(core::read_file(path), path); }
void write_visemes(const std::string& path, const VisemeSet& set) {
  core::write_file_atomic(path, format_visemes(set));
}

ConflictTable parse_conflicts(std::string_view text, const std::string& file) {
  const core::JsonReader reader(text, file, "channels.conflicts", {1, 0});
  const JsonValue doc = reader.root();
  doc.only_keys({"pairs"});
  ConflictTable t;
  for (const JsonValue& o : doc.at("pairs").items()) {
    o.only_keys({"a", "b", "rationale"});
    ConflictPair pair;
    pair.a = o.at("a").string();
    pair.b = o.at("b").string();
    pair.rationale = o.string_or("rationale", "");
    t.pairs.push_back(std::move(pair));
    try {
      t.validate();
    } catch (const InvalidInput& e) {
      o.fail(e.what());
    }
  }
  return t;
}

std::string format_conflicts(const ConflictTable& table) {
  table.validate();
  Json doc = core::make_envelope("channels.conflicts", {1, 0});
  Json ps = Json::array();
  for (const ConflictPair& p : table.pairs) ps.push_back(Json{{"a", p.a}, {"b", p.b}, {"rationale", p.rationale}});
  doc["pairs"] = ps;
  return doc.dump(1) + "\n";
}

ConflictTable read_conflicts(const std::string& path) { return parse_conflicts(core::read_file(path), path); }
void write_conflicts(const std::string& path, const ConflictTable& table) {
  core::write_file_atomic(path, format_conflicts(table));
}

Tracks parse_tracks_json(std::string_view text, const std::string& file) {
  const core::JsonReader reader(text, file, "tracks", {1, 0});
  const JsonValue doc = reader.root();
  doc.only_keys({"fps", "names", "frames"});
  Tracks t;
  const JsonValue fps = doc.at("fps");
  t.fps = fps.number();
  if (!(t.fps > 0 && t.fps <= 1e6)) fps.fail("fps must be in (0, 1e6]");
  const JsonValue names = doc.at("names");
  std::set<std::string> seen;
  for (const JsonValue& n : names.items()) {
    t.names.push_back(n.string());
    if (t.names.back().empty() || t.names.back() == "time") n.fail("bad column name");
    if (!seen.insert(t.names.back()).second) n.fail("column \"" + t.names.back() + "\" repeated");
  }
  const JsonValue frames = doc.at("frames").expect_array();
  if (t.names.empty() && frames.size() != 0) names.fail("frames without column names");
  t.values.reserve(frames.size() * t.names.size());
  for (const JsonValue& row : frames.items()) {
    row.expect_array();
    if (row.size() != t.names.size())
      row.fail("expected " + std::to_string(t.names.size()) + " values, got " +
               std::to_string(row.size()));
    for (const JsonValue& v : row.items()) t.values.push_back(v.number());
  }
  return t;
}

std::string format_tracks_json(const Tracks& tracks) {
  tracks.validate();
  Json doc = core::make_envelope("tracks", {1, 0});
  doc["fps"] = tracks.fps;
  doc["names"] = tracks.names;
  // one frame per line keeps the file diffable and streamable
  std::string out = doc.dump();
  out.pop_back();  // '}'
  out += ",\"frames\":[";
  const std::size_t n = tracks.names.size();
  for (std::size_t f = 0; f < tracks.frames(); ++f) {
    out += f ? ",\n[" : "\n[";
    for (std::size_t c = 0; c < n; ++c) {
      if (c) out += ',';
      out += Json(tracks.values[f * n + c]).dump();
    }
    out += ']';
  }
  out += "]}\n";
  return out;
}

Tracks parse_tracks_csv(std::string_view text, const std::string& file) {
  Tracks t;
  std::vector<std::string> fields;
  std::size_t line_no = 0, header_line = 0;
  const auto fail_at = [&](std::size_t col, const std::string& msg) {
    SourceLocation where;
    where.file = file;
    where.line = line_no;
    where.column = col;
    throw FormatError(where, msg);
  };
  std::vector<double> times;
  for (const core::Line& l : core::Lines(text)) {
    const std::string_view line = l.text;
    line_no = l.number;
    if (line.empty()) {
      if (header_line == 0) fail_at(1, "empty header");
      continue;
    }
    if (header_line == 0 && core::is_csv_comment(line)) continue;  // "# emoface x.y.z" stamp
    std::string err;
    if (const std::size_t col = core::split_csv_line(line, fields, &err)) fail_at(col, err);
    if (header_line == 0) {
      header_line = line_no;
      if (fields.empty() || fields[0] != "time") fail_at(1, "the first column must be \"time\"");
      std::set<std::string> seen;
      for (std::size_t c = 1; c < fields.size(); ++c) {
        if (fields[c].empty() || fields[c] == "time") fail_at(c + 1, "bad column name");
        if (!seen.insert(fields[c]).second) fail_at(c + 1, "column \"" + fields[c] + "\" repeated");
        t.names.push_back(fields[c]);
      }
      continue;
    }
    if (fields.size() != t.names.size() + 1)
      fail_at(0, "expected " + std::to_string(t.names.size() + 1) + " fields, got " +
                     std::to_string(fields.size()));
    for (std::size_t c = 0; c < fields.size(); ++c) {
      const auto v = core::parse_number(fields[c]);  // locale-free, finite, whole field
      if (!v) fail_at(c + 1, "not a finite number: \"" + fields[c] + "\"");
      if (c == 0)
        times.push_back(*v);
      else
        t.values.push_back(*v);
    }
    if (t.values.size() > (std::size_t{1} << 28)) fail_at(0, "too many values");
  }
  if (header_line == 0) fail_at(1, "empty file");
  if (times.size() >= 2) {
    t.fps = 1.0 / (times[1] - times[0]);
    if (!(std::isfinite(t.fps) && t.fps > 0)) {
      line_no = header_line + 2;
      fail_at(1, "time must increase");
    }
    const double period = (times.back() - times.front()) / static_cast<double>(times.size() - 1);
    t.fps = 1.0 / period;
    if (std::abs(t.fps - std::round(t.fps)) < 1e-6 * t.fps) t.fps = std::round(t.fps);
    for (std::size_t f = 0; f < times.size(); ++f) {
      if (std::abs(times[f] - static_cast<double>(f) * period) > 1e-6 + 1e-9 * times[f]) {
        line_no = header_line + 1 + f;
        fail_at(1, "time column is not uniform from 0 (frame " + std::to_string(f) + ")");
      }
    }
  } else if (times.size() == 1 && times[0] != 0.0) {
    line_no = header_line + 1;
    fail_at(1, "the first frame must be at time 0");
  }
  return t;
}

std::string format_tracks_csv(const Tracks& tracks) {
  tracks.validate();
  std::string out = core::csv_stamp() + "time";
  for (const auto& n : tracks.names) {
    out += ',';
    core::append_csv_field(out, n);
  }
  out += '\n';
  char buf[64];
  const std::size_t n = tracks.names.size();
  for (std::size_t f = 0; f < tracks.frames(); ++f) {
    std::snprintf(buf, sizeof buf, "%.17g", tracks.time(f));
    out += buf;
    for (std::size_t c = 0; c < n; ++c) {
      std::snprintf(buf, sizeof buf, ",%.17g", tracks.values[f * n + c]);
      out += buf;
    }
    out += '\n';
  }
  return out;
}

namespace {
bool is_csv(const std::string& path) {
  return path.size() >= 4 && (path.compare(path.size() - 4, 4, ".csv") == 0 || path.compare(path.size() - 4, 4, ".CSV") == 0);
}
}  // namespace

Tracks read_tracks(const std::string& path) {
  const std::string text = core::read_file(path);
  return is_csv(path) ? parse_tracks_csv(text, path) : parse_tracks_json(text, path);
}

std::string format_tracks(const Tracks& tracks, const std::string& path) {
  return is_csv(path) ? format_tracks_csv(tracks) : format_tracks_json(tracks);
}

void write_tracks(const std::string& path, const Tracks& tracks) {
  core::write_file_atomic(path, format_tracks(tracks, path));
}

}  // namespace emoface::channels
