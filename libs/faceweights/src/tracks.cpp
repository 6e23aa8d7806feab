#include "emoface/faceweights/tracks.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "emoface/core/csv.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/core/text.hpp"
#include "emoface/faceweights/mapper.hpp"
#include "emoface/faceweights/names.hpp"

namespace emoface::faceweights {
namespace {


std::string fixed(double v, int precision) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", precision, v);
  std::string s(buf);
  if (s == "-0" || s.find_first_not_of("-0.") == std::string::npos) s = s[0] == '-' ? s.substr(1) : s;
  return s;
}

int integer_fps(double fps) {
  const double r = std::round(fps);
  if (!(std::fabs(fps - r) < 1e-9) || r < 1 || r > 1000)
    throw InvalidInput("Live Link Face timecode needs an integer frame rate in [1, 1000], got " +
                       std::to_string(fps));
  return static_cast<int>(r);
}

// Live Link Face angle columns → emoface parameters (radians; + yaw = subject's left, + pitch = up,
// as docs/muscles.md). The eye columns are averaged into the one gaze of the muscle model.
double param_or_zero(const std::vector<std::string>& names, const std::vector<double>& v,
                     std::string_view name) {
  auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? 0.0 : v[static_cast<std::size_t>(it - names.begin())];
}

}  // namespace

std::string_view to_string(TrackFormat f) noexcept {
  switch (f) {
    case TrackFormat::ArkitCsv: return "arkit-csv";
    case TrackFormat::FacsCsv: return "facs-csv";
    case TrackFormat::LiveLinkFaceCsv: return "livelink-csv";
  }
  return "?";
}

std::optional<TrackFormat> track_format_from_string(std::string_view s) noexcept {
  if (s == "arkit-csv") return TrackFormat::ArkitCsv;
  if (s == "facs-csv") return TrackFormat::FacsCsv;
  if (s == "livelink-csv") return TrackFormat::LiveLinkFaceCsv;
  return std::nullopt;
}

std::string live_link_timecode(double seconds, int fps) {
  if (!(seconds >= 0.0) || !std::isfinite(seconds)) throw InvalidInput("timecode: time must be >= 0");
  if (fps < 1 || fps > 1000) throw InvalidInput("timecode: fps must be in [1, 1000]");
  // Round to the millisecond of a frame first so 0.999999 frames does not print as FF.1000.
  const double frames_total = std::round(seconds * fps * 1000.0) / 1000.0;
  const auto whole = static_cast<long long>(std::floor(frames_total));
  const long long sub = std::llround((frames_total - static_cast<double>(whole)) * 1000.0);
  const long long ff = whole % fps;
  const long long secs = whole / fps;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%02lld:%02lld:%02lld:%02lld.%03lld", secs / 3600, (secs / 60) % 60,
                secs % 60, ff, sub);
  return buf;
}

std::optional<double> parse_live_link_timecode(std::string_view text, int fps) {
  if (fps < 1) return std::nullopt;
  long long h = 0, m = 0, s = 0, f = 0;
  double sub = 0.0;
  std::string t(text);
  int consumed = 0;
  if (std::sscanf(t.c_str(), "%lld:%lld:%lld:%lld%n", &h, &m, &s, &f, &consumed) != 4) return std::nullopt;
  std::string rest = t.substr(static_cast<std::size_t>(consumed));
  if (!rest.empty()) {
    if (rest[0] != '.' || rest.size() < 2) return std::nullopt;
    for (std::size_t i = 1; i < rest.size(); ++i) {
      if (!std::isdigit(static_cast<unsigned char>(rest[i]))) return std::nullopt;
    }
    sub = core::parse_number("0" + rest).value_or(0.0);  // digits only: always parses
  }
  if (h < 0 || m < 0 || m >= 60 || s < 0 || s >= 60 || f < 0 || f >= fps) return std::nullopt;
  return static_cast<double>((h * 60 + m) * 60 + s) + (static_cast<double>(f) + sub) / fps;
}

