#include "emoface/mindmotion/live.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "emoface/bridge/weight_space.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/mindmotion/behaviour.hpp"
#include "emoface/mindmotion/muscle_tracks.hpp"
#include "emoface/motiongraph/weights.hpp"
#include "emoface/muscles/parameters.hpp"

namespace emoface::mindmotion {

namespace mg = emoface::motiongraph;

void LiveCharacterOptions::validate() const {
  simulation.validate();
  player.validate();
  if (!(hint_path_fraction > 0.0 && hint_path_fraction <= 1.0))
    throw InvalidInput("live character: hint_path_fraction must be in (0, 1]");
}

LiveCharacterOptions live_character_options() {
  LiveCharacterOptions o;
  o.player.synthesis = varied_synthesis();
  return o;
}

struct LiveCharacter::Impl {
  const mg::MotionGraph& graph;
  const bridge::LandmarkFitter* fitter;
  LiveCharacterOptions options;
  mindmap::World world;
  mg::MotionPlayer player;
  double clock = 0.0;
  std::vector<mindmap::TriggeredAction> pending;  // triggered, not yet due (chains)
  std::vector<mindmap::TriggeredAction> done;
  std::size_t dropped = 0;
  std::vector<double> params;
  std::vector<double> side;  // landmark fit warm start
  std::uint64_t params_frame = std::numeric_limits<std::uint64_t>::max();
  Eigen::MatrixXd neutral_ibug;  // landmark graphs

  static mg::PlayerOptions player_options(const mg::MotionGraph& g, LiveCharacterOptions o) {
    mg::PlayerOptions p = o.player;
    if (mg::is_weight_space(g.dimensions)) {
      const mg::PlayerOptions w = mg::weight_player_options();
      p.synthesis.smoothing = w.synthesis.smoothing;
      p.idle.smoothing = w.idle.smoothing;
    }
    p.synthesis.seed = core::derive_seed(o.seed, 1);
    p.idle.seed = core::derive_seed(o.seed, 2);
    return p;
  }
  static mindmap::SimulationOptions sim_options(LiveCharacterOptions o) {
    o.simulation.seed = o.seed;
    return o.simulation;
  }

  Impl(const mg::MotionGraph& g, mindmap::MindMap map, LiveCharacterOptions o,
       const bridge::LandmarkFitter* f)
      : graph(g),
        fitter(f),
        options((o.validate(), o)),
        world({std::move(map)}, sim_options(o)),
        player(g, player_options(g, o)),
        params(muscles::kParameterCount, 0.0),
        side(muscles::kSideParameterCount, 0.0) {
    const std::vector<std::string> labels = graph_labels(graph);
    for (const auto& a : world.map(0).actions)
      if (a.performable && std::find(labels.begin(), labels.end(), a.label) == labels.end())
        throw InvalidInput("live character: action \"" + a.name + "\" has the label \"" + a.label +
                           "\" that the motion graph cannot synthesize");
    if (mg::is_weight_space(graph.dimensions)) {
      if (graph.landmark_ids().empty()) throw InvalidInput("live character: empty weight graph");
    } else {
      if (!fitter) throw InvalidInput("live character: a landmark graph needs a LandmarkFitter");
      neutral_ibug = graph_neutral_ibug68(graph);
    }
  }

  void play(const mindmap::TriggeredAction& a) {
    const mg::Label label = mg::label_from_string(a.label);
    switch (a.cause) {
      case mindmap::Cause::Stimulus:
        player.interrupt(label);
        break;
      case mindmap::Cause::Chain:
        player.queue(label);
        break;
      case mindmap::Cause::Decay:
        if (player.busy()) {
          ++dropped;
          return;
        }
        player.queue(label, options.hint_path_fraction);
        break;
    }
    done.push_back(a);
  }

