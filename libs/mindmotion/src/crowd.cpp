#include "emoface/mindmotion/crowd.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <exception>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>
#include <thread>

#include "emoface/bridge/face_landmark_model.hpp"
#include "emoface/core/csv.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/core/font.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/facemesh/io.hpp"
#include "emoface/mindmap/chart.hpp"
#include "emoface/motiongraph/layout.hpp"
#include "emoface/motiongraph/preprocess.hpp"
#include "emoface/muscles/parameters.hpp"

namespace emoface::mindmotion {

namespace mg = motiongraph;
namespace fm = facemesh;

mg::MotionGraph default_motion_graph(const mg::SyntheticOptions& database, const mg::GraphOptions& graph) {
  // The one place that picks the synthetic landmark model for a crowd without a graph (issue #9 §2).
  const mg::Database db = mg::generate_synthetic_database(bridge::FaceLandmarkModel(), database);
  return mg::build_graph(mg::preprocess(db, mg::default_layout()), graph);
}

CrowdFaces::CrowdFaces(const std::vector<mindmap::MindMap>& maps, const std::vector<std::string>& rig_specs) {
  std::map<std::string, std::string> rig_of;  // character -> rig file
  std::string everyone;                        // "" = the built-in default face
  bool have_everyone = false;
  for (const auto& spec : rig_specs) {
    const auto eq = spec.find('=');
    const std::string name = eq == std::string::npos ? "" : spec.substr(0, eq);
    const bool named = std::any_of(maps.begin(), maps.end(), [&](const mindmap::MindMap& m) { return m.character == name; });
    if (named) {
      rig_of[name] = spec.substr(eq + 1);
    } else if (!have_everyone) {
      everyone = spec;
      have_everyone = true;
    } else {
      throw InvalidInput("crowd rigs: only one rig may be given for everyone (use NAME=FILE for one character)");
    }
  }
  std::vector<std::string> file_of;  // per character
  for (const auto& m : maps) file_of.push_back(rig_of.count(m.character) ? rig_of[m.character] : everyone);
  std::map<std::string, CrowdRig> by_file;
  for (const auto& f : file_of) {
    if (by_file.count(f)) continue;
    auto face = fm::load_face_or_builtin(f);
    solvers_.push_back(std::make_unique<muscles::FaceSolver>(std::move(face.mesh), std::move(face.rig)));
    fitters_.push_back(std::make_unique<bridge::LandmarkFitter>(*solvers_.back()));
    by_file[f] = {solvers_.back().get(), fitters_.back().get()};
  }
  if (by_file.size() <= 1) {
    rigs_.push_back(by_file.empty() ? CrowdRig{} : by_file.begin()->second);
  } else {
    for (const auto& f : file_of) rigs_.push_back(by_file[f]);
  }
}

void CrowdOptions::validate() const {
  simulation.validate();
  motion.validate();
  if (!(fps == 0.0 || (fps > 0.0 && fps <= 240.0)))
    throw InvalidInput("CrowdOptions: fps must be 0 (the graph's rate) or in (0, 240]");
  if (!(key_window > 0.0 && key_window <= 60.0)) throw InvalidInput("CrowdOptions: key_window must be in (0, 60] s");
}

void CrowdRenderOptions::validate() const {
  if (face_width < 32 || face_width > 2048) throw InvalidInput("CrowdRenderOptions: face_width must be in [32, 2048]");
  if (face_height != 0 && (face_height < 32 || face_height > 2048))
    throw InvalidInput("CrowdRenderOptions: face_height must be 0 or in [32, 2048]");
  if (strip_height < 8 || strip_height > 512) throw InvalidInput("CrowdRenderOptions: strip_height must be in [8, 512]");
  if (columns < 0 || columns > 16) throw InvalidInput("CrowdRenderOptions: columns must be 0 (auto) or in [1, 16]");
  if (gap < 0 || gap > 64) throw InvalidInput("CrowdRenderOptions: gap must be in [0, 64]");
  if (!(zoom >= 0.5 && zoom <= 4.0)) throw InvalidInput("CrowdRenderOptions: zoom must be in [0.5, 4]");
  if (threads < 0 || threads > 64) throw InvalidInput("CrowdRenderOptions: threads must be in [0, 64]");
}

double face_distance(const Crowd& crowd, std::size_t a, std::size_t b) {
  if (a >= crowd.characters.size() || b >= crowd.characters.size())
    throw InvalidInput("face_distance: character index out of range");
  const auto& ta = crowd.characters[a].tracks;
  const auto& tb = crowd.characters[b].tracks;
  const std::size_t n = std::min(ta.size(), tb.size());
  if (n == 0) return 0.0;
  double sum = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    double d2 = 0.0;
    const std::size_t m = std::min(ta[k].values.size(), tb[k].values.size());
    for (std::size_t j = 0; j < m; ++j) d2 += (ta[k].values[j] - tb[k].values[j]) * (ta[k].values[j] - tb[k].values[j]);
    sum += std::sqrt(d2);
  }
  return sum / static_cast<double>(n);
}