std::string format_weight_track(TrackFormat format, const std::vector<std::string>& names,
                                const std::vector<double>& times,
                                const std::vector<std::vector<double>>& frames, double fps,
                                int precision) {
  if (times.size() != frames.size()) throw InvalidInput("format_weight_track: one time per frame");
  if (precision < 1 || precision > 17) throw InvalidInput("format_weight_track: precision 1-17");
  for (std::size_t i = 0; i < times.size(); ++i) {
    if (!std::isfinite(times[i]) || times[i] < 0.0 || (i > 0 && times[i] < times[i - 1]))
      throw InvalidInput("format_weight_track: times must be finite, >= 0 and non-decreasing");
  }
  const bool live_link = format == TrackFormat::LiveLinkFaceCsv;
  const Mapper mapper(builtin_weight_set(format == TrackFormat::FacsCsv ? "facs" : "arkit"), names);
  const int ifps = live_link ? integer_fps(fps) : 0;
  std::string out;
  if (live_link) {
    out += "Timecode,BlendShapeCount";
    for (const auto& c : live_link_face_columns()) out += "," + c;
  } else {
    out += core::csv_stamp();
    out += "time";
    for (const auto& t : mapper.set().targets) {
      out += ',';
      core::append_csv_field(out, t.name);
    }
  }
  out += '\n';
  std::vector<double> w(mapper.target_count());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (frames[i].size() != names.size())
      throw InvalidInput("format_weight_track: frame " + std::to_string(i) + " has " +
                         std::to_string(frames[i].size()) + " values, expected " +
                         std::to_string(names.size()));
    mapper.forward(frames[i].data(), w.data());
    if (live_link) {
      out += live_link_timecode(times[i], ifps) + ",61";
      for (int k : live_link_face_to_arkit()) out += "," + fixed(w[static_cast<std::size_t>(k)], precision);
      const double head[3] = {param_or_zero(names, frames[i], "head_yaw"),
                              param_or_zero(names, frames[i], "head_pitch"),
                              param_or_zero(names, frames[i], "head_roll")};
      const double eye[3] = {param_or_zero(names, frames[i], "eye_gaze_yaw"),
                             param_or_zero(names, frames[i], "eye_gaze_pitch"), 0.0};
      for (double v : head) out += "," + fixed(v, precision);
      for (int e = 0; e < 2; ++e) {
        for (double v : eye) out += "," + fixed(v, precision);
      }
    } else {
      out += fixed(times[i], precision);
      for (double v : w) out += "," + fixed(v, precision);
    }
    out += '\n';
  }
  return out;
}

void write_weight_track(const std::string& path, TrackFormat format,
                        const std::vector<std::string>& names, const std::vector<double>& times,
                        const std::vector<std::vector<double>>& frames, double fps) {
  core::write_file_atomic(path, format_weight_track(format, names, times, frames, fps));
}

std::string format_fixed_rate_track(TrackFormat format, const std::vector<std::string>& names,
                                   double fps, const std::vector<double>& values, int precision) {
  if (names.empty() || values.size() % names.size() != 0)
    throw InvalidInput("format_weight_track: values must hold whole frames of names.size() values");
  if (!(fps > 0.0) || !std::isfinite(fps)) throw InvalidInput("format_weight_track: fps must be > 0");
  const std::size_t n = values.size() / names.size();
  std::vector<double> times(n);
  std::vector<std::vector<double>> frames(n);
  for (std::size_t i = 0; i < n; ++i) {
    times[i] = static_cast<double>(i) / fps;
    frames[i].assign(values.begin() + static_cast<long>(i * names.size()),
                     values.begin() + static_cast<long>((i + 1) * names.size()));
  }
  return format_weight_track(format, names, times, frames, fps, precision);
}

