#include "emoface/mindmap/mind_map.hpp"

#include <cmath>
#include <set>

#include "emoface/core/errors.hpp"

namespace emoface::mindmap {

std::string_view to_string(DecayCurve curve) {
  switch (curve) {
    case DecayCurve::Linear: return "linear";
    case DecayCurve::Quadratic: return "quadratic";
    case DecayCurve::Sigmoid: return "sigmoid";
  }
  return "linear";
}

std::optional<DecayCurve> decay_curve_from_string(std::string_view name) {
  if (name == "linear") return DecayCurve::Linear;
  if (name == "quadratic") return DecayCurve::Quadratic;
  if (name == "sigmoid") return DecayCurve::Sigmoid;
  return std::nullopt;
}

const std::vector<double>* Traits::affection_towards(std::string_view character) const {
  for (const auto& row : affection)
    if (row.first == character) return &row.second;
  return nullptr;
}

std::optional<std::size_t> MindMap::find_emotion(std::string_view name) const {
  for (std::size_t i = 0; i < emotions.size(); ++i)
    if (emotions[i] == name) return i;
  return std::nullopt;
}

std::optional<std::size_t> MindMap::find_action(std::string_view name) const {
  for (std::size_t i = 0; i < actions.size(); ++i)
    if (actions[i].name == name) return i;
  return std::nullopt;
}

namespace {

[[noreturn]] void fail(const MindMap& map, const std::string& message) {
  throw InvalidInput("mind map \"" + map.character + "\": " + message);
}

void check_unit(const MindMap& map, double v, const std::string& what) {
  if (!std::isfinite(v) || v < 0.0 || v > 1.0)
    fail(map, what + " must be a finite number in [0, 1]");
}

void check_array(const MindMap& map, const std::vector<double>& a, const std::string& what) {
  if (a.size() != map.emotions.size())
    fail(map, what + " has " + std::to_string(a.size()) + " entries; expected one per emotion node (" +
                  std::to_string(map.emotions.size()) + ")");
  for (std::size_t i = 0; i < a.size(); ++i) check_unit(map, a[i], what + "[" + map.emotions[i] + "]");
}

}  // namespace

void validate(const MindMap& map) {
  if (map.character.empty()) fail(map, "the character name is empty");
  if (map.emotions.empty()) fail(map, "at least one emotion node is required");
  std::set<std::string> names;
  for (const auto& e : map.emotions) {
    if (e.empty()) fail(map, "an emotion node has an empty name");
    if (!names.insert(e).second) fail(map, "duplicate node name \"" + e + "\"");
  }
  const std::size_t ne = map.emotions.size(), na = map.actions.size();
  for (const auto& a : map.actions) {
    if (a.name.empty()) fail(map, "an action node has an empty name");
    if (!names.insert(a.name).second) fail(map, "duplicate node name \"" + a.name + "\"");
    if (!a.receivable && !a.performable)
      fail(map, "action \"" + a.name + "\" is neither receivable nor performable");
    if (a.performable && a.label.empty())
      fail(map, "performing action \"" + a.name + "\" has no expression label");
  }
  std::set<std::pair<std::size_t, std::size_t>> seen;
  for (const auto& e : map.stimulus_edges) {
    if (e.action >= na || e.emotion >= ne) fail(map, "a stimulus edge refers to a missing node");
    if (!map.actions[e.action].receivable)
      fail(map, "stimulus edge from \"" + map.actions[e.action].name + "\", which is not receivable");
    if (!seen.insert({e.action, e.emotion}).second)
      fail(map, "duplicate stimulus edge " + map.actions[e.action].name + " -> " + map.emotions[e.emotion]);
    check_unit(map, e.weight, "weight of stimulus edge " + map.actions[e.action].name + " -> " +
                                  map.emotions[e.emotion]);
  }
  seen.clear();
  for (const auto& e : map.response_edges) {
    if (e.action >= na || e.emotion >= ne) fail(map, "a response edge refers to a missing node");
    if (!map.actions[e.action].performable)
      fail(map, "response edge to \"" + map.actions[e.action].name + "\", which is not performable");
    if (!seen.insert({e.emotion, e.action}).second)
      fail(map, "duplicate response edge " + map.emotions[e.emotion] + " -> " + map.actions[e.action].name);
    check_unit(map, e.weight, "weight of response edge " + map.emotions[e.emotion] + " -> " +
                                  map.actions[e.action].name);
  }
  seen.clear();
  for (const auto& e : map.chain_edges) {
    if (e.from >= na || e.to >= na) fail(map, "a chain edge refers to a missing action");
    if (!map.actions[e.from].performable || !map.actions[e.to].performable)
      fail(map, "chain edge " + map.actions[e.from].name + " -> " + map.actions[e.to].name +
                    " joins an action that is not performable");
    if (e.from == e.to) fail(map, "chain edge from \"" + map.actions[e.from].name + "\" to itself");
    if (!seen.insert({e.from, e.to}).second)
      fail(map, "duplicate chain edge " + map.actions[e.from].name + " -> " + map.actions[e.to].name);
  }
  if (!map.representative.empty()) {
    if (map.representative.size() != ne)
      fail(map, "representative actions: expected one entry per emotion node");
    for (std::size_t e = 0; e < ne; ++e) {
      const std::size_t a = map.representative[e];
      if (a == kNone) continue;
      if (a >= na) fail(map, "representative of \"" + map.emotions[e] + "\" is a missing action");
      if (!map.actions[a].performable)
        fail(map, "representative of \"" + map.emotions[e] + "\" (\"" + map.actions[a].name +
                      "\") is not performable");
    }
  }
  const Traits& t = map.traits;
  check_array(map, t.starting_mood, "starting_mood");
  check_array(map, t.personality, "personality");
  if (!t.background_context.empty()) check_array(map, t.background_context, "background_context");
  std::set<std::string> others;
  for (const auto& row : t.affection) {
    if (row.first.empty()) fail(map, "an affection row has an empty character name");
    if (!others.insert(row.first).second) fail(map, "duplicate affection row \"" + row.first + "\"");
    check_array(map, row.second, "affection[" + row.first + "]");
  }
  check_unit(map, t.lambda, "lambda");
  check_unit(map, t.alpha, "alpha");
  check_unit(map, t.beta, "beta");
  if (!std::isfinite(t.decay_duration) || t.decay_duration <= 0.0)
    fail(map, "decay duration must be a finite number of seconds > 0");
}

void validate_labels(const MindMap& map, const std::vector<std::string>& known) {
  for (const auto& a : map.actions) {
    if (!a.performable) continue;
    bool ok = false;
    for (const auto& k : known) ok = ok || k == a.label;
    if (!ok) {
      std::string list;
      for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
      fail(map, "action \"" + a.name + "\" has unknown expression label \"" + a.label +
                    "\" (known: " + list + ")");
    }
  }
}

std::string summary(const MindMap& map) {
  const std::size_t edges =
      map.stimulus_edges.size() + map.response_edges.size() + map.chain_edges.size();
  return map.character + ": " + std::to_string(map.emotion_count()) + " emotion nodes, " +
         std::to_string(map.actions.size()) + " actions, " + std::to_string(edges) + " edges";
}

}  // namespace emoface::mindmap
