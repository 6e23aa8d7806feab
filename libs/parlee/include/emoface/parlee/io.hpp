#pragma once
// Files of the parlee library (docs/parlee.md, "File formats"):
//  * agent file  — JSON, envelope "emoface.parlee_agent" 1.0: personality (16 named dimensions),
//                  thresholds, decay, effect matrix, motivation, planning, learning, liking, standards
//  * events      — NDJSON, one Event per line: {"time":12,"action":"(shot oteam)","outcome":"goal"}
//  * timeline    — NDJSON, one StepRecord per line (every emotion by name, the ESV, goals, events)
#include <string>
#include <vector>

#include "emoface/parlee/agent.hpp"

namespace emoface::parlee {

/// Parses an agent document; missing fields keep AgentConfig defaults. Throws FormatError naming
/// `file` and the JSON pointer for wrong types, unknown names, out-of-range values.
AgentConfig parse_agent(const std::string& text, const std::string& file);
AgentConfig read_agent_file(const std::string& path);
/// Every field, so parse_agent(write_agent(c)) == c.
std::string write_agent(const AgentConfig& config);

/// Parses NDJSON events (blank lines skipped). Errors name the line.
std::vector<Event> parse_events(const std::string& text, const std::string& file);
std::vector<Event> read_events_file(const std::string& path);
std::string write_events(const std::vector<Event>& events);

/// One NDJSON line (with '\n') for a step.
std::string timeline_line(const StepRecord& record);

}  // namespace emoface::parlee
