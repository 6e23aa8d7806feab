#include "emoface/mindmap/io.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <initializer_list>
#include <set>

#include "emoface/core/csv.hpp"
#include "emoface/core/io.hpp"

namespace emoface::mindmap {
namespace {

using Json = nlohmann::ordered_json;
constexpr core::FormatVersion kVersion{1, 0};

class Parser {
 public:
  Parser(std::string file, std::size_t line, bool strict)
      : file_(std::move(file)), line_(line), strict_(strict) {}

  [[noreturn]] void fail(const std::string& ptr, const std::string& message) const {
    throw FormatError(SourceLocation{file_, ptr, line_, 0}, message);
  }
  const Json& member(const Json& obj, const std::string& ptr, const char* key) const {
    auto it = obj.find(key);
    if (it == obj.end()) fail(ptr, std::string("missing mandatory field \"") + key + "\"");
    return *it;
  }
  const Json* optional(const Json& obj, const char* key) const {
    auto it = obj.find(key);
    return it == obj.end() ? nullptr : &*it;
  }
  void object(const Json& j, const std::string& ptr) const {
    if (!j.is_object()) fail(ptr, "expected an object");
  }
  void array(const Json& j, const std::string& ptr) const {
    if (!j.is_array()) fail(ptr, "expected an array");
  }
  std::string string(const Json& j, const std::string& ptr) const {
    if (!j.is_string()) fail(ptr, "expected a string");
    std::string s = j.get<std::string>();
    if (s.empty()) fail(ptr, "expected a non-empty string");
    return s;
  }
  bool boolean(const Json& j, const std::string& ptr) const {
    if (!j.is_boolean()) fail(ptr, "expected true or false");
    return j.get<bool>();
  }
  double number(const Json& j, const std::string& ptr, double lo, double hi) const {
    if (!j.is_number()) fail(ptr, "expected a number");
    const double v = j.get<double>();
    if (!std::isfinite(v) || v < lo || v > hi)
      fail(ptr, "value " + std::to_string(v) + " out of range [" + fmt(lo) + ", " + fmt(hi) + "]");
    return v;
  }
  void only_keys(const Json& obj, const std::string& ptr, std::initializer_list<const char*> keys) const {
    if (!strict_) return;  // a newer minor version may add fields
    for (auto it = obj.begin(); it != obj.end(); ++it) {
      bool known = false;
      for (const char* k : keys) known = known || it.key() == k;
      if (!known) fail(ptr + "/" + core::json_pointer_token(it.key()), "unknown field \"" + it.key() + "\"");
    }
  }
  static std::string fmt(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
  }

 private:
  std::string file_;
  std::size_t line_;
  bool strict_;
};

std::vector<double> unit_array(const Parser& p, const Json& j, const std::string& ptr, std::size_t n) {
  p.array(j, ptr);
  if (j.size() != n)
    p.fail(ptr, "has " + std::to_string(j.size()) + " entries; expected one per emotion node (" +
                    std::to_string(n) + ")");
  std::vector<double> out(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = p.number(j[i], ptr + "/" + std::to_string(i), 0.0, 1.0);
  return out;
}

Json to_json_array(const std::vector<double>& v) {
  Json a = Json::array();
  for (double x : v) a.push_back(x);
  return a;
}


// Calls fn(object, line) for every non-blank NDJSON line that does not start with '#'. A syntax
// error becomes a FormatError naming the line (and the column within it).
template <class Fn>
void for_each_ndjson(std::string_view text, const std::string& file, Fn fn) {
  std::size_t line_no = 0, pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string_view::npos || line[first] == '#') continue;
    Json j;
    try {
      j = core::parse_json(line, file);
    } catch (const FormatError& e) {
      throw FormatError(SourceLocation{file, "", line_no, e.where().column}, e.message());
    }
    if (core::is_stream_header(j)) continue;  // {"format": "emoface.…", …}: the stream's version stamp
    const Parser p(file, line_no, true);
    p.object(j, "");
    fn(j, p, line_no);
  }
}

}  // namespace