std::vector<std::vector<double>> fit_weight_track(const WeightTrack& track, const Mapper& mapper,
                                                  TrackFitReport* report) {
  if (track.targets != mapper.set().target_names())
    throw InvalidInput("fit_weight_track: the track's targets are not the mapper's set '" +
                       mapper.set().set + "'");
  TrackFitReport rep;
  std::vector<std::vector<double>> out;
  std::vector<double> params(mapper.parameter_count(), 0.0);
  const auto& names = mapper.parameter_names();
  for (std::size_t i = 0; i < track.weights.size(); ++i) {
    const FitReport r = mapper.inverse(track.weights[i], params);
    rep.max_iterations = std::max(rep.max_iterations, r.sweeps);
    if (!r.converged) ++rep.not_converged;
    for (const auto& u : r.unrepresented) {
      if (std::find(rep.unrepresented.begin(), rep.unrepresented.end(), u) == rep.unrepresented.end())
        rep.unrepresented.push_back(u);
    }
    if (i < track.pose.size()) {
      for (const auto& [name, v] : track.pose[i]) {
        auto it = std::find(names.begin(), names.end(), name);
        if (it != names.end()) params[static_cast<std::size_t>(it - names.begin())] = v;
      }
    }
    out.push_back(params);
  }
  rep.frames = out.size();
  if (report) *report = std::move(rep);
  return out;
}

void WeightTrackReadOptions::validate() const {
  if (!(fps > 0.0) || fps > 1000.0) throw InvalidInput("WeightTrackReadOptions: fps in (0, 1000]");
}

