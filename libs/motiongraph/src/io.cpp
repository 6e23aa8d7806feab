#include "emoface/motiongraph/io.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <tuple>
#include <utility>

#include "emoface/core/csv.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/core/json_reader.hpp"
#include "emoface/core/text.hpp"

namespace emoface::motiongraph {

namespace {

using Json = nlohmann::ordered_json;
constexpr core::FormatVersion kVersion{1, 0};
constexpr std::size_t kMaxLandmarks = 100000;

[[noreturn]] void fail(const std::string& file, const std::string& pointer, const std::string& msg) {
  throw FormatError({file, pointer, 0, 0}, msg);
}
[[noreturn]] void fail_line(const std::string& file, std::size_t line, std::size_t column,
                            const std::string& msg) {
  throw FormatError({file, "", line, column}, msg);
}

// The header fields both JSON documents share: dimensions (1 = weights, 2, 3) and frame rate.
std::pair<int, double> dimensions_and_rate(const core::JsonValue& doc) {
  const core::JsonValue jdims = doc.at("dimensions");
  const std::size_t dims = jdims.index(3);
  if (dims < 1) jdims.fail("dimensions must be 1 (weights), 2 or 3");
  const double rate = doc.at("frame_rate").number();
  if (!(rate > 0.0)) doc.at("frame_rate").fail("frame_rate must be > 0");
  return {static_cast<int>(dims), rate};
}

using core::JsonValue;

// Typed getters on core::JsonReader values (located errors, the unknown-field rule of
// docs/formats.md: each object's only_keys is checked after its fields, so a bad known field is
// reported before an unknown one).
std::vector<int> indices(const JsonValue& v, std::size_t limit) {
  std::vector<int> out;
  for (const JsonValue& item : v.expect_array().items()) {
    if (limit == 0) item.fail("no index is valid here (the range is empty)");
    out.push_back(static_cast<int>(item.index(limit - 1)));
  }
  return out;
}

// A flat array of `size` finite numbers. The values are read straight from the document; only a bad
// one builds its JSON pointer (large databases and graphs hold millions of numbers).
Eigen::RowVectorXd vector(const JsonValue& v, Eigen::Index size) {
  v.expect_array(static_cast<std::size_t>(size));
  Eigen::RowVectorXd out(size);
  const Json& arr = v.json();
  for (Eigen::Index i = 0; i < size; ++i) {
    const Json& x = arr[static_cast<std::size_t>(i)];
    if (!x.is_number() || !std::isfinite(x.get<double>())) v[static_cast<std::size_t>(i)].number();
    out[i] = x.get<double>();
  }
  return out;
}

Label label(const JsonValue& v) {
  const std::string name = v.string();
  try {
    return label_from_string(name);
  } catch (const InvalidInput& e) {
    v.fail(e.what());
  }
}

std::vector<Label> labels(const JsonValue& v) {
  std::vector<Label> out;
  for (const JsonValue& item : v.expect_array().items()) out.push_back(label(item));
  return out;
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

Database parse_database_json(std::string_view text, const std::string& file, OnError on_error,
                             ReadReport* report) {
  const core::JsonReader reader(text, file, "landmark_database", kVersion);
  const JsonValue doc = reader.root();
  Database db;
  std::tie(db.dimensions, db.frame_rate) = dimensions_and_rate(doc);
  const auto dims = static_cast<std::size_t>(db.dimensions);
  db.landmark_count = doc.at("landmark_count").index(kMaxLandmarks);
  if (db.landmark_count == 0) doc.at("landmark_count").fail("landmark_count must be > 0");
  if (auto ids = doc.find("landmark_ids")) db.landmark_ids = indices(*ids, std::size_t{1} << 30);
  const JsonValue seqs = doc.at("sequences").expect_array();
  const auto width = static_cast<Eigen::Index>(db.landmark_count * dims);
  std::map<std::string, std::size_t> ids;
  for (std::size_t s = 0; s < seqs.size(); ++s) {
    try {
      const JsonValue js = seqs[s];
      Sequence seq;
      const JsonValue id = js.at("id");
      seq.id = id.string();
      if (seq.id.empty()) id.fail("empty sequence id");
      if (ids.count(seq.id)) id.fail("duplicate sequence id \"" + seq.id + "\"");
      seq.subject = js.at("subject").string();
      seq.label = label(js.at("label"));
      const JsonValue frames = js.at("frames").expect_array();
      if (frames.size() == 0) frames.fail("a sequence needs at least one frame");
      for (std::size_t f = 0; f < frames.size(); ++f) {
        const Eigen::RowVectorXd v = vector(frames[f], width);
        Pose p(static_cast<Eigen::Index>(db.landmark_count), db.dimensions);
        for (Eigen::Index i = 0; i < p.rows(); ++i)
          for (int j = 0; j < db.dimensions; ++j) p(i, j) = v[i * db.dimensions + j];
        seq.frames.push_back(std::move(p));
      }
      js.only_keys({"id", "subject", "label", "frames"});
      ids.emplace(seq.id, s);
      db.sequences.push_back(std::move(seq));
    } catch (const FormatError& e) {
      if (on_error == OnError::Stop) throw;
      if (report) report->skipped.push_back(e.what());
    }
  }
  doc.only_keys({"dimensions", "landmark_count", "frame_rate", "landmark_ids", "sequences"});
  validated(file, [&] {
    validate(db, 1);
    return 0;
  });
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
  std::size_t width = 0;
  std::map<std::string, std::size_t> index;
  std::set<std::string> bad;  // ids of skipped sequences (OnError::Skip)
  // Line by line rather than core::CsvTable: with Skip, a row of the wrong width drops its sequence
  // instead of ending the read.
  for (const core::Line& numbered : core::Lines(text)) {
    const std::size_t line_no = numbered.number;
    const std::string_view line = numbered.text;
    if (line.empty()) continue;
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
        const std::optional<double> v = core::parse_number(s);
        if (!v) fail_line(file, line_no, c + 1, "expected a finite number, got \"" + s + "\"");
        const std::size_t k = c - 4;
        p(static_cast<Eigen::Index>(k / db.dimensions),
          static_cast<Eigen::Index>(k % db.dimensions)) = *v;
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
  const core::JsonReader reader(text, file, "landmark_layout", kVersion);
  const JsonValue doc = reader.root();
  LandmarkLayout l;
  l.source_landmark_count = doc.at("source_landmark_count").index(kMaxLandmarks);
  for (const JsonValue& jr : doc.at("regions").items()) {
    Region r;
    r.name = jr.at("name").string();
    r.landmarks = indices(jr.at("landmarks"), l.source_landmark_count);
    if (auto a = jr.find("alignment")) r.alignment = indices(*a, l.source_landmark_count);
    jr.only_keys({"name", "landmarks", "alignment"});
    l.regions.push_back(std::move(r));
  }
  doc.only_keys({"source_landmark_count", "regions", "comment"});  // comment: for people
  validated(file, [&] {
    l.validate();
    return 0;
  });
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
  const core::JsonReader reader(text, file, "motion_graph", kVersion);
  const JsonValue doc = reader.root();
  MotionGraph g;
  std::tie(g.dimensions, g.frame_rate) = dimensions_and_rate(doc);
  const auto dims = static_cast<std::size_t>(g.dimensions);
  g.lambda = doc.at("lambda").number();
  if (g.lambda < 0.0) doc.at("lambda").fail("lambda must be >= 0");
  constexpr std::size_t kMaxCount = std::size_t{1} << 40;
  g.source_frames = doc.at("source_frames").index(kMaxCount);
  const JsonValue regions = doc.at("regions").expect_array();
  if (regions.size() == 0) regions.fail("a motion graph needs at least one region");
  for (const JsonValue& jr : regions.items()) {
    RegionGraph r;
    r.name = jr.at("name").string();
    const JsonValue landmarks = jr.at("landmarks");
    r.landmarks = indices(landmarks, kMaxLandmarks);
    if (r.landmarks.empty()) landmarks.fail("a region needs landmarks");
    const auto width = static_cast<Eigen::Index>(r.landmarks.size() * dims);
    r.neutral = vector(jr.at("neutral"), width);
    const JsonValue nodes = jr.at("nodes").expect_array();
    if (nodes.size() == 0) nodes.fail("a region graph needs at least one node");
    for (const JsonValue& jn : nodes.items()) {
      Node n;
      n.displacement = vector(jn.at("displacement"), width);
      n.velocity = vector(jn.at("velocity"), width);
      n.labels = labels(jn.at("labels"));
      n.peak_labels = labels(jn.at("peak_labels"));
      n.frame_count = jn.at("frame_count").index(kMaxCount);
      n.mean_run = jn.at("mean_run").number();
      if (n.mean_run < 1.0 || n.mean_run > 1e3)
        jn.at("mean_run").fail("mean_run must be in [1, 1000]");
      n.frames_from_neutral = jn.at("frames_from_neutral").number();
      n.peak_length_mean = jn.at("peak_length_mean").number();
      n.peak_length_std = jn.at("peak_length_std").number();
      if (n.frames_from_neutral < 0.0 || n.frames_from_neutral > 1e5 || n.peak_length_mean < 0.0 ||
          n.peak_length_mean > 1e5 || n.peak_length_std < 0.0 || n.peak_length_std > 1e5)
        jn.fail("frame statistics must be in [0, 1e5]");
      jn.only_keys({"displacement", "velocity", "labels", "frame_count", "mean_run",
                    "frames_from_neutral", "peak_labels", "peak_length_mean", "peak_length_std"});
      r.nodes.push_back(std::move(n));
    }
    r.neutral_node = jr.at("neutral_node").index(r.nodes.size() - 1);
    for (const JsonValue& je : jr.at("edges").items()) {
      je.expect_array(3);
      Edge e;
      e.from = je[0].index(r.nodes.size() - 1);
      e.to = je[1].index(r.nodes.size() - 1);
      e.weight = je[2].number();
      if (e.weight < 0.0) je[2].fail("edge weights must be >= 0");
      r.edges.push_back(e);
    }
    jr.only_keys({"name", "landmarks", "neutral", "neutral_node", "nodes", "edges"});
    g.regions.push_back(std::move(r));
  }
  doc.only_keys({"dimensions", "frame_rate", "lambda", "source_frames", "regions"});
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
  constexpr std::string_view kSpace = " \t\r\v\f";
  for (const core::Line& l : core::Lines(text)) {
    const std::size_t line_no = l.number;
    std::string_view rest = l.text;
    std::vector<double> row;
    while (true) {
      const std::size_t begin = rest.find_first_not_of(kSpace);
      if (begin == std::string_view::npos) break;
      rest.remove_prefix(begin);
      const std::string_view tok = rest.substr(0, rest.find_first_of(kSpace));
      rest.remove_prefix(tok.size());
      const std::optional<double> v = core::parse_number(tok);
      if (!v)
        fail_line(file, line_no, row.size() + 1,
                  "expected a finite number, got \"" + std::string(tok.substr(0, 40)) + "\"");
      if (row.size() == per_line)
        fail_line(file, line_no, 1, "expected " + std::to_string(per_line) + " number(s), got more");
      row.push_back(*v);
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