  // Actions due at or before `t`, in time order (stable).
  void run_due(double t) {
    std::stable_sort(pending.begin(), pending.end(),
                     [](const auto& x, const auto& y) { return x.time < y.time; });
    std::size_t k = 0;
    while (k < pending.size() && pending[k].time <= t) play(pending[k++]);
    pending.erase(pending.begin(), pending.begin() + static_cast<std::ptrdiff_t>(k));
  }
};

LiveCharacter::LiveCharacter(const mg::MotionGraph& graph, mindmap::MindMap map,
                             LiveCharacterOptions options, const bridge::LandmarkFitter* fitter)
    : impl_((!mg::is_weight_space(graph.dimensions) && !fitter
                 ? throw InvalidInput("live character: a landmark graph needs a LandmarkFitter")
                 : 0,
             std::make_unique<Impl>(graph, std::move(map), std::move(options), fitter))) {}
LiveCharacter::~LiveCharacter() = default;
LiveCharacter::LiveCharacter(LiveCharacter&&) noexcept = default;

void LiveCharacter::push_stimulus(const std::string& stimulus,
                                  const std::vector<std::pair<std::string, double>>& weights) {
  mindmap::Event e;
  e.time = impl_->clock;
  e.target = impl_->world.map(0).character;
  e.stimulus = stimulus;
  e.weights = weights;
  std::vector<mindmap::TriggeredAction> out;
  impl_->world.apply(e, &out);  // throws with the world unchanged
  impl_->pending.insert(impl_->pending.end(), out.begin(), out.end());
  impl_->run_due(impl_->clock);
}

void LiveCharacter::update(double dt) {
  if (!(dt >= 0.0 && dt <= 3600.0)) throw InvalidInput("live character: dt must be in [0, 3600] s");
  Impl& m = *impl_;
  const double target = m.clock + dt;
  // Frames due up to the new clock; actions are applied at their own time between frames.
  const double fps = m.graph.frame_rate;
  while (true) {
    const double next_frame_time = static_cast<double>(m.player.frames_played()) / fps;
    if (next_frame_time > target) break;
    std::vector<mindmap::TriggeredAction> out;
    m.world.advance_to(std::max(m.world.time(), next_frame_time), &out);
    m.pending.insert(m.pending.end(), out.begin(), out.end());
    m.run_due(next_frame_time);
    m.player.next_frame();
  }
  std::vector<mindmap::TriggeredAction> out;
  m.world.advance_to(std::max(m.world.time(), target), &out);
  m.pending.insert(m.pending.end(), out.begin(), out.end());
  m.run_due(target);
  m.clock = target;
}

double LiveCharacter::time() const noexcept { return impl_->clock; }
const std::vector<double>& LiveCharacter::mood() const { return impl_->world.mood(0); }
const mindmap::MindMap& LiveCharacter::map() const { return impl_->world.map(0); }
const std::vector<mindmap::TriggeredAction>& LiveCharacter::actions() const noexcept {
  return impl_->done;
}
std::size_t LiveCharacter::dropped_hints() const noexcept { return impl_->dropped; }
mg::Label LiveCharacter::label() const noexcept { return impl_->player.label(); }
const mg::Pose& LiveCharacter::pose() const noexcept { return impl_->player.current(); }
std::uint64_t LiveCharacter::frames() const noexcept { return impl_->player.frames_played(); }

const std::vector<double>& LiveCharacter::parameters() {
  Impl& m = *impl_;
  if (m.params_frame == m.player.frames_played()) return m.params;
  if (mg::is_weight_space(m.graph.dimensions)) {
    // Exact: the ARKit mapping's inverse (warm started from the previous frame).
    const auto w = mg::weight_frames(m.graph, {m.player.current()}, 52);
    bridge::arkit_mapper().inverse(w[0], m.params);
  } else {
    CharacterMotion one;
    one.frame_rate = m.graph.frame_rate;
    one.frames = {m.player.current()};
    const auto targets = face_displacements(m.graph, one, m.fitter->neutral_landmarks());
    m.fitter->fit(targets[0], m.side);
    std::copy(m.side.begin(), m.side.end(), m.params.begin());
  }
  m.params_frame = m.player.frames_played();
  return m.params;
}

}  // namespace emoface::mindmotion
