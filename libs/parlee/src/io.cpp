#include "emoface/parlee/io.hpp"

#include <cmath>

#include "emoface/core/io.hpp"

namespace emoface::parlee {
namespace {

using Json = nlohmann::ordered_json;
constexpr core::FormatVersion kAgentVersion{1, 1};  // 1.1: appraisal, display

struct Reader {
  const std::string& file;
  [[noreturn]] void fail(const std::string& ptr, const std::string& msg) const {
    throw FormatError(SourceLocation{file, ptr, 0, 0}, msg);
  }
  double number(const Json& j, const std::string& ptr, double lo, double hi) const {
    if (!j.is_number()) fail(ptr, "expected a number");
    const double v = j.get<double>();
    if (!std::isfinite(v) || v < lo || v > hi)
      fail(ptr, "value must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return v;
  }
  int integer(const Json& j, const std::string& ptr, int lo, int hi) const {
    if (!j.is_number_integer()) fail(ptr, "expected an integer");
    const auto v = j.get<long long>();
    if (v < lo || v > hi) fail(ptr, "value must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return static_cast<int>(v);
  }
  std::string string(const Json& j, const std::string& ptr) const {
    if (!j.is_string()) fail(ptr, "expected a string");
    return j.get<std::string>();
  }
  bool boolean(const Json& j, const std::string& ptr) const {
    if (!j.is_boolean()) fail(ptr, "expected true or false");
    return j.get<bool>();
  }
  const Json& object(const Json& j, const std::string& ptr) const {
    if (!j.is_object()) fail(ptr, "expected an object");
    return j;
  }
};

std::string tok(const std::string& s) { return core::json_pointer_token(s); }

void emotion_map(const Reader& r, const Json& j, const std::string& ptr, EmotionVector& out, double lo, double hi) {
  for (const auto& [k, v] : r.object(j, ptr).items()) {
    Emotion e;
    try {
      e = emotion_from_string(k);
    } catch (const InvalidInput&) {
      r.fail(ptr + "/" + tok(k), "unknown emotion '" + k + "'");
    }
    out[index(e)] = r.number(v, ptr + "/" + tok(k), lo, hi);
  }
}

Json emotion_json(const EmotionVector& v) {
  Json j = Json::object();
  for (std::size_t i = 0; i < kEmotionCount; ++i) j[std::string(to_string(static_cast<Emotion>(i)))] = v[i];
  return j;
}

}  // namespace

AgentConfig parse_agent(const std::string& text, const std::string& file) {
  const Json doc = core::parse_json(text, file);
  core::check_envelope(doc, "parlee_agent", kAgentVersion, file);
  const Reader r{file};
  AgentConfig c;
  for (const auto& [key, v] : doc.items()) {
    const std::string ptr = "/" + tok(key);
    if (key == "format" || key == "version" || key == "generator") continue;
    if (key == "name") c.name = r.string(v, ptr);
    else if (key == "self") c.self = r.string(v, ptr);
    else if (key == "seed") {
      if (!v.is_number_unsigned()) r.fail(ptr, "expected a non-negative integer");
      c.seed = v.get<std::uint64_t>();
    } else if (key == "personality") {
      for (const auto& [k, x] : r.object(v, ptr).items()) {
        Trait t;
        try {
          t = trait_from_string(k);
        } catch (const InvalidInput&) {
          r.fail(ptr + "/" + tok(k), "unknown personality dimension '" + k + "'");
        }
        c.personality[t] = r.number(x, ptr + "/" + tok(k), 0.0, 1.0);
      }
    } else if (key == "emotions") {
      for (const auto& [k, x] : r.object(v, ptr).items()) {
        const std::string p = ptr + "/" + tok(k);
        if (k == "alpha") emotion_map(r, x, p, c.emotions.alpha, 0.0, 1e6);
        else if (k == "omega") emotion_map(r, x, p, c.emotions.omega, 1e-9, 1e6);
        else if (k == "decay") emotion_map(r, x, p, c.emotions.decay, 0.0, 1.0);
        else if (k == "decay_model") {
          try {
            c.emotions.decay_model = decay_model_from_string(r.string(x, p));
          } catch (const InvalidInput& e) {
            r.fail(p, e.what());
          }
        } else if (k == "step_seconds") {
          c.emotions.step_seconds = r.number(x, p, 1e-9, 1e9);
        } else if (k == "low_intensity_rate") {
          c.emotions.low_intensity_rate = r.number(x, p, 0.0, 1.0);
        } else if (k == "effect") {
          if (!x.is_array()) r.fail(p, "expected an array of {from, to, value}");
          c.emotions.effect = {};
          for (std::size_t n = 0; n < x.size(); ++n) {
            const std::string pe = p + "/" + std::to_string(n);
            const Json& e = r.object(x[n], pe);
            if (!e.contains("from") || !e.contains("to") || !e.contains("value")) r.fail(pe, "needs from, to, value");
            Emotion from, to;
            try {
              from = emotion_from_string(r.string(e["from"], pe + "/from"));
              to = emotion_from_string(r.string(e["to"], pe + "/to"));
            } catch (const InvalidInput& err) {
              r.fail(pe, err.what());
            }
            c.emotions.effect[index(from)][index(to)] = r.number(e["value"], pe + "/value", 0.0, 1.0);
          }
        } else {
          r.fail(p, "unknown field '" + k + "'");
        }
      }
      try {
        c.emotions.validate();
      } catch (const InvalidInput& e) {
        r.fail(ptr, e.what());
      }
    } else if (key == "motivation") {
      for (const auto& [k, x] : r.object(v, ptr).items()) {
        const std::string p = ptr + "/" + tok(k);
        const double val = r.number(x, p, 0.0, 1.0);
        if (k == "hunger") c.motivation.hunger = val;
        else if (k == "fatigue") c.motivation.fatigue = val;
        else if (k == "thirst") c.motivation.thirst = val;
        else if (k == "pain") c.motivation.pain = val;
        else r.fail(p, "unknown field '" + k + "'");
      }
    } else if (key == "planning") {
      for (const auto& [k, x] : r.object(v, ptr).items()) {
        const std::string p = ptr + "/" + tok(k);
        if (k == "horizon") c.planning.horizon = r.integer(x, p, 0, 64);
        else if (k == "model_depth") c.planning.model_depth = r.integer(x, p, -1, 64);
        else if (k == "semantics") {
          try {
            c.planning.semantics = goal_semantics_from_string(r.string(x, p));
          } catch (const InvalidInput& e) {
            r.fail(p, e.what());
          }
        } else r.fail(p, "unknown field '" + k + "'");
      }
    } else if (key == "replenishment") {
      if (!v.is_array()) r.fail(ptr, "expected an array of {goal, need, threshold}");
      for (std::size_t n = 0; n < v.size(); ++n) {
        const std::string pe = ptr + "/" + std::to_string(n);
        const Json& e = r.object(v[n], pe);
        ReplenishmentGoal g;
        for (const auto& [k, x] : e.items()) {
          const std::string p = pe + "/" + tok(k);
          if (k == "goal")
            g.goal = r.string(x, p);
          else if (k == "threshold")
            g.threshold = r.number(x, p, 1e-9, 1.0);
          else if (k == "need") {
            try {
              g.need = need_from_string(r.string(x, p));
            } catch (const InvalidInput& err) {
              r.fail(p, err.what());
            }
          } else
            r.fail(p, "unknown field '" + k + "'");
        }
        if (g.goal.empty()) r.fail(pe, "needs a goal name");
        c.replenishment.push_back(g);
      }
    } else if (key == "decay_clock") {
      try {
        c.decay_clock = decay_clock_from_string(r.string(v, ptr));
      } catch (const InvalidInput& e) {
        r.fail(ptr, e.what());
      }
    } else if (key == "time_unit_seconds") {
      c.time_unit_seconds = r.number(v, ptr, 1e-9, 1e9);
    } else if (key == "on_disallowed") {
      try {
        c.on_disallowed = disallowed_event_from_string(r.string(v, ptr));
      } catch (const InvalidInput& e) {
        r.fail(ptr, e.what());
      }
    } else if (key == "appraisal") {
      for (const auto& [k, x] : r.object(v, ptr).items()) {
        const std::string p = ptr + "/" + tok(k);
        if (k == "prospect") {
          try {
            c.appraisal.prospect = prospect_mode_from_string(r.string(x, p));
          } catch (const InvalidInput& e) {
            r.fail(p, e.what());
          }
        } else if (k == "compound") {
          try {
            c.appraisal.compound = compound_rule_from_string(r.string(x, p));
          } catch (const InvalidInput& e) {
            r.fail(p, e.what());
          }
        } else if (k == "surprise_threshold") {
          c.appraisal.surprise_threshold = r.number(x, p, 1e-9, 1.0);
        } else {
          r.fail(p, "unknown field '" + k + "'");
        }
      }
    } else if (key == "learning") {
      for (const auto& [k, x] : r.object(v, ptr).items()) {
        const std::string p = ptr + "/" + tok(k);
        if (k == "outcomes") c.learn_outcomes = r.boolean(x, p);
        else if (k == "prior_count") c.learning_prior = r.number(x, p, 0.0, 1e9);
        else if (k == "liking_rate") c.liking_rate = r.number(x, p, 0.0, 1.0);
        else r.fail(p, "unknown field '" + k + "'");
      }
    } else if (key == "liking") {
      for (const auto& [k, x] : r.object(v, ptr).items()) c.liking[k] = r.number(x, ptr + "/" + tok(k), -1.0, 1.0);
    } else if (key == "body_events") {
      for (const auto& [k, x] : r.object(v, ptr).items()) {
        try {
          c.body_events[k] = body_event_from_string(r.string(x, ptr + "/" + tok(k)));
        } catch (const InvalidInput& e) {
          r.fail(ptr + "/" + tok(k), e.what());
        }
      }
    } else if (key == "praiseworthiness") {
      for (const auto& [k, x] : r.object(v, ptr).items())
        c.praiseworthiness[k] = r.number(x, ptr + "/" + tok(k), -1.0, 1.0);
    } else {
      r.fail(ptr, "unknown field '" + key + "'");
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
  std::size_t line_no = 0, pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_no;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    auto fail = [&](const std::string& msg) { throw FormatError(SourceLocation{file, "", line_no, 0}, msg); };
    Json j;
    try {
      j = Json::parse(line);
    } catch (const nlohmann::json::exception& e) {
      fail(std::string("malformed JSON: ") + e.what());
    }
    if (!j.is_object()) fail("expected a JSON object");
    Event ev;
    for (const auto& [k, v] : j.items()) {
      if (k == "time") {
        if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < 0 || v.get<double>() > 1e9)
          fail("time must be a number in [0, 1e9]");
        ev.time = v.get<double>();
      } else if (k == "action" || k == "outcome" || k == "note") {
        if (!v.is_string()) fail(k + " must be a string");
        (k == "action" ? ev.action : k == "outcome" ? ev.outcome : ev.note) = v.get<std::string>();
      } else if (k == "feedback") {
        if (!v.is_number() || !(v.get<double>() >= -1.0 && v.get<double>() <= 1.0)) fail("feedback must be in [-1,1]");
        ev.feedback = v.get<double>();
      } else {
        fail("unknown field '" + k + "'");
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
