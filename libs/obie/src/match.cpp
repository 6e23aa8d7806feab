#include "emoface/obie/match.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "json_reader.hpp"

namespace emoface::obie {

using detail::Json;
using detail::Reader;

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
  const Json doc = core::parse_json(text, file);
  core::check_envelope(doc, "obie.match", core::FormatVersion{kMatchFormatMajor, kMatchFormatMinor}, file);
  const Reader r(file);
  r.only_keys(doc, "", {"format", "version", "generator", "title", "domain", "teams", "duration", "goal_outcomes",
                        "events", "key_moments", "commentary"});
  MatchScript m;
  m.base_dir = std::filesystem::path(file).parent_path().string();
  if (doc.contains("title")) m.title = r.string(doc["title"], "/title");
  if (!doc.contains("domain")) r.fail("", "missing field \"domain\" (parlee domain file, relative to this file)");
  if (doc["domain"].is_string()) {
    m.domain.push_back(r.string(doc["domain"], "/domain", false));
  } else {
    const Json& d = r.array(doc["domain"], "/domain", 16);
    if (d.empty()) r.fail("/domain", "at least one domain file is required");
    for (std::size_t i = 0; i < d.size(); ++i) m.domain.push_back(r.string(d[i], Reader::at("/domain", i), false));
  }
  if (doc.contains("teams")) {
    const Json& t = r.object(doc["teams"], "/teams");
    r.only_keys(t, "/teams", {"for", "against"});
    auto team = [&](const char* key, Team& out) {
      const std::string p = Reader::at("/teams", key);
      if (!t.contains(key)) r.fail("/teams", std::string("missing field \"") + key + "\"");
      const Json& o = r.object(t[key], p);
      r.only_keys(o, p, {"side", "name"});
      if (!o.contains("side")) r.fail(p, "missing field \"side\" (the domain object of this team)");
      out.side = r.string(o["side"], p + "/side", false);
      out.name = o.contains("name") ? r.string(o["name"], p + "/name") : out.side;
    };
    team("for", m.for_team);
    team("against", m.against_team);
    if (m.for_team.side == m.against_team.side) r.fail("/teams/against/side", "the two teams must be different sides");
  }
  if (doc.contains("duration")) m.duration = r.number(doc["duration"], "/duration", 1e-9, 1000);
  if (doc.contains("goal_outcomes")) {
    const Json& g = r.array(doc["goal_outcomes"], "/goal_outcomes", 64);
    m.goal_outcomes.clear();
    for (std::size_t i = 0; i < g.size(); ++i) m.goal_outcomes.push_back(r.string(g[i], Reader::at("/goal_outcomes", i), false));
  }
  if (!doc.contains("events")) r.fail("", "missing field \"events\"");
  const Json& ev = r.array(doc["events"], "/events", kMaxMatchEvents);
  double prev = 0.0;
  for (std::size_t i = 0; i < ev.size(); ++i) {
    const std::string p = Reader::at("/events", i);
    const Json& e = r.object(ev[i], p);
    r.only_keys(e, p, {"minute", "action", "outcome", "feedback", "note"});
    MatchEvent me;
    if (!e.contains("minute")) r.fail(p, "missing field \"minute\"");
    me.minute = r.number(e["minute"], p + "/minute", 0, m.duration);
    if (me.minute < prev) r.fail(p + "/minute", "minutes must not decrease (previous event at " + Reader::fmt(prev) + ")");
    prev = me.minute;
    if (!e.contains("action")) r.fail(p, "missing field \"action\" (\"\" = the agent on turn passes)");
    me.action = r.string(e["action"], p + "/action");
    if (e.contains("outcome")) me.outcome = r.string(e["outcome"], p + "/outcome");
    if (e.contains("feedback")) me.feedback = r.number(e["feedback"], p + "/feedback", -1, 1);
    if (e.contains("note")) me.note = r.string(e["note"], p + "/note");
    m.events.push_back(std::move(me));
  }
  if (doc.contains("key_moments")) {
    const Json& k = r.array(doc["key_moments"], "/key_moments", 1000);
    for (std::size_t i = 0; i < k.size(); ++i) {
      const std::string p = Reader::at("/key_moments", i);
      const Json& o = r.object(k[i], p);
      r.only_keys(o, p, {"minute", "label"});
      KeyMoment km;
      if (!o.contains("minute")) r.fail(p, "missing field \"minute\"");
      km.minute = r.number(o["minute"], p + "/minute", 0, m.duration);
      if (o.contains("label")) km.label = r.string(o["label"], p + "/label");
      m.key_moments.push_back(std::move(km));
    }
  }
  if (doc.contains("commentary")) {
    const Json& c = r.array(doc["commentary"], "/commentary", kMaxMatchEvents);
    for (std::size_t i = 0; i < c.size(); ++i) {
      const std::string p = Reader::at("/commentary", i);
      const Json& o = r.object(c[i], p);
      r.only_keys(o, p, {"minute", "text"});
      Commentary cm;
      if (!o.contains("minute")) r.fail(p, "missing field \"minute\"");
      cm.minute = r.number(o["minute"], p + "/minute", 0, m.duration);
      if (!o.contains("text")) r.fail(p, "missing field \"text\"");
      cm.text = r.string(o["text"], p + "/text", false);
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
