#include "emoface/mindmap/io.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <initializer_list>
#include <set>

#include "emoface/core/csv.hpp"
#include "emoface/core/io.hpp"
#include "emoface/core/json_reader.hpp"
#include "emoface/core/text.hpp"

namespace emoface::mindmap {
namespace {

using Json = nlohmann::ordered_json;
constexpr core::FormatVersion kVersion{1, 0};

using core::JsonValue;

// A non-empty string (names of characters, nodes, stimuli).
std::string name(const JsonValue& v) {
  std::string s = v.string();
  if (s.empty()) v.fail("expected a non-empty string");
  return s;
}

std::vector<double> unit_array(const JsonValue& j, std::size_t n) {
  j.expect_array();
  if (j.size() != n)
    j.fail("has " + std::to_string(j.size()) + " entries; expected one per emotion node (" +
           std::to_string(n) + ")");
  std::vector<double> out(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = j[i].number(0.0, 1.0);
  return out;
}

Json to_json_array(const std::vector<double>& v) {
  Json a = Json::array();
  for (double x : v) a.push_back(x);
  return a;
}

// Calls fn(record, line) for every non-blank NDJSON line that does not start with '#', each record
// read through core::JsonReader. The stream header ({"format": "emoface.<kind>", "version"}, the
// stream's version stamp) is skipped and sets the unknown-field rule: records of a stream of a
// newer minor version than `supported` may add fields (ignored); otherwise unknown fields are
// errors. Every error is a FormatError naming the line (and the JSON pointer, or the column of a
// syntax error).
template <class Fn>
void for_each_ndjson(std::string_view text, const std::string& file, std::string_view kind,
                     core::FormatVersion supported, Fn fn) {
  bool strict = true;
  for (const core::Line& line : core::Lines(text)) {
    const std::string_view body = core::trim(line.text);
    if (body.empty() || body[0] == '#') continue;
    try {
      Json j = core::parse_json(body, file);
      if (core::is_stream_header(j)) {
        if (j["format"] == "emoface." + std::string(kind)) {
          const core::JsonReader header(core::ParsedJson{std::move(j)}, file, kind, supported);
          strict = header.strict();
        }
        continue;
      }
      const core::JsonReader reader(core::ParsedJson{std::move(j)}, file, strict);
      fn(reader.root().expect_object(), line.number);
    } catch (const FormatError& e) {
      SourceLocation where = e.where();
      where.line = line.number;
      throw FormatError(where, e.message());
    }
  }
}

}  // namespace

MindMap parse_mind_map(std::string_view json_text, const std::string& file,
                       const std::vector<std::string>& known_labels) {
  const core::JsonReader reader(json_text, file, kMindMapKind, kVersion);
  const JsonValue doc = reader.root();
  doc.only_keys({"character", "emotions", "actions", "stimulus_edges", "response_edges",
                 "chain_edges", "representatives", "traits"});
  MindMap m;
  m.character = name(doc.at("character"));
  std::set<std::string> names;
  const JsonValue emotions = doc.at("emotions").expect_array();
  if (emotions.size() == 0) emotions.fail("at least one emotion node is required");
  for (const JsonValue& e : emotions.items()) {
    m.emotions.push_back(name(e));
    if (!names.insert(m.emotions.back()).second)
      e.fail("duplicate node name \"" + m.emotions.back() + "\"");
  }
  const std::size_t n = m.emotions.size();
  auto emotion_ref = [&](const JsonValue& j) {
    const std::string e_name = name(j);
    auto e = m.find_emotion(e_name);
    if (!e) j.fail("dangling edge: no emotion node \"" + e_name + "\"");
    return *e;
  };
  auto action_ref = [&](const JsonValue& j, bool receive, bool perform) {
    const std::string a_name = name(j);
    auto a = m.find_action(a_name);
    if (!a) j.fail("dangling edge: no action node \"" + a_name + "\"");
    if (receive && !m.actions[*a].receivable)
      j.fail("action \"" + a_name + "\" cannot be received");
    if (perform && !m.actions[*a].performable)
      j.fail("action \"" + a_name + "\" cannot be performed");
    return *a;
  };

  if (auto actions = doc.find("actions")) {
    for (const JsonValue& a : actions->items()) {
      a.only_keys({"name", "receive", "perform", "label"});
      ActionNode node;
      node.name = name(a.at("name"));
      if (!names.insert(node.name).second)
        a.at("name").fail("duplicate node name \"" + node.name + "\"");
      node.receivable = a.boolean_or("receive", node.receivable);
      node.performable = a.boolean_or("perform", node.performable);
      if (!node.receivable && !node.performable)
        a.fail(
            "an action must be received and/or performed (\"receive\": true, \"perform\": true)");
      if (auto l = a.find("label")) {
        node.label = name(*l);
        if (!known_labels.empty() &&
            std::find(known_labels.begin(), known_labels.end(), node.label) == known_labels.end()) {
          std::string list;
          for (const auto& k : known_labels) list += (list.empty() ? "" : ", ") + k;
          l->fail("unknown expression label \"" + node.label + "\" (known: " + list + ")");
        }
      }
      if (node.performable && node.label.empty())
        a.fail("a performing action needs an expression \"label\"");
      m.actions.push_back(std::move(node));
    }
  }
  if (auto edges = doc.find("stimulus_edges")) {
    std::set<std::pair<std::size_t, std::size_t>> seen;
    for (const JsonValue& e : edges->items()) {
      e.only_keys({"stimulus", "emotion", "weight"});
      StimulusEdge se;
      se.action = action_ref(e.at("stimulus"), true, false);
      se.emotion = emotion_ref(e.at("emotion"));
      se.weight = e.at("weight").number(0.0, 1.0);
      if (!seen.insert({se.action, se.emotion}).second) e.fail("duplicate edge");
      m.stimulus_edges.push_back(se);
    }
  }
  if (auto edges = doc.find("response_edges")) {
    std::set<std::pair<std::size_t, std::size_t>> seen;
    for (const JsonValue& e : edges->items()) {
      e.only_keys({"emotion", "action", "weight"});
      ResponseEdge re;
      re.emotion = emotion_ref(e.at("emotion"));
      re.action = action_ref(e.at("action"), false, true);
      re.weight = e.at("weight").number(0.0, 1.0);
      if (!seen.insert({re.emotion, re.action}).second) e.fail("duplicate edge");
      m.response_edges.push_back(re);
    }
  }
  if (auto edges = doc.find("chain_edges")) {
    std::set<std::pair<std::size_t, std::size_t>> seen;
    for (const JsonValue& e : edges->items()) {
      e.only_keys({"from", "to"});
      ChainEdge ce;
      ce.from = action_ref(e.at("from"), false, true);
      ce.to = action_ref(e.at("to"), false, true);
      if (ce.from == ce.to) e.fail("a chain edge cannot join an action to itself");
      if (!seen.insert({ce.from, ce.to}).second) e.fail("duplicate edge");
      m.chain_edges.push_back(ce);
    }
  }
  if (auto reps = doc.find("representatives")) {
    m.representative.assign(n, kNone);
    for (const auto& [key, v] : reps->members()) {
      auto e = m.find_emotion(key);
      if (!e) v.fail("no emotion node \"" + key + "\"");
      m.representative[*e] = action_ref(v, false, true);
    }
  }
  const JsonValue traits = doc.at("traits");
  traits.only_keys({"starting_mood", "personality", "background_context", "affection", "lambda",
                    "alpha", "beta", "decay"});
  Traits& t = m.traits;
  t.starting_mood = unit_array(traits.at("starting_mood"), n);
  t.personality = unit_array(traits.at("personality"), n);
  if (auto bg = traits.find("background_context")) t.background_context = unit_array(*bg, n);
  if (auto aff = traits.find("affection")) {
    for (const auto& [who, row] : aff->members()) {
      if (who.empty()) row.fail("empty character name");
      t.affection.emplace_back(who, unit_array(row, n));
    }
  }
  t.lambda = traits.at("lambda").number(0.0, 1.0);
  t.alpha = traits.at("alpha").number(0.0, 1.0);
  t.beta = traits.at("beta").number(0.0, 1.0);
  const JsonValue decay = traits.at("decay");
  decay.only_keys({"duration", "curve"});
  t.decay_duration = decay.at("duration").number(1e-6, 1e6);
  const std::string curve = name(decay.at("curve"));
  auto c = decay_curve_from_string(curve);
  if (!c) decay.at("curve").fail("unknown curve \"" + curve + "\" (linear|quadratic|sigmoid)");
  t.decay_curve = *c;
  try {
    validate(m);
  } catch (const InvalidInput& e) {
    doc.fail(e.what());
  }
  return m;
}

MindMap read_mind_map(const std::string& path, const std::vector<std::string>& known_labels) {
  return parse_mind_map(core::read_file(path), path, known_labels);
}

std::string to_json_text(const MindMap& m) {
  validate(m);
  Json doc = core::make_envelope(kMindMapKind, kVersion);
  doc["character"] = m.character;
  doc["emotions"] = m.emotions;
  Json actions = Json::array();
  for (const auto& a : m.actions) {
    Json j;
    j["name"] = a.name;
    if (a.receivable) j["receive"] = true;
    if (a.performable) j["perform"] = true;
    if (!a.label.empty()) j["label"] = a.label;
    actions.push_back(std::move(j));
  }
  doc["actions"] = std::move(actions);
  Json se = Json::array(), re = Json::array(), ce = Json::array();
  for (const auto& e : m.stimulus_edges)
    se.push_back({{"stimulus", m.actions[e.action].name}, {"emotion", m.emotions[e.emotion]}, {"weight", e.weight}});
  for (const auto& e : m.response_edges)
    re.push_back({{"emotion", m.emotions[e.emotion]}, {"action", m.actions[e.action].name}, {"weight", e.weight}});
  for (const auto& e : m.chain_edges)
    ce.push_back({{"from", m.actions[e.from].name}, {"to", m.actions[e.to].name}});
  doc["stimulus_edges"] = std::move(se);
  doc["response_edges"] = std::move(re);
  doc["chain_edges"] = std::move(ce);
  if (!m.representative.empty()) {
    Json reps = Json::object();
    for (std::size_t e = 0; e < m.emotions.size(); ++e)
      if (m.representative[e] != kNone) reps[m.emotions[e]] = m.actions[m.representative[e]].name;
    doc["representatives"] = std::move(reps);
  }
  Json t;
  t["starting_mood"] = to_json_array(m.traits.starting_mood);
  t["personality"] = to_json_array(m.traits.personality);
  if (!m.traits.background_context.empty()) t["background_context"] = to_json_array(m.traits.background_context);
  if (!m.traits.affection.empty()) {
    Json aff = Json::object();
    for (const auto& [who, row] : m.traits.affection) aff[who] = to_json_array(row);
    t["affection"] = std::move(aff);
  }
  t["lambda"] = m.traits.lambda;
  t["alpha"] = m.traits.alpha;
  t["beta"] = m.traits.beta;
  t["decay"] = {{"duration", m.traits.decay_duration}, {"curve", std::string(to_string(m.traits.decay_curve))}};
  doc["traits"] = std::move(t);
  return doc.dump(2) + "\n";
}

void write_mind_map(const MindMap& map, const std::string& path) {
  core::write_file_atomic(path, to_json_text(map));
}

std::vector<MindMap> read_mind_map_dir(const std::string& dir,
                                       const std::vector<std::string>& known_labels) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw IoError(dir + ": not a directory");
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(dir, ec))
    if (entry.is_regular_file() && entry.path().extension() == ".json") files.push_back(entry.path().string());
  if (ec) throw IoError(dir + ": cannot list: " + ec.message());
  std::sort(files.begin(), files.end());
  if (files.empty()) throw InvalidInput(dir + ": no mind maps (*.json)");
  std::vector<MindMap> maps;
  std::set<std::string> names;
  for (const auto& f : files) {
    maps.push_back(read_mind_map(f, known_labels));
    if (!names.insert(maps.back().character).second)
      throw InvalidInput(f + ": a second mind map of character \"" + maps.back().character + "\"");
  }
  return maps;
}

