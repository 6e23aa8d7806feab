// Capture readers and writers (issue 19, item 1): OpenFace 2.0 CSV, MediaPipe face-landmarker
// NDJSON.
#include "emoface/motiongraph/capture.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>

#include "emoface/core/csv.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/core/text.hpp"

namespace emoface::motiongraph {

namespace {

constexpr std::size_t kIbug = 68;
constexpr std::size_t kMediaPipePoints = 478;
constexpr double kMaxCoordinate = 1e6;  // pixels or millimetres: anything larger is a broken file

[[noreturn]] void fail(const std::string& file, std::size_t line, std::size_t column,
                       const std::string& msg) {
  throw FormatError({file, "", line, column}, msg);
}

[[noreturn]] void fail_json(const std::string& file, std::size_t line, const std::string& pointer,
                            const std::string& msg) {
  throw FormatError({file, pointer, line, 0}, msg);
}

std::string trim(std::string_view s) {
  std::size_t a = 0, b = s.size();
  while (a < b && (s[a] == ' ' || s[a] == '\t')) ++a;
  while (b > a && (s[b - 1] == ' ' || s[b - 1] == '\t' || s[b - 1] == '\r')) --b;
  return std::string(s.substr(a, b - a));
}

// The locale-free parser of every emoface reader (core/text.hpp).
bool parse_number(const std::string& s, double& v) {
  const std::optional<double> x = core::parse_number(s);
  if (x) v = *x;
  return x.has_value();
}

std::string stem(const std::string& path) { return std::filesystem::path(path).stem().string(); }

bool is_au_column(const std::string& name) {
  // OpenFace 2.0: AU01_r … AU45_r (intensity 0–5) and AU01_c … AU45_c (presence 0/1).
  return name.size() == 6 && name[0] == 'A' && name[1] == 'U' &&
         std::isdigit(static_cast<unsigned char>(name[2])) &&
         std::isdigit(static_cast<unsigned char>(name[3])) && name[4] == '_' &&
         (name[5] == 'r' || name[5] == 'c');
}

// Splits text into lines keeping 1-based numbers; a UTF-8 BOM on the first line is dropped.
std::vector<std::pair<std::size_t, std::string_view>> lines_of(std::string_view text) {
  std::vector<std::pair<std::size_t, std::string_view>> out;
  if (text.size() >= 3 && text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  for (const core::Line& line : core::Lines(text)) out.emplace_back(line.number, line.text);
  return out;
}

}  // namespace

void TrackedFrames::validate() const {
  const std::size_t n = frames.size();
  if (dimensions < 1 || dimensions > 3)
    throw InvalidInput("tracked frames: dimensions must be 1 (weights), 2 or 3");
  // Weight takes (dimensions 1): every frame holds the same number of channels.
  const Eigen::Index rows =
      dimensions == 1 ? (n > 0 ? std::max<Eigen::Index>(frames[0].rows(), 1) : 1)
                      : static_cast<Eigen::Index>(kIbug);
  if (times.size() != n || confidence.size() != n || success.size() != n)
    throw InvalidInput("tracked frames \"" + id +
                       "\": times, confidence and success need one value per frame");
  if (!labels.empty() && labels.size() != n)
    throw InvalidInput("tracked frames \"" + id + "\": one label per frame");
  if (au.size() != (au_names.empty() ? au.size() : n))
    throw InvalidInput("tracked frames \"" + id + "\": one AU row per frame");
  for (std::size_t i = 0; i < n; ++i) {
    if (frames[i].rows() != rows || frames[i].cols() != dimensions || !frames[i].allFinite())
      throw InvalidInput("tracked frames \"" + id + "\": frame " + std::to_string(i) + " is not " +
                         std::to_string(rows) +
                         (dimensions == 1 ? " finite weights" : " finite landmarks"));
    if (!std::isfinite(times[i]) || (i > 0 && !(times[i] > times[i - 1])))
      throw InvalidInput("tracked frames \"" + id + "\": times must be finite and increasing");
    if (!(confidence[i] >= 0.0 && confidence[i] <= 1.0) || (success[i] != 0 && success[i] != 1))
      throw InvalidInput("tracked frames \"" + id +
                         "\": confidence in [0, 1] and success 0/1 expected");
    if (!au_names.empty() && au[i].size() != au_names.size())
      throw InvalidInput("tracked frames \"" + id + "\": AU row " + std::to_string(i) +
                         " has the wrong size");
  }
}

void OpenFaceReadOptions::validate() const {
  if (face_id < 0) throw InvalidInput("OpenFace reader: face_id must be >= 0");
}

TrackedFrames parse_openface_csv(std::string_view text, const std::string& file,
                                 const OpenFaceReadOptions& options) {
  options.validate();
  TrackedFrames t;
  t.id = stem(file);
  t.dimensions = options.use_3d ? 3 : 2;
  const auto lines = lines_of(text);
  std::size_t i = 0;
  while (i < lines.size() &&
         (core::is_csv_comment(lines[i].second) || trim(lines[i].second).empty()))
    ++i;
  if (i == lines.size()) fail(file, 0, 0, "empty file: no OpenFace header");
  std::vector<std::string> fields;
  std::string error;
  const std::size_t header_line = lines[i].first;
  if (const std::size_t col = core::split_csv_line(lines[i].second, fields, &error))
    fail(file, header_line, col, "malformed header: " + error);
  std::map<std::string, std::size_t> column;
  for (std::size_t c = 0; c < fields.size(); ++c) {
    const std::string name = trim(fields[c]);
    if (name.empty()) fail(file, header_line, c + 1, "empty column name");
    if (!column.emplace(name, c).second)
      fail(file, header_line, c + 1, "column \"" + name + "\" appears twice");
  }
  auto need = [&](const std::string& name) {
    const auto it = column.find(name);
    if (it == column.end()) fail(file, header_line, 0, "missing column \"" + name + "\"");
    return it->second;
  };
  const std::size_t c_time = need("timestamp"), c_conf = need("confidence"),
                    c_succ = need("success");
  const auto face_it = column.find("face_id");
  std::vector<std::array<std::size_t, 3>> c_lm(kIbug);
  const char* axes2[] = {"x_", "y_", ""};
  const char* axes3[] = {"X_", "Y_", "Z_"};
  for (std::size_t l = 0; l < kIbug; ++l)
    for (int a = 0; a < t.dimensions; ++a)
      c_lm[l][static_cast<std::size_t>(a)] =
          need((options.use_3d ? axes3 : axes2)[a] + std::to_string(l));
  std::size_t c_label = fields.size();
  if (!options.label_column.empty()) c_label = need(options.label_column);
  std::vector<std::size_t> c_au;
  for (std::size_t c = 0; c < fields.size(); ++c) {
    const std::string name = trim(fields[c]);
    if (is_au_column(name)) {
      t.au_names.push_back(name);
      c_au.push_back(c);
    }
  }
  const std::size_t width = fields.size();
  for (++i; i < lines.size(); ++i) {
    const std::size_t no = lines[i].first;  // (no structured binding: lambdas capture it, C++17)
    const std::string_view line = lines[i].second;
    if (trim(line).empty()) continue;
    if (const std::size_t col = core::split_csv_line(line, fields, &error))
      fail(file, no, col, "malformed row: " + error);
    if (fields.size() != width)
      fail(file, no, 0,
           "expected " + std::to_string(width) + " fields, got " + std::to_string(fields.size()));
    auto number = [&](std::size_t c) {
      double v = 0.0;
      const std::string s = trim(fields[c]);
      if (!parse_number(s, v)) fail(file, no, c + 1, "expected a finite number, got \"" + s + "\"");
      return v;
    };
    if (face_it != column.end()) {
      const double f = number(face_it->second);
      if (f != std::floor(f) || f < 0)
        fail(file, no, face_it->second + 1, "face_id must be a non-negative integer");
      if (static_cast<int>(f) != options.face_id) continue;
    }
    const double time = number(c_time), conf = number(c_conf), succ = number(c_succ);
    if (!t.times.empty() && !(time > t.times.back()))
      fail(file, no, c_time + 1,
           "timestamps must increase (" + trim(fields[c_time]) + " after " +
               std::to_string(t.times.back()) + ")");
    if (!(conf >= 0.0 && conf <= 1.0)) fail(file, no, c_conf + 1, "confidence must be in [0, 1]");
    if (succ != 0.0 && succ != 1.0) fail(file, no, c_succ + 1, "success must be 0 or 1");
    Pose p(static_cast<Eigen::Index>(kIbug), t.dimensions);
    for (std::size_t l = 0; l < kIbug; ++l)
      for (int a = 0; a < t.dimensions; ++a) {
        const std::size_t c = c_lm[l][static_cast<std::size_t>(a)];
        const double v = number(c);
        if (std::abs(v) > kMaxCoordinate)
          fail(file, no, c + 1, "coordinate out of range (|v| > 1e6)");
        p(static_cast<Eigen::Index>(l), a) = v;
      }
    std::vector<double> au;
    for (std::size_t c : c_au) au.push_back(number(c));
    t.times.push_back(time);
    t.confidence.push_back(conf);
    t.success.push_back(static_cast<char>(succ));
    t.frames.push_back(std::move(p));
    if (!t.au_names.empty()) t.au.push_back(std::move(au));
    if (c_label < width) t.labels.push_back(trim(fields[c_label]));
  }
  if (t.frames.empty())
    fail(file, header_line, 0, "no frames (of face_id " + std::to_string(options.face_id) + ")");
  return t;
}

TrackedFrames read_openface_csv(const std::string& path, const OpenFaceReadOptions& options) {
  return parse_openface_csv(core::read_file(path), path, options);
}

std::string openface_csv(const TrackedFrames& take) {
  take.validate();
  std::string out = "frame, face_id, timestamp, confidence, success";
  const char* names2[] = {"x_", "y_"};
  const char* names3[] = {"X_", "Y_", "Z_"};
  for (int a = 0; a < take.dimensions; ++a)
    for (std::size_t l = 0; l < kIbug; ++l)
      out += std::string(", ") + (take.dimensions == 3 ? names3 : names2)[a] + std::to_string(l);
  for (const auto& n : take.au_names) out += ", " + n;
  if (!take.labels.empty()) out += ", label";
  out += '\n';
  char buf[128];
  for (std::size_t i = 0; i < take.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%zu, 0, %.17g, %.17g, %d", i + 1, take.times[i],
                  take.confidence[i], static_cast<int>(take.success[i]));
    out += buf;
    for (int a = 0; a < take.dimensions; ++a)
      for (std::size_t l = 0; l < kIbug; ++l) {
        std::snprintf(buf, sizeof buf, ", %.17g", take.frames[i](static_cast<Eigen::Index>(l), a));
        out += buf;
      }
    for (double v : take.au.empty() ? std::vector<double>{} : take.au[i]) {
      std::snprintf(buf, sizeof buf, ", %.17g", v);
      out += buf;
    }
    if (!take.labels.empty()) {
      out += ',';  // no space: a quoted label must start the field
      core::append_csv_field(out, take.labels[i]);
    }
    out += '\n';
  }
  return out;
}

// ---- MediaPipe ----------------------------------------------------------------------------------

// MediaPipe face-landmarker point(s) for each iBUG-68 point (0-based iBUG order; two indices =
// their mean). Correspondence after Peizhi Yan, "Mediapipe_2_Dlib_Landmarks" (github.com/PeizhiYan/
// Mediapipe_2_Dlib_Landmarks, mp2dlib.py, 2024), which maps the 478 points onto the 68 dlib/iBUG
// points (dlib's 68-point model follows iBUG 300-W). Cross-checked against the jaw, brow and
// eye-corner rows of ros4hri/hri_face_detect (doc/mediapipe_face_mesh_2_ros4hri.md) and MediaPipe's
// canonical face model; docs/motiongraph.md has the table.
const std::vector<std::vector<int>>& mediapipe_to_ibug68() {
  static const std::vector<std::vector<int>> table = {
      // jaw 0–16 (the subject's right ear to left ear)
      {127},
      {234},
      {93},
      {132, 58},
      {58, 172},
      {136},
      {150},
      {176},
      {152},
      {400},
      {379},
      {365},
      {397, 288},
      {361},
      {323},
      {454},
      {356},
      // brows 17–21 (subject's right), 22–26 (left)
      {70},
      {63},
      {105},
      {66},
      {107},
      {336},
      {296},
      {334},
      {293},
      {300},
      // nose bridge 27–30, lower nose 31–35
      {168, 6},
      {197, 195},
      {5},
      {4},
      {75},
      {97},
      {2},
      {326},
      {305},
      // eyes 36–41 (right), 42–47 (left)
      {33},
      {160},
      {158},
      {133},
      {153},
      {144},
      {362},
      {385},
      {387},
      {263},
      {373},
      {380},
      // outer lips 48–59
      {61},
      {39},
      {37},
      {0},
      {267},
      {269},
      {291},
      {321},
      {314},
      {17},
      {84},
      {91},
      // inner lips 60–67
      {78},
      {82},
      {13},
      {312},
      {308},
      {317},
      {14},
      {87}};
  return table;
}

void MediaPipeReadOptions::validate() const {
  if (!(image_width > 0.0 && image_width <= 1e5) || !(image_height > 0.0 && image_height <= 1e5))
    throw InvalidInput("MediaPipe reader: image_width and image_height must be in (0, 1e5] pixels");
}

TrackedFrames parse_mediapipe_ndjson(std::string_view text, const std::string& file,
                                     const MediaPipeReadOptions& options) {
  options.validate();
  TrackedFrames t;
  t.id = stem(file);
  t.dimensions = options.use_z ? 3 : 2;
  const auto& table = mediapipe_to_ibug68();
  bool any_label = false;
  for (const auto& numbered : lines_of(text)) {
    const std::size_t no = numbered.first;
    const std::string line = trim(numbered.second);
    if (line.empty() || line[0] == '#') continue;
    nlohmann::json doc;
    try {
      doc = nlohmann::json::parse(line);
    } catch (const nlohmann::json::parse_error& e) {
      fail(file, no, e.byte, "not JSON: " + std::string(e.what()).substr(0, 120));
    } catch (const nlohmann::json::exception& e) {  // e.g. out_of_range: a number overflows a double
      fail(file, no, 0, "not JSON: " + std::string(e.what()).substr(0, 120));
    }
    if (!doc.is_object()) fail_json(file, no, "", "expected an object per line");
    auto num = [&](const nlohmann::json& v, const std::string& pointer, double limit) {
      if (!v.is_number()) fail_json(file, no, pointer, "expected a number");
      const double x = v.get<double>();
      if (!std::isfinite(x) || std::abs(x) > limit)
        fail_json(file, no, pointer, "number out of range");
      return x;
    };
    if (!doc.contains("timestamp_ms")) fail_json(file, no, "/timestamp_ms", "missing field");
    const double time = num(doc["timestamp_ms"], "/timestamp_ms", 1e12) / 1000.0;
    if (!t.times.empty() && !(time > t.times.back()))
      fail_json(file, no, "/timestamp_ms", "timestamps must increase");
    if (!doc.contains("face_landmarks") || !doc["face_landmarks"].is_array())
      fail_json(file, no, "/face_landmarks", "expected a list of faces");
    const auto& faces = doc["face_landmarks"];
    Pose p = Pose::Zero(static_cast<Eigen::Index>(kIbug), t.dimensions);
    bool found = false;
    if (!faces.empty()) {
      const auto& pts = faces[0];
      if (!pts.is_array() || pts.size() != kMediaPipePoints)
        fail_json(file, no, "/face_landmarks/0", "expected 478 points");
      Eigen::MatrixXd all(static_cast<Eigen::Index>(kMediaPipePoints), 3);
      for (std::size_t k = 0; k < kMediaPipePoints; ++k) {
        const std::string at = "/face_landmarks/0/" + std::to_string(k);
        if (!pts[k].is_object()) fail_json(file, no, at, "expected {\"x\", \"y\", \"z\"}");
        const char* keys[] = {"x", "y", "z"};
        for (int a = 0; a < 3; ++a) {
          if (!pts[k].contains(keys[a]))
            fail_json(file, no, at + "/" + keys[a], "missing coordinate");
          all(static_cast<Eigen::Index>(k), a) = num(pts[k][keys[a]], at + "/" + keys[a], 100.0);
        }
      }
      for (std::size_t l = 0; l < kIbug; ++l) {
        Eigen::RowVector3d m = Eigen::RowVector3d::Zero();
        for (int idx : table[l]) m += all.row(idx);
        m /= static_cast<double>(table[l].size());
        p(static_cast<Eigen::Index>(l), 0) = m[0] * options.image_width;
        p(static_cast<Eigen::Index>(l), 1) = m[1] * options.image_height;
        if (t.dimensions == 3) p(static_cast<Eigen::Index>(l), 2) = m[2] * options.image_width;
      }
      found = true;
    }
    std::string label;
    if (doc.contains("label")) {
      if (!doc["label"].is_string()) fail_json(file, no, "/label", "expected a string");
      label = doc["label"].get<std::string>();
      any_label = true;
    }
    t.times.push_back(time);
    t.confidence.push_back(found ? 1.0 : 0.0);
    t.success.push_back(found ? 1 : 0);
    t.frames.push_back(std::move(p));
    t.labels.push_back(std::move(label));
  }
  if (t.frames.empty()) fail(file, 0, 0, "no frames");
  if (!any_label) t.labels.clear();
  return t;
}

TrackedFrames read_mediapipe_ndjson(const std::string& path, const MediaPipeReadOptions& options) {
  return parse_mediapipe_ndjson(core::read_file(path), path, options);
}

Eigen::MatrixXd mediapipe_points_from_ibug68(const Pose& ibug,
                                             const MediaPipeReadOptions& options) {
  options.validate();
  if (ibug.rows() != static_cast<Eigen::Index>(kIbug) || (ibug.cols() != 2 && ibug.cols() != 3) ||
      !ibug.allFinite())
    throw InvalidInput("mediapipe_points_from_ibug68: need 68 finite landmarks by 2 or 3");
  Eigen::MatrixXd norm(static_cast<Eigen::Index>(kIbug), 3);
  norm.setZero();
  norm.col(0) = ibug.col(0) / options.image_width;
  norm.col(1) = ibug.col(1) / options.image_height;
  if (ibug.cols() == 3) norm.col(2) = ibug.col(2) / options.image_width;
  Eigen::MatrixXd out(static_cast<Eigen::Index>(kMediaPipePoints), 3);
  out.rowwise() = norm.colwise().mean();
  std::vector<char> set(kMediaPipePoints, 0);
  const auto& table = mediapipe_to_ibug68();
  for (std::size_t l = 0; l < kIbug; ++l) {
    const auto& idx = table[l];
    const Eigen::RowVector3d target = norm.row(static_cast<Eigen::Index>(l));
    if (idx.size() == 1) {
      out.row(idx[0]) = target;
      set[static_cast<std::size_t>(idx[0])] = 1;
    } else {  // the pair's mean must be the point; an index already placed keeps its position
      const int a = idx[0], b = idx[1];
      if (set[static_cast<std::size_t>(a)] && set[static_cast<std::size_t>(b)])
        throw InvalidInput("mediapipe_points_from_ibug68: correspondence over-determined");
      if (set[static_cast<std::size_t>(a)]) {
        out.row(b) = 2.0 * target - out.row(a);
      } else if (set[static_cast<std::size_t>(b)]) {
        out.row(a) = 2.0 * target - out.row(b);
      } else {
        out.row(a) = target;
        out.row(b) = target;
      }
      set[static_cast<std::size_t>(a)] = set[static_cast<std::size_t>(b)] = 1;
    }
  }
  return out;
}

std::string mediapipe_ndjson(const std::vector<double>& times,
                             const std::vector<Eigen::MatrixXd>& points,
                             const std::vector<std::string>& labels) {
  if (times.size() != points.size() || (!labels.empty() && labels.size() != points.size()))
    throw InvalidInput("mediapipe_ndjson: one time (and label) per frame");
  std::string out;
  char buf[96];
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!std::isfinite(times[i]) || (i > 0 && !(times[i] > times[i - 1])))
      throw InvalidInput("mediapipe_ndjson: times must be finite and increasing");
    std::snprintf(buf, sizeof buf, "{\"timestamp_ms\": %.17g, \"face_landmarks\": [",
                  times[i] * 1000.0);
    out += buf;
    const Eigen::MatrixXd& p = points[i];
    if (p.size() > 0) {
      if (p.rows() != static_cast<Eigen::Index>(kMediaPipePoints) || p.cols() != 3 ||
          !p.allFinite())
        throw InvalidInput("mediapipe_ndjson: a face is 478 finite points by 3");
      out += '[';
      for (Eigen::Index k = 0; k < p.rows(); ++k) {
        std::snprintf(buf, sizeof buf, "%s{\"x\": %.8g, \"y\": %.8g, \"z\": %.8g}", k ? ", " : "",
                      p(k, 0), p(k, 1), p(k, 2));
        out += buf;
      }
      out += ']';
    }
    out += ']';
    if (!labels.empty()) out += ", \"label\": " + nlohmann::json(labels[i]).dump();
    out += "}\n";
  }
  return out;
}

std::string mediapipe_ndjson(const TrackedFrames& take, const MediaPipeReadOptions& options) {
  take.validate();
  std::vector<Eigen::MatrixXd> points;
  for (std::size_t i = 0; i < take.size(); ++i)
    points.push_back(take.success[i] ? mediapipe_points_from_ibug68(take.frames[i], options)
                                     : Eigen::MatrixXd());
  return mediapipe_ndjson(take.times, points, take.labels);
}

}  // namespace emoface::motiongraph
