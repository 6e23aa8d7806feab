#include "emoface/parlee/chart.hpp"

#include <algorithm>
#include <cmath>

#include "emoface/core/errors.hpp"

namespace emoface::parlee {

const std::vector<ChartEmotion>& chart_emotions() {
  static const std::vector<ChartEmotion> kEmotions = {{"fear", 3, {130, 40, 160}},
                                                      {"happiness", 1, {230, 140, 0}},
                                                      {"surprise", 5, {0, 140, 200}},
                                                      {"sadness", 0, {30, 60, 200}}};
  return kEmotions;
}

core::ChartAxis time_axis(double last_time, const std::string& label) {
  if (!std::isfinite(last_time)) throw InvalidInput("time_axis: the last time must be finite");
  core::ChartAxis axis;
  axis.min = 0;
  axis.max = std::ceil(std::max(last_time, 10.0) / 10) * 10;
  axis.grid_step = axis.tick_step = 10;
  axis.label = label;
  return axis;
}

double last_time(const std::vector<std::vector<StepRecord>>& runs) {
  double t = 0;
  for (const auto& run : runs)
    for (const auto& r : run)
      if (std::isfinite(r.time)) t = std::max(t, r.time);
  return t;
}

std::vector<core::ChartPanel> emotion_panels(const std::string& name,
                                             const std::vector<StepRecord>& run) {
  std::vector<core::ChartPanel> panels;
  for (const auto& c : chart_emotions()) {
    core::ChartPanel panel;
    panel.title = name + " " + c.name;
    panel.y.min = 0;
    panel.y.max = 1;
    panel.y.grid_step = panel.y.tick_step = 0.5;
    panel.y.label = "intensity";
    core::ChartSeries s;
    s.colour = c.rgb;
    s.name = c.name;
    for (const auto& r : run) {
      s.x.push_back(r.time);
      s.y.push_back(r.basic[c.basic]);
    }
    panel.series.push_back(std::move(s));
    panels.push_back(std::move(panel));
  }
  return panels;
}

}  // namespace emoface::parlee