std::vector<Event> parse_events(std::string_view text, const std::string& file) {
  std::vector<Event> events;
  for_each_ndjson(text, file, "mindmap_events", {1, 0}, [&](const JsonValue& j, std::size_t line) {
    j.only_keys({"time", "to", "stimulus", "from", "weights", "context", "affection"});
    Event ev;
    ev.line = line;
    ev.time = j.at("time").number(0.0, 1e9);
    ev.target = name(j.at("to"));
    // Runtime trait changes (issue 19): {"time", "to", "context": [...], "affection": {"ben": [...]}}
    // instead of a stimulus. Sizes are checked against the target's map when applied.
    auto unit_list = [&](const JsonValue& a) {
      if (!a.is_array()) a.fail("expected an array of numbers in [0, 1]");
      if (a.size() > 4096) a.fail("too many values");
      std::vector<double> v;
      for (const JsonValue& x : a.items()) v.push_back(x.number(0.0, 1.0));
      return v;
    };
    if (auto c = j.find("context")) {
      ev.context = unit_list(*c);
      if (ev.context.empty()) c->fail("empty background context");
    }
    if (auto a = j.find("affection")) {
      a->expect_object();
      if (a->size() == 0) a->fail("no affection row");
      for (const auto& [who, row] : a->members()) {
        if (who.empty()) a->fail("empty character name");
        ev.affection.emplace_back(who, unit_list(row));
      }
    }
    const bool change = !ev.context.empty() || !ev.affection.empty();
    if (change && j.has("stimulus"))
      j.at("stimulus")
          .fail("an event either delivers a stimulus or changes context/affection, not both");
    if (!change) ev.stimulus = name(j.at("stimulus"));
    if (auto from = j.find("from")) ev.source = name(*from);
    if (auto w = j.find("weights"))
      for (const auto& [k, v] : w->members()) ev.weights.emplace_back(k, v.number(0.0, 1.0));
    events.push_back(std::move(ev));
  });
  return events;
}

