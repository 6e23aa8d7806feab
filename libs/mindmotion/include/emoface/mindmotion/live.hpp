#pragma once
// A live mind-map character (issue 19 item 5): stimuli arrive frame by frame, the mind map updates
// the mood (paper §6.1, eqs. 2–4) and chooses actions, their expression labels drive motion-graph
// synthesis through motiongraph::MotionPlayer (prepared ahead, interruptible), and every frame
// becomes face parameters — through the exact ARKit mapping for a weight graph
// (bridge/weight_space.hpp) or the landmark fit for a landmark graph (bridge/landmark_fit.hpp).
//
//   mindmotion::LiveCharacter rex(graph, read_mind_map("data/mindmap/crowd/rex.json"));
//   rex.push_stimulus("insult");                 // at the current clock
//   for (;;) { rex.update(1.0 / 60); use(rex.parameters()); }   // 42 muscles::parameter_names()
//
// A stimulus-chosen action interrupts the motion playing (it starts from the current frame, no
// jump); chained actions are queued; mood-decay hints are played from the leading path nodes only
// and dropped while the face is busy (as mindmotion::synthesize_behaviour does offline).
// Deterministic for the seed and the sequence of calls. Not thread-safe.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "emoface/bridge/landmark_fit.hpp"
#include "emoface/mindmap/mind_map.hpp"
#include "emoface/mindmap/simulation.hpp"
#include "emoface/motiongraph/graph.hpp"
#include "emoface/motiongraph/player.hpp"

namespace emoface::mindmotion {

struct LiveCharacterOptions {
  mindmap::SimulationOptions simulation;  ///< mood form, chains, decay hints (seed: below)
  /// Motion: transitions with §5.1 variation (varied_synthesis()), idle when done. For a weight
  /// graph the smoothing and idle options are replaced by the weight presets.
  motiongraph::PlayerOptions player;
  double hint_path_fraction = 0.35;  ///< (0, 1], as BehaviourMotionOptions
  std::uint64_t seed = 0;            ///< mind-map choices and motion variation
  void validate() const;
};

/// The default live options: varied synthesis (mindmotion::varied_synthesis()).
LiveCharacterOptions live_character_options();

class LiveCharacter {
 public:
  /// `graph` must outlive the character. A landmark graph needs `fitter` (68 iBUG landmarks, 2D
  /// graph; also outliving the character) for parameters(); a weight graph must be ARKit-52.
  /// Throws InvalidInput for an invalid map, a label of the map the graph cannot synthesize, or a
  /// landmark graph without a fitter.
  LiveCharacter(const motiongraph::MotionGraph& graph, mindmap::MindMap map,
                LiveCharacterOptions options = live_character_options(),
                const bridge::LandmarkFitter* fitter = nullptr);
  ~LiveCharacter();
  LiveCharacter(LiveCharacter&&) noexcept;
  LiveCharacter(const LiveCharacter&) = delete;
  LiveCharacter& operator=(const LiveCharacter&) = delete;

  /// A stimulus at the current clock: `stimulus` is an action node of the map (or, with `weights`,
  /// a world stimulus the map may lack: emotion name → weight in [0, 1], copied per §6.1). Throws
  /// InvalidInput for an unknown stimulus that cannot be copied or bad weights (nothing changes).
  void push_stimulus(const std::string& stimulus,
                     const std::vector<std::pair<std::string, double>>& weights = {});
  /// Advances the clock by dt seconds (finite, [0, 3600]): mood decay, due actions, and every
  /// motion frame due (graph frame rate).
  void update(double dt);

  double time() const noexcept;
  const std::vector<double>& mood() const;  ///< one value per emotion node of the map
  const mindmap::MindMap& map() const;
  /// Actions triggered so far (stimulus, chain, decay), in time order.
  const std::vector<mindmap::TriggeredAction>& actions() const noexcept;
  std::size_t dropped_hints() const noexcept;
  motiongraph::Label label() const noexcept;       ///< label of the motion playing
  const motiongraph::Pose& pose() const noexcept;  ///< the current frame (graph units)
  /// Face parameters of the current frame (muscles::parameter_names(), 42 values).
  const std::vector<double>& parameters();
  std::uint64_t frames() const noexcept;  ///< motion frames played

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace emoface::mindmotion
