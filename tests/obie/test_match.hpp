#pragma once
// The short match of the obie tests: the first 13 minutes of the §7.4 match (the against team
// scores at 12'), with the domain referenced by absolute path.
#include <string>

namespace emoface::obie::test {

inline std::string short_match_json(const std::string& extra_events = "") {
  return std::string(R"J({"format": "emoface.obie.match", "version": "1.0", "title": "short",
  "domain": ")J") + EMOFACE_SOURCE_DIR + R"J(/data/parlee/football.domain",
  "teams": {"for": {"side": "team", "name": "For"}, "against": {"side": "oteam", "name": "Against"}},
  "duration": 14,
  "events": [
    {"minute": 1, "action": "(re-kickoff team)", "outcome": "started", "note": "kick-off"},
    {"minute": 2, "action": "(pass-from-hf team)", "outcome": "kept"},
    {"minute": 3, "action": "(pass-from-hf team)", "outcome": "kept"},
    {"minute": 4, "action": "(pass-from-hf team)", "outcome": "advanced"},
    {"minute": 5, "action": "(tackle-in-hf oteam)", "outcome": "won"},
    {"minute": 6, "action": "(pass-from-hf oteam)", "outcome": "kept"},
    {"minute": 7, "action": "(pass-from-hf oteam)", "outcome": "advanced"},
    {"minute": 8, "action": "(pass-from-ohf oteam)", "outcome": "kept"},
    {"minute": 9, "action": "(block-in-hf team)", "outcome": "nothing"},
    {"minute": 10, "action": "(pass-from-ohf oteam)", "outcome": "advanced"},
    {"minute": 11, "action": "(block-in-pr team)", "outcome": "nothing"},
    {"minute": 12, "action": "(shot oteam)", "outcome": "goal", "note": "0-1"},
    {"minute": 13, "action": "(re-kickoff team)", "outcome": "started"})J" +
         extra_events + R"J(],
  "key_moments": [{"minute": 0, "label": "start"}, {"minute": 12, "label": "0-1"}]})J";
}

}  // namespace emoface::obie::test