std::vector<Event> read_events(const std::string& path) { return parse_events(core::read_file(path), path); }

std::string events_to_ndjson(const std::vector<Event>& events) {
  std::string out = core::ndjson_header("mindmap_events", {1, 0});
  for (const auto& e : events) {
    Json j;
    j["time"] = e.time;
    j["to"] = e.target;
    if (!e.changes_traits()) j["stimulus"] = e.stimulus;
    if (!e.context.empty()) j["context"] = e.context;
    if (!e.affection.empty()) {
      Json a = Json::object();
      for (const auto& [k, v] : e.affection) a[k] = v;
      j["affection"] = std::move(a);
    }
    if (!e.source.empty()) j["from"] = e.source;
    if (!e.weights.empty()) {
      Json w = Json::object();
      for (const auto& [k, v] : e.weights) w[k] = v;
      j["weights"] = std::move(w);
    }
    out += j.dump() + "\n";
  }
  return out;
}

std::string mood_timeline_csv(const SimulationResult& r, const MindMap& map, std::size_t c) {
  const std::size_t n = map.emotion_count();
  if (c >= r.mood.size() || r.mood[c].size() != r.times.size() * n)
    throw InvalidInput("mood_timeline_csv: character index or emotion count does not match the result");
  std::string out = core::csv_stamp() + "time";
  for (const auto& e : map.emotions) {
    out += ',';
    core::append_csv_field(out, e);
  }
  out += '\n';
  char buf[32];
  for (std::size_t k = 0; k < r.times.size(); ++k) {
    std::snprintf(buf, sizeof buf, "%.6f", r.times[k]);
    out += buf;
    for (std::size_t e = 0; e < n; ++e) {
      std::snprintf(buf, sizeof buf, ",%.6f", r.mood[c][k * n + e]);
      out += buf;
    }
    out += '\n';
  }
  return out;
}

