#pragma once
// Emotion charts (thesis Figs. 7.4–7.11): what parlee puts on them — one panel per charted emotion
// (fear, happiness, surprise, sadness, with their colours), intensity 0 … 1, time in match minutes
// with a grid line and a tick value every 10 — as core::ChartPanel / core::ChartAxis values drawn
// by core::draw_chart, the one chart routine (issue 18 item 3). Used by `parlee run --plot`
// (stage_run_charts, report.hpp) and by the obie pipeline (libs/obie), so both draw the same
// charts.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "emoface/core/chart.hpp"
#include "emoface/parlee/agent.hpp"

namespace emoface::parlee {

/// The four emotions of the thesis' charts, with their basic-emotion index (ESV order) and colour:
/// fear, happiness, surprise, sadness (Figs. 7.4, 7.5, 7.7, 7.8).
struct ChartEmotion {
  const char* name;
  std::size_t basic;  ///< index into StepRecord::basic (sadness, happiness, anger, fear, disgust, surprise)
  std::array<std::uint8_t, 3> rgb;
};
const std::vector<ChartEmotion>& chart_emotions();

/// The time axis of the emotion charts: [0, last_time rounded up to a multiple of 10 (at least
/// 10)], a grid line and a tick value every 10 units, titled `label`. Throws InvalidInput for a
/// last_time that is not finite.
core::ChartAxis time_axis(double last_time, const std::string& label);

/// One panel per chart_emotions() entry for one run: titled "<name> <emotion>", the basic
/// intensity over StepRecord::time as a 2-pixel line named by the emotion (for the legend), on a y
/// axis [0, 1] titled "intensity" with grid lines and tick values at 0, 0.5 and 1, 150 pixels high.
std::vector<core::ChartPanel> emotion_panels(const std::string& name,
                                             const std::vector<StepRecord>& run);

/// The longest time of the runs (0 for none): the end of their common time axis.
double last_time(const std::vector<std::vector<StepRecord>>& runs);

}  // namespace emoface::parlee
