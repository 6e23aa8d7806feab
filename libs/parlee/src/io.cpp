#include "emoface/parlee/io.hpp"

#include <cmath>

#include "emoface/core/io.hpp"
#include "emoface/core/json_reader.hpp"
#include "emoface/core/text.hpp"

namespace emoface::parlee {
namespace {

using Json = nlohmann::ordered_json;
constexpr core::FormatVersion kAgentVersion{1, 1};  // 1.1: appraisal, display

using core::JsonValue;

// The unknown-field rule of docs/formats.md (core::JsonReader): a field this reader does not know
// is an error in a document of version 1.1 or older, and ignored in a newer minor.
void unknown_field(const JsonValue& v, const std::string& key) {
  if (v.reader().strict()) v.fail("unknown field \"" + key + "\"");
}

// A name → enum lookup whose InvalidInput becomes a FormatError at `v`.
template <class Parse>
auto named(const JsonValue& v, Parse parse) {
  const std::string name = v.string();
  try {
    return parse(name);
  } catch (const InvalidInput& e) {
    v.fail(e.what());
  }
}

void emotion_map(const JsonValue& j, EmotionVector& out, double lo, double hi) {
  for (const auto& [k, v] : j.members()) {
    Emotion e;
    try {
      e = emotion_from_string(k);
    } catch (const InvalidInput&) {
      v.fail("unknown emotion '" + k + "'");
    }
    out[index(e)] = v.number(lo, hi);
  }
}

Json emotion_json(const EmotionVector& v) {
  Json j = Json::object();
  for (std::size_t i = 0; i < kEmotionCount; ++i) j[std::string(to_string(static_cast<Emotion>(i)))] = v[i];
  return j;
}

}  // namespace

AgentConfig parse_agent(const std::string& text, const std::string& file) {
  const core::JsonReader reader(text, file, "parlee_agent", kAgentVersion);
  AgentConfig c;
  for (const auto& [key, v] : reader.root().expect_object().members()) {
    if (key == "format" || key == "version" || key == "generator") continue;
    if (key == "name")
      c.name = v.string();
    else if (key == "self")
      c.self = v.string();
    else if (key == "seed") {
      if (!v.json().is_number_unsigned()) v.fail("expected a non-negative integer");
      c.seed = v.json().get<std::uint64_t>();
    } else if (key == "personality") {
      for (const auto& [k, x] : v.members()) {
        Trait t;
        try {
          t = trait_from_string(k);
        } catch (const InvalidInput&) {
          x.fail("unknown personality dimension '" + k + "'");
        }
        c.personality[t] = x.number(0.0, 1.0);
      }
    } else if (key == "emotions") {
      for (const auto& [k, x] : v.members()) {
        if (k == "alpha")
          emotion_map(x, c.emotions.alpha, 0.0, 1e6);
        else if (k == "omega")
          emotion_map(x, c.emotions.omega, 1e-9, 1e6);
        else if (k == "decay")
          emotion_map(x, c.emotions.decay, 0.0, 1.0);
        else if (k == "decay_model")
          c.emotions.decay_model = named(x, decay_model_from_string);
        else if (k == "step_seconds")
          c.emotions.step_seconds = x.number(1e-9, 1e9);
        else if (k == "low_intensity_rate")
          c.emotions.low_intensity_rate = x.number(0.0, 1.0);
        else if (k == "effect") {
          c.emotions.effect = {};
          for (const JsonValue& e : x.items()) {
            e.expect_object();
            if (!e.has("from") || !e.has("to") || !e.has("value")) e.fail("needs from, to, value");
            Emotion from, to;
            try {
              from = emotion_from_string(e.at("from").string());
              to = emotion_from_string(e.at("to").string());
            } catch (const InvalidInput& err) {
              e.fail(err.what());
            }
            c.emotions.effect[index(from)][index(to)] = e.at("value").number(0.0, 1.0);
            e.only_keys({"from", "to", "value"});
          }
        } else
          unknown_field(x, k);
      }
      try {
        c.emotions.validate();
      } catch (const InvalidInput& e) {
        v.fail(e.what());
      }
    } else if (key == "motivation") {
      for (const auto& [k, x] : v.members()) {
        if (k == "hunger")
          c.motivation.hunger = x.number(0.0, 1.0);
        else if (k == "fatigue")
          c.motivation.fatigue = x.number(0.0, 1.0);
        else if (k == "thirst")
          c.motivation.thirst = x.number(0.0, 1.0);
        else if (k == "pain")
          c.motivation.pain = x.number(0.0, 1.0);
        else
          unknown_field(x, k);
      }
    } else if (key == "planning") {
      for (const auto& [k, x] : v.members()) {
        if (k == "horizon")
          c.planning.horizon = static_cast<int>(x.integer(0, 64));
        else if (k == "model_depth")
          c.planning.model_depth = static_cast<int>(x.integer(-1, 64));
        else if (k == "semantics")
          c.planning.semantics = named(x, goal_semantics_from_string);
        else
          unknown_field(x, k);
      }
    } else if (key == "replenishment") {
      for (const JsonValue& e : v.items()) {
        ReplenishmentGoal g;
        for (const auto& [k, x] : e.members()) {
          if (k == "goal")
            g.goal = x.string();
          else if (k == "threshold")
            g.threshold = x.number(1e-9, 1.0);
          else if (k == "need")
            g.need = named(x, need_from_string);
          else
            unknown_field(x, k);
        }
        if (g.goal.empty()) e.fail("needs a goal name");
        c.replenishment.push_back(g);
      }
    } else if (key == "decay_clock") {
      c.decay_clock = named(v, decay_clock_from_string);
    } else if (key == "time_unit_seconds") {
      c.time_unit_seconds = v.number(1e-9, 1e9);
    } else if (key == "on_disallowed") {
      c.on_disallowed = named(v, disallowed_event_from_string);
    } else if (key == "appraisal") {
      for (const auto& [k, x] : v.members()) {
        if (k == "prospect")
          c.appraisal.prospect = named(x, prospect_mode_from_string);
        else if (k == "compound")
          c.appraisal.compound = named(x, compound_rule_from_string);
        else if (k == "surprise_threshold")
          c.appraisal.surprise_threshold = x.number(1e-9, 1.0);
        else
          unknown_field(x, k);
      }
    } else if (key == "learning") {
      for (const auto& [k, x] : v.members()) {
        if (k == "outcomes")
          c.learn_outcomes = x.boolean();
        else if (k == "prior_count")
          c.learning_prior = x.number(0.0, 1e9);
        else if (k == "liking_rate")
          c.liking_rate = x.number(0.0, 1.0);
        else
          unknown_field(x, k);
      }
    } else if (key == "liking") {
      for (const auto& [k, x] : v.members()) c.liking[k] = x.number(-1.0, 1.0);
    } else if (key == "body_events") {
      for (const auto& [k, x] : v.members()) c.body_events[k] = named(x, body_event_from_string);
    } else if (key == "praiseworthiness") {
      for (const auto& [k, x] : v.members()) c.praiseworthiness[k] = x.number(-1.0, 1.0);
    } else {
      unknown_field(v, key);
    }
  }
  return c;
}

AgentConfig read_agent_file(const std::string& path) {
  return parse_agent(core::read_file(path, std::size_t{4} << 20), path);
}

std::string write_agent(const AgentConfig& c) {
  Json j = core::make_envelope("parlee_agent", kAgentVersion);
  j["name"] = c.name;
  j["self"] = c.self;
  j["seed"] = c.seed;
  Json p = Json::object();
  for (std::size_t i = 0; i < kTraitCount; ++i) p[std::string(to_string(static_cast<Trait>(i)))] = c.personality.values[i];
  j["personality"] = p;
  Json e = Json::object();
  e["alpha"] = emotion_json(c.emotions.alpha);
  e["omega"] = emotion_json(c.emotions.omega);
  e["decay"] = emotion_json(c.emotions.decay);
  e["decay_model"] = std::string(to_string(c.emotions.decay_model));
  e["step_seconds"] = c.emotions.step_seconds;
  e["low_intensity_rate"] = c.emotions.low_intensity_rate;
  Json m = Json::array();
  for (std::size_t a = 0; a < kEmotionCount; ++a)
    for (std::size_t b = 0; b < kEmotionCount; ++b)
      if (c.emotions.effect[a][b] != 0.0)
        m.push_back({{"from", std::string(to_string(static_cast<Emotion>(a)))},
                     {"to", std::string(to_string(static_cast<Emotion>(b)))},
                     {"value", c.emotions.effect[a][b]}});
  e["effect"] = m;
  j["emotions"] = e;
  j["motivation"] = {{"hunger", c.motivation.hunger}, {"fatigue", c.motivation.fatigue},
                     {"thirst", c.motivation.thirst}, {"pain", c.motivation.pain}};
  j["planning"] = {{"horizon", c.planning.horizon}, {"model_depth", c.planning.model_depth},
                   {"semantics", to_string(c.planning.semantics)}};
  j["on_disallowed"] = std::string(to_string(c.on_disallowed));
  j["decay_clock"] = std::string(to_string(c.decay_clock));
  j["time_unit_seconds"] = c.time_unit_seconds;
  Json rep = Json::array();
  for (const auto& g : c.replenishment)
    rep.push_back(
        {{"goal", g.goal}, {"need", std::string(to_string(g.need))}, {"threshold", g.threshold}});
  j["replenishment"] = rep;
  j["appraisal"] = {{"prospect", std::string(to_string(c.appraisal.prospect))},
                    {"compound", std::string(to_string(c.appraisal.compound))},
                    {"surprise_threshold", c.appraisal.surprise_threshold}};
  j["learning"] = {{"outcomes", c.learn_outcomes}, {"prior_count", c.learning_prior}, {"liking_rate", c.liking_rate}};
  Json l = Json::object();
  for (const auto& [k, v] : c.liking) l[k] = v;
  j["liking"] = l;
  Json pw = Json::object();
  for (const auto& [k, v] : c.praiseworthiness) pw[k] = v;
  j["praiseworthiness"] = pw;
  Json be = Json::object();
  for (const auto& [k, v] : c.body_events) be[k] = std::string(to_string(v));
  j["body_events"] = be;
  return j.dump(2) + "\n";
}

std::vector<Event> parse_events(const std::string& text, const std::string& file) {
  std::vector<Event> out;
  for (const core::Line& line : core::Lines(text)) {
    if (core::trim(line.text).empty()) continue;
    const std::size_t line_no = line.number;
    auto fail = [&](const std::string& msg) {
      throw FormatError(SourceLocation{file, "", line_no, 0}, msg);
    };
    Json j;
    try {
      j = Json::parse(line.text);
    } catch (const nlohmann::json::exception& e) {
      fail(std::string("malformed JSON: ") + e.what());
    }
    if (!j.is_object()) fail("expected a JSON object");
    Event ev;
    for (const auto& [k, v] : j.items()) {
      if (k == "time") {
        if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < 0 ||
            v.get<double>() > 1e9)
          fail("time must be a number in [0, 1e9]");
        ev.time = v.get<double>();
      } else if (k == "action" || k == "outcome" || k == "note") {
        if (!v.is_string()) fail(k + " must be a string");
        (k == "action" ? ev.action : k == "outcome" ? ev.outcome : ev.note) = v.get<std::string>();
      } else if (k == "feedback") {
        if (!v.is_number() || !(v.get<double>() >= -1.0 && v.get<double>() <= 1.0))
          fail("feedback must be in [-1,1]");
        ev.feedback = v.get<double>();
      } else {
        // Events carry no version: every field must be known (docs/formats.md).
        fail("unknown field \"" + k + "\"");
      }
    }
    if (!out.empty() && ev.time < out.back().time) fail("time decreases");
    out.push_back(std::move(ev));
  }
  return out;
}