std::vector<std::vector<double>> face_distances(const Crowd& crowd) {
  const std::size_t n = crowd.characters.size();
  std::vector<std::vector<double>> d(n, std::vector<double>(n, 0.0));
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b) d[a][b] = d[b][a] = face_distance(crowd, a, b);
  return d;
}

std::vector<double> Crowd::strip_values(std::size_t c, std::size_t k) const {
  if (c >= maps.size() || k >= frame_count()) throw InvalidInput("Crowd::strip_values: character or frame out of range");
  const mindmap::MindMap& map = maps[c];
  const std::size_t n = map.emotion_count();
  std::vector<double> out(emotions.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t s = 0; s < emotions.size(); ++s)
    if (const auto e = map.find_emotion(emotions[s])) out[s] = simulation.mood[c][k * n + *e];
  return out;
}

namespace {

using Clock = std::chrono::steady_clock;

// Adds the wall and CPU time since construction to a StageTime when destroyed.
class StageTimer {
 public:
  explicit StageTimer(StageTime& into) : into_(into), wall_(Clock::now()), cpu_(std::clock()) {}
  ~StageTimer() {
    into_.wall += std::chrono::duration<double>(Clock::now() - wall_).count();
    into_.cpu += static_cast<double>(std::clock() - cpu_) / CLOCKS_PER_SEC;
  }
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;

 private:
  StageTime& into_;
  Clock::time_point wall_;
  std::clock_t cpu_;
};

// Parameter frames at the graph's rate → `count` frames at `fps` (linear interpolation, clamped at the
// last fitted frame; contraction levels stay in [0, 1] because interpolation is convex).
std::vector<muscles::ParameterFrame> resample(const std::vector<muscles::ParameterFrame>& in, double in_fps,
                                              double fps, std::size_t count) {
  std::vector<muscles::ParameterFrame> out(count);
  for (std::size_t k = 0; k < count; ++k) {
    out[k].time = static_cast<double>(k) / fps;
    if (in.empty()) {
      out[k].values.assign(muscles::kParameterCount, 0.0);
      continue;
    }
    const double s = std::min(static_cast<double>(k) * (in_fps / fps), static_cast<double>(in.size() - 1));
    const auto i = static_cast<std::size_t>(std::floor(s));
    const double w = s - static_cast<double>(i);
    const auto& a = in[i].values;
    const auto& b = in[std::min(i + 1, in.size() - 1)].values;
    out[k].values.resize(a.size());
    for (std::size_t j = 0; j < a.size(); ++j) out[k].values[j] = w == 0.0 ? a[j] : (1.0 - w) * a[j] + w * b[j];
  }
  return out;
}

void check_rigs(const std::vector<CrowdRig>& rigs, std::size_t characters, const char* who) {
  if (rigs.size() != 1 && rigs.size() != characters)
    throw InvalidInput(std::string(who) + ": give one rig for everyone or one per character (" +
                       std::to_string(characters) + "), not " + std::to_string(rigs.size()));
  for (const auto& r : rigs)
    if (!r.solver || !r.fitter) throw InvalidInput(std::string(who) + ": a rig has a null solver or fitter");
}

}  // namespace

