#pragma once
// The retarget report (JSON, envelope kind "retarget_report", version 1.0): alignment, landmarks
// (source, initial, final; detected or searched), GA report with the error curve. nlohmann-json stays
// behind this header. Output only: no emoface tool reads it back, so there is no reader.
#include <string>

#include "emoface/retarget/retarget.hpp"

namespace emoface::retarget {

inline constexpr int kReportFormatMajor = 1;
inline constexpr int kReportFormatMinor = 1;  ///< 1.1: alignment report (method, axis/angle, confidence, cues)

/// Deterministic JSON (ends with a newline). `include_time` = false drops GaReport::seconds so that two
/// runs with the same seed give byte-identical files.
std::string format_report(const RetargetResult& result, bool include_time = true);
/// Writes atomically.
void write_report(const std::string& path, const RetargetResult& result, bool include_time = true);

}  // namespace emoface::retarget