WeightTrack parse_weight_track(std::string_view text, const WeightSet& set, const std::string& file,
                               const WeightTrackReadOptions& options) {
  options.validate();
  auto fail = [&](std::size_t line, std::size_t column, const std::string& message) -> void {
    throw FormatError(SourceLocation{file, "", line, column}, message);
  };
  std::size_t line_no = 0;
  const core::Lines lines(text);  // numbered, without '\r'
  auto next = lines.begin();
  auto next_line = [&](std::string_view& line) {
    if (next == lines.end()) return false;
    line = next->text;
    line_no = next->number;
    ++next;
    return true;
  };
  std::string_view line;
  bool have_header = false;
  while (next_line(line)) {
    if (core::is_csv_comment(line) || line.find_first_not_of(" \r\t") == std::string_view::npos) continue;
    have_header = true;
    break;
  }
  if (!have_header) fail(0, 0, "empty file: expected a header naming the " + set.set + " targets");
  if (line.size() >= 3 && line.substr(0, 3) == "\xEF\xBB\xBF") line.remove_prefix(3);
  std::vector<std::string> header;
  std::string err;
  if (std::size_t col = core::split_csv_line(line, header, &err)) fail(line_no, col, err);
  enum Kind { kTarget, kTime, kTimecode, kIgnore, kPose };
  struct Column {
    Kind kind;
    std::size_t index;  // target index, or pose slot
  };
  static const std::vector<std::pair<std::string, std::string>> pose_columns = {
      {"headyaw", "head_yaw"},         {"headpitch", "head_pitch"},    {"headroll", "head_roll"},
      {"lefteyeyaw", "eye_gaze_yaw"},  {"lefteyepitch", "eye_gaze_pitch"}, {"lefteyeroll", ""},
      {"righteyeyaw", "eye_gaze_yaw"}, {"righteyepitch", "eye_gaze_pitch"}, {"righteyeroll", ""}};
  std::vector<Column> columns;
  std::vector<int> seen(set.targets.size(), 0);
  bool has_time = false, has_pose = false;
  const std::size_t header_line = line_no;
  for (std::size_t c = 0; c < header.size(); ++c) {
    const std::string key = core::ascii_lower(header[c]);
    if (key == "time" || key == "timecode") {
      if (has_time) fail(header_line, c + 1, "two time columns");
      has_time = true;
      columns.push_back({key == "time" ? kTime : kTimecode, 0});
      continue;
    }
    // Live Link Face's count column and emoface's metadata columns (emo2muscle passes "id" through)
    if (key == "blendshapecount" || key == "id" || key == "frame" || key == "index" ||
        key == "label" || key == "name") {
      columns.push_back({kIgnore, 0});
      continue;
    }
    auto pose = std::find_if(pose_columns.begin(), pose_columns.end(),
                             [&](const auto& p) { return p.first == key; });
    if (pose != pose_columns.end()) {
      has_pose = true;
      columns.push_back({kPose, static_cast<std::size_t>(pose - pose_columns.begin())});
      continue;
    }
    if (auto t = set.find(header[c])) {
      if (seen[*t]++) fail(header_line, c + 1, "column '" + header[c] + "' repeated");
      columns.push_back({kTarget, *t});
      continue;
    }
    if (!options.ignore_unknown_columns)
      fail(header_line, c + 1,
           "unknown column '" + header[c] + "' (not a '" + set.set + "' target; see docs/formats.md)");
    columns.push_back({kIgnore, 0});
  }
  for (std::size_t t = 0; t < seen.size(); ++t) {
    if (!seen[t])
      fail(header_line, 0, "missing column '" + set.targets[t].name + "' (every '" + set.set +
                               "' target is required)");
  }
  WeightTrack track;
  track.targets = set.target_names();
  std::vector<std::string> fields;
  const int tc_fps = static_cast<int>(std::lround(options.fps));
  while (next_line(line)) {
    if (line.find_first_not_of(" \r\t") == std::string_view::npos) continue;
    if (std::size_t col = core::split_csv_line(line, fields, &err)) fail(line_no, col, err);
    if (fields.size() != columns.size())
      fail(line_no, 0, "row has " + std::to_string(fields.size()) + " fields, header has " +
                           std::to_string(columns.size()));
    std::vector<double> w(set.targets.size(), 0.0);
    std::map<std::string, double> pose;
    std::map<std::string, int> pose_n;
    double time = static_cast<double>(track.times.size()) / options.fps;
    for (std::size_t c = 0; c < fields.size(); ++c) {
      const Column& col = columns[c];
      if (col.kind == kIgnore) continue;
      if (col.kind == kTimecode) {
        auto t = parse_live_link_timecode(fields[c], tc_fps);
        if (!t) fail(line_no, c + 1, "bad timecode '" + fields[c] + "' (HH:MM:SS:FF.fff)");
        time = *t;
        continue;
      }
      const auto parsed = core::parse_number(fields[c], /*allow_non_finite=*/true);  // locale-free
      if (!parsed) fail(line_no, c + 1, "'" + header[c] + "': not a number: '" + fields[c] + "'");
      const double v = *parsed;
      if (!std::isfinite(v)) fail(line_no, c + 1, "'" + header[c] + "': NaN or infinite");
      if (col.kind == kTime) {
        if (v < 0.0) fail(line_no, c + 1, "time must be >= 0");
        time = v;
      } else if (col.kind == kTarget) {
        if (v < 0.0 || v > 1.0)
          fail(line_no, c + 1, "'" + header[c] + "' = " + fields[c] + " is outside [0, 1]");
        w[col.index] = v;
      } else {
        const std::string& name = pose_columns[col.index].second;
        if (name.empty()) continue;
        pose[name] += v;
        ++pose_n[name];
      }
    }
    for (auto& [name, v] : pose) v /= pose_n[name];
    track.times.push_back(time);
    track.weights.push_back(std::move(w));
    if (has_pose) track.pose.push_back(std::move(pose));
  }
  if (track.weights.empty()) fail(line_no, 0, "no rows after the header");
  const double t0 = track.times.front();
  for (double& t : track.times) t -= t0;
  return track;
}

WeightTrack read_weight_track(const std::string& path, const WeightSet& set,
                              const WeightTrackReadOptions& options) {
  return parse_weight_track(core::read_file(path), set, path, options);
}

}  // namespace emoface::faceweights
