#pragma once
// Files of the mindmap library (layouts in docs/mindmap.md):
//   mind maps      JSON, format "emoface.mindmap" 1.x, nodes referred to by name
//   events         NDJSON, one stimulus per line: {"time":1.5,"to":"bob","stimulus":"gift",
//                  "from":"alice"} or a world stimulus {"time":3,"to":"*","stimulus":"explosion",
//                  "weights":{"fear":0.9,"surprise":0.7}}
//   mood timeline  CSV: time,<emotion>... per character
//   actions        NDJSON (one TriggeredAction per line) or CSV
#include <string>
#include <string_view>
#include <vector>

#include "emoface/mindmap/mind_map.hpp"
#include "emoface/mindmap/simulation.hpp"

namespace emoface::mindmap {

inline constexpr std::string_view kMindMapKind = "mindmap";

/// Parses and validates a mind map. Every problem (bad JSON, envelope, missing mandatory traits,
/// dangling edges, array sizes not matching the emotion nodes, weights out of range, duplicates)
/// throws FormatError naming `file` and the JSON pointer of the offending field. When `known_labels`
/// is not empty, every expression label must be one of them (e.g. the labels of a motion graph).
MindMap parse_mind_map(std::string_view json_text, const std::string& file = "<mindmap>",
                       const std::vector<std::string>& known_labels = {});
MindMap read_mind_map(const std::string& path, const std::vector<std::string>& known_labels = {});
/// A version-1.0 document; parse_mind_map(to_json_text(m)) == m for valid maps.
std::string to_json_text(const MindMap& map);
void write_mind_map(const MindMap& map, const std::string& path);
/// Every "*.json" file of `dir` (sorted by file name). Throws FormatError/IoError; InvalidInput for
/// two maps of the same character or an empty directory.
std::vector<MindMap> read_mind_map_dir(const std::string& dir,
                                       const std::vector<std::string>& known_labels = {});

/// Parses an events stream (NDJSON; blank lines and lines starting with '#' are skipped). Errors are
/// FormatError with file and line (and the JSON pointer of the field).
std::vector<Event> parse_events(std::string_view text, const std::string& file = "<events>");
std::vector<Event> read_events(const std::string& path);
std::string events_to_ndjson(const std::vector<Event>& events);

/// CSV "time,<emotion 1>,..." of one character of a simulation result (6 decimals).
std::string mood_timeline_csv(const SimulationResult& result, const MindMap& map, std::size_t character);
/// One JSON object per action: time, character, action, label, emotion, mood, cause, stimulus, depth.
std::string actions_to_ndjson(const std::vector<TriggeredAction>& actions);
/// Inverse of actions_to_ndjson (FormatError with line on bad input).
std::vector<TriggeredAction> parse_actions(std::string_view text, const std::string& file = "<actions>");
/// Same columns as CSV with a header row.
std::string actions_to_csv(const std::vector<TriggeredAction>& actions);

}  // namespace emoface::mindmap
