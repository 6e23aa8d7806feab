#pragma once
// The match script (`emoface.obie.match`, JSON, version 1.0): what Obie watches (thesis §7.4).
//
//   {"format": "emoface.obie.match", "version": "1.0", "generator": "emoface x.y.z",
//    "title": "Obie's match (thesis §7.4)",
//    "domain": "../parlee/football.domain",            // parlee domain file(s), relative to this file
//    "teams": {"for": {"side": "team", "name": "For"}, "against": {"side": "oteam", "name": "Against"}},
//    "duration": 90,                                    // match minutes
//    "goal_outcomes": ["goal"],                         // outcome labels that count as a goal
//    "events": [{"minute": 12, "action": "(shot oteam)", "outcome": "goal", "note": "…"}, …],
//    "key_moments": [{"minute": 12, "label": "against 0-1"}, …],
//    "commentary": [{"minute": 12, "text": "…"}]}      // optional
//
// Events use parlee's vocabulary (docs/parlee.md, "Events"): `action` is a domain action of the agent
// on turn (a prefix of its arguments is enough, "" = pass), `outcome` a label, "case-N" or a 1-based
// number ("" = sampled with the agent's seed), optional `feedback` in [−1, 1] and `note`.
// Minutes must not decrease. Errors are FormatError with the file and a JSON pointer.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "emoface/parlee/agent.hpp"

namespace emoface::obie {

inline constexpr int kMatchFormatMajor = 1;
inline constexpr int kMatchFormatMinor = 0;

struct Team {
  std::string side;  ///< the domain object of this side (e.g. "team", "oteam")
  std::string name;  ///< shown in summaries (e.g. "For")
};

struct MatchEvent {
  double minute = 0.0;             ///< match minute, in [0, duration]
  std::string action;              ///< parlee action text, "" = the agent on turn passes
  std::string outcome;             ///< outcome label, "case-N", 1-based number, or "" (sampled)
  std::optional<double> feedback;  ///< feedback in [−1, 1] on the supporter's own last action
  std::string note;
};

struct KeyMoment {
  double minute = 0.0;  ///< in [0, duration]
  std::string label;
};

struct Commentary {
  double minute = 0.0;
  std::string text;  ///< non-empty
};

struct MatchScript {
  std::string title;
  std::vector<std::string> domain;  ///< domain file(s) as written: relative to base_dir unless absolute
  std::string base_dir;             ///< directory of the script file (not stored; "" = current directory)
  Team for_team{"team", "For"};
  Team against_team{"oteam", "Against"};
  double duration = 90.0;           ///< match minutes, in (0, 1000]
  std::vector<std::string> goal_outcomes{"goal"};
  std::vector<MatchEvent> events;
  std::vector<KeyMoment> key_moments;
  std::vector<Commentary> commentary;

  /// Domain paths resolved against base_dir.
  std::vector<std::string> domain_paths() const;
  /// Throws InvalidInput naming the field (the reader reports the same checks with a JSON pointer).
  void validate() const;
};

/// Most events a script may hold (a 90-minute match has about 100).
inline constexpr std::size_t kMaxMatchEvents = 100000;

/// Parses a match script; `file` names it in errors and sets base_dir to its directory.
MatchScript parse_match(std::string_view text, const std::string& file);
MatchScript read_match_file(const std::string& path);
/// Serialises (envelope with generator, deterministic, one event per line, ends with a newline).
std::string write_match(const MatchScript& match);

/// The script's events as parlee events (time = minute).
std::vector<parlee::Event> to_parlee_events(const MatchScript& match);

/// Builds a script from parlee events (e.g. data/parlee/match.ndjson): events copied (time → minute),
/// duration = max(90, last minute). Key moments and teams are the caller's.
MatchScript match_from_events(const std::vector<parlee::Event>& events);

}  // namespace emoface::obie
