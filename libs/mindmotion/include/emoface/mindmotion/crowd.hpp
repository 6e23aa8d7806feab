#pragma once
// A crowd (issue #9 §2; paper §6.1, Fig. 1 and Fig. 4): several characters, each driven by its own
// mind map, receive the same stimuli; every character's triggered actions become motion-graph
// landmark motion (synthesize_behaviour), the motion becomes muscle tracks through the bridge
// (fit_muscle_tracks), and a compositor deforms each character's face (muscles::FaceSolver) and
// renders the faces side by side (facemesh::render; a grid past four characters), each with a mood
// strip under it: one bar per emotion node, its height the character's current mood value, in the
// emotion's colour (docs/mindmotion.md).
//
//   Crowd crowd = animate_crowd(maps, events, graph, {{&solver, &fitter}}, options);
//   CrowdRenderer renderer(crowd, {{&solver, &fitter}});
//   for (std::size_t k = 0; k < crowd.frame_count(); ++k) video.add_frame(renderer.frame(k).rgb);
//   core::Image sheet = renderer.key_moment_sheet();   // one row per stimulus (Fig. 4 style)
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "emoface/bridge/landmark_fit.hpp"
#include "emoface/core/image.hpp"
#include "emoface/facemesh/render.hpp"
#include "emoface/mindmap/mind_map.hpp"
#include "emoface/mindmap/simulation.hpp"
#include "emoface/mindmotion/behaviour.hpp"
#include "emoface/mindmotion/muscle_tracks.hpp"
#include "emoface/motiongraph/graph.hpp"
#include "emoface/motiongraph/synthetic.hpp"
#include "emoface/muscles/io.hpp"
#include "emoface/muscles/solver.hpp"

namespace emoface::mindmotion {

/// Largest crowd animate_crowd accepts (the grid and the per-frame cost grow with it).
inline constexpr std::size_t kMaxCrowdSize = 16;

/// The motion graph used when the caller has none: the synthetic CK+-like database of the face-driven
/// landmark model (bridge::FaceLandmarkModel with its defaults, as `mgraph generate`; the one place that
/// picks the landmark model), cleaned and aligned with the default layout, and built with `graph`
/// options — what `mgraph generate` + `mgraph build` give with the same options. Deterministic for given
/// options. About 3 s with the defaults (70 sequences); tests pass fewer sequences.
motiongraph::MotionGraph default_motion_graph(const motiongraph::SyntheticOptions& database = {},
                                              const motiongraph::GraphOptions& graph = {});

/// A face a character wears: the solver that deforms it and a bridge fitter built on that solver.
/// Both must outlive every Crowd and CrowdRenderer that uses them.
struct CrowdRig {
  const muscles::FaceSolver* solver = nullptr;
  const bridge::LandmarkFitter* fitter = nullptr;
};

/// The faces of a crowd: one muscle solver and landmark fitter per distinct rig file, built once.
/// `rig_specs` are as on the command line: "FILE" gives everyone that rig, "NAME=FILE" gives it to the
/// character NAME only (a spec whose part before '=' names no character is a FILE for everyone); characters
/// without a rig get the built-in default face. Throws InvalidInput for two rigs for everyone, and what
/// facemesh::load_face throws for a missing or bad rig.
class CrowdFaces {
 public:
  CrowdFaces(const std::vector<mindmap::MindMap>& maps, const std::vector<std::string>& rig_specs);
  /// One CrowdRig shared by everyone when all characters have the same face, else one per character in
  /// map order — the form animate_crowd and CrowdRenderer take.
  const std::vector<CrowdRig>& rigs() const noexcept { return rigs_; }