Crowd animate_crowd(std::vector<mindmap::MindMap> maps, std::vector<mindmap::Event> events,
                    const mg::MotionGraph& graph, const std::vector<CrowdRig>& rigs, const CrowdOptions& options,
                    CrowdTimings* timings) {
  options.validate();
  if (maps.size() < 2) throw InvalidInput("crowd: needs at least 2 characters, got " + std::to_string(maps.size()));
  if (maps.size() > kMaxCrowdSize)
    throw InvalidInput("crowd: at most " + std::to_string(kMaxCrowdSize) + " characters, got " +
                       std::to_string(maps.size()));
  check_rigs(rigs, maps.size(), "crowd");
  if (!(graph.frame_rate > 0.0 && std::isfinite(graph.frame_rate))) throw InvalidInput("crowd: the motion graph has no frame rate");
  CrowdTimings t;
  Crowd crowd;
  crowd.fps = options.fps > 0.0 ? options.fps : graph.frame_rate;
  crowd.maps = maps;
  for (const auto& m : maps)
    for (const auto& e : m.emotions)
      if (std::find(crowd.emotions.begin(), crowd.emotions.end(), e) == crowd.emotions.end()) crowd.emotions.push_back(e);

  std::stable_sort(events.begin(), events.end(), [](const auto& a, const auto& b) { return a.time < b.time; });
  std::vector<std::pair<double, std::vector<std::string>>> moments;  // stimulus times of the input events
  for (const auto& e : events) {
    if (e.changes_traits()) continue;  // context/affection changes are not key moments
    if (moments.empty() || e.time > moments.back().first + 1e-9) moments.push_back({e.time, {}});
    auto& names = moments.back().second;
    if (std::find(names.begin(), names.end(), e.stimulus) == names.end()) names.push_back(e.stimulus);
  }

  mindmap::SimulationOptions so = options.simulation;
  so.frame_rate = crowd.fps;  // one mood row per output frame
  so.seed = options.seed;
  {
    StageTimer timer(t.simulation);
    crowd.simulation = mindmap::simulate(std::move(maps), std::move(events), so);
  }

  const std::size_t frames = crowd.frame_count();
  BehaviourMotionOptions mo = options.motion;
  mo.seed = options.seed;
  for (std::size_t c = 0; c < crowd.maps.size(); ++c) {
    CrowdCharacter ch;
    ch.name = crowd.maps[c].character;
    ch.rig = rigs.size() == 1 ? 0 : c;
    {
      StageTimer timer(t.synthesis);
      // One graph frame past the duration, so that the last output frame (at `duration`) has motion.
      ch.motion = synthesize_behaviour(graph, crowd.simulation.actions, ch.name, c,
                                       crowd.simulation.duration + 1.0 / graph.frame_rate, mo);
    }
    {
      StageTimer timer(t.fitting);
      const auto fitted = fit_muscle_tracks(*rigs[ch.rig].fitter, graph, ch.motion, &ch.fit);
      ch.tracks = resample(fitted, ch.motion.frame_rate, crowd.fps, frames);
    }
    crowd.characters.push_back(std::move(ch));
  }

  // Key moments (paper Fig. 4: key poses of the same stimuli under different mind maps).
  for (std::size_t i = 0; i < moments.size(); ++i) {
    const double start = moments[i].first;
    const auto k0 = static_cast<std::size_t>(std::max(0.0, std::ceil(start * crowd.fps - 1e-9)));
    if (k0 >= frames) break;
    double end = start + options.key_window;
    if (i + 1 < moments.size()) end = std::min(end, moments[i + 1].first);
    KeyMoment km;
    km.time = start;
    km.stimuli = moments[i].second;
    for (const auto& ch : crowd.characters) {
      // The key pose of a reaction: the last frame of the first action segment requested inside the
      // window — synthesis ends at the peak node of its label (paper §5) — before chained actions and
      // the idle around the peak move on. A character that did not react shows the window's middle.
      double key_time = 0.5 * (start + end);
      for (const auto& s : ch.motion.segments) {
        if (s.kind != SegmentKind::Action || s.requested_time < start - 1e-9 || s.requested_time >= end - 1e-9) continue;
        key_time = static_cast<double>(s.first_frame + s.frame_count - 1) / ch.motion.frame_rate;
        break;
      }
      km.frames.push_back(std::min(static_cast<std::size_t>(std::floor(key_time * crowd.fps + 1e-9)), frames - 1));
    }
    crowd.key_moments.push_back(std::move(km));
  }
  if (timings) *timings = t;
  return crowd;
}

