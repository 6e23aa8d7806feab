#include "emoface/runtime/character.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "character_impl.hpp"
#include "emoface/channels/parameters.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/core/rng.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/facemesh/io.hpp"
#include "emoface/faceweights/names.hpp"
#include "emoface/faceweights/weight_set.hpp"
#include "emoface/fuzzyexpr/engine.hpp"
#include "emoface/fuzzyexpr/names.hpp"
#include "emoface/mindmap/simulation.hpp"
#include "emoface/mindmotion/live.hpp"
#include "emoface/motiongraph/weights.hpp"
#include "emoface/muscles/parameters.hpp"
#include "emoface/muscles/solver.hpp"
#include "emoface/parlee/emotion.hpp"
#include "emoface/runtime/streaming.hpp"
#include "json_util.hpp"

namespace emoface::runtime {

namespace ch = emoface::channels;
using detail::Json;

namespace {

constexpr double kHold = 1e7;  // s: a display is held until the next one takes over
constexpr std::uint64_t kBlinkStream = 1, kGazeStream = 2, kHeadStream = 3;

std::size_t param_index(const std::string& name) {
  const auto& names = ch::default_parameter_names();
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end())
    throw Error("runtime: parameter '" + name + "' missing from the parameter list");
  return static_cast<std::size_t>(it - names.begin());
}

std::vector<std::string> side_names() {
  std::vector<std::string> out;
  for (auto n : fuzzyexpr::side_parameter_names()) out.emplace_back(n);
  return out;
}

}  // namespace

std::string_view to_string(SourceKind kind) noexcept {
  switch (kind) {
    case SourceKind::Parlee:
      return "parlee";
    case SourceKind::MindMap:
      return "mindmap";
    case SourceKind::MindMotion:
      return "mindmotion";
    default:
      return "direct";
  }
}

SourceKind source_kind_from_string(std::string_view name) {
  if (name == "direct") return SourceKind::Direct;
  if (name == "parlee") return SourceKind::Parlee;
  if (name == "mindmap") return SourceKind::MindMap;
  if (name == "mindmotion") return SourceKind::MindMotion;
  throw InvalidInput("unknown emotion source '" + std::string(name) +
                     "' (direct, parlee, mindmap, mindmotion)");
}

void DisplayOptions::validate() const {
  if (!(onset > 0 && onset <= 5)) throw InvalidInput("display.onset must be in (0, 5] s");
  if (!(offset > 0 && offset <= 5)) throw InvalidInput("display.offset must be in (0, 5] s");
  if (!(tolerance >= 0 && tolerance < 1)) throw InvalidInput("display.tolerance must be in [0, 1)");
}

void MotionSourceOptions::validate() const {
  if (!graph)
    throw InvalidInput("mindmotion source: no motion graph (source.graph or source.graph_file)");
  if (!(hint_path_fraction > 0 && hint_path_fraction <= 1))
    throw InvalidInput("mindmotion source: source.hint_path_fraction must be in (0, 1]");
  const std::string what = "mindmotion source: source.graph" +
                           (graph_file.empty() ? "" : "_file \"" + graph_file + "\"");
  const std::size_t channels = graph->landmark_ids().size();
  // ids: ARKit channels (faceweights' "arkit" order) of a weight graph, iBUG ids of landmarks
  if (motiongraph::is_weight_space(graph->dimensions)) {
    if (channels == 0) throw InvalidInput(what + " is an empty weight-space graph");
    for (int id : graph->landmark_ids())
      if (id < 0 || id >= 52)
        throw InvalidInput(what + " has weight channel " + std::to_string(id) +
                           ": the runtime takes ARKit-52 weight graphs (channels 0-51)");
  } else {
    if (graph->dimensions != 2)
      throw InvalidInput(what + " is a " + std::to_string(graph->dimensions) +
                         "D landmark graph; the runtime takes 2D iBUG-68 landmark graphs");
    for (int id : graph->landmark_ids())
      if (id < 0 || id >= 68)
        throw InvalidInput(what + " has landmark id " + std::to_string(id) +
                           ", not an iBUG-68 id (0-67)");
  }
}

