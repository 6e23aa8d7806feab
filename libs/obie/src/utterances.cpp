#include "emoface/obie/utterances.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "emoface/core/rng.hpp"
#include "json_reader.hpp"

namespace emoface::obie {

using detail::Json;
using detail::JsonValue;

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
  const core::JsonReader reader(
      text, file, "obie.utterances",
      core::FormatVersion{kUtterancesFormatMajor, kUtterancesFormatMinor});
  const JsonValue doc = reader.root();
  doc.only_keys({"refractory", "delay", "max_wait", "rules"});
  UtteranceSet set;
  if (auto v = doc.find("refractory")) set.refractory = v->number(0.5, 600);
  if (auto v = doc.find("delay")) set.delay = v->number(0, 10);
  if (auto v = doc.find("max_wait")) set.max_wait = v->number(0, 600);
  for (const JsonValue& o : detail::array(detail::required(doc, "rules"), 64).items()) {
    o.only_keys({"emotion", "threshold", "rise", "texts"});
    UtteranceRule rule;
    const JsonValue emotion = detail::required(o, "emotion");
    rule.emotion = detail::string(emotion);
    try {
      esv_index(rule.emotion);
    } catch (const InvalidInput& e) {
      emotion.fail(e.what());
    }
    if (auto v = o.find("threshold")) rule.threshold = v->number(1e-9, 1);
    if (auto v = o.find("rise")) rule.rise = v->number(1e-9, 1);
    const JsonValue texts = detail::array(detail::required(o, "texts"), 256);
    if (texts.size() == 0) texts.fail("needs at least one text");
    for (const JsonValue& tv : texts.items()) {
      std::string t = detail::string(tv, false);
      if (t.size() > 200) tv.fail("an utterance is short: at most 200 bytes");
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
