#include "emoface/mindmap/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <queue>
#include <set>

#include "emoface/core/errors.hpp"

namespace emoface::mindmap {

std::string_view to_string(Cause cause) {
  switch (cause) {
    case Cause::Stimulus: return "stimulus";
    case Cause::Chain: return "chain";
    case Cause::Decay: return "decay";
  }
  return "stimulus";
}

std::optional<Cause> cause_from_string(std::string_view name) {
  if (name == "stimulus") return Cause::Stimulus;
  if (name == "chain") return Cause::Chain;
  if (name == "decay") return Cause::Decay;
  return std::nullopt;
}

void SimulationOptions::validate() const {
  auto bad = [](const char* what) { throw InvalidInput(std::string("SimulationOptions: ") + what); };
  if (!(tie_tolerance >= 0.0 && tie_tolerance <= 1.0)) bad("tie_tolerance must be in [0, 1]");
  if (!(chain_delay >= 0.0 && std::isfinite(chain_delay))) bad("chain_delay must be finite and >= 0");
  if (max_chain_length < 1) bad("max_chain_length must be >= 1");
  if (!(decay_interval > 0.0 && std::isfinite(decay_interval))) bad("decay_interval must be finite and > 0");
  if (!(sigmoid_steepness > 0.0 && sigmoid_steepness <= 200.0)) bad("sigmoid_steepness must be in (0, 200]");
  if (!(frame_rate > 0.0 && frame_rate <= 1000.0)) bad("frame_rate must be in (0, 1000]");
  if (!(duration >= 0.0 && duration <= 1e6)) bad("duration must be in [0, 1e6] seconds");
  if (propagation_depth > 64) bad("propagation_depth must be <= 64");
}

namespace {

// "event on line 7: " (or "event: " when the line is unknown), the prefix of every event error.
std::string event_prefix(const Event& event) {
  return event.line ? "event on line " + std::to_string(event.line) + ": " : "event: ";
}

}  // namespace

std::size_t top_emotion(const double* mood, std::size_t n) noexcept {
  std::size_t best = 0;
  for (std::size_t i = 1; i < n; ++i)
    if (mood[i] > mood[best]) best = i;
  return best;
}

// paper §6.1 step 3: "the performing action is selected, based on edge weight closest to the mood
// value (fuzziness is added for similar edge values)"
std::size_t choose_response(const MindMap& map, std::size_t emotion, double mood_value,
                            double tie_tolerance, core::Rng& rng) {
  double best = INFINITY;
  for (const auto& e : map.response_edges)
    if (e.emotion == emotion) best = std::min(best, std::fabs(e.weight - mood_value));
  if (!std::isfinite(best)) return kNone;
  // Allocation-free: count the candidates, draw one, find it.
  const double limit = best + tie_tolerance + 1e-12;
  std::size_t count = 0;
  for (const auto& e : map.response_edges)
    count += e.emotion == emotion && std::fabs(e.weight - mood_value) <= limit;
  std::size_t pick = count == 1 ? 0 : static_cast<std::size_t>(rng.uniform_int(count));
  for (const auto& e : map.response_edges)
    if (e.emotion == emotion && std::fabs(e.weight - mood_value) <= limit && pick-- == 0) return e.action;
  return kNone;  // unreachable
}

std::vector<std::size_t> chain_from(const MindMap& map, std::size_t first, std::size_t max_length) {
  std::vector<std::size_t> order;
  std::vector<char> seen(map.actions.size(), 0);
  std::vector<std::size_t> stack{first};
  while (!stack.empty() && order.size() < max_length) {
    const std::size_t a = stack.back();
    stack.pop_back();
    if (seen[a]) continue;  // cycle protection: every action at most once per chain
    seen[a] = 1;
    order.push_back(a);
    // Push successors in reverse so that they are visited in edge order.
    for (auto it = map.chain_edges.rbegin(); it != map.chain_edges.rend(); ++it)
      if (it->from == a && !seen[it->to]) stack.push_back(it->to);
  }
  return order;
}

World::World(std::vector<MindMap> maps, SimulationOptions options) : options_(options) {
  options_.validate();
  std::set<std::string> names;
  characters_.reserve(maps.size());
  for (std::size_t c = 0; c < maps.size(); ++c) {
    validate(maps[c]);
    if (!names.insert(maps[c].character).second)
      throw InvalidInput("duplicate character \"" + maps[c].character + "\"");
    Character ch{std::move(maps[c]), {}, {}, {}, {}, 0.0, 0.0, true, core::Rng(options_.seed, c)};
    const std::size_t n = ch.map.emotion_count();
    ch.mood = ch.map.traits.starting_mood;
    ch.start = ch.mood;
    ch.ptraits.resize(n);
    ch.scratch.resize(n);
    const Traits& t = ch.map.traits;
    personality_traits(t.personality.data(),
                       t.background_context.empty() ? nullptr : t.background_context.data(),
                       ch.ptraits.data(), n);
    // The starting mood decays like the mood after an update at t = 0 (docs/mindmap.md).
    ch.next_hint = options_.decay_interval;
    characters_.push_back(std::move(ch));
  }
}

std::optional<std::size_t> World::find(std::string_view character) const {
  for (std::size_t c = 0; c < characters_.size(); ++c)
    if (characters_[c].map.character == character) return c;
  return std::nullopt;
}

void World::decay(Character& ch, double t, std::vector<TriggeredAction>* out) {
  if (!ch.decaying) return;
  const Traits& tr = ch.map.traits;
  const std::size_t n = ch.map.emotion_count();
  const double end = ch.last_update + tr.decay_duration;
  // paper §6.1: "in certain intervals when the mood is decaying" the representative node of the
  // emotional node with the highest mood is triggered (no synthesis when there is none).
  while (ch.next_hint <= t && ch.next_hint < end) {
    decayed_mood(ch.start.data(), tr.personality.data(), ch.next_hint - ch.last_update,
                 tr.decay_duration, tr.decay_curve, options_.sigmoid_steepness, ch.scratch.data(), n);
    const std::size_t e = top_emotion(ch.scratch.data(), n);
    const std::size_t a = ch.map.representative_of(e);
    if (a != kNone && out)
      out->push_back({ch.next_hint, ch.map.character, ch.map.actions[a].name, ch.map.actions[a].label,
                      ch.map.emotions[e], ch.scratch[e], Cause::Decay, {}, 0, {}});
    ch.next_hint += options_.decay_interval;
  }
  if (t >= end) {
    ch.mood = tr.personality;
    ch.decaying = false;
  } else {
    decayed_mood(ch.start.data(), tr.personality.data(), t - ch.last_update, tr.decay_duration,
                 tr.decay_curve, options_.sigmoid_steepness, ch.mood.data(), n);
  }
}

void World::advance_to(double t, std::vector<TriggeredAction>* out) {
  if (!std::isfinite(t) || t < time_)
    throw InvalidInput("World::advance_to: time " + std::to_string(t) + " is before the clock (" +
                       std::to_string(time_) + ")");
  for (auto& ch : characters_) decay(ch, t, out);
  time_ = t;
}

// paper §6.1: "the character will copy the stimulus and respective emotional weights from the mind
// map of the stimulus source. For world stimuli ... the particular stimulus should contain the
// emotional node and edge weights to be copied."
World::CopyPlan World::plan_copy(std::size_t c, const Event& event) const {
  const MindMap& m = characters_[c].map;
  const std::string where = event_prefix(event);
  if (!options_.copy_unknown_stimuli)
    throw InvalidInput(where + "character \"" + m.character + "\" has no stimulus \"" + event.stimulus + "\"");
  if (m.find_emotion(event.stimulus))
    throw InvalidInput(where + "stimulus \"" + event.stimulus + "\" is an emotion node of \"" + m.character + "\"");
  CopyPlan plan;
  plan.from = "world";
  const MindMap* src = nullptr;
  std::optional<std::size_t> src_action;
  if (!event.source.empty()) {
    src = &characters_[*find(event.source)].map;
    src_action = src->find_action(event.stimulus);
    if (src_action && !src->actions[*src_action].receivable) src_action.reset();
  }
  if (src_action) {
    plan.from = src->character;
    for (const auto& e : src->stimulus_edges)
      if (e.action == *src_action)
        if (auto me = m.find_emotion(src->emotions[e.emotion])) plan.edges.emplace_back(*me, e.weight);
  } else if (!event.weights.empty()) {
    for (const auto& [name, w] : event.weights) {
      if (!std::isfinite(w) || w < 0.0 || w > 1.0)
        throw InvalidInput(where + "weight of \"" + name + "\" must be in [0, 1]");
      if (auto me = m.find_emotion(name)) plan.edges.emplace_back(*me, w);
    }
  } else {
    throw InvalidInput(where + "character \"" + m.character + "\" has no stimulus \"" + event.stimulus +
                       "\", and neither the source nor the event carries its weights");
  }
  return plan;
}

std::size_t World::learn(std::size_t c, const Event& event, const CopyPlan& plan) {
  MindMap& m = characters_[c].map;
  std::size_t a;
  if (auto existing = m.find_action(event.stimulus)) {
    a = *existing;  // a performing-only action becomes receivable
  } else {
    a = m.actions.size();
    m.actions.push_back({event.stimulus, true, false, {}});
  }
  m.actions[a].receivable = true;
  for (const auto& [e, w] : plan.edges) m.stimulus_edges.push_back({a, e, w});
  copied_.push_back({event.time, m.character, event.stimulus, plan.from, plan.edges.size()});
  return a;
}

void World::deliver(std::size_t c, const Event& event, const CopyPlan* plan,
                    std::vector<TriggeredAction>* out) {
  Character& ch = characters_[c];
  const std::size_t n = ch.map.emotion_count();
  std::optional<std::size_t> a = ch.map.find_action(event.stimulus);
  if (plan) a = learn(c, event, *plan);
  const Traits& tr = ch.map.traits;
  // paper §6.1 step 1: the stimulus' emotion weights (ActionEmot)
  std::fill(ch.scratch.begin(), ch.scratch.end(), 0.0);
  for (const auto& e : ch.map.stimulus_edges)
    if (e.action == *a) ch.scratch[e.emotion] = e.weight;
  // step 2: eqs. 2–4
  const std::vector<double>* affect = event.source.empty() ? nullptr : tr.affection_towards(event.source);
  perceived_stimulus(ch.scratch.data(), affect ? affect->data() : nullptr, tr.lambda, ch.scratch.data(), n);
  update_mood(ch.mood.data(), ch.scratch.data(), ch.ptraits.data(), tr.alpha, tr.beta,
              options_.mood_form, n);
  ch.start = ch.mood;
  ch.last_update = event.time;
  ch.next_hint = event.time + options_.decay_interval;
  ch.decaying = true;
  // step 3: the top emotion chooses a performing action; chains follow in order
  const std::size_t e = top_emotion(ch.mood.data(), n);
  const std::size_t first = choose_response(ch.map, e, ch.mood[e], options_.tie_tolerance, ch.rng);
  if (first == kNone || !out) return;
  const auto chain = chain_from(ch.map, first, options_.max_chain_length);
  for (std::size_t k = 0; k < chain.size(); ++k) {
    const ActionNode& act = ch.map.actions[chain[k]];
    out->push_back({event.time + static_cast<double>(k) * options_.chain_delay, ch.map.character,
                    act.name, act.label, ch.map.emotions[e], ch.mood[e],
                    k == 0 ? Cause::Stimulus : Cause::Chain, event.stimulus, k, event.source});
  }
}

namespace {
void check_unit_row(const std::vector<double>& v, std::size_t n, const std::string& what) {
  if (v.size() != n)
    throw InvalidInput(what + " has " + std::to_string(v.size()) + " values, expected one per emotion node (" +
                       std::to_string(n) + ")");
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i]) || v[i] < 0.0 || v[i] > 1.0)
      throw InvalidInput(what + " value " + std::to_string(i) + " must be in [0, 1]");
}
}  // namespace

