#include "emoface/obie/utterances.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "emoface/core/rng.hpp"
#include "json_reader.hpp"

namespace emoface::obie {

using detail::Json;
using detail::Reader;

namespace {
constexpr std::array<const char*, 6> kEsvNames = {"sadness", "happiness", "anger", "fear", "disgust", "surprise"};
bool in(double x, double lo, double hi) { return std::isfinite(x) && x >= lo && x <= hi; }
}  // namespace

std::size_t esv_index(std::string_view emotion) {
  for (std::size_t k = 0; k < kEsvNames.size(); ++k)
    if (emotion == kEsvNames[k]) return k;
  throw InvalidInput("unknown emotion \"" + std::string(emotion) +
                     "\" (expected sadness, happiness, anger, fear, disgust or surprise)");
}

void UtteranceSet::validate() const {
  if (!in(refractory, 0.5, 600)) throw InvalidInput("utterances: refractory must be in [0.5, 600] s");
  if (!in(delay, 0, 10)) throw InvalidInput("utterances: delay must be in [0, 10] s");
  if (!in(max_wait, 0, 600)) throw InvalidInput("utterances: max_wait must be in [0, 600] s");
  for (std::size_t i = 0; i < rules.size(); ++i) {
    const auto& r = rules[i];
    const std::string where = "utterances: rules[" + std::to_string(i) + "]: ";
    try {
      esv_index(r.emotion);
    } catch (const InvalidInput& e) {
      throw InvalidInput(where + e.what());
    }
    if (!(in(r.threshold, 0, 1) && r.threshold > 0)) throw InvalidInput(where + "threshold must be in (0, 1]");
    if (!(in(r.rise, 0, 1) && r.rise > 0)) throw InvalidInput(where + "rise must be in (0, 1]");
    if (r.texts.empty()) throw InvalidInput(where + "needs at least one text");
    for (const auto& t : r.texts)
      if (t.empty() || t.size() > 200) throw InvalidInput(where + "texts must be 1-200 bytes");
  }
}

UtteranceSet parse_utterances(std::string_view text, const std::string& file) {
  const Json doc = core::parse_json(text, file);
  core::check_envelope(doc, "obie.utterances", core::FormatVersion{kUtterancesFormatMajor, kUtterancesFormatMinor},
                       file);
  const Reader r(file);
  r.only_keys(doc, "", {"format", "version", "generator", "refractory", "delay", "max_wait", "rules"});
  UtteranceSet set;
  if (doc.contains("refractory")) set.refractory = r.number(doc["refractory"], "/refractory", 0.5, 600);
  if (doc.contains("delay")) set.delay = r.number(doc["delay"], "/delay", 0, 10);
  if (doc.contains("max_wait")) set.max_wait = r.number(doc["max_wait"], "/max_wait", 0, 600);
  if (!doc.contains("rules")) r.fail("", "missing field \"rules\"");
  const Json& rules = r.array(doc["rules"], "/rules", 64);
  for (std::size_t i = 0; i < rules.size(); ++i) {
    const std::string p = Reader::at("/rules", i);
    const Json& o = r.object(rules[i], p);
    r.only_keys(o, p, {"emotion", "threshold", "rise", "texts"});
    UtteranceRule rule;
    if (!o.contains("emotion")) r.fail(p, "missing field \"emotion\"");
    rule.emotion = r.string(o["emotion"], p + "/emotion");
    try {
      esv_index(rule.emotion);
    } catch (const InvalidInput& e) {
      r.fail(p + "/emotion", e.what());
    }
    if (o.contains("threshold")) rule.threshold = r.number(o["threshold"], p + "/threshold", 1e-9, 1);
    if (o.contains("rise")) rule.rise = r.number(o["rise"], p + "/rise", 1e-9, 1);
    if (!o.contains("texts")) r.fail(p, "missing field \"texts\"");
    const Json& texts = r.array(o["texts"], p + "/texts", 256);
    if (texts.empty()) r.fail(p + "/texts", "needs at least one text");
    for (std::size_t k = 0; k < texts.size(); ++k) {
      const std::string tp = Reader::at(p + "/texts", k);
      std::string t = r.string(texts[k], tp, false);
      if (t.size() > 200) r.fail(tp, "an utterance is short: at most 200 bytes");
      rule.texts.push_back(std::move(t));
    }
    set.rules.push_back(std::move(rule));
  }
  return set;
}

UtteranceSet read_utterances_file(const std::string& path) { return parse_utterances(core::read_file(path), path); }

std::string write_utterances(const UtteranceSet& set) {
  set.validate();
  Json doc = core::make_envelope("obie.utterances", core::FormatVersion{kUtterancesFormatMajor, kUtterancesFormatMinor});
  doc["refractory"] = set.refractory;
  doc["delay"] = set.delay;
  doc["max_wait"] = set.max_wait;
  Json rules = Json::array();
  for (const auto& r : set.rules)
    rules.push_back({{"emotion", r.emotion}, {"threshold", r.threshold}, {"rise", r.rise}, {"texts", r.texts}});
  doc["rules"] = rules;
  return doc.dump(2) + "\n";
}

std::vector<PlannedUtterance> choose_utterances(const std::vector<parlee::StepRecord>& records,
                                                const std::vector<double>& step_seconds, const UtteranceSet& set,
                                                std::uint64_t seed, const SpeechDuration& duration) {
  set.validate();
  if (records.size() != step_seconds.size())
    throw InvalidInput("choose_utterances: one animation time per timeline record is needed");
  std::vector<PlannedUtterance> out;
  double last_start = -1e300, last_duration = 0.0;
  for (std::size_t k = 1; k < records.size(); ++k) {
    const auto& now = records[k].shown;  // what the agent reveals (§5.6.5), like the face
    const auto& before = records[k - 1].shown;
    const UtteranceRule* best = nullptr;
    double best_margin = -1.0;
    for (const auto& rule : set.rules) {
      const std::size_t e = esv_index(rule.emotion);
      const bool crossed = now[e] >= rule.threshold && before[e] < rule.threshold;
      const bool jumped = now[e] >= rule.threshold && now[e] - before[e] >= rule.rise;
      if (!(crossed || jumped)) continue;
      const double margin = now[e] - rule.threshold;
      if (margin > best_margin) {  // first rule wins ties (file order)
        best_margin = margin;
        best = &rule;
      }
    }
    if (!best) continue;
    const double wanted = step_seconds[k] + set.delay;
    const double earliest = std::max(wanted, last_start + std::max(set.refractory, last_duration + 0.3));
    if (earliest - wanted > set.max_wait + 1e-9) continue;
    core::Rng rng(seed, k);  // stream = step: a choice does not depend on the others
    PlannedUtterance u;
    u.step = k;
    u.minute = records[k].time;
    u.time = earliest;
    u.emotion = best->emotion;
    u.intensity = now[esv_index(best->emotion)];
    u.text = best->texts[static_cast<std::size_t>(rng.uniform_int(best->texts.size()))];
    last_start = u.time;
    last_duration = duration ? std::max(0.0, duration(u.text)) : 0.0;
    out.push_back(std::move(u));
  }
  return out;
}

}  // namespace emoface::obie