void CharacterOptions::validate() const {
  if (!(fps >= 10 && fps <= 1000)) throw InvalidInput("fps must be in [10, 1000]");
  if (!(lookahead >= 0 && lookahead <= 0.3)) throw InvalidInput("lookahead must be in [0, 0.3] s");
  display.validate();
  blink.validate();
  gaze.validate();
  head.validate();
  if (!(chunk_seconds >= 1 && chunk_seconds <= 600))
    throw InvalidInput("chunk_seconds must be in [1, 600]");
  mix.validate();
  coarticulation.validate();
  if (!(silence_pad > 0 && silence_pad <= 2)) throw InvalidInput("silence_pad must be in (0, 2] s");
  speech.validate();
  if (!(step_seconds > 0 && step_seconds <= 3600))
    throw InvalidInput("step_seconds must be in (0, 3600]");
  if (!(direct_decay_per_second > 0 && direct_decay_per_second <= 1))
    throw InvalidInput("direct_decay_per_second must be in (0, 1]");
}

void CharacterConfig::validate() const {
  options.validate();
  if (source == SourceKind::Parlee) {
    agent.validate();
    if (domain_text.empty()) throw InvalidInput("parlee source: empty domain");
  }
  if (source == SourceKind::MindMap || source == SourceKind::MindMotion) mindmap::validate(map);
  if (source == SourceKind::MindMotion) motion.validate();
}

// ------------------------------------------------------------------------------------ state

Character::Impl::Impl(CharacterConfig c) : config(std::move(c)) {
  config.validate();
  const CharacterOptions& o = config.options;
  lookahead = static_cast<std::size_t>(std::ceil(o.lookahead * o.fps - 1e-9));
  if (config.source == SourceKind::Parlee) {
    parlee::DomainSpec spec;
    parlee::parse_domain_text(config.domain_text, "<domain>", spec);
    domain = std::make_unique<parlee::Domain>(std::move(spec));
    // one decay implementation (parlee::decayed, §5.6.3 per second): the agent's events are timed
    // in thesis steps of options.step_seconds (as in snapshots' logs), decayed by that time
    config.agent.decay_clock = parlee::DecayClock::Time;
    config.agent.time_unit_seconds = o.step_seconds;
    config.agent.emotions.step_seconds = o.step_seconds;
    make_agent();
    occ_last = agent->emotions();
    phi = parlee::decay_multipliers(config.agent.emotions, config.agent.personality);
  } else if (config.source == SourceKind::MindMap) {
    world = std::make_unique<mindmap::World>(std::vector<mindmap::MindMap>{config.map});
  }
  if (config.source == SourceKind::MindMap || config.source == SourceKind::MindMotion)
    for (std::size_t k = 0; k < 6; ++k)
      mood_node[k] = config.map.find_emotion(parlee::kBasicEmotionNames[k]);
  emotion = StreamingChannel(side_names());
  blinks = StreamingChannel({"eye_blink_l", "eye_blink_r"});
  gaze = StreamingChannel({"eye_gaze_yaw", "eye_gaze_pitch"});
  head = StreamingChannel({"head_yaw", "head_pitch", "head_roll"});
  visemes.validate();
  lip_params = visemes.parameters();
  std::array<std::vector<std::size_t>, ch::kChannelCount> cp;
  const auto indices = [](const std::vector<std::string>& names) {
    std::vector<std::size_t> out;
    for (const auto& n : names) out.push_back(param_index(n));
    return out;
  };
  cp[static_cast<std::size_t>(ch::Channel::Manipulator)] = indices(blinks.parameters());
  cp[static_cast<std::size_t>(ch::Channel::Lip)] = indices(lip_params);
  cp[static_cast<std::size_t>(ch::Channel::EmotionDisplay)] = indices(emotion.parameters());
  cp[static_cast<std::size_t>(ch::Channel::Gaze)] = indices(gaze.parameters());
  cp[static_cast<std::size_t>(ch::Channel::Head)] = indices(head.parameters());
  for (std::size_t k = 0; k < ch::kChannelCount; ++k) raw[k].assign(cp[k].size(), 0.0);
  mixer = StreamingMixer(ch::default_parameter_names(), cp, ch::default_conflict_table(), o.mix,
                         o.fps, lookahead);
  esv_ring.assign(lookahead + 1, std::array<double, 6>{});
  params_out.assign(ch::default_parameter_names().size(), 0.0);
  if (!config.face.empty()) {
    facemesh::Face face = config.face == "default"   ? facemesh::make_default_face()
                          : config.face == "generic" ? facemesh::make_generic_face()
                                                     : facemesh::load_face(config.face);
    solver = std::make_unique<muscles::FaceSolver>(std::move(face.mesh), std::move(face.rig));
  }
  if (config.source == SourceKind::MindMotion) make_live();
}