MindMap parse_mind_map(std::string_view json_text, const std::string& file,
                       const std::vector<std::string>& known_labels) {
  const Json doc = core::parse_json(json_text, file);
  const core::FormatVersion version = core::check_envelope(doc, kMindMapKind, kVersion, file);
  const Parser p(file, 0, version.minor <= kVersion.minor);
  p.only_keys(doc, "", {"format", "version", "generator", "character", "emotions", "actions",
                        "stimulus_edges", "response_edges", "chain_edges", "representatives", "traits"});
  MindMap m;
  m.character = p.string(p.member(doc, "", "character"), "/character");
  std::set<std::string> names;
  const Json& emotions = p.member(doc, "", "emotions");
  p.array(emotions, "/emotions");
  if (emotions.empty()) p.fail("/emotions", "at least one emotion node is required");
  for (std::size_t i = 0; i < emotions.size(); ++i) {
    const std::string ptr = "/emotions/" + std::to_string(i);
    m.emotions.push_back(p.string(emotions[i], ptr));
    if (!names.insert(m.emotions.back()).second) p.fail(ptr, "duplicate node name \"" + m.emotions.back() + "\"");
  }
  const std::size_t n = m.emotions.size();
  auto emotion_ref = [&](const Json& j, const std::string& ptr) {
    const std::string name = p.string(j, ptr);
    auto e = m.find_emotion(name);
    if (!e) p.fail(ptr, "dangling edge: no emotion node \"" + name + "\"");
    return *e;
  };
  auto action_ref = [&](const Json& j, const std::string& ptr, bool receive, bool perform) {
    const std::string name = p.string(j, ptr);
    auto a = m.find_action(name);
    if (!a) p.fail(ptr, "dangling edge: no action node \"" + name + "\"");
    if (receive && !m.actions[*a].receivable) p.fail(ptr, "action \"" + name + "\" cannot be received");
    if (perform && !m.actions[*a].performable) p.fail(ptr, "action \"" + name + "\" cannot be performed");
    return *a;
  };

  if (const Json* actions = p.optional(doc, "actions")) {
    p.array(*actions, "/actions");
    for (std::size_t i = 0; i < actions->size(); ++i) {
      const std::string ptr = "/actions/" + std::to_string(i);
      const Json& a = (*actions)[i];
      p.object(a, ptr);
      p.only_keys(a, ptr, {"name", "receive", "perform", "label"});
      ActionNode node;
      node.name = p.string(p.member(a, ptr, "name"), ptr + "/name");
      if (!names.insert(node.name).second) p.fail(ptr + "/name", "duplicate node name \"" + node.name + "\"");
      if (const Json* r = p.optional(a, "receive")) node.receivable = p.boolean(*r, ptr + "/receive");
      if (const Json* f = p.optional(a, "perform")) node.performable = p.boolean(*f, ptr + "/perform");
      if (!node.receivable && !node.performable)
        p.fail(ptr, "an action must be received and/or performed (\"receive\": true, \"perform\": true)");
      if (const Json* l = p.optional(a, "label")) {
        node.label = p.string(*l, ptr + "/label");
        if (!known_labels.empty() &&
            std::find(known_labels.begin(), known_labels.end(), node.label) == known_labels.end()) {
          std::string list;
          for (const auto& k : known_labels) list += (list.empty() ? "" : ", ") + k;
          p.fail(ptr + "/label", "unknown expression label \"" + node.label + "\" (known: " + list + ")");
        }
      }
      if (node.performable && node.label.empty())
        p.fail(ptr, "a performing action needs an expression \"label\"");
      m.actions.push_back(std::move(node));
    }
  }
  if (const Json* edges = p.optional(doc, "stimulus_edges")) {
    p.array(*edges, "/stimulus_edges");
    std::set<std::pair<std::size_t, std::size_t>> seen;
    for (std::size_t i = 0; i < edges->size(); ++i) {
      const std::string ptr = "/stimulus_edges/" + std::to_string(i);
      const Json& e = (*edges)[i];
      p.object(e, ptr);
      p.only_keys(e, ptr, {"stimulus", "emotion", "weight"});
      StimulusEdge se;
      se.action = action_ref(p.member(e, ptr, "stimulus"), ptr + "/stimulus", true, false);
      se.emotion = emotion_ref(p.member(e, ptr, "emotion"), ptr + "/emotion");
      se.weight = p.number(p.member(e, ptr, "weight"), ptr + "/weight", 0.0, 1.0);
      if (!seen.insert({se.action, se.emotion}).second) p.fail(ptr, "duplicate edge");
      m.stimulus_edges.push_back(se);
    }
  }
  if (const Json* edges = p.optional(doc, "response_edges")) {
    p.array(*edges, "/response_edges");
    std::set<std::pair<std::size_t, std::size_t>> seen;
    for (std::size_t i = 0; i < edges->size(); ++i) {
      const std::string ptr = "/response_edges/" + std::to_string(i);
      const Json& e = (*edges)[i];
      p.object(e, ptr);
      p.only_keys(e, ptr, {"emotion", "action", "weight"});
      ResponseEdge re;
      re.emotion = emotion_ref(p.member(e, ptr, "emotion"), ptr + "/emotion");
      re.action = action_ref(p.member(e, ptr, "action"), ptr + "/action", false, true);
      re.weight = p.number(p.member(e, ptr, "weight"), ptr + "/weight", 0.0, 1.0);
      if (!seen.insert({re.emotion, re.action}).second) p.fail(ptr, "duplicate edge");
      m.response_edges.push_back(re);
    }
  }
  if (const Json* edges = p.optional(doc, "chain_edges")) {
    p.array(*edges, "/chain_edges");
    std::set<std::pair<std::size_t, std::size_t>> seen;
    for (std::size_t i = 0; i < edges->size(); ++i) {
      const std::string ptr = "/chain_edges/" + std::to_string(i);
      const Json& e = (*edges)[i];
      p.object(e, ptr);
      p.only_keys(e, ptr, {"from", "to"});
      ChainEdge ce;
      ce.from = action_ref(p.member(e, ptr, "from"), ptr + "/from", false, true);
      ce.to = action_ref(p.member(e, ptr, "to"), ptr + "/to", false, true);
      if (ce.from == ce.to) p.fail(ptr, "a chain edge cannot join an action to itself");
      if (!seen.insert({ce.from, ce.to}).second) p.fail(ptr, "duplicate edge");
      m.chain_edges.push_back(ce);
    }
  }
  if (const Json* reps = p.optional(doc, "representatives")) {
    p.object(*reps, "/representatives");
    m.representative.assign(n, kNone);
    for (auto it = reps->begin(); it != reps->end(); ++it) {
      const std::string ptr = "/representatives/" + core::json_pointer_token(it.key());
      auto e = m.find_emotion(it.key());
      if (!e) p.fail(ptr, "no emotion node \"" + it.key() + "\"");
      m.representative[*e] = action_ref(it.value(), ptr, false, true);
    }
  }
  const Json& traits = p.member(doc, "", "traits");
  p.object(traits, "/traits");
  p.only_keys(traits, "/traits", {"starting_mood", "personality", "background_context", "affection",
                                  "lambda", "alpha", "beta", "decay"});
  Traits& t = m.traits;
  t.starting_mood = unit_array(p, p.member(traits, "/traits", "starting_mood"), "/traits/starting_mood", n);
  t.personality = unit_array(p, p.member(traits, "/traits", "personality"), "/traits/personality", n);
  if (const Json* bg = p.optional(traits, "background_context"))
    t.background_context = unit_array(p, *bg, "/traits/background_context", n);
  if (const Json* aff = p.optional(traits, "affection")) {
    p.object(*aff, "/traits/affection");
    for (auto it = aff->begin(); it != aff->end(); ++it) {
      const std::string ptr = "/traits/affection/" + core::json_pointer_token(it.key());
      if (it.key().empty()) p.fail(ptr, "empty character name");
      t.affection.emplace_back(it.key(), unit_array(p, it.value(), ptr, n));
    }
  }
  t.lambda = p.number(p.member(traits, "/traits", "lambda"), "/traits/lambda", 0.0, 1.0);
  t.alpha = p.number(p.member(traits, "/traits", "alpha"), "/traits/alpha", 0.0, 1.0);
  t.beta = p.number(p.member(traits, "/traits", "beta"), "/traits/beta", 0.0, 1.0);
  const Json& decay = p.member(traits, "/traits", "decay");
  p.object(decay, "/traits/decay");
  p.only_keys(decay, "/traits/decay", {"duration", "curve"});
  t.decay_duration = p.number(p.member(decay, "/traits/decay", "duration"), "/traits/decay/duration", 1e-6, 1e6);
  const std::string curve = p.string(p.member(decay, "/traits/decay", "curve"), "/traits/decay/curve");
  auto c = decay_curve_from_string(curve);
  if (!c) p.fail("/traits/decay/curve", "unknown curve \"" + curve + "\" (linear|quadratic|sigmoid)");
  t.decay_curve = *c;
  try {
    validate(m);
  } catch (const InvalidInput& e) {
    p.fail("", e.what());
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
  for_each_ndjson(text, file, [&](const Json& j, const Parser& p, std::size_t line) {
    p.only_keys(j, "", {"time", "to", "stimulus", "from", "weights", "context", "affection"});
    Event ev;
    ev.line = line;
    ev.time = p.number(p.member(j, "", "time"), "/time", 0.0, 1e9);
    ev.target = p.string(p.member(j, "", "to"), "/to");
    // Runtime trait changes (issue 19): {"time", "to", "context": [...], "affection": {"ben": [...]}}
    // instead of a stimulus. Sizes are checked against the target's map when applied.
    auto unit_list = [&](const Json& a, const std::string& ptr) {
      if (!a.is_array()) p.fail(ptr, "expected an array of numbers in [0, 1]");
      if (a.size() > 4096) p.fail(ptr, "too many values");
      std::vector<double> v;
      for (std::size_t i = 0; i < a.size(); ++i) v.push_back(p.number(a[i], ptr + "/" + std::to_string(i), 0.0, 1.0));
      return v;
    };
    if (const Json* c = p.optional(j, "context")) {
      ev.context = unit_list(*c, "/context");
      if (ev.context.empty()) p.fail("/context", "empty background context");
    }
    if (const Json* a = p.optional(j, "affection")) {
      p.object(*a, "/affection");
      if (a->empty()) p.fail("/affection", "no affection row");
      for (auto it = a->begin(); it != a->end(); ++it) {
        if (it.key().empty()) p.fail("/affection", "empty character name");
        ev.affection.emplace_back(it.key(), unit_list(it.value(), "/affection/" + core::json_pointer_token(it.key())));
      }
    }
    const bool change = !ev.context.empty() || !ev.affection.empty();
    if (change && p.optional(j, "stimulus"))
      p.fail("/stimulus", "an event either delivers a stimulus or changes context/affection, not both");
    if (!change) ev.stimulus = p.string(p.member(j, "", "stimulus"), "/stimulus");
    if (const Json* from = p.optional(j, "from")) ev.source = p.string(*from, "/from");
    if (const Json* w = p.optional(j, "weights")) {
      p.object(*w, "/weights");
      for (auto it = w->begin(); it != w->end(); ++it)
        ev.weights.emplace_back(it.key(), p.number(it.value(), "/weights/" + core::json_pointer_token(it.key()), 0.0, 1.0));
    }
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
  for_each_ndjson(text, file, [&](const Json& j, const Parser& p, std::size_t) {
    p.only_keys(j, "", {"time", "character", "action", "label", "emotion", "mood", "cause", "stimulus", "depth", "at"});
    TriggeredAction a;
    a.time = p.number(p.member(j, "", "time"), "/time", 0.0, 1e9);
    a.character = p.string(p.member(j, "", "character"), "/character");
    a.action = p.string(p.member(j, "", "action"), "/action");
    a.label = p.string(p.member(j, "", "label"), "/label");
    a.emotion = p.string(p.member(j, "", "emotion"), "/emotion");
    a.mood = p.number(p.member(j, "", "mood"), "/mood", 0.0, 1.0);
    const std::string cause = p.string(p.member(j, "", "cause"), "/cause");
    auto c = cause_from_string(cause);
    if (!c) p.fail("/cause", "unknown cause \"" + cause + "\" (stimulus|chain|decay)");
    a.cause = *c;
    const Json& s = p.member(j, "", "stimulus");
    if (!s.is_string()) p.fail("/stimulus", "expected a string");
    a.stimulus = s.get<std::string>();
    a.chain_depth = static_cast<std::size_t>(p.number(p.member(j, "", "depth"), "/depth", 0.0, 1e6));
    if (const Json* at = p.optional(j, "at")) a.addressee = p.string(*at, "/at");
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