core::Image mood_strip(const std::vector<double>& values, const std::vector<std::uint32_t>& colours,
                       int width, int height, const std::vector<std::string>& labels) {
  if (values.size() != colours.size()) throw InvalidInput("mood_strip: one colour per value is needed");
  if (!labels.empty() && labels.size() != values.size())
    throw InvalidInput("mood_strip: one label per value is needed (or none)");
  if (width < 8 || width > 8192 || height < 8 || height > 8192)
    throw InvalidInput("mood_strip: width and height must be in [8, 8192]");
  const int n = static_cast<int>(values.size());
  if (n > 0 && width / n < 4)
    throw InvalidInput("mood_strip: " + std::to_string(n) + " bars do not fit in " + std::to_string(width) + " pixels");
  core::Image img(width, height);
  if (n == 0) return img;
  const int slot = width / n, left = (width - slot * n) / 2;
  const int pad = std::max(1, slot / 6);
  // labels (issue 19): a text row of 8 pixels at the bottom of strips of at least 24 pixels
  const bool text = !labels.empty() && height >= 24;
  const int bars_height = text ? height - 8 : height;
  const int top = std::max(1, bars_height / 10),
            bottom = bars_height - 1 - std::max(1, bars_height / 10);  // frame rows
  constexpr core::Rgb kFrame{0xc8, 0xc8, 0xc8};
  for (int i = 0; i < n; ++i) {
    const double v = values[static_cast<std::size_t>(i)];
    if (std::isnan(v)) continue;  // the character lacks this emotion node
    const int x0 = left + i * slot + pad, x1 = left + (i + 1) * slot - pad - 1;  // frame columns (inclusive)
    core::fill_rect(img, x0, top, x1 - x0 + 1, 1, kFrame);
    core::fill_rect(img, x0, bottom, x1 - x0 + 1, 1, kFrame);
    core::fill_rect(img, x0, top, 1, bottom - top + 1, kFrame);
    core::fill_rect(img, x1, top, 1, bottom - top + 1, kFrame);
    const int inner = bottom - top - 1;  // rows strictly inside the frame
    const int mid = top + 1 + inner / 2;
    core::fill_rect(img, x0 + 1, mid, std::min(x1 - 1, x0 + 2) - x0, 1, kFrame);  // 0.5 tick
    core::fill_rect(img, std::max(x0 + 1, x1 - 2), mid, x1 - std::max(x0 + 1, x1 - 2), 1, kFrame);
    const double clamped = std::clamp(v, 0.0, 1.0);
    const int bar = static_cast<int>(std::lround(clamped * inner));
    core::fill_rect(img, x0 + 1, bottom - bar, x1 - x0 - 1, bar,
                    core::rgb_from_hex(colours[static_cast<std::size_t>(i)]));
    if (text) {
      const std::size_t fit = static_cast<std::size_t>(std::max(0, (x1 - x0 + 2) / 4));
      const std::string t = labels[static_cast<std::size_t>(i)].substr(0, fit);
      core::draw_text(img, (x0 + x1 + 1 - core::text_width(t, 1)) / 2 + 1, height - 7, t,
                      {60, 60, 60}, 1);
    }
  }
  return img;
}