std::vector<Event> read_events_file(const std::string& path) {
  return parse_events(core::read_file(path, std::size_t{64} << 20), path);
}

std::string write_events(const std::vector<Event>& events) {
  std::string out;
  for (const auto& e : events) {
    Json j = Json::object();
    j["time"] = e.time;
    j["action"] = e.action;
    if (!e.outcome.empty()) j["outcome"] = e.outcome;
    if (e.feedback) j["feedback"] = *e.feedback;
    if (!e.note.empty()) j["note"] = e.note;
    out += j.dump() + "\n";
  }
  return out;
}

std::string timeline_line(const StepRecord& r) {
  Json j = Json::object();
  j["step"] = r.step;
  j["time"] = r.time;
  if (!r.note.empty()) j["note"] = r.note;
  Json acts = Json::array();
  for (const auto& a : r.actions)
    acts.push_back({{"actor", a.actor}, {"action", a.action}, {"outcome", a.outcome}, {"p_event", a.p_event},
                    {"effects", a.effects}});
  j["events"] = acts;
  Json goals = Json::object();
  for (std::size_t k = 0; k < r.goal_names.size(); ++k) {
    goals[r.goal_names[k]] = {{"p", r.goal_probability[k]}, {"status", to_string(r.goal_status[k])}};
    if (k < r.goal_active.size() && !r.goal_active[k]) goals[r.goal_names[k]]["active"] = false;
  }
  j["goals"] = goals;
  j["emotions"] = emotion_json(r.emotions);
  j["impulse"] = emotion_json(r.impulse);
  Json esv = Json::object();
  for (std::size_t k = 0; k < 6; ++k) esv[std::string(kBasicEmotionNames[k])] = r.basic[k];
  j["esv"] = esv;
  Json shown = Json::object();
  for (std::size_t k = 0; k < 6; ++k) shown[std::string(kBasicEmotionNames[k])] = r.shown[k];
  j["shown"] = shown;
  Json l = Json::object();
  for (const auto& [k, v] : r.liking) l[k] = v;
  j["liking"] = l;
  j["state"] = r.state;
  if (!r.skipped.empty()) j["skipped"] = r.skipped;
  return j.dump() + "\n";
}

}  // namespace emoface::parlee
