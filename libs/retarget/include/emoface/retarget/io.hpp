#pragma once
// The retarget report (JSON, envelope kind "retarget_report", version 1.0): alignment, landmarks
// (source, initial, final; detected or searched), GA report with the error curve. nlohmann-json stays
// behind this header. Output only: no emoface tool reads it back, so there is no reader.
#include <string>
#include <string_view>

#include "emoface/retarget/retarget.hpp"
#include "emoface/retarget/transfer.hpp"

namespace emoface::retarget {

inline constexpr int kReportFormatMajor = 1;
/// 1.1: alignment report (method, axis/angle, confidence, cues); 1.2: "transfer" section (mode transfer:
/// frame, registration, residuals per region, landmark confidence per iBUG point, parts, timings).
inline constexpr int kReportFormatMinor = 4;  // 1.3: transfer.lids; 1.4: alignment.refined/refine_*

/// Deterministic JSON (ends with a newline). `include_time` = false drops GaReport::seconds so that two
/// runs with the same seed give byte-identical files.
std::string format_report(const RetargetResult& result, bool include_time = true);
/// Writes atomically.
void write_report(const std::string& path, const RetargetResult& result, bool include_time = true);

/// The report of a transfer: everything of format_report for the fit plus a "transfer" object.
std::string format_transfer_report(const TransferResult& result, bool include_time = true);
void write_transfer_report(const std::string& path, const TransferResult& result, bool include_time = true);

/// User landmarks file (JSON, envelope kind "landmarks", version 1.0):
///   {"format": "emoface.landmarks", "version": "1.0", "scheme": "ibug68",
///    "points": [ 1234, [x, y, z], null, ... ]}      // exactly 68 entries, iBUG order (0-based)
/// An entry is a target vertex id (0-based integer), a point [x, y, z] in the mesh file's own frame and
/// units, or null (unknown). Throws FormatError naming the file and the JSON pointer of the problem
/// (wrong count, negative or non-integer ids, non-finite or malformed points, unknown fields).
/// Vertex ids are checked against the mesh by UserLandmarks::validate (transfer_rig).
inline constexpr int kLandmarksFormatMajor = 1;
inline constexpr int kLandmarksFormatMinor = 0;
UserLandmarks parse_landmarks(std::string_view text, const std::string& source = "<landmarks>");
std::string format_landmarks(const UserLandmarks& landmarks);
UserLandmarks read_landmarks(const std::string& path);
void write_landmarks(const std::string& path, const UserLandmarks& landmarks);

}  // namespace emoface::retarget