// The live character of the MindMotion source: seeded by options.seed; a landmark graph is fitted
// on the character's face (the default face without one). Its 42 parameters feed the emotion
// channel's 35 (by name); blinks, gaze and head stay with their own channels.
void Character::Impl::make_live() {
  const MotionSourceOptions& s = config.motion;
  mindmotion::LiveCharacterOptions o = mindmotion::live_character_options();
  o.seed = config.options.seed;
  o.hint_path_fraction = s.hint_path_fraction;
  if (!s.variation) {
    o.player.synthesis.vary_duration = false;
    o.player.synthesis.replace_probability = 0.0;
    o.player.synthesis.vary_peak = false;
  }
  if (!motiongraph::is_weight_space(s.graph->dimensions)) {
    if (!solver) {
      facemesh::Face face = facemesh::make_default_face();
      fit_solver = std::make_unique<muscles::FaceSolver>(std::move(face.mesh), std::move(face.rig));
    }
    fitter = std::make_unique<bridge::LandmarkFitter>(solver ? *solver : *fit_solver);
  }
  try {
    live = std::make_unique<mindmotion::LiveCharacter>(*s.graph, config.map, o, fitter.get());
  } catch (const InvalidInput& e) {
    throw InvalidInput(std::string("mindmotion source (source.graph") +
                       (s.graph_file.empty() ? "" : "_file \"" + s.graph_file + "\"") +
                       ", source.map): " + e.what());
  }
  const auto& names = muscles::parameter_names();
  for (const std::string& p : emotion.parameters()) {
    const auto it = std::find(names.begin(), names.end(), p);
    if (it == names.end()) throw Error("runtime: parameter '" + p + "' missing from the muscles");
    live_cols.push_back(static_cast<std::size_t>(it - names.begin()));
  }
  live_prev.assign(live_cols.size(), 0.0);
  live_cur.assign(live_cols.size(), 0.0);
}

// Plays the live character's frames due up to time t (never backwards).
void Character::Impl::advance_live(double t) {
  if (t > live->time()) live->update(t - live->time());
}

void Character::Impl::make_agent() {
  agent = std::make_unique<parlee::Agent>(*domain, config.agent);
}

std::array<double, 6> Character::Impl::esv_at(double t) {
  std::array<double, 6> e{};
  switch (config.source) {
    case SourceKind::Direct: {
      const double d = config.options.direct_decay_per_second;
      const double f = d == 1.0 ? 1.0 : std::pow(d, t - direct_time);
      for (std::size_t k = 0; k < 6; ++k) e[k] = direct[k] * f;
      break;
    }
    case SourceKind::Parlee: {
      const parlee::EmotionVector occ =
          parlee::decayed(occ_last, config.agent.emotions, phi, std::max(0.0, t - t_last));
      e = parlee::basic_emotions(occ, config.agent.emotions);
      break;
    }
    case SourceKind::MindMap:
    case SourceKind::MindMotion: {
      if (world && t > world->time()) world->advance_to(t, nullptr);
      const auto& mood = world ? world->mood(0) : live->mood();
      for (std::size_t k = 0; k < 6; ++k)
        e[k] = mood_node[k] ? std::clamp(mood[*mood_node[k]], 0.0, 1.0) : 0.0;
      break;
    }
  }
  return e;
}

// Blinks and gaze/head noise, one chunk of chunk_seconds at a time, each from its own seeded stream
// (seed, 4·chunk + kind): the same seed gives the same movements however update() is called.
void Character::Impl::generate_chunks(double t) {
  const CharacterOptions& o = config.options;
  while (static_cast<double>(chunks) * o.chunk_seconds <= t + o.chunk_seconds) {
    const double begin = static_cast<double>(chunks) * o.chunk_seconds;
    const double end = begin + o.chunk_seconds;
    const auto add = [](StreamingChannel& c, const std::vector<ch::Movement>& ms) {
      for (const auto& m : ms)
        if (m.timing.start > c.last_start() && m.timing.end > c.last_end()) c.append(m);
    };
    if (o.blinks) {
      core::Rng rng(o.seed, 4 * chunks + kBlinkStream);
      add(blinks, ch::generate_blinks(begin, end, o.blink, rng));
    }
    if (o.gaze_noise) {
      core::Rng rng(o.seed, 4 * chunks + kGazeStream);
      add(gaze, ch::generate_noise(begin, end, gaze.parameters(), o.gaze, rng, "gaze noise"));
    }
    if (o.head_noise) {
      core::Rng rng(o.seed, 4 * chunks + kHeadStream);
      add(head, ch::generate_noise(begin, end, head.parameters(), o.head, rng, "head noise"));
    }
    ++chunks;
  }
}