void World::set_background_context(std::size_t c, const std::vector<double>& context) {
  Character& ch = characters_.at(c);
  const std::size_t n = ch.map.emotion_count();
  if (!context.empty()) check_unit_row(context, n, "background context of \"" + ch.map.character + "\"");
  Traits& t = ch.map.traits;
  t.background_context = context;
  personality_traits(t.personality.data(), t.background_context.empty() ? nullptr : t.background_context.data(),
                     ch.ptraits.data(), n);
}

void World::set_affection(std::size_t c, const std::string& other, const std::vector<double>& row) {
  Character& ch = characters_.at(c);
  const std::string what = "affection of \"" + ch.map.character + "\" towards \"" + other + "\"";
  if (other.empty()) throw InvalidInput("affection of \"" + ch.map.character + "\": empty character name");
  if (other == ch.map.character) throw InvalidInput(what + ": a character has no affection row for itself");
  if (!row.empty()) check_unit_row(row, ch.map.emotion_count(), what);
  auto& rows = ch.map.traits.affection;
  auto it = std::find_if(rows.begin(), rows.end(), [&](const auto& r) { return r.first == other; });
  if (row.empty()) {
    if (it != rows.end()) rows.erase(it);
  } else if (it != rows.end()) {
    it->second = row;
  } else {
    rows.emplace_back(other, row);
  }
}

