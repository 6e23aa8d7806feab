#pragma once
// Files of the channels library. JSON documents carry the emoface envelope:
//   emoface.channels.visemes   viseme targets, dominance parameters, phoneme → viseme table
//   emoface.channels.conflicts the conflict table (pairs with a rationale)
//   emoface.tracks             parameter tracks at a fixed frame rate:
//                              {"fps": 100, "names": [...], "frames": [[v, ...], ...]}
// and parameter tracks as CSV: a header "time,<name>,..." and one row per frame (time = frame/fps,
// seconds). Readers throw FormatError naming the file and JSON pointer (or line/column for CSV).
#include <string>
#include <string_view>

#include "emoface/channels/conflicts.hpp"
#include "emoface/channels/dominance.hpp"
#include "emoface/channels/mixer.hpp"

namespace emoface::channels {

VisemeSet parse_visemes(std::string_view json_text, const std::string& file = "<visemes>");
std::string format_visemes(const VisemeSet& set);
VisemeSet read_visemes(const std::string& path);
void write_visemes(const std::string& path, const VisemeSet& set);

ConflictTable parse_conflicts(std::string_view json_text, const std::string& file = "<conflicts>");
std::string format_conflicts(const ConflictTable& table);
ConflictTable read_conflicts(const std::string& path);
void write_conflicts(const std::string& path, const ConflictTable& table);

Tracks parse_tracks_json(std::string_view json_text, const std::string& file = "<tracks>");
std::string format_tracks_json(const Tracks& tracks);
/// CSV reader: the frame rate is recovered from the time column, which must be uniform (frame f at
/// f/fps within 1e-6 s).
Tracks parse_tracks_csv(std::string_view csv_text, const std::string& file = "<tracks>");
std::string format_tracks_csv(const Tracks& tracks);
/// By the extension of `path`: ".csv" → CSV, anything else (including "-") → JSON.
std::string format_tracks(const Tracks& tracks, const std::string& path);
/// By extension: ".csv" → CSV, anything else → JSON.
Tracks read_tracks(const std::string& path);
void write_tracks(const std::string& path, const Tracks& tracks);

}  // namespace emoface::channels