void Character::Impl::build_utt(Utt& u) const {
  u.co = std::make_unique<ch::Coarticulation>(visemes, u.segs, config.options.coarticulation);
  u.col.assign(lip_params.size(), -1);
  for (std::size_t i = 0; i < lip_params.size(); ++i)
    u.col[i] = u.co->parameter_index(lip_params[i]);
}

void Character::Impl::raw_frame() {
  const std::size_t n = mixer.frames_in();
  const double t = static_cast<double>(n) / config.options.fps;
  generate_chunks(t);
  const bool motion = config.source == SourceKind::MindMotion;
  if (motion) advance_live(t);
  const std::array<double, 6> esv = esv_at(t);
  // emotion display (channel 4): a new held display when the felt ESV moved past the tolerance
  double moved =
      shown_any ? 0.0
                : (std::any_of(esv.begin(), esv.end(), [](double v) { return v > 0; }) ? 1.0 : 0.0);
  for (std::size_t k = 0; k < 6 && shown_any; ++k)
    moved = std::max(moved, std::abs(esv[k] - shown[k]));
  if (!motion && moved > config.options.display.tolerance && t > emotion.last_start()) {
    fuzzyexpr::Esv in{};
    for (std::size_t k = 0; k < 6; ++k) in[k] = esv[k];
    const auto sides = fuzzyexpr::expand_to_sides(engine.convert(in));
    ch::Movement m;
    for (std::size_t i = 0; i < sides.size(); ++i)
      m.targets.push_back({emotion.parameters()[i], sides[i]});
    m.timing =
        ch::Timing{t, t + kHold, config.options.display.onset, config.options.display.offset};
    m.label = "display";
    emotion.append(m);
    shown = esv;
    shown_any = true;
  }
  using C = ch::Channel;
  blinks.sample(t, raw[static_cast<std::size_t>(C::Manipulator)].data());
  auto& display = raw[static_cast<std::size_t>(C::EmotionDisplay)];
  if (motion) {
    // The synthesized motion is the emotion display, interpolated between the graph's last two
    // frames (one graph frame, 1/30 s, later than the graph: without it a 60 fps character would
    // hold each 30 fps pose for two frames and take the whole step at once).
    const std::uint64_t frames = live->frames();
    if (frames != live_frame) {
      const std::vector<double>& p = live->parameters();
      live_prev = live_cur;
      for (std::size_t i = 0; i < live_cur.size(); ++i) live_cur[i] = p[live_cols[i]];
      if (live_frame == 0) live_prev = live_cur;
      live_frame = frames;
    }
    const double fg = config.motion.graph->frame_rate;
    const double u =  // 0 before the first graph frame (live_prev = live_cur = 0 then)
        frames == 0 ? 0.0 : std::clamp((t - static_cast<double>(frames - 1) / fg) * fg, 0.0, 1.0);
    for (std::size_t i = 0; i < display.size(); ++i)
      display[i] = live_prev[i] + u * (live_cur[i] - live_prev[i]);
  } else {
    emotion.sample(t, display.data());
  }
  gaze.sample(t, raw[static_cast<std::size_t>(C::Gaze)].data());
  head.sample(t, raw[static_cast<std::size_t>(C::Head)].data());
  auto& lip = raw[static_cast<std::size_t>(C::Lip)];
  std::fill(lip.begin(), lip.end(), 0.0);
  while (!utts.empty() && utts.front().end < t) utts.erase(utts.begin());
  for (const Utt& u : utts) {
    if (t < u.start || t > u.end) continue;
    for (std::size_t i = 0; i < lip.size(); ++i)
      if (u.col[i] >= 0) lip[i] = u.co->value(static_cast<std::size_t>(u.col[i]), t);
    break;
  }
  for (StreamingChannel* c : {&blinks, &emotion, &gaze, &head}) c->prune(t);
  std::array<const double*, ch::kChannelCount> ptr{};
  for (std::size_t k = 0; k < ch::kChannelCount; ++k) ptr[k] = raw[k].data();
  esv_ring[n % (lookahead + 1)] = esv;
  mixer.push(ptr);
  if (mixer.frames_out() > 0) {
    params_out = mixer.output();
    esv_out = esv_ring[(mixer.frames_out() - 1) % (lookahead + 1)];
  }
}