void World::apply(const Event& event, std::vector<TriggeredAction>* out) {
  const std::string where = event_prefix(event);
  if (!std::isfinite(event.time) || event.time < time_)
    throw InvalidInput(where + "time must be finite and not before the previous event");
  if (event.changes_traits()) {  // runtime change of background context / affection (issue 19)
    std::vector<std::size_t> targets;
    for (std::size_t c = 0; c < characters_.size(); ++c)
      if (event.target == "*" || characters_[c].map.character == event.target) targets.push_back(c);
    if (targets.empty()) throw InvalidInput(where + "unknown target character \"" + event.target + "\"");
    // Check on copies first, so a bad change leaves the world as it was.
    for (std::size_t c : targets) {
      const std::size_t n = characters_[c].map.emotion_count();
      try {
        if (!event.context.empty()) check_unit_row(event.context, n, "background context");
        for (const auto& [other, row] : event.affection) {
          if (other.empty() || other == characters_[c].map.character)
            throw InvalidInput("affection towards \"" + other + "\": not another character");
          if (!row.empty()) check_unit_row(row, n, "affection towards \"" + other + "\"");
        }
      } catch (const InvalidInput& e) {
        throw InvalidInput(where + "character \"" + characters_[c].map.character + "\": " + e.what());
      }
    }
    advance_to(event.time, out);
    for (std::size_t c : targets) {
      if (!event.context.empty()) set_background_context(c, event.context);
      for (const auto& [other, row] : event.affection) set_affection(c, other, row);
    }
    return;
  }
  if (event.stimulus.empty()) throw InvalidInput(where + "empty stimulus name");
  if (!event.source.empty() && !find(event.source))
    throw InvalidInput(where + "unknown source character \"" + event.source + "\"");
  std::optional<std::size_t> target;
  if (event.target != "*") {
    target = find(event.target);
    if (!target) throw InvalidInput(where + "unknown target character \"" + event.target + "\"");
    if (event.target == event.source) throw InvalidInput(where + "a character cannot stimulate itself");
  }
  // Every target is checked (and its copy planned) before any state changes, so a bad event leaves
  // the world as it was.
  std::vector<std::size_t> targets;
  std::vector<std::optional<CopyPlan>> plans;
  for (std::size_t c = 0; c < characters_.size(); ++c) {
    if (target ? c != *target : characters_[c].map.character == event.source) continue;
    const MindMap& m = characters_[c].map;
    const auto a = m.find_action(event.stimulus);
    targets.push_back(c);
    plans.push_back(a && m.actions[*a].receivable ? std::nullopt : std::optional<CopyPlan>(plan_copy(c, event)));
  }
  advance_to(event.time, out);
  for (std::size_t k = 0; k < targets.size(); ++k)
    deliver(targets[k], event, plans[k] ? &*plans[k] : nullptr, out);
}