 private:
  std::vector<std::unique_ptr<muscles::FaceSolver>> solvers_;
  std::vector<std::unique_ptr<bridge::LandmarkFitter>> fitters_;
  std::vector<CrowdRig> rigs_;
};

struct CrowdOptions {
  /// Mind-map simulation (eq. 4 form, tie tolerance, chain delay, decay interval, duration, propagation).
  /// Its frame_rate is replaced by the output frame rate and its seed by `seed`.
  mindmap::SimulationOptions simulation;
  /// Motion synthesis per character; its seed is replaced by `seed` (each character then draws from
  /// core::derive_seed(seed, character index), as in synthesize_behaviour).
  BehaviourMotionOptions motion;
  /// Output frames per second (muscle tracks, mood rows, video frames); 0 = the motion graph's rate.
  /// Else (0, 240]; the fitted tracks are resampled linearly when it differs from the graph's rate.
  double fps = 0.0;
  /// A key moment looks for each character's reaction from the stimulus time until the next stimulus,
  /// at most this many seconds, (0, 60].
  double key_window = 4.0;
  std::uint64_t seed = 0;
  void validate() const;  ///< throws InvalidInput
};

struct CrowdCharacter {
  std::string name;
  std::size_t rig = 0;                          ///< index into the rigs given to animate_crowd
  CharacterMotion motion;                       ///< landmark motion at the graph's frame rate
  std::vector<muscles::ParameterFrame> tracks;  ///< frame_count() rows at `fps` (time = k / fps)
  TrackFitSummary fit;                          ///< of the fit at the graph's frame rate
};

/// One stimulus time of the input events and, per character, the key pose of its reaction: the last
/// frame (the reached peak, paper §5) of its first action segment requested in the window after the
/// stimulus; the middle of the window when it did not react.
struct KeyMoment {
  double time = 0.0;                  ///< seconds
  std::vector<std::string> stimuli;   ///< distinct stimulus names of the events at that time
  std::vector<std::size_t> frames;    ///< per character, a frame index in [0, frame_count())
};

struct Crowd {
  mindmap::SimulationResult simulation;  ///< mood rows sampled at `fps`: row k belongs to frame k
  std::vector<mindmap::MindMap> maps;    ///< in character order (as given)
  std::vector<CrowdCharacter> characters;
  /// Union of the characters' emotion node names in first-seen order: the mood-strip slots, and
  /// slot i is drawn in mindmap::emotion_colour(i).
  std::vector<std::string> emotions;
  std::vector<KeyMoment> key_moments;    ///< in time order; stimuli past the last frame are skipped
  double fps = 30.0;
  std::size_t frame_count() const noexcept { return simulation.times.size(); }
  /// Mood of character c at frame k per strip slot (emotions); NaN where the character lacks the node.
  std::vector<double> strip_values(std::size_t c, std::size_t k) const;
};

/// How different two characters' faces are (issue 19): the mean over the crowd's frames of the
/// Euclidean distance between the two characters' parameter vectors (all muscles::kParameterCount
/// values of `tracks`, contraction units; jaw and head parameters included). 0 for identical faces.
/// Throws InvalidInput for an index out of range.
double face_distance(const Crowd& crowd, std::size_t a, std::size_t b);

/// face_distance for every pair: a symmetric matrix (characters × characters) with a zero diagonal.
std::vector<std::vector<double>> face_distances(const Crowd& crowd);

/// Time spent in one stage: wall-clock seconds and the process' CPU seconds (std::clock; the stages of
/// animate_crowd run on one thread, so on a loaded machine `cpu` is the better measure of their cost).
struct StageTime {
  double wall = 0.0;
  double cpu = 0.0;
};

/// Time per stage (for the docs and the CLI's summary; never written to files).
struct CrowdTimings {
  StageTime simulation;  ///< mind-map simulation (all characters)
  StageTime synthesis;   ///< motion-graph synthesis (all characters)
  StageTime fitting;     ///< bridge fit + resampling (all characters)
};

/// Runs the stimuli through the characters' mind maps (mindmap::simulate), synthesizes each character's
/// motion and fits its muscle tracks on its rig. `rigs` has one entry (shared by everyone) or one per
/// map. Throws InvalidInput for fewer than 2 or more than kMaxCrowdSize characters, a wrong number of
/// rigs or null pointers, bad options, and whatever the simulation, synthesis or fit reject (unknown
/// characters, labels the graph cannot synthesize, ...). Deterministic for a seed.
Crowd animate_crowd(std::vector<mindmap::MindMap> maps, std::vector<mindmap::Event> events,
                    const motiongraph::MotionGraph& graph, const std::vector<CrowdRig>& rigs,
                    const CrowdOptions& options = {}, CrowdTimings* timings = nullptr);

struct CrowdRenderOptions {
  int face_width = 240;    ///< pixels per face, [32, 2048]
  int face_height = 0;     ///< pixels per face; 0 = face_width · 7/6 (the default face's framing), else [32, 2048]
  int strip_height = 40;   ///< mood strip under each face, pixels, [8, 512]
  int columns = 0;         ///< grid columns; 0 = one row up to 4 characters, else ⌈√N⌉; else [1, 16]
  int gap = 6;             ///< white pixels between and around cells, [0, 64]
  /// Camera distance divided by this (1 = facemesh's whole-head framing; the default 1.3 fills the
  /// cell with the face, so small expressions stay visible at small sizes), [0.5, 4].
  double zoom = 1.3;
  facemesh::View view = facemesh::View::Front;
  /// Threads that render the cells of one frame, [0, 64]; 0 = the hardware's, at most one per character.
  /// The pictures do not depend on it (each cell is rendered alone).
  int threads = 0;
  void validate() const;   ///< throws InvalidInput
};

/// Draws a mood strip: `values.size()` equal slots left to right; slot i shows a bar of height
/// values[i] · (inner height) in colours[i] (0xRRGGBB) on a light frame that marks the full scale 1
/// (with a tick at 0.5); a NaN value leaves its slot blank (no frame), a zero value draws an empty
/// frame. Values are clamped to [0, 1]. Throws InvalidInput for mismatched sizes or a size out of
/// [8, 8192]. With `labels` (one per value, or empty) and a strip of at least 24 pixels, the bottom
/// 8 rows carry each slot's label (core::draw_text at scale 1, cut to the slot's width) and the
/// bars keep the rows above; smaller strips draw no text.
core::Image mood_strip(const std::vector<double>& values, const std::vector<std::uint32_t>& colours,
                       int width, int height, const std::vector<std::string>& labels = {});

/// Deforms and renders a Crowd: one cell per character (face over mood strip) in a grid.
class CrowdRenderer {
 public:
  /// `rigs` must be the ones given to animate_crowd (same count, same faces). Keeps references to
  /// `crowd` and the rigs.
  CrowdRenderer(const Crowd& crowd, const std::vector<CrowdRig>& rigs, CrowdRenderOptions options = {});

