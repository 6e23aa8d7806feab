#include "emoface/bridge/weight_space.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/core/rng.hpp"
#include "emoface/faceweights/names.hpp"
#include "emoface/faceweights/tracks.hpp"
#include "emoface/motiongraph/weights.hpp"
#include "emoface/muscles/parameters.hpp"

namespace emoface::bridge {

namespace mg = emoface::motiongraph;
namespace fw = emoface::faceweights;

namespace {
constexpr std::size_t kArkit = 52;

bool starts_with(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

std::vector<int> channels_with(const std::vector<const char*>& prefixes) {
  std::vector<int> out;
  const auto& names = fw::arkit_names();
  for (std::size_t i = 0; i < names.size(); ++i)
    for (const char* p : prefixes)
      if (starts_with(names[i], p)) {
        out.push_back(static_cast<int>(i));
        break;
      }
  return out;
}
}  // namespace

mg::LandmarkLayout arkit_layout() {
  mg::LandmarkLayout layout;
  layout.source_landmark_count = kArkit;
  layout.regions = {{"eyes", channels_with({"eyeBlink", "eyeLook", "eyeSquint", "eyeWide"}), {}},
                    {"eyebrows", channels_with({"brow"}), {}},
                    {"nose", channels_with({"noseSneer"}), {}},
                    {"mouth", channels_with({"mouth"}), {}},
                    {"cheeks_jaw", channels_with({"cheek", "jaw"}), {}}};
  layout.validate();
  return layout;
}

const fw::Mapper& arkit_mapper() {
  static const fw::Mapper mapper(fw::builtin_weight_set("arkit"), muscles::parameter_names());
  return mapper;
}

std::vector<double> expression_weights(const FaceLandmarkModel& face, mg::Label label,
                                       double intensity) {
  const std::vector<double> side = face.side_parameters(label, intensity);
  std::vector<double> params(muscles::kParameterCount, 0.0);
  std::copy(side.begin(), side.end(), params.begin());
  return arkit_mapper().forward(params);
}

void WeightDatabaseOptions::validate() const {
  database.validate();
  if (!(gain_std >= 0.0 && std::isfinite(gain_std)))
    throw InvalidInput("weight database: gain_std must be a finite number >= 0");
  if (!(noise_std >= 0.0 && std::isfinite(noise_std)))
    throw InvalidInput("weight database: noise_std must be a finite number >= 0");
}

namespace {
// Per-subject channel gains (stream 1, as the landmark database's identities).
std::vector<Eigen::VectorXd> subject_gains(const WeightDatabaseOptions& o) {
  core::Rng rng(o.database.seed, 1);
  std::vector<Eigen::VectorXd> gains(o.database.subjects, Eigen::VectorXd::Ones(kArkit));
  for (auto& g : gains)
    for (Eigen::Index c = 0; c < g.size(); ++c) g[c] = std::max(0.2, rng.normal(1.0, o.gain_std));
  return gains;
}

double clamp01(double v) { return std::clamp(v, 0.0, 1.0); }
}  // namespace

mg::Database generate_weight_database(const FaceLandmarkModel& face,
                                      const WeightDatabaseOptions& options) {
  options.validate();
  const mg::SyntheticOptions& so = options.database;
  const std::size_t count = mg::synthetic_sequence_count(so);
  const auto gains = subject_gains(options);
  mg::Database db;
  db.dimensions = 1;
  db.landmark_count = kArkit;
  db.frame_rate = so.frame_rate;
  for (std::size_t index = 0; index < count; ++index) {
    // The landmark database's stream and draw order for the length and the peak (synthetic.cpp).
    core::Rng rng(so.seed, 100 + index);
    const mg::Label label = so.labels[index % so.labels.size()];
    const std::size_t subject = index % so.subjects;
    rng.normal();  // the landmark database draws a head offset here; keep the streams aligned
    rng.normal();
    const std::size_t n = so.min_frames + static_cast<std::size_t>(
                                              rng.uniform_int(so.max_frames - so.min_frames + 1));
    const double peak = rng.uniform(so.min_intensity, so.max_intensity);
    mg::Sequence seq;
    char name[48];
    std::snprintf(name, sizeof name, "S%03zu", subject + 1);
    seq.subject = name;
    std::snprintf(name, sizeof name, "_%03zu", index / so.subjects + 1);
    seq.id = seq.subject + name;
    seq.label = label;
    for (std::size_t f = 0; f < n; ++f) {
      const double x = mg::onset_curve(static_cast<double>(f), static_cast<double>(n - 1));
      const std::vector<double> w = expression_weights(face, label, std::min(1.0, peak * x));
      mg::Pose p(static_cast<Eigen::Index>(kArkit), 1);
      for (std::size_t c = 0; c < kArkit; ++c)
        p(static_cast<Eigen::Index>(c), 0) =
            clamp01(w[c] * gains[subject][static_cast<Eigen::Index>(c)] +
                    rng.normal(0.0, options.noise_std));
      seq.frames.push_back(std::move(p));
    }
    db.sequences.push_back(std::move(seq));
  }
  return db;
}

mg::TrackedFrames parse_live_link_take(std::string_view text, const std::string& file, double fps,
                                       const std::string& id) {
  fw::WeightTrackReadOptions ro;
  ro.fps = fps;
  const fw::WeightTrack track =
      fw::parse_weight_track(text, fw::builtin_weight_set("arkit"), file, ro);
  mg::TrackedFrames t;
  t.id = id;
  if (t.id.empty()) {  // the file's stem
    const std::size_t slash = file.find_last_of('/');
    t.id = file.substr(slash == std::string::npos ? 0 : slash + 1);
    const std::size_t dot = t.id.find_last_of('.');
    if (dot != std::string::npos && dot > 0) t.id.resize(dot);
  }
  t.dimensions = 1;
  for (std::size_t i = 0; i < track.weights.size(); ++i) {
    if (i > 0 && !(track.times[i] > track.times[i - 1]))
      throw FormatError({file, "", i + 2, 1}, "times must increase (Timecode or time column)");
    mg::Pose p(static_cast<Eigen::Index>(kArkit), 1);
    for (std::size_t c = 0; c < kArkit; ++c)
      p(static_cast<Eigen::Index>(c), 0) = track.weights[i][c];
    t.frames.push_back(std::move(p));
    t.times.push_back(track.times[i]);
    t.confidence.push_back(1.0);
    t.success.push_back(1);
  }
  t.validate();
  return t;
}

mg::TrackedFrames read_live_link_take(const std::string& path, double fps) {
  return parse_live_link_take(core::read_file(path), path, fps);
}

std::string live_link_csv(const mg::TrackedFrames& take, double fps) {
  take.validate();
  if (take.dimensions != 1 || (!take.frames.empty() && take.frames[0].rows() != 52))
    throw InvalidInput("live_link_csv: take \"" + take.id + "\" is not a 52-channel weight take");
  const int ifps = static_cast<int>(std::lround(fps));
  if (!(fps > 0.0) || std::abs(fps - ifps) > 1e-9 || ifps > 1000)
    throw InvalidInput("live_link_csv: Live Link Face needs an integer frame rate in [1, 1000]");
  std::string out = "Timecode,BlendShapeCount";
  for (const auto& c : fw::live_link_face_columns()) out += "," + c;
  out += '\n';
  char buf[40];
  for (std::size_t i = 0; i < take.size(); ++i) {
    out += fw::live_link_timecode(take.times[i], ifps) + ",61";
    for (int k : fw::live_link_face_to_arkit()) {
      const double v = take.frames[i](k, 0);
      if (!(v >= 0.0 && v <= 1.0))
        throw InvalidInput("live_link_csv: frame " + std::to_string(i) +
                           " has a weight outside [0, 1]");
      std::snprintf(buf, sizeof buf, ",%.17g", v);
      out += buf;
    }
    out += ",0,0,0,0,0,0,0,0,0\n";  // head and eye angles: weight takes carry no pose
  }
  return out;
}

mg::TrackedFrames weight_take(const mg::MotionGraph& graph, const std::vector<mg::Pose>& frames,
                              const std::string& id) {
  const auto weights = mg::weight_frames(graph, frames, kArkit);
  mg::TrackedFrames t;
  t.id = id;
  t.dimensions = 1;
  for (std::size_t k = 0; k < weights.size(); ++k) {
    t.frames.push_back(Eigen::Map<const Eigen::VectorXd>(weights[k].data(), kArkit));
    t.times.push_back(static_cast<double>(k) / graph.frame_rate);
    t.confidence.push_back(1.0);
    t.success.push_back(1);
  }
  return t;
}

void WeightTakeOptions::validate() const {
  database.validate();
  if (rest_frames < 1) throw InvalidInput("weight takes: rest_frames must be >= 1");
  if (hold_frames > 10000) throw InvalidInput("weight takes: hold_frames must be <= 10000");
}

std::vector<mg::TrackedFrames> generate_weight_takes(const FaceLandmarkModel& face,
                                                     const WeightTakeOptions& options) {
  options.validate();
  WeightDatabaseOptions clean = options.database;
  clean.noise_std = 0.0;  // noise is added per take frame below
  const mg::Database db = generate_weight_database(face, clean);
  const double fps = db.frame_rate;
  const std::size_t subjects = options.database.database.subjects;
  std::vector<mg::TrackedFrames> takes;
  for (std::size_t s = 0; s < subjects; ++s) {
    core::Rng rng(options.database.database.seed, 5000 + s);
    mg::TrackedFrames t;
    char name[32];
    std::snprintf(name, sizeof name, "take_S%03zu", s + 1);
    t.id = name;
    t.dimensions = 1;
    const mg::Pose rest = mg::Pose::Zero(52, 1);
    auto push = [&](const mg::Pose& p, const std::string& label) {
      mg::Pose q = p;
      for (Eigen::Index c = 0; c < q.rows(); ++c)
        q(c, 0) = clamp01(q(c, 0) + rng.normal(0.0, options.database.noise_std));
      t.times.push_back(static_cast<double>(t.frames.size()) / fps);
      t.frames.push_back(std::move(q));
      t.confidence.push_back(1.0);
      t.success.push_back(1);
      t.labels.push_back(label);
    };
    for (std::size_t k = s; k < db.sequences.size(); k += subjects) {
      const mg::Sequence& seq = db.sequences[k];
      const std::string label = mg::to_string(seq.label);
      for (std::size_t i = 0; i < options.rest_frames; ++i) push(rest, "neutral");
      for (std::size_t i = 1; i < seq.frames.size(); ++i) push(seq.frames[i], label);
      for (std::size_t i = 0; i < options.hold_frames; ++i) push(seq.frames.back(), label);
      for (std::size_t i = seq.frames.size() - 1; i-- > 1;) push(seq.frames[i], label);
    }
    for (std::size_t i = 0; i < options.rest_frames; ++i) push(rest, "neutral");
    takes.push_back(std::move(t));
  }
  return takes;
}

mg::LabelTable weight_take_labels(const std::vector<mg::TrackedFrames>& takes,
                                  const mg::TrimOptions& trimming) {
  mg::LabelTable table;
  for (const mg::TrackedFrames& t : takes) {
    if (t.labels.empty())
      throw InvalidInput("weight take labels: take \"" + t.id + "\" has no label column");
    const auto segments = mg::find_segments(t, trimming);
    for (std::size_t k = 0; k < segments.size(); ++k) {
      const mg::Label l = mg::label_from_string(t.labels[segments[k].peak]);
      if (l != mg::Label::Neutral) table.entries[{t.id, std::to_string(k)}] = l;
    }
  }
  return table;
}

std::vector<muscles::ParameterFrame> weight_parameters(const mg::MotionGraph& graph,
                                                       const std::vector<mg::Pose>& frames,
                                                       WeightDriveReport* report) {
  const auto weights = mg::weight_frames(graph, frames, kArkit);
  const fw::Mapper& mapper = arkit_mapper();
  std::vector<muscles::ParameterFrame> out;
  WeightDriveReport rep;
  std::vector<double> params(muscles::kParameterCount, 0.0);
  for (std::size_t k = 0; k < weights.size(); ++k) {
    const fw::FitReport fr = mapper.inverse(weights[k], params);
    if (!fr.converged) ++rep.not_converged;
    for (const auto& u : fr.unrepresented)
      if (std::find(rep.unrepresented.begin(), rep.unrepresented.end(), u) ==
          rep.unrepresented.end())
        rep.unrepresented.push_back(u);
    const std::vector<double> back = mapper.forward(params);
    const auto& set = mapper.set();
    for (std::size_t c = 0; c < back.size(); ++c)
      if (!set.targets[c].terms.empty())
        rep.max_weight_error = std::max(rep.max_weight_error, std::abs(back[c] - weights[k][c]));
    muscles::ParameterFrame f;
    f.time = static_cast<double>(k) / graph.frame_rate;
    f.values = params;
    out.push_back(std::move(f));
  }
  rep.frames = out.size();
  if (report) *report = std::move(rep);
  return out;
}

}  // namespace emoface::bridge