EventResult Character::Impl::emotions_event(const std::array<double, 6>& e,
                                            const std::array<bool, 6>& given, bool replace) {
  if (config.source != SourceKind::Direct)
    return {false, "emotion input needs a character with the direct source (this one is " +
                       std::string(to_string(config.source)) + ")"};
  for (std::size_t k = 0; k < 6; ++k)
    if (given[k] && !(e[k] >= 0 && e[k] <= 1))
      return {false,
              "emotion '" + std::string(parlee::kBasicEmotionNames[k]) + "' must be in [0, 1]"};
  const std::array<double, 6> now = esv_at(time);
  for (std::size_t k = 0; k < 6; ++k) direct[k] = given[k] ? e[k] : (replace ? 0.0 : now[k]);
  direct_time = time;
  return {true, ""};
}

EventResult Character::Impl::parlee_event(parlee::Event e, bool log) {
  if (config.source != SourceKind::Parlee)
    return {false, "a ParleE event needs a character with the parlee source (this one is " +
                       std::string(to_string(config.source)) + ")"};
  e.time = time / config.options.step_seconds;
  parlee::StepRecord rec;
  std::string refused;
  try {
    rec = agent->step(e);
    refused = rec.skipped;  // an agent with on_disallowed = skip reports instead of throwing
  } catch (const std::exception& ex) {
    refused = ex.what();
  }
  if (!refused.empty()) {
    // the agent may have taken its own turn before refusing: rebuild it from the event log, so a
    // refused event leaves the character exactly as if it had never been pushed
    make_agent();
    for (const auto& past : parlee_log) agent->step(past);
    return {false, "event skipped: " + refused};
  }
  if (log) parlee_log.push_back(e);
  occ_last = agent->emotions();  // decayed by the agent over the time since its last event
  t_last = time;
  return {true, ""};
}

EventResult Character::Impl::mind_event(mindmap::Event e, bool log) {
  if (config.source == SourceKind::MindMotion) {
    if (!e.target.empty() && e.target != config.map.character)
      return {false, "stimulus skipped: the target '" + e.target + "' is not this character ('" +
                         config.map.character + "')"};
    e.time = time;
    e.target = config.map.character;
    try {
      advance_live(time);  // the stimulus acts at the input clock
      live->push_stimulus(e.stimulus, e.weights);
    } catch (const std::exception& ex) {
      return {false, std::string("stimulus skipped: ") + ex.what()};  // the mood is unchanged
    }
    if (log) mind_log.push_back(e);
    return {true, ""};
  }
  if (config.source != SourceKind::MindMap)
    return {false,
            "a mind-map stimulus needs a character with the mindmap or mindmotion source "
            "(this one is " +
                std::string(to_string(config.source)) + ")"};
  e.time = std::max(time, world->time());
  if (e.target.empty()) e.target = config.map.character;
  try {
    world->apply(e, nullptr);
  } catch (const std::exception& ex) {
    return {false,
            std::string("stimulus skipped: ") + ex.what()};  // World::apply leaves it unchanged
  }
  if (log) mind_log.push_back(e);
  return {true, ""};
}

// ------------------------------------------------------------------------------------ Character