namespace {

struct Box {
  Eigen::Vector3d centre;
  double height;
};
Box bounding_box(const fm::Vertices& v) {
  const Eigen::Vector3d lo = v.colwise().minCoeff().transpose(), hi = v.colwise().maxCoeff().transpose();
  return {0.5 * (lo + hi), hi.y() - lo.y()};
}

// Frames a rig like the default face is framed by RenderOptions' defaults: same relative target and a
// camera distance scaled by the head's height, so a retargeted (larger or smaller) head fills its cell
// alike. Zooming in moves the target towards the centre of the 68 landmarks (brows to chin), so the
// face, not the skull, stays in the picture.
fm::RenderOptions framing(const fm::Mesh& neutral, const Eigen::MatrixXd& landmarks, fm::View view, int width,
                          int height, double zoom) {
  static const Box reference = bounding_box(fm::make_generic_face().mesh.vertices);
  fm::RenderOptions o;
  o.view = view;
  o.width = width;
  o.height = height;
  const Box b = bounding_box(neutral.vertices);
  if (b.height > 0.0 && reference.height > 0.0) {
    const double s = b.height / reference.height;
    o.target = b.centre + (o.target - reference.centre) * s;
    o.distance *= s;
  }
  o.distance /= zoom;
  const Eigen::Vector3d face_centre = landmarks.colwise().mean().transpose();
  if (face_centre.allFinite()) o.target += (face_centre - o.target) * (1.0 - 1.0 / zoom);
  o.validate();
  return o;
}

}  // namespace

CrowdRenderer::CrowdRenderer(const Crowd& crowd, const std::vector<CrowdRig>& rigs, CrowdRenderOptions options)
    : crowd_(crowd), rigs_(rigs), options_(options) {
  options_.validate();
  const std::size_t n = crowd.characters.size();
  if (n == 0 || n > kMaxCrowdSize) throw InvalidInput("CrowdRenderer: the crowd has no characters or too many");
  check_rigs(rigs_, n, "CrowdRenderer");
  for (const auto& ch : crowd.characters) {
    if (ch.rig >= rigs_.size()) throw InvalidInput("CrowdRenderer: character \"" + ch.name + "\" uses a rig that was not given");
    if (ch.tracks.size() != crowd.frame_count())
      throw InvalidInput("CrowdRenderer: character \"" + ch.name + "\" has tracks of another length than the frames");
  }
  face_height_ = options_.face_height > 0 ? options_.face_height : options_.face_width * 7 / 6;
  const int count = static_cast<int>(n);
  columns_ = options_.columns > 0 ? std::min(options_.columns, count)
                                  : (count <= 4 ? count : static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count)))));
  rows_ = (count + columns_ - 1) / columns_;
  if (!crowd.emotions.empty() && options_.face_width / static_cast<int>(crowd.emotions.size()) < 4)
    throw InvalidInput("CrowdRenderer: " + std::to_string(crowd.emotions.size()) +
                       " emotion bars do not fit under a face of width " + std::to_string(options_.face_width));
  for (std::size_t i = 0; i < crowd.emotions.size(); ++i) slot_colours_.push_back(mindmap::emotion_colour(i));
  for (const auto& r : rigs_) {
    colours_.push_back(fm::material_colors(r.solver->rig(), r.solver->neutral()));
    render_options_.push_back(framing(r.solver->neutral(), r.fitter->neutral_landmarks(), options_.view, options_.face_width, face_height_, options_.zoom));
  }
}

core::Image CrowdRenderer::cell(std::size_t c, std::size_t k) const {
  if (c >= crowd_.characters.size() || k >= crowd_.frame_count()) throw InvalidInput("CrowdRenderer: character or frame out of range");
  const CrowdCharacter& ch = crowd_.characters[c];
  const muscles::FaceSolver& solver = *rigs_[ch.rig].solver;
  const muscles::Deformation d = solver.deform(ch.tracks[k].values);
  const core::Image face =
      fm::render(fm::Mesh{d.vertices, solver.neutral().faces}, colours_[ch.rig], d.crease,
                 render_options_[ch.rig], fm::paint_for(solver.rig()));
  const core::Image strip = mood_strip(crowd_.strip_values(c, k), slot_colours_,
                                       options_.face_width, options_.strip_height, crowd_.emotions);
  core::Image out(cell_width(), cell_height());
  core::blit(out, face, 0, 0);
  core::blit(out, strip, 0, face_height_);
  if (options_.face_width >= 64) {  // the character's name on a white label (issue 19)
    const int sc = options_.face_width >= 160 ? 2 : 1;
    const int w = std::min(out.width, 4 + core::text_width(ch.name, sc));
    const int h = std::min(face_height_, 4 + core::text_height(sc) + 2);
    core::fill_rect(out, 0, 0, w, h, {255, 255, 255});
    core::draw_text(out, 3, 3, ch.name, {40, 40, 40}, sc);
  }
  return out;
}

