#include "emoface/obie/match.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "json_reader.hpp"

namespace emoface::obie {

using detail::Json;
using detail::JsonValue;

std::vector<std::string> MatchScript::domain_paths() const {
  std::vector<std::string> out;
  for (const auto& d : domain) {
    const std::filesystem::path p(d);
    out.push_back(p.is_absolute() || base_dir.empty() ? p.string() : (std::filesystem::path(base_dir) / p).string());
  }
  return out;
}

void MatchScript::validate() const {
  if (domain.empty()) throw InvalidInput("match: domain: at least one domain file is required");
  for (const auto& d : domain)
    if (d.empty()) throw InvalidInput("match: domain: a file name is empty");
  if (for_team.side.empty() || against_team.side.empty()) throw InvalidInput("match: teams: side must not be empty");
  if (for_team.side == against_team.side) throw InvalidInput("match: teams: the two sides must differ");
  if (!(duration > 0 && duration <= 1000)) throw InvalidInput("match: duration must be in (0, 1000] minutes");
  if (events.size() > kMaxMatchEvents) throw InvalidInput("match: too many events");
  double prev = 0.0;
  for (std::size_t i = 0; i < events.size(); ++i) {
    const auto& e = events[i];
    const std::string where = "match: events[" + std::to_string(i) + "]: ";
    if (!std::isfinite(e.minute) || e.minute < 0 || e.minute > duration)
      throw InvalidInput(where + "minute must be in [0, duration]");
    if (e.minute < prev) throw InvalidInput(where + "minutes must not decrease");
    prev = e.minute;
    if (e.feedback && !(std::abs(*e.feedback) <= 1)) throw InvalidInput(where + "feedback must be in [-1, 1]");
  }
  for (std::size_t i = 0; i < key_moments.size(); ++i)
    if (!std::isfinite(key_moments[i].minute) || key_moments[i].minute < 0 || key_moments[i].minute > duration)
      throw InvalidInput("match: key_moments[" + std::to_string(i) + "]: minute must be in [0, duration]");
  for (std::size_t i = 0; i < commentary.size(); ++i) {
    if (!std::isfinite(commentary[i].minute) || commentary[i].minute < 0 || commentary[i].minute > duration)
      throw InvalidInput("match: commentary[" + std::to_string(i) + "]: minute must be in [0, duration]");
    if (commentary[i].text.empty()) throw InvalidInput("match: commentary[" + std::to_string(i) + "]: text is empty");
  }
}

MatchScript parse_match(std::string_view text, const std::string& file) {
  const core::JsonReader reader(text, file, "obie.match",
                                core::FormatVersion{kMatchFormatMajor, kMatchFormatMinor});
  const JsonValue doc = reader.root();
  doc.only_keys({"title", "domain", "teams", "duration", "goal_outcomes", "events", "key_moments",
                 "commentary"});
  MatchScript m;
  m.base_dir = std::filesystem::path(file).parent_path().string();
  if (auto t = doc.find("title")) m.title = detail::string(*t);
  const JsonValue domain =
      detail::required(doc, "domain", "(parlee domain file, relative to this file)");
  if (domain.is_string()) {
    m.domain.push_back(detail::string(domain, false));
  } else {
    detail::array(domain, 16);
    if (domain.size() == 0) domain.fail("at least one domain file is required");
    for (const JsonValue& d : domain.items()) m.domain.push_back(detail::string(d, false));
  }
  if (auto t = doc.find("teams")) {
    t->only_keys({"for", "against"});
    auto team = [&](const char* key, Team& out) {
      const JsonValue o = detail::required(*t, key);
      o.only_keys({"side", "name"});
      out.side =
          detail::string(detail::required(o, "side", "(the domain object of this team)"), false);
      out.name = o.has("name") ? detail::string(o.at("name")) : out.side;
    };
    team("for", m.for_team);
    team("against", m.against_team);
    if (m.for_team.side == m.against_team.side)
      t->at("against").at("side").fail("the two teams must be different sides");
  }
  if (auto d = doc.find("duration")) m.duration = d->number(1e-9, 1000);
  if (auto g = doc.find("goal_outcomes")) {
    m.goal_outcomes.clear();
    for (const JsonValue& o : detail::array(*g, 64).items())
      m.goal_outcomes.push_back(detail::string(o, false));
  }
  double prev = 0.0;
  for (const JsonValue& e :
       detail::array(detail::required(doc, "events"), kMaxMatchEvents).items()) {
    e.only_keys({"minute", "action", "outcome", "feedback", "note"});
    MatchEvent me;
    const JsonValue minute = detail::required(e, "minute");
    me.minute = minute.number(0, m.duration);
    if (me.minute < prev)
      minute.fail("minutes must not decrease (previous event at " + detail::fmt(prev) + ")");
    prev = me.minute;
    me.action = detail::string(detail::required(e, "action", "(\"\" = the agent on turn passes)"));
    if (auto o = e.find("outcome")) me.outcome = detail::string(*o);
    if (auto f = e.find("feedback")) me.feedback = f->number(-1, 1);
    if (auto n = e.find("note")) me.note = detail::string(*n);
    m.events.push_back(std::move(me));
  }
  if (auto k = doc.find("key_moments")) {
    for (const JsonValue& o : detail::array(*k, 1000).items()) {
      o.only_keys({"minute", "label"});
      KeyMoment km;
      km.minute = detail::required(o, "minute").number(0, m.duration);
      if (auto l = o.find("label")) km.label = detail::string(*l);
      m.key_moments.push_back(std::move(km));
    }
  }
  if (auto c = doc.find("commentary")) {
    for (const JsonValue& o : detail::array(*c, kMaxMatchEvents).items()) {
      o.only_keys({"minute", "text"});
      Commentary cm;
      cm.minute = detail::required(o, "minute").number(0, m.duration);
      cm.text = detail::string(detail::required(o, "text"), false);
      m.commentary.push_back(std::move(cm));
    }
  }
  return m;
}

MatchScript read_match_file(const std::string& path) { return parse_match(core::read_file(path), path); }

namespace {
Json number_json(double x) {
  if (std::floor(x) == x && std::abs(x) < 1e15) return Json(static_cast<long long>(x));
  return Json(x);
}
}  // namespace

std::string write_match(const MatchScript& match) {
  match.validate();
  Json doc = core::make_envelope("obie.match", core::FormatVersion{kMatchFormatMajor, kMatchFormatMinor});
  doc["title"] = match.title;
  if (match.domain.size() == 1) {
    doc["domain"] = match.domain[0];
  } else {
    doc["domain"] = match.domain;
  }
  doc["teams"] = {{"for", {{"side", match.for_team.side}, {"name", match.for_team.name}}},
                  {"against", {{"side", match.against_team.side}, {"name", match.against_team.name}}}};
  doc["duration"] = number_json(match.duration);
  doc["goal_outcomes"] = match.goal_outcomes;
  // Header fields on the first lines, then one event / moment / comment per line (diff-friendly).
  std::string out = "{";
  bool first = true;
  for (auto it = doc.begin(); it != doc.end(); ++it) {
    out += first ? "\n  " : ",\n  ";
    first = false;
    out += Json(it.key()).dump() + ": " + it.value().dump();
  }
  auto list = [&](const char* key, const std::vector<Json>& items) {
    out += ",\n  " + Json(key).dump() + ": [";
    for (std::size_t i = 0; i < items.size(); ++i) out += (i ? ",\n    " : "\n    ") + items[i].dump();
    out += items.empty() ? "]" : "\n  ]";
  };
  std::vector<Json> items;
  for (const auto& e : match.events) {
    Json j = {{"minute", number_json(e.minute)}, {"action", e.action}};
    if (!e.outcome.empty()) j["outcome"] = e.outcome;
    if (e.feedback) j["feedback"] = *e.feedback;
    if (!e.note.empty()) j["note"] = e.note;
    items.push_back(std::move(j));
  }
  list("events", items);
  items.clear();
  for (const auto& k : match.key_moments) items.push_back({{"minute", number_json(k.minute)}, {"label", k.label}});
  list("key_moments", items);
  items.clear();
  for (const auto& c : match.commentary) items.push_back({{"minute", number_json(c.minute)}, {"text", c.text}});
  list("commentary", items);
  out += "\n}\n";
  return out;
}

std::vector<parlee::Event> to_parlee_events(const MatchScript& match) {
  std::vector<parlee::Event> out;
  out.reserve(match.events.size());
  for (const auto& e : match.events) {
    parlee::Event p;
    p.time = e.minute;
    p.action = e.action;
    p.outcome = e.outcome;
    p.feedback = e.feedback;
    p.note = e.note;
    out.push_back(std::move(p));
  }
  return out;
}

MatchScript match_from_events(const std::vector<parlee::Event>& events) {
  MatchScript m;
  m.domain.clear();
  double last = 0.0;
  for (const auto& e : events) {
    if (!std::isfinite(e.time) || e.time < 0) throw InvalidInput("match_from_events: event times must be finite and >= 0");
    MatchEvent me;
    me.minute = e.time;
    me.action = e.action;
    me.outcome = e.outcome;
    me.feedback = e.feedback;
    me.note = e.note;
    last = std::max(last, e.time);
    m.events.push_back(std::move(me));
  }
  m.duration = std::max(90.0, std::ceil(last));
  return m;
}

}  // namespace emoface::obie
