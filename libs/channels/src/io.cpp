#include "emoface/channels/io.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>

#include "emoface/core/csv.hpp"
#include "emoface/core/io.hpp"

namespace emoface::channels {

namespace {

using Json = nlohmann::ordered_json;

[[noreturn]] void fail(const std::string& file, const std::string& pointer, const std::string& msg) {
  SourceLocation where;
  where.file = file;
  where.json_pointer = pointer.empty() ? "/" : pointer;
  throw FormatError(where, msg);
}

const Json& field(const Json& obj, const char* key, const std::string& file, const std::string& ptr) {
  const auto it = obj.find(key);
  if (it == obj.end()) fail(file, ptr, std::string("missing field \"") + key + "\"");
  return *it;
}

double number(const Json& v, const std::string& file, const std::string& ptr) {
  if (!v.is_number()) fail(file, ptr, "expected a number");
  const double d = v.get<double>();
  if (!std::isfinite(d)) fail(file, ptr, "not a finite number");
  return d;
}

std::string string(const Json& v, const std::string& file, const std::string& ptr) {
  if (!v.is_string()) fail(file, ptr, "expected a string");
  return v.get<std::string>();
}

const Json& object(const Json& v, const std::string& file, const std::string& ptr) {
  if (!v.is_object()) fail(file, ptr, "expected an object");
  return v;
}

const Json& array(const Json& v, const std::string& file, const std::string& ptr) {
  if (!v.is_array()) fail(file, ptr, "expected an array");
  return v;
}

std::string tok(const std::string& s) { return core::json_pointer_token(s); }

Dominance parse_dominance(const Json& j, const std::string& file, const std::string& ptr) {
  object(j, file, ptr);
  Dominance d;
  for (const auto& [k, v] : j.items()) {
    const std::string p = ptr + "/" + tok(k);
    if (k == "alpha") d.alpha = number(v, file, p);
    else if (k == "theta_anticipatory") d.theta_anticipatory = number(v, file, p);
    else if (k == "theta_carryover") d.theta_carryover = number(v, file, p);
    else if (k == "c") d.c = number(v, file, p);
    else if (k == "peak_offset") d.peak_offset = number(v, file, p);
    else fail(file, p, "unknown dominance field \"" + k + "\"");
  }
  try {
    d.validate();
  } catch (const InvalidInput& e) {
    fail(file, ptr, e.what());
  }
  return d;
}

Json dominance_json(const Dominance& d) {
  return Json{{"alpha", d.alpha}, {"theta_anticipatory", d.theta_anticipatory},
              {"theta_carryover", d.theta_carryover}, {"c", d.c}, {"peak_offset", d.peak_offset}};
}

}  // namespace

VisemeSet parse_visemes(std::string_view text, const std::string& file) {
  const Json doc = core::parse_json(text, file);
  core::check_envelope(doc, "channels.visemes", {1, 0}, file);
  VisemeSet set;
  if (doc.contains("silence")) set.silence = string(doc["silence"], file, "/silence");
  const Json& vs = array(field(doc, "visemes", file, ""), file, "/visemes");
  for (std::size_t i = 0; i < vs.size(); ++i) {
    const std::string p = "/visemes/" + std::to_string(i);
    const Json& v = object(vs[i], file, p);
    Viseme vis;
    vis.name = string(field(v, "name", file, p), file, p + "/name");
    if (v.contains("dominance")) vis.dominance = parse_dominance(v["dominance"], file, p + "/dominance");
    if (v.contains("targets")) {
      for (const auto& [k, t] : object(v["targets"], file, p + "/targets").items())
        vis.targets.push_back({k, number(t, file, p + "/targets/" + tok(k))});
    }
    if (v.contains("per_parameter")) {
      for (const auto& [k, d] : object(v["per_parameter"], file, p + "/per_parameter").items())
        vis.per_parameter[k] = parse_dominance(d, file, p + "/per_parameter/" + tok(k));
    }
    for (const auto& [k, unused] : v.items()) {
      (void)unused;
      if (k != "name" && k != "dominance" && k != "targets" && k != "per_parameter" && k != "note")
        fail(file, p + "/" + tok(k), "unknown viseme field \"" + k + "\"");
    }
    set.visemes.push_back(std::move(vis));
  }
  if (doc.contains("phonemes")) {
    for (const auto& [k, v] : object(doc["phonemes"], file, "/phonemes").items())
      set.phoneme_to_viseme[k] = string(v, file, "/phonemes/" + tok(k));
  }
  try {
    set.validate();
  } catch (const InvalidInput& e) {
    fail(file, "/visemes", e.what());
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
  const Json doc = core::parse_json(text, file);
  core::check_envelope(doc, "channels.conflicts", {1, 0}, file);
  ConflictTable t;
  const Json& ps = array(field(doc, "pairs", file, ""), file, "/pairs");
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const std::string p = "/pairs/" + std::to_string(i);
    const Json& o = object(ps[i], file, p);
    ConflictPair pair;
    pair.a = string(field(o, "a", file, p), file, p + "/a");
    pair.b = string(field(o, "b", file, p), file, p + "/b");
    if (o.contains("rationale")) pair.rationale = string(o["rationale"], file, p + "/rationale");
    t.pairs.push_back(std::move(pair));
    try {
      t.validate();
    } catch (const InvalidInput& e) {
      fail(file, p, e.what());
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
  const Json doc = core::parse_json(text, file);
  core::check_envelope(doc, "tracks", {1, 0}, file);
  Tracks t;
  t.fps = number(field(doc, "fps", file, ""), file, "/fps");
  if (!(t.fps > 0 && t.fps <= 1e6)) fail(file, "/fps", "fps must be in (0, 1e6]");
  const Json& names = array(field(doc, "names", file, ""), file, "/names");
  std::set<std::string> seen;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string p = "/names/" + std::to_string(i);
    t.names.push_back(string(names[i], file, p));
    if (t.names.back().empty() || t.names.back() == "time") fail(file, p, "bad column name");
    if (!seen.insert(t.names.back()).second) fail(file, p, "column \"" + t.names.back() + "\" repeated");
  }
  const Json& frames = array(field(doc, "frames", file, ""), file, "/frames");
  if (names.empty() && !frames.empty()) fail(file, "/names", "frames without column names");
  t.values.reserve(frames.size() * names.size());
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const std::string p = "/frames/" + std::to_string(f);
    const Json& row = array(frames[f], file, p);
    if (row.size() != names.size())
      fail(file, p, "expected " + std::to_string(names.size()) + " values, got " + std::to_string(row.size()));
    for (std::size_t c = 0; c < row.size(); ++c) t.values.push_back(number(row[c], file, p + "/" + std::to_string(c)));
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
  std::size_t line_no = 0, pos = 0, header_line = 0;
  const auto fail_at = [&](std::size_t col, const std::string& msg) {
    SourceLocation where;
    where.file = file;
    where.line = line_no;
    where.column = col;
    throw FormatError(where, msg);
  };
  std::vector<double> times;
  while (pos < text.size()) {
    std::size_t eol = text.find('\n', pos);
    if (eol == std::string_view::npos) eol = text.size();
    const std::string_view line = text.substr(pos, eol - pos);
    pos = eol + 1;
    ++line_no;
    if (line.empty() || line == "\r") {
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
      fail_at(0, "expected " + std::to_string(t.names.size() + 1) + " fields, got " + std::to_string(fields.size()));
    for (std::size_t c = 0; c < fields.size(); ++c) {
      const char* b = fields[c].c_str();
      char* e = nullptr;
      const double v = std::strtod(b, &e);
      if (fields[c].empty() || *e != '\0' || !std::isfinite(v)) fail_at(c + 1, "not a finite number: \"" + fields[c] + "\"");
      if (c == 0) times.push_back(v);
      else t.values.push_back(v);
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