core::Image CrowdRenderer::compose(const std::vector<std::size_t>& frames) const {
  const std::size_t n = crowd_.characters.size();
  if (frames.size() != n) throw InvalidInput("CrowdRenderer::compose: one frame per character is needed");
  for (std::size_t c = 0; c < n; ++c)
    if (frames[c] >= crowd_.frame_count()) throw InvalidInput("CrowdRenderer::compose: frame out of range");
  // Cells are independent: render them on up to `threads` threads (character c on thread c mod T).
  std::size_t workers = options_.threads > 0 ? static_cast<std::size_t>(options_.threads)
                                             : std::max(1u, std::thread::hardware_concurrency());
  workers = std::min(workers, n);
  std::vector<core::Image> cells(n);
  std::vector<std::exception_ptr> errors(workers);
  auto work = [&](std::size_t t) {
    try {
      for (std::size_t c = t; c < n; c += workers) cells[c] = cell(c, frames[c]);
    } catch (...) {
      errors[t] = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  for (std::size_t t = 1; t < workers; ++t) pool.emplace_back(work, t);
  work(0);
  for (auto& th : pool) th.join();
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
  core::Image out(width(), height());
  for (std::size_t c = 0; c < n; ++c) {
    const int col = static_cast<int>(c) % columns_, row = static_cast<int>(c) / columns_;
    core::blit(out, cells[c], options_.gap + col * (cell_width() + options_.gap),
               options_.gap + row * (cell_height() + options_.gap));
  }
  return out;
}

core::Image CrowdRenderer::frame(std::size_t k) const {
  return compose(std::vector<std::size_t>(crowd_.characters.size(), k));
}

core::Image CrowdRenderer::key_moment_sheet() const {
  if (crowd_.key_moments.empty()) throw InvalidInput("CrowdRenderer: no key moments (no stimulus inside the frames)");
  constexpr int kRule = 2;  // grey rule between moments
  const int header = width() >= 200 ? 16 : 0;  // "<time> s: <stimuli>" above each moment (issue 19)
  core::Image out(width(),
                  static_cast<int>(crowd_.key_moments.size()) * (header + height() + kRule) - kRule,
                  {160, 160, 160});
  int y = 0;
  for (const auto& km : crowd_.key_moments) {
    if (header > 0) {
      core::fill_rect(out, 0, y, out.width, header, {255, 255, 255});
      std::ostringstream t;
      t << std::fixed << std::setprecision(1) << km.time << " s:";
      for (std::size_t i = 0; i < km.stimuli.size(); ++i) t << (i ? ", " : " ") << km.stimuli[i];
      core::draw_text(out, options_.gap + 2, y + 4, t.str(), {40, 40, 40}, 2);
    }
    core::blit(out, compose(km.frames), 0, y + header);
    y += header + height() + kRule;
  }
  return out;
}

std::string key_moments_csv(const Crowd& crowd) {
  std::string out = core::csv_stamp() + "time,stimuli";
  for (const auto& ch : crowd.characters) {
    out += ',';
    core::append_csv_field(out, ch.name + "_frame");
  }
  for (const auto& ch : crowd.characters) {
    out += ',';
    core::append_csv_field(out, ch.name + "_time");
  }
  out += '\n';
  char buf[64];
  for (const auto& km : crowd.key_moments) {
    std::snprintf(buf, sizeof buf, "%.6f,", km.time);
    out += buf;
    std::string joined;
    for (const auto& s : km.stimuli) joined += (joined.empty() ? "" : "+") + s;
    core::append_csv_field(out, joined);
    for (std::size_t f : km.frames) out += "," + std::to_string(f);
    for (std::size_t f : km.frames) {
      std::snprintf(buf, sizeof buf, ",%.6f", static_cast<double>(f) / crowd.fps);
      out += buf;
    }
    out += '\n';
  }
  return out;
}

}  // namespace emoface::mindmotion