  int columns() const noexcept { return columns_; }
  int rows() const noexcept { return rows_; }
  int cell_width() const noexcept { return options_.face_width; }
  int cell_height() const noexcept { return face_height_ + options_.strip_height; }
  /// Size of frame(): columns·cell + (columns + 1)·gap by rows·cell + (rows + 1)·gap.
  int width() const noexcept { return columns_ * cell_width() + (columns_ + 1) * options_.gap; }
  int height() const noexcept { return rows_ * cell_height() + (rows_ + 1) * options_.gap; }

  /// Character c at frame k: the deformed face rendered over its mood strip (cell_width ×
  /// cell_height). Faces at least 64 pixels wide carry the character's name in the top-left corner,
  /// strips of at least 24 pixels the emotion names under their bars (issue 19).
  core::Image cell(std::size_t c, std::size_t k) const;
  /// Every character at frame k, in grid order (row-major, character order); cells render in parallel.
  core::Image frame(std::size_t k) const;
  /// Character c at frames[c] (a frame of mixed times, e.g. key moments); frames.size() = characters.
  core::Image compose(const std::vector<std::size_t>& frames) const;
  /// The key moments stacked top to bottom, one composed row of all characters per stimulus (a
  /// crowd of more than 4 keeps its grid per moment). Sheets at least 200 pixels wide give each
  /// moment a 16-pixel header "<time> s: <stimuli>" (issue 19). Throws InvalidInput when there is
  /// no key moment.
  core::Image key_moment_sheet() const;

 private:
  const Crowd& crowd_;
  std::vector<CrowdRig> rigs_;
  CrowdRenderOptions options_;
  int face_height_ = 0, columns_ = 1, rows_ = 1;
  std::vector<std::vector<Eigen::Vector3f>> colours_;       // per rig, per vertex
  std::vector<facemesh::RenderOptions> render_options_;     // per rig (framing follows the rig's size)
  std::vector<std::uint32_t> slot_colours_;
};

/// Key moments as CSV "time,stimuli,<character>_frame...,<character>_time..." (stimuli joined by '+').
std::string key_moments_csv(const Crowd& crowd);

}  // namespace emoface::mindmotion
