#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "emoface/core/chart.hpp"
#include "emoface/core/image.hpp"
#include "emoface/core/io.hpp"
#include "emoface/obie/pipeline.hpp"
#include "emoface/parlee/chart.hpp"
#include "emoface/parlee/io.hpp"

namespace emoface::obie {

namespace {

std::string minute_text(double minute) {
  char buf[32];
  if (std::floor(minute) == minute) std::snprintf(buf, sizeof buf, "%d'", static_cast<int>(minute));
  else std::snprintf(buf, sizeof buf, "%.1f'", minute);
  return buf;
}

double round6(double x) { return std::round(x * 1e6) / 1e6; }

}  // namespace

core::Image emotion_chart(const ObieResult& result) {
  core::ChartSpec spec;
  spec.width = 960;
  spec.x = parlee::time_axis(parlee::last_time({result.timeline}), "match minute");
  spec.panels = parlee::emotion_panels(result.agent_name, result.timeline);
  for (auto& panel : spec.panels) panel.height = 120;
  for (const auto& g : result.goals)
    spec.markers.push_back({g.minute,
                            std::to_string(g.for_score) + "-" + std::to_string(g.against_score),
                            {200, 60, 60}});
  spec.title = "obie (" + result.agent_name + "): felt basic emotions, goals marked with the score";
  return core::draw_chart(spec);
}

core::Image key_moment_sheet(const ObieResult& result) {
  if (result.key_frames.empty()) throw InvalidInput("key_moment_sheet: the match has no key moments");
  const int w = result.key_frames.front().image.width, h = result.key_frames.front().image.height;
  const int caption = 44, gap = 6;
  const int n = static_cast<int>(result.key_frames.size());
  const int columns = std::min(n, 4), rows = (n + columns - 1) / columns;
  core::Image sheet(columns * w + (columns + 1) * gap, rows * (h + caption) + (rows + 1) * gap);
  for (int i = 0; i < n; ++i) {
    const auto& kf = result.key_frames[static_cast<std::size_t>(i)];
    if (kf.image.width != w || kf.image.height != h) throw InvalidInput("key_moment_sheet: frames differ in size");
    const int x0 = gap + (i % columns) * (w + gap), y0 = gap + (i / columns) * (h + caption + gap);
    core::blit(sheet, kf.image, x0, y0);
    const std::string line2 = "shows: " + expression_text(kf.shown);
    std::string line1 = minute_text(kf.moment.minute) + " " + kf.moment.label;
    const int max_chars = std::max(1, (w - 8) / 8);
    if (static_cast<int>(line1.size()) > max_chars) line1.resize(static_cast<std::size_t>(max_chars));
    core::draw_text(sheet, x0 + 4, y0 + h + 6, line1, {30, 30, 30}, 2);
    core::draw_text(sheet, x0 + 4, y0 + h + 24, line2, {120, 40, 40}, 2);
  }
  return sheet;
}

std::string format_timeline(const ObieResult& result) {
  std::string out = core::ndjson_header("obie.timeline", {1, 0});
  const std::string agent = nlohmann::json(result.agent_name).dump();
  for (std::size_t k = 0; k < result.timeline.size(); ++k) {
    const std::string line = parlee::timeline_line(result.timeline[k]);
    out += "{\"agent\":" + agent + ",\"anim_time\":" + nlohmann::json(round6(result.step_seconds[k])).dump() + "," +
           line.substr(1);
  }
  return out;
}

std::string format_summary(const ObieResult& result, const MatchScript& match, bool timings) {
  auto doc = core::make_envelope("obie.summary", core::FormatVersion{1, 0});
  doc["match"] = match.title;
  doc["agent"] = result.agent_name;
  doc["teams"] = {{"for", match.for_team.name}, {"against", match.against_team.name}};
  int f = 0, a = 0;
  nlohmann::ordered_json goals = nlohmann::ordered_json::array();
  for (const auto& g : result.goals) {
    goals.push_back({{"minute", g.minute}, {"team", g.team}, {"side", g.side}, {"score", std::to_string(g.for_score) + "-" + std::to_string(g.against_score)}});
    f = g.for_score;
    a = g.against_score;
  }
  doc["final_score"] = std::to_string(f) + "-" + std::to_string(a);
  doc["goals"] = goals;
  nlohmann::ordered_json peaks = nlohmann::ordered_json::object();
  for (const auto& p : result.peaks) peaks[p.emotion] = {{"value", round6(p.value)}, {"minute", p.minute}};
  doc["peaks"] = peaks;
  nlohmann::ordered_json utt = nlohmann::ordered_json::array();
  for (const auto& u : result.utterances)
    utt.push_back({{"minute", u.minute}, {"time", round6(u.time)}, {"emotion", u.emotion},
                   {"intensity", round6(u.intensity)}, {"text", u.text}});
  doc["utterances"] = utt;
  nlohmann::ordered_json km = nlohmann::ordered_json::array();
  for (const auto& k : result.key_frames)
    km.push_back({{"minute", k.moment.minute},
                  {"label", k.moment.label},
                  {"time", round6(k.time)},
                  {"frame", k.frame},
                  {"shows", expression_text(k.shown)}});
  doc["key_moments"] = km;
  doc["fps"] = result.head.tracks.fps;
  doc["frames"] = result.frames;
  doc["frames_rendered"] = result.frames_rendered;
  doc["seconds"] = round6(result.seconds());
  doc["audio_samples"] = result.head.audio.size();
  doc["sample_rate"] = result.head.sample_rate;
  doc["match_minutes"] = match.duration;
  if (timings) {
    nlohmann::ordered_json t = nlohmann::ordered_json::object();
    double total = 0;
    for (const auto& s : result.timings) {
      t[s.stage] = std::round(s.seconds * 1000) / 1000;
      total += s.seconds;
    }
    t["total"] = std::round(total * 1000) / 1000;
    doc["timings_s"] = t;
  }
  return doc.dump(2) + "\n";
}

}  // namespace emoface::obie
