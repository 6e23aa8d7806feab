#include "emoface/motiongraph/io.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "emoface/core/csv.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"

namespace emoface::motiongraph {

namespace {

using Json = nlohmann::ordered_json;
constexpr core::FormatVersion kVersion{1, 0};
constexpr std::size_t kMaxLandmarks = 100000;

[[noreturn]] void fail(const std::string& file, const std::string& pointer, const std::string& msg) {
  SourceLocation where;
  where.file = file;
  where.json_pointer = pointer;
  throw FormatError(where, msg);
}
[[noreturn]] void fail_line(const std::string& file, std::size_t line, std::size_t column,
                            const std::string& msg) {
  SourceLocation where;
  where.file = file;
  where.line = line;
  where.column = column;
  throw FormatError(where, msg);
}

// Located accessors: every bad field names its JSON pointer.
struct Reader {
  std::string file;
  const Json& field(const Json& obj, const std::string& ptr, const char* key) const {
    if (!obj.is_object()) fail(file, ptr, "expected an object");
    auto it = obj.find(key);
    if (it == obj.end()) fail(file, ptr + "/" + key, std::string("missing field \"") + key + "\"");
    return *it;
  }
  double number(const Json& v, const std::string& ptr) const {
    if (!v.is_number()) fail(file, ptr, "expected a number");
    const double x = v.get<double>();
    if (!std::isfinite(x)) fail(file, ptr, "number is not finite");
    return x;
  }
  double number(const Json& obj, const std::string& ptr, const char* key) const {
    return number(field(obj, ptr, key), ptr + "/" + key);
  }
  std::size_t count(const Json& obj, const std::string& ptr, const char* key, std::size_t max) const {
    const Json& v = field(obj, ptr, key);
    if (!v.is_number_integer() || v.get<long long>() < 0 || static_cast<unsigned long long>(v.get<long long>()) > max)
      fail(file, ptr + "/" + key, "expected an integer in [0, " + std::to_string(max) + "]");
    return static_cast<std::size_t>(v.get<long long>());
  }
  std::string string(const Json& obj, const std::string& ptr, const char* key) const {
    const Json& v = field(obj, ptr, key);
    if (!v.is_string()) fail(file, ptr + "/" + key, "expected a string");
    return v.get<std::string>();
  }
  const Json& array(const Json& obj, const std::string& ptr, const char* key) const {
    const Json& v = field(obj, ptr, key);
    if (!v.is_array()) fail(file, ptr + "/" + key, "expected an array");
    return v;
  }
  Label label(const Json& v, const std::string& ptr) const {
    if (!v.is_string()) fail(file, ptr, "expected a label string");
    try {
      return label_from_string(v.get<std::string>());
    } catch (const InvalidInput& e) {
      fail(file, ptr, e.what());
    }
  }
  std::vector<int> indices(const Json& arr, const std::string& ptr, std::size_t limit) const {
    if (!arr.is_array()) fail(file, ptr, "expected an array of indices");
    std::vector<int> out;
    for (std::size_t i = 0; i < arr.size(); ++i) {
      const Json& v = arr[i];
      if (!v.is_number_integer() || v.get<long long>() < 0 || v.get<long long>() >= static_cast<long long>(limit))
        fail(file, ptr + "/" + std::to_string(i), "expected an index in [0, " + std::to_string(limit) + ")");
      out.push_back(static_cast<int>(v.get<long long>()));
    }
    return out;
  }
  Eigen::RowVectorXd vector(const Json& arr, const std::string& ptr, Eigen::Index size) const {
    if (!arr.is_array() || static_cast<Eigen::Index>(arr.size()) != size)
      fail(file, ptr, "expected an array of " + std::to_string(size) + " numbers");
    Eigen::RowVectorXd out(size);
    for (Eigen::Index i = 0; i < size; ++i) out[i] = number(arr[static_cast<std::size_t>(i)], ptr + "/" + std::to_string(i));
    return out;
  }
};

// core::parse_json, plus number overflow ("1e999") reported as FormatError too.
Json parse(std::string_view text, const std::string& file) {
  try {
    return core::parse_json(text, file);
  } catch (const nlohmann::json::exception& e) {
    fail(file, "", std::string("invalid JSON: ") + e.what());
  }
}

// Converts an InvalidInput from validate() into a FormatError naming the file.
template <class F>
auto validated(const std::string& file, F&& body) {
  try {
    return body();
  } catch (const InvalidInput& e) {
    fail(file, "", e.what());
  }
}

Json flat(const Pose& p) {
  Json a = Json::array();
  for (Eigen::Index i = 0; i < p.rows(); ++i)
    for (Eigen::Index j = 0; j < p.cols(); ++j) a.push_back(p(i, j));
  return a;
}
Json flat(const Eigen::RowVectorXd& v) {
  Json a = Json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(v[i]);
  return a;
}
Json labels_json(const std::vector<Label>& ls) {
  Json a = Json::array();
  for (Label l : ls) a.push_back(to_string(l));
  return a;
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

// ---------------------------------------------------------------- database JSON
std::string database_to_json(const Database& db) {
  validate(db, 1);
  Json doc = core::make_envelope("landmark_database", kVersion);
  doc["dimensions"] = db.dimensions;
  doc["landmark_count"] = db.landmark_count;
  doc["frame_rate"] = db.frame_rate;
  if (!db.landmark_ids.empty()) doc["landmark_ids"] = db.landmark_ids;
  Json seqs = Json::array();
  for (const Sequence& s : db.sequences) {
    Json js;
    js["id"] = s.id;
    js["subject"] = s.subject;
    js["label"] = to_string(s.label);
    Json frames = Json::array();
    for (const Pose& p : s.frames) frames.push_back(flat(p));
    js["frames"] = std::move(frames);
    seqs.push_back(std::move(js));
  }
  doc["sequences"] = std::move(seqs);
  return doc.dump() + "\n";
}

std::string to_string(OnError on_error) { return on_error == OnError::Stop ? "stop" : "skip"; }

OnError on_error_from_string(std::string_view name) {
  if (name == "stop") return OnError::Stop;
  if (name == "skip") return OnError::Skip;
  throw InvalidInput("unknown on-error policy \"" + std::string(name) + "\" (known: stop, skip)");
}

Database parse_database_json(std::string_view text, const std::string& file, OnError on_error,
                             ReadReport* report) {
  const Json doc = parse(text, file);
  core::check_envelope(doc, "landmark_database", kVersion, file);
  Reader rd{file};
  Database db;
  const std::size_t dims = rd.count(doc, "", "dimensions", 3);
  if (dims < 1 || dims > 3) fail(file, "/dimensions", "dimensions must be 1 (weights), 2 or 3");
  db.dimensions = static_cast<int>(dims);
  db.landmark_count = rd.count(doc, "", "landmark_count", kMaxLandmarks);
  if (db.landmark_count == 0) fail(file, "/landmark_count", "landmark_count must be > 0");
  db.frame_rate = rd.number(doc, "", "frame_rate");
  if (!(db.frame_rate > 0.0)) fail(file, "/frame_rate", "frame_rate must be > 0");
  if (doc.contains("landmark_ids"))
    db.landmark_ids = rd.indices(doc["landmark_ids"], "/landmark_ids", std::size_t{1} << 30);
  const Json& seqs = rd.array(doc, "", "sequences");
  const Eigen::Index width = static_cast<Eigen::Index>(db.landmark_count * dims);
  std::map<std::string, std::size_t> ids;
  for (std::size_t s = 0; s < seqs.size(); ++s) {
    const std::string ptr = "/sequences/" + std::to_string(s);
    try {
      const Json& js = seqs[s];
      Sequence seq;
      seq.id = rd.string(js, ptr, "id");
      if (seq.id.empty()) fail(file, ptr + "/id", "empty sequence id");
      if (ids.count(seq.id)) fail(file, ptr + "/id", "duplicate sequence id \"" + seq.id + "\"");
      seq.subject = rd.string(js, ptr, "subject");
      seq.label = rd.label(rd.field(js, ptr, "label"), ptr + "/label");
      const Json& frames = rd.array(js, ptr, "frames");
      if (frames.empty()) fail(file, ptr + "/frames", "a sequence needs at least one frame");
      for (std::size_t f = 0; f < frames.size(); ++f) {
        const std::string fp = ptr + "/frames/" + std::to_string(f);
        const Eigen::RowVectorXd v = rd.vector(frames[f], fp, width);
        Pose p(static_cast<Eigen::Index>(db.landmark_count), db.dimensions);
        for (Eigen::Index i = 0; i < p.rows(); ++i)
          for (int j = 0; j < db.dimensions; ++j) p(i, j) = v[i * db.dimensions + j];
        seq.frames.push_back(std::move(p));
      }
      ids.emplace(seq.id, s);
      db.sequences.push_back(std::move(seq));
    } catch (const FormatError& e) {
      if (on_error == OnError::Stop) throw;
      if (report) report->skipped.push_back(e.what());
    }
  }
  validated(file, [&] { validate(db, 1); return 0; });
  return db;
}

// ---------------------------------------------------------------- database CSV
std::string database_to_csv(const Database& db) {
  validate(db, 1);
  // Weight space (dimensions 1): one column w<i> per channel.
  static const char* axes_xyz[] = {"x", "y", "z"};
  static const char* axes_w[] = {"w"};
  const char* const* axes = db.dimensions == 1 ? axes_w : axes_xyz;
  std::string out = core::csv_stamp() + "sequence,subject,label,frame";
  for (std::size_t i = 0; i < db.landmark_count; ++i)
    for (int j = 0; j < db.dimensions; ++j) out += "," + std::string(axes[j]) + std::to_string(i);
  out += "\n";
  char buf[40];
  for (const Sequence& s : db.sequences) {
    for (std::size_t f = 0; f < s.frames.size(); ++f) {
      core::append_csv_field(out, s.id);
      out += ",";
      core::append_csv_field(out, s.subject);
      out += "," + to_string(s.label) + "," + std::to_string(f);
      for (Eigen::Index i = 0; i < s.frames[f].rows(); ++i)
        for (int j = 0; j < db.dimensions; ++j) {
          std::snprintf(buf, sizeof buf, ",%.17g", s.frames[f](i, j));
          out += buf;
        }
      out += "\n";
    }
  }
  return out;
}

Database parse_database_csv(std::string_view text, const std::string& file, double frame_rate, OnError on_error,
                            ReadReport* report) {
  if (!(frame_rate > 0.0) || !std::isfinite(frame_rate)) throw InvalidInput("CSV frame_rate must be > 0");
  Database db;
  db.frame_rate = frame_rate;
  std::vector<std::string> fields;
  std::size_t line_no = 0, pos = 0, width = 0;
  std::map<std::string, std::size_t> index;
  std::set<std::string> bad;  // ids of skipped sequences (OnError::Skip)
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_no;
    if (line.empty() || line == "\r") continue;
    if (width == 0 && core::is_csv_comment(line)) continue;  // "# emoface x.y.z" stamp
    std::string err;
    if (std::size_t col = core::split_csv_line(line, fields, &err)) {
      if (width == 0 || on_error == OnError::Stop) fail_line(file, line_no, col, err);
      // Unreadable row: its sequence is caught by the frame numbering of the next row.
      if (report) report->skipped.push_back(file + ":" + std::to_string(line_no) + ":" + std::to_string(col) + ": " + err);
      continue;
    }
    if (width == 0) {  // header
      if (fields.size() < 6 || fields[0] != "sequence" || fields[1] != "subject" || fields[2] != "label" ||
          fields[3] != "frame")
        fail_line(file, line_no, 1, "header must start with sequence,subject,label,frame,x0,y0");
      const std::size_t coords = fields.size() - 4;
      const bool three = fields.size() >= 7 && fields[6] == "z0";
      const bool weights = fields[4] == "w0";  // weight space: w0, w1, ...
      db.dimensions = weights ? 1 : three ? 3 : 2;
      if (coords % static_cast<std::size_t>(db.dimensions) != 0)
        fail_line(file, line_no, fields.size(), "coordinate columns are not a multiple of the dimensions");
      db.landmark_count = coords / static_cast<std::size_t>(db.dimensions);
      if (db.landmark_count > kMaxLandmarks) fail_line(file, line_no, 1, "too many landmark columns");
      static const char* axes_xyz[] = {"x", "y", "z"};
      static const char* axes_w[] = {"w"};
      const char* const* axes = weights ? axes_w : axes_xyz;
      for (std::size_t c = 4; c < fields.size(); ++c) {
        const std::size_t k = c - 4;
        const std::string want = axes[k % db.dimensions] + std::to_string(k / db.dimensions);
        if (fields[c] != want) fail_line(file, line_no, c + 1, "expected column \"" + want + "\"");
      }
      width = fields.size();
      continue;
    }
    // A row of a sequence that was skipped: the sequence was reported once, drop the rest quietly.
    if (!fields.empty() && bad.count(fields[0])) continue;
    try {
      if (fields.size() != width)
        fail_line(file, line_no, std::min(fields.size(), width) + 1,
                  "expected " + std::to_string(width) + " fields, got " + std::to_string(fields.size()));
      Label label;
      try {
        label = label_from_string(fields[2]);
      } catch (const InvalidInput& e) {
        fail_line(file, line_no, 3, e.what());
      }
      auto it = index.find(fields[0]);
      if (it == index.end()) {
        if (fields[0].empty()) fail_line(file, line_no, 1, "empty sequence id");
        it = index.emplace(fields[0], db.sequences.size()).first;
        db.sequences.push_back({fields[0], fields[1], label, {}});
      } else if (it->second + 1 != db.sequences.size()) {
        fail_line(file, line_no, 1, "rows of sequence \"" + fields[0] + "\" are not contiguous");
      }
      Sequence& seq = db.sequences[it->second];
      if (seq.subject != fields[1] || seq.label != label)
        fail_line(file, line_no, 2, "subject or label changes within sequence \"" + seq.id + "\"");
      if (fields[3] != std::to_string(seq.frames.size()))
        fail_line(file, line_no, 4, "expected frame " + std::to_string(seq.frames.size()));
      Pose p(static_cast<Eigen::Index>(db.landmark_count), db.dimensions);
      for (std::size_t c = 4; c < width; ++c) {
        const std::string& s = fields[c];
        char* stop = nullptr;
        errno = 0;
        const double v = std::strtod(s.c_str(), &stop);
        if (s.empty() || stop != s.c_str() + s.size() || errno == ERANGE || !std::isfinite(v))
          fail_line(file, line_no, c + 1, "expected a finite number, got \"" + s + "\"");
        const std::size_t k = c - 4;
        p(static_cast<Eigen::Index>(k / db.dimensions), static_cast<Eigen::Index>(k % db.dimensions)) = v;
      }
  seq.frames.push_back(std::move(p));
    } catch (const FormatError& e) {
      if (on_error == OnError::Stop) throw;
      if (report) report->skipped.push_back(e.what());
      const std::string id = fields.empty() ? std::string() : fields[0];
      bad.insert(id);
      auto it = index.find(id);
      if (it != index.end() && it->second + 1 == db.sequences.size()) {  // drop its rows so far
        db.sequences.pop_back();
        index.erase(it);
      }
    }
  }
  if (width == 0) fail_line(file, 1, 1, "empty CSV (no header)");
  validated(file, [&] { validate(db, 1); return 0; });
  return db;
}

Database read_database(const std::string& path, double csv_frame_rate, OnError on_error, ReadReport* report) {
  const std::string text = core::read_file(path);
  if (ends_with(path, ".csv")) return parse_database_csv(text, path, csv_frame_rate, on_error, report);
  return parse_database_json(text, path, on_error, report);
}

void write_database(const std::string& path, const Database& db) {
  core::write_file_atomic(path, ends_with(path, ".csv") ? database_to_csv(db) : database_to_json(db));
}

// ---------------------------------------------------------------- layout
std::string layout_to_json(const LandmarkLayout& layout) {
  layout.validate();
  Json doc = core::make_envelope("landmark_layout", kVersion);
  doc["source_landmark_count"] = layout.source_landmark_count;
  Json regions = Json::array();
  for (const Region& r : layout.regions)
    regions.push_back({{"name", r.name}, {"landmarks", r.landmarks}, {"alignment", r.alignment}});
  doc["regions"] = std::move(regions);
  return doc.dump(2) + "\n";
}

LandmarkLayout parse_layout_json(std::string_view text, const std::string& file) {
  const Json doc = parse(text, file);
  core::check_envelope(doc, "landmark_layout", kVersion, file);
  Reader rd{file};
  LandmarkLayout l;
  l.source_landmark_count = rd.count(doc, "", "source_landmark_count", kMaxLandmarks);
  const Json& regions = rd.array(doc, "", "regions");
  for (std::size_t i = 0; i < regions.size(); ++i) {
    const std::string ptr = "/regions/" + std::to_string(i);
    Region r;
    r.name = rd.string(regions[i], ptr, "name");
    r.landmarks = rd.indices(rd.field(regions[i], ptr, "landmarks"), ptr + "/landmarks", l.source_landmark_count);
    if (regions[i].contains("alignment"))
      r.alignment = rd.indices(regions[i]["alignment"], ptr + "/alignment", l.source_landmark_count);
    l.regions.push_back(std::move(r));
  }
  validated(file, [&] { l.validate(); return 0; });
  return l;
}

LandmarkLayout read_layout(const std::string& path) { return parse_layout_json(core::read_file(path), path); }

// ---------------------------------------------------------------- graph
std::string graph_to_json(const MotionGraph& g) {
  Json doc = core::make_envelope("motion_graph", kVersion);
  doc["dimensions"] = g.dimensions;
  doc["frame_rate"] = g.frame_rate;
  doc["lambda"] = g.lambda;
  doc["source_frames"] = g.source_frames;
  Json regions = Json::array();
  for (const RegionGraph& r : g.regions) {
    Json jr;
    jr["name"] = r.name;
    jr["landmarks"] = r.landmarks;
    jr["neutral"] = flat(r.neutral);
    jr["neutral_node"] = r.neutral_node;
    Json nodes = Json::array();
    for (const Node& n : r.nodes) {
      Json jn;
      jn["displacement"] = flat(n.displacement);
      jn["velocity"] = flat(n.velocity);
      jn["labels"] = labels_json(n.labels);
      jn["frame_count"] = n.frame_count;
      jn["mean_run"] = n.mean_run;
      jn["frames_from_neutral"] = n.frames_from_neutral;
      jn["peak_labels"] = labels_json(n.peak_labels);
      jn["peak_length_mean"] = n.peak_length_mean;
      jn["peak_length_std"] = n.peak_length_std;
      nodes.push_back(std::move(jn));
    }
    jr["nodes"] = std::move(nodes);
    Json edges = Json::array();
    for (const Edge& e : r.edges) edges.push_back(Json::array({e.from, e.to, e.weight}));
    jr["edges"] = std::move(edges);
    regions.push_back(std::move(jr));
  }
  doc["regions"] = std::move(regions);
  return doc.dump() + "\n";
}

MotionGraph parse_graph_json(std::string_view text, const std::string& file) {
  const Json doc = parse(text, file);
  core::check_envelope(doc, "motion_graph", kVersion, file);
  Reader rd{file};
  MotionGraph g;
  const std::size_t dims = rd.count(doc, "", "dimensions", 3);
  if (dims < 1 || dims > 3) fail(file, "/dimensions", "dimensions must be 1 (weights), 2 or 3");
  g.dimensions = static_cast<int>(dims);
  g.frame_rate = rd.number(doc, "", "frame_rate");
  if (!(g.frame_rate > 0.0)) fail(file, "/frame_rate", "frame_rate must be > 0");
  g.lambda = rd.number(doc, "", "lambda");
  if (g.lambda < 0.0) fail(file, "/lambda", "lambda must be >= 0");
  g.source_frames = rd.count(doc, "", "source_frames", std::size_t{1} << 40);
  const Json& regions = rd.array(doc, "", "regions");
  if (regions.empty()) fail(file, "/regions", "a motion graph needs at least one region");
  for (std::size_t ri = 0; ri < regions.size(); ++ri) {
    const std::string ptr = "/regions/" + std::to_string(ri);
    const Json& jr = regions[ri];
    RegionGraph r;
    r.name = rd.string(jr, ptr, "name");
    r.landmarks = rd.indices(rd.field(jr, ptr, "landmarks"), ptr + "/landmarks", kMaxLandmarks);
    if (r.landmarks.empty()) fail(file, ptr + "/landmarks", "a region needs landmarks");
    const Eigen::Index width = static_cast<Eigen::Index>(r.landmarks.size() * dims);
    r.neutral = rd.vector(rd.field(jr, ptr, "neutral"), ptr + "/neutral", width);
    const Json& nodes = rd.array(jr, ptr, "nodes");
    if (nodes.empty()) fail(file, ptr + "/nodes", "a region graph needs at least one node");
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const std::string np = ptr + "/nodes/" + std::to_string(i);
      const Json& jn = nodes[i];
      Node n;
      n.displacement = rd.vector(rd.field(jn, np, "displacement"), np + "/displacement", width);
      n.velocity = rd.vector(rd.field(jn, np, "velocity"), np + "/velocity", width);
      const Json& ls = rd.array(jn, np, "labels");
      for (std::size_t k = 0; k < ls.size(); ++k) n.labels.push_back(rd.label(ls[k], np + "/labels/" + std::to_string(k)));
      const Json& ps = rd.array(jn, np, "peak_labels");
      for (std::size_t k = 0; k < ps.size(); ++k)
        n.peak_labels.push_back(rd.label(ps[k], np + "/peak_labels/" + std::to_string(k)));
      n.frame_count = rd.count(jn, np, "frame_count", std::size_t{1} << 40);
      n.mean_run = rd.number(jn, np, "mean_run");
      if (n.mean_run < 1.0 || n.mean_run > 1e3) fail(file, np + "/mean_run", "mean_run must be in [1, 1000]");
      n.frames_from_neutral = rd.number(jn, np, "frames_from_neutral");
      n.peak_length_mean = rd.number(jn, np, "peak_length_mean");
      n.peak_length_std = rd.number(jn, np, "peak_length_std");
      if (n.frames_from_neutral < 0.0 || n.frames_from_neutral > 1e5 || n.peak_length_mean < 0.0 ||
          n.peak_length_mean > 1e5 || n.peak_length_std < 0.0 || n.peak_length_std > 1e5)
        fail(file, np, "frame statistics must be in [0, 1e5]");
      r.nodes.push_back(std::move(n));
    }
    r.neutral_node = rd.count(jr, ptr, "neutral_node", r.nodes.size() - 1);
    const Json& edges = rd.array(jr, ptr, "edges");
    for (std::size_t i = 0; i < edges.size(); ++i) {
      const std::string ep = ptr + "/edges/" + std::to_string(i);
      const Json& je = edges[i];
      if (!je.is_array() || je.size() != 3) fail(file, ep, "expected [from, to, weight]");
      Edge e;
      for (int k = 0; k < 2; ++k) {
        if (!je[k].is_number_integer() || je[k].get<long long>() < 0 ||
            je[k].get<long long>() >= static_cast<long long>(r.nodes.size()))
          fail(file, ep + "/" + std::to_string(k), "node index out of range");
      }
      e.from = je[0].get<std::size_t>();
      e.to = je[1].get<std::size_t>();
      e.weight = rd.number(je[2], ep + "/2");
      if (e.weight < 0.0) fail(file, ep + "/2", "edge weights must be >= 0");
      r.edges.push_back(e);
    }
    g.regions.push_back(std::move(r));
  }
  return g;
}

MotionGraph read_graph(const std::string& path) { return parse_graph_json(core::read_file(path), path); }
void write_graph(const std::string& path, const MotionGraph& graph) {
  core::write_file_atomic(path, graph_to_json(graph));
}

// ---------------------------------------------------------------- CK+
namespace {
namespace fs = std::filesystem;

std::vector<fs::path> sorted_entries(const fs::path& dir, bool directories) {
  std::vector<fs::path> out;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (directories ? it->is_directory() : it->is_regular_file()) out.push_back(it->path());
  if (ec) throw IoError("cannot list " + dir.string() + ": " + ec.message());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

// Whitespace-separated numbers, `per_line` per non-empty line.
std::vector<std::vector<double>> parse_ck_numbers(std::string_view text, const std::string& file,
                                                  std::size_t per_line) {
  std::vector<std::vector<double>> rows;
  std::size_t line_no = 0, pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    const std::string line(text.substr(pos, end - pos));
    pos = end + 1;
    ++line_no;
    std::istringstream ls(line);
    std::vector<double> row;
    std::string tok;
    while (ls >> tok) {
      char* stop = nullptr;
      errno = 0;
      const double v = std::strtod(tok.c_str(), &stop);
      if (stop != tok.c_str() + tok.size() || errno == ERANGE || !std::isfinite(v))
        fail_line(file, line_no, row.size() + 1, "expected a finite number, got \"" + tok.substr(0, 40) + "\"");
      if (row.size() == per_line)
        fail_line(file, line_no, 1, "expected " + std::to_string(per_line) + " number(s), got more");
      row.push_back(v);
    }
    if (row.empty()) continue;
    if (row.size() != per_line)
      fail_line(file, line_no, 1,
                "expected " + std::to_string(per_line) + " number(s), got " + std::to_string(row.size()));
    rows.push_back(std::move(row));
  }
  return rows;
}

Pose parse_ck_landmarks(std::string_view text, const std::string& file, std::size_t expected) {
  const auto rows = parse_ck_numbers(text, file, 2);
  if (rows.empty()) fail_line(file, 1, 1, "no landmarks");
  if (rows.size() > kMaxLandmarks) fail_line(file, kMaxLandmarks + 1, 1, "too many landmarks");
  if (expected != 0 && rows.size() != expected)
    fail_line(file, rows.size(), 1,
              "has " + std::to_string(rows.size()) + " landmarks, expected " + std::to_string(expected));
  Pose p(static_cast<Eigen::Index>(rows.size()), 2);
  for (std::size_t i = 0; i < rows.size(); ++i) p.row(static_cast<Eigen::Index>(i)) << rows[i][0], rows[i][1];
  return p;
}

Label parse_ck_emotion(std::string_view text, const std::string& file) {
  // CK+ Emotion codes (Lucey et al. 2010).
  static const Label codes[] = {Label::Neutral, Label::Anger, Label::Contempt, Label::Disgust,
                                Label::Fear,    Label::Happiness, Label::Sadness, Label::Surprise};
  const auto rows = parse_ck_numbers(text, file, 1);
  if (rows.size() != 1) fail_line(file, 1, 1, "expected one emotion code");
  const double c = rows[0][0];
  if (c != std::floor(c) || c < 0 || c > 7) fail_line(file, 1, 1, "emotion code must be 0..7");
  return codes[static_cast<int>(c)];
}

Database read_ck_plus(const std::string& root, const CkPlusOptions& options, ReadReport* report) {
  const fs::path lm_root = fs::path(root) / "Landmarks", emo_root = fs::path(root) / "Emotion";
  if (!fs::is_directory(lm_root)) throw IoError("CK+ root \"" + root + "\" has no Landmarks/ directory");
  constexpr std::size_t kMaxFile = std::size_t{16} << 20;
  Database db;
  db.dimensions = 2;
  db.frame_rate = options.frame_rate;
  for (const fs::path& subject : sorted_entries(lm_root, true)) {
    for (const fs::path& seq_dir : sorted_entries(subject, true)) {
      std::vector<fs::path> files;
      for (const fs::path& f : sorted_entries(seq_dir, false))
        if (ends_with(f.filename().string(), "_landmarks.txt")) files.push_back(f);
      if (files.empty()) continue;
      Sequence seq;
      seq.subject = subject.filename().string();
      seq.id = seq.subject + "_" + seq_dir.filename().string();
      const fs::path emo_dir = emo_root / subject.filename() / seq_dir.filename();
      try {
        std::vector<fs::path> emo;
        if (fs::is_directory(emo_dir))
          for (const fs::path& f : sorted_entries(emo_dir, false))
            if (ends_with(f.filename().string(), "_emotion.txt")) emo.push_back(f);
        if (emo.empty() && !options.keep_unlabelled) continue;
        if (emo.size() > 1) throw FormatError({emo_dir.string(), "", 0, 0}, "more than one emotion file");
        if (!emo.empty()) seq.label = parse_ck_emotion(core::read_file(emo[0].string(), kMaxFile), emo[0].string());
        std::size_t expected = db.landmark_count;  // 0 until the first frame is read
        for (const fs::path& f : files) {
          seq.frames.push_back(parse_ck_landmarks(core::read_file(f.string(), kMaxFile), f.string(), expected));
          expected = static_cast<std::size_t>(seq.frames.back().rows());
        }
      } catch (const Error& e) {  // FormatError, IoError
        if (options.on_error == OnError::Stop) throw;
        if (report) report->skipped.push_back(e.what());
        continue;
      }
      if (db.landmark_count == 0) db.landmark_count = static_cast<std::size_t>(seq.frames.front().rows());
      db.sequences.push_back(std::move(seq));
    }
  }
  if (db.sequences.empty()) throw IoError("CK+ root \"" + root + "\": no labelled landmark sequences found");
  validated(root, [&] { validate(db, 1); return 0; });
  return db;
}

}  // namespace emoface::motiongraph