MindMap map_at(std::vector<MindMap> maps, std::vector<Event> events, std::size_t c, double time,
               const SimulationOptions& options) {
  World world(std::move(maps), options);
  if (c >= world.size()) throw InvalidInput("map_at: character index out of range");
  std::stable_sort(events.begin(), events.end(),
                   [](const Event& a, const Event& b) { return a.time < b.time; });
  for (const Event& e : events)
    if (e.time <= time) world.apply(e, nullptr);
  return world.map(c);
}

SimulationResult simulate(std::vector<MindMap> maps, std::vector<Event> events,
                          const SimulationOptions& options) {
  World world(std::move(maps), options);
  std::stable_sort(events.begin(), events.end(),
                   [](const Event& a, const Event& b) { return a.time < b.time; });
  SimulationResult r;
  double duration = options.duration;
  if (duration == 0.0) {
    double longest = 0.0;
    for (std::size_t c = 0; c < world.size(); ++c)
      longest = std::max(longest, world.map(c).traits.decay_duration);
    duration = (events.empty() ? 0.0 : events.back().time) + longest;
    duration = std::ceil(duration * options.frame_rate - 1e-9) / options.frame_rate;  // on the grid
  }
  r.duration = duration;
  for (std::size_t c = 0; c < world.size(); ++c) r.characters.push_back(world.map(c).character);
  r.mood.resize(world.size());
  const auto samples = static_cast<std::size_t>(std::floor(duration * options.frame_rate + 1e-9)) + 1;
  // Pending events in time order (ties: first queued first); propagated actions join the queue.
  struct Pending {
    double time;
    std::size_t seq, depth;
    Event event;
  };
  auto later = [](const Pending& a, const Pending& b) { return a.time != b.time ? a.time > b.time : a.seq > b.seq; };
  std::priority_queue<Pending, std::vector<Pending>, decltype(later)> queue(later);
  std::size_t seq = 0;
  for (auto& e : events) queue.push({e.time, seq++, 0, std::move(e)});
  std::vector<TriggeredAction> fresh;
  auto run_next = [&] {
    Pending p = queue.top();
    queue.pop();
    fresh.clear();
    world.apply(p.event, &fresh);
    for (const auto& a : fresh) {
      // §6.1 "as the characters interact": a performed action that is also a stimulus in the
      // performer's map reaches every other character, up to propagation_depth hops.
      if (p.depth < options.propagation_depth && a.cause != Cause::Decay) {
        const MindMap& m = world.map(*world.find(a.character));
        const auto ia = m.find_action(a.action);
        if (ia && m.actions[*ia].receivable) {
          // Addressed actions reach only their addressee (option; issue 19), others everyone.
          const bool at = options.propagate_to_addressee && !a.addressee.empty() && world.find(a.addressee);
          Event e{a.time, at ? a.addressee : "*", a.action, a.character, {}, p.event.line, {}, {}};
          queue.push({a.time, seq++, p.depth + 1, std::move(e)});
        }
      }
      r.actions.push_back(a);
    }
  };
  for (std::size_t k = 0; k < samples; ++k) {
    const double t = static_cast<double>(k) / options.frame_rate;
    while (!queue.empty() && queue.top().time <= t) run_next();
    world.advance_to(t, &r.actions);
    r.times.push_back(t);
    for (std::size_t c = 0; c < world.size(); ++c)
      r.mood[c].insert(r.mood[c].end(), world.mood(c).begin(), world.mood(c).end());
  }
  // Events after the timeline still count (their actions are reported).
  while (!queue.empty()) run_next();
  std::stable_sort(r.actions.begin(), r.actions.end(),
                   [](const TriggeredAction& a, const TriggeredAction& b) { return a.time < b.time; });
  r.copied = world.copied();
  return r;
}

}  // namespace emoface::mindmap