std::string actions_to_ndjson(const std::vector<TriggeredAction>& actions) {
  std::string out = core::ndjson_header("mindmap_actions", {1, 0});
  for (const auto& a : actions) {
    Json j;
    j["time"] = a.time;
    j["character"] = a.character;
    j["action"] = a.action;
    j["label"] = a.label;
    j["emotion"] = a.emotion;
    j["mood"] = a.mood;
    j["cause"] = std::string(to_string(a.cause));
    j["stimulus"] = a.stimulus;
    j["depth"] = a.chain_depth;
    if (!a.addressee.empty()) j["at"] = a.addressee;
    out += j.dump() + "\n";
  }
  return out;
}

std::vector<TriggeredAction> parse_actions(std::string_view text, const std::string& file) {
  std::vector<TriggeredAction> out;
  for_each_ndjson(text, file, "mindmap_actions", {1, 0}, [&](const JsonValue& j, std::size_t) {
    j.only_keys({"time", "character", "action", "label", "emotion", "mood", "cause", "stimulus",
                 "depth", "at"});
    TriggeredAction a;
    a.time = j.at("time").number(0.0, 1e9);
    a.character = name(j.at("character"));
    a.action = name(j.at("action"));
    a.label = name(j.at("label"));
    a.emotion = name(j.at("emotion"));
    a.mood = j.at("mood").number(0.0, 1.0);
    const std::string cause = name(j.at("cause"));
    auto c = cause_from_string(cause);
    if (!c) j.at("cause").fail("unknown cause \"" + cause + "\" (stimulus|chain|decay)");
    a.cause = *c;
    a.stimulus = j.at("stimulus").string();
    a.chain_depth = j.at("depth").index(1000000);
    if (auto at = j.find("at")) a.addressee = name(*at);
    out.push_back(std::move(a));
  });
  return out;
}

std::string actions_to_csv(const std::vector<TriggeredAction>& actions) {
  std::string out = core::csv_stamp() + "time,character,action,label,emotion,mood,cause,stimulus,depth\n";
  char buf[64];
  for (const auto& a : actions) {
    std::snprintf(buf, sizeof buf, "%.6f,", a.time);
    out += buf;
    for (const std::string* s : {&a.character, &a.action, &a.label, &a.emotion}) {
      core::append_csv_field(out, *s);
      out += ',';
    }
    std::snprintf(buf, sizeof buf, "%.6f,", a.mood);
    out += buf;
    out += to_string(a.cause);
    out += ',';
    core::append_csv_field(out, a.stimulus);
    out += ',' + std::to_string(a.chain_depth) + '\n';
  }
  return out;
}

}  // namespace emoface::mindmap