Character::Character(CharacterConfig config) : impl_(std::make_unique<Impl>(std::move(config))) {}
Character::Character(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Character::~Character() = default;
Character::Character(Character&&) noexcept = default;
Character& Character::operator=(Character&&) noexcept = default;

EventResult Character::push_emotions(const std::array<double, 6>& esv, bool replace) {
  std::array<bool, 6> given;
  given.fill(true);
  return impl_->emotions_event(esv, given, replace);
}

EventResult Character::push_parlee_event(const parlee::Event& event) {
  return impl_->parlee_event(event, true);
}
EventResult Character::push_stimulus(const mindmap::Event& event) {
  return impl_->mind_event(event, true);
}

EventResult Character::push_event(std::string_view text) {
  Json doc;
  try {
    doc = Json::parse(text.begin(), text.end());
  } catch (const std::exception& e) {
    return {false, std::string("event is not valid JSON: ") + e.what()};
  }
  if (!doc.is_object()) return {false, "event must be a JSON object"};
  try {
    if (doc.contains("emotions")) {
      const Json& em = doc["emotions"];
      if (!em.is_object()) return {false, "\"emotions\" must be an object of name: intensity"};
      std::array<double, 6> e{};
      std::array<bool, 6> given{};
      for (auto it = em.begin(); it != em.end(); ++it) {
        const auto pos = std::find(parlee::kBasicEmotionNames.begin(),
                                   parlee::kBasicEmotionNames.end(), it.key());
        if (pos == parlee::kBasicEmotionNames.end())
          return {false, "unknown emotion '" + it.key() +
                             "' (sadness happiness anger fear disgust surprise)"};
        if (!it.value().is_number()) return {false, "emotion '" + it.key() + "' must be a number"};
        const auto k = static_cast<std::size_t>(pos - parlee::kBasicEmotionNames.begin());
        e[k] = it.value().get<double>();
        given[k] = true;
      }
      for (auto it = doc.begin(); it != doc.end(); ++it)
        if (it.key() != "emotions" && it.key() != "replace")
          return {false, "unknown field '" + it.key() + "'"};
      const bool replace =
          doc.contains("replace") && doc["replace"].is_boolean() && doc["replace"].get<bool>();
      return impl_->emotions_event(e, given, replace);
    }
    if (doc.contains("action")) {
      parlee::Event e;
      for (auto it = doc.begin(); it != doc.end(); ++it) {
        const std::string& k = it.key();
        if (k == "action" || k == "outcome" || k == "note") {
          if (!it.value().is_string()) return {false, "\"" + k + "\" must be a string"};
        } else if (k == "feedback") {
          if (!it.value().is_number()) return {false, "\"feedback\" must be a number in [-1, 1]"};
        } else {
          return {false, "unknown field '" + k + "' of a ParleE event"};
        }
      }
      e.action = doc["action"].get<std::string>();
      if (doc.contains("outcome")) e.outcome = doc["outcome"].get<std::string>();
      if (doc.contains("note")) e.note = doc["note"].get<std::string>();
      if (doc.contains("feedback")) e.feedback = doc["feedback"].get<double>();
      return impl_->parlee_event(std::move(e), true);
    }
    if (doc.contains("stimulus")) {
      mindmap::Event e;
      for (auto it = doc.begin(); it != doc.end(); ++it) {
        const std::string& k = it.key();
        if (k == "stimulus" || k == "source" || k == "target") {
          if (!it.value().is_string()) return {false, "\"" + k + "\" must be a string"};
        } else if (k == "weights") {
          if (!it.value().is_object())
            return {false, "\"weights\" must be an object of emotion: weight"};
          for (auto w = it.value().begin(); w != it.value().end(); ++w) {
            if (!w.value().is_number())
              return {false, "weight of '" + w.key() + "' must be a number"};
            e.weights.emplace_back(w.key(), w.value().get<double>());
          }
        } else {
          return {false, "unknown field '" + k + "' of a mind-map stimulus"};
        }
      }
      e.stimulus = doc["stimulus"].get<std::string>();
      if (doc.contains("source")) e.source = doc["source"].get<std::string>();
      if (doc.contains("target")) e.target = doc["target"].get<std::string>();
      return impl_->mind_event(std::move(e), true);
    }
  } catch (const std::exception& e) {
    return {false, std::string("event skipped: ") + e.what()};
  }
  return {false, "event has none of \"emotions\", \"action\", \"stimulus\""};
}

void Character::set_synthesizer(std::shared_ptr<const ch::SpeechSynthesizer> s) {
  impl_->synth = std::move(s);
}

double Character::speak(const ch::Utterance& u) {
  Impl& m = *impl_;
  if (u.phonemes.empty()) throw InvalidInput("speak: the utterance has no phonemes");
  const double pad = m.config.options.silence_pad;
  double start = m.time + pad;
  if (!m.utts.empty()) start = std::max(start, m.utts.back().end + pad);
  Impl::Utt utt;
  utt.start = start - pad;
  utt.segs.push_back({m.visemes.silence, start - pad, start, 0.0, "pad"});
  double prev = 0.0;
  for (const ch::PhonemeTiming& p : u.phonemes) {
    if (!(std::isfinite(p.start) && std::isfinite(p.end) && p.end > p.start &&
          p.start >= prev - 1e-9))
      throw InvalidInput("speak: phoneme timings must increase");
    utt.segs.push_back(
        {m.visemes.viseme_for_phoneme(p.phoneme), start + p.start, start + p.end, 0.0, p.phoneme});
    prev = p.end;
  }
  utt.end = start + prev + pad;
  utt.segs.push_back({m.visemes.silence, start + prev, utt.end, 0.0, "pad"});
  m.build_utt(utt);
  m.utts.push_back(std::move(utt));
  return start;
}

ch::Utterance Character::speak(std::string_view text, double* start) {
  if (!impl_->synth)
    impl_->synth = std::make_shared<ch::EspeakProgram>(impl_->config.options.speech);
  ch::Utterance u = impl_->synth->synthesize(text);
  const double s = speak(u);
  if (start) *start = s;
  return u;
}

void Character::update(double dt) {
  if (!(std::isfinite(dt) && dt >= 0 && dt <= 3600))
    throw InvalidInput("update: dt must be in [0, 3600] s");
  Impl& m = *impl_;
  m.time += dt;
  while (static_cast<double>(m.mixer.frames_in()) / m.config.options.fps <= m.time + 1e-9)
    m.raw_frame();
}

double Character::input_time() const noexcept { return impl_->time; }
double Character::output_time() const noexcept {
  const std::size_t f = impl_->mixer.frames_out();
  return f == 0 ? 0.0 : static_cast<double>(f - 1) / impl_->config.options.fps;
}
double Character::latency() const noexcept {
  return static_cast<double>(impl_->lookahead) / impl_->config.options.fps;
}
const std::array<double, 6>& Character::emotions() const noexcept { return impl_->esv_out; }
const std::vector<double>& Character::parameters() const noexcept { return impl_->params_out; }
const std::vector<std::string>& Character::parameter_names() {
  return ch::default_parameter_names();
}
const CharacterConfig& Character::config() const noexcept { return impl_->config; }

std::vector<double> Character::occ_emotions() const {
  if (impl_->config.source != SourceKind::Parlee) return {};
  std::vector<double> out(parlee::kEmotionCount);
  const parlee::EmotionVector now =
      parlee::decayed(impl_->occ_last, impl_->config.agent.emotions, impl_->phi,
                      std::max(0.0, impl_->time - impl_->t_last));
  std::copy(now.begin(), now.end(), out.begin());
  return out;
}

namespace {
const std::vector<double>& mapped(std::unique_ptr<faceweights::Mapper>& mapper, const char* set,
                                  std::vector<double>& out, std::size_t& frame, std::size_t now,
                                  const std::vector<double>& params) {
  if (!mapper)
    mapper = std::make_unique<faceweights::Mapper>(faceweights::builtin_weight_set(set),
                                                   ch::default_parameter_names());
  if (frame != now || out.size() != mapper->target_count()) {
    out.resize(mapper->target_count());
    mapper->forward(params.data(), out.data());
    frame = now;
  }
  return out;
}
}  // namespace

const std::vector<double>& Character::arkit() {
  Impl& m = *impl_;
  return mapped(m.arkit, "arkit", m.arkit_out, m.arkit_frame, m.mixer.frames_out(), m.params_out);
}

const std::vector<double>& Character::facs() {
  Impl& m = *impl_;
  return mapped(m.facs, "facs", m.facs_out, m.facs_frame, m.mixer.frames_out(), m.params_out);
}

const std::vector<std::string>& Character::arkit_names() {
  static const std::vector<std::string> names =
      faceweights::builtin_weight_set("arkit").target_names();
  return names;
}

std::vector<std::string> Character::facs_names() {
  return faceweights::builtin_weight_set("facs").target_names();
}

bool Character::has_face() const noexcept { return impl_->solver != nullptr; }

const facemesh::Vertices& Character::vertices() {
  Impl& m = *impl_;
  if (!m.solver) throw InvalidInput("vertices: the character has no face (config \"face\")");
  if (m.deformed_frame != m.mixer.frames_out()) {
    m.solver->deform(m.params_out, m.deformation, m.workspace);
    m.deformed_frame = m.mixer.frames_out();
  }
  return m.deformation.vertices;
}

const facemesh::Mesh& Character::mesh() const {
  if (!impl_->solver) throw InvalidInput("mesh: the character has no face (config \"face\")");
  return impl_->solver->neutral();
}

}  // namespace emoface::runtime
