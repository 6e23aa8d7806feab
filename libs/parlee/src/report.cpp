#include "emoface/parlee/report.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "emoface/parlee/chart.hpp"
#include "emoface/parlee/io.hpp"

namespace emoface::parlee {

std::size_t goal_index(const Domain& domain, const std::string& name) {
  if (domain.goals().empty()) throw InvalidInput("the domain declares no goal");
  if (name.empty()) return 0;
  for (std::size_t g = 0; g < domain.goals().size(); ++g)
    if (domain.goals()[g].name == name) return g;
  throw InvalidInput("no goal named '" + name + "'");
}

std::string format_plan(const Domain& domain, std::size_t goal, const PlanOptions& o,
                        const PlanResult& r, bool json) {
  const auto& g = domain.goals().at(goal);
  const std::string& agent = domain.spec().agents[static_cast<std::size_t>(g.agent)];
  std::ostringstream out;
  if (json) {
    nlohmann::ordered_json j;
    j["goal"] = g.name;
    j["agent"] = agent;
    j["horizon"] = o.horizon;
    j["model_depth"] = o.model_depth;
    j["semantics"] = to_string(o.semantics);
    j["probability"] = r.probability;
    j["states_evaluated"] = r.states_evaluated;
    nlohmann::ordered_json steps = nlohmann::ordered_json::array();
    for (const auto& s : r.steps)
      steps.push_back({{"agent", domain.spec().agents[static_cast<std::size_t>(s.agent)]},
                       {"action", domain.action_text(s.action)},
                       {"p_choice", s.choice},
                       {"p_goal_after", s.value},
                       {"expected_outcome", domain.actions()[s.action].outcomes[s.outcome].label}});
    j["plan"] = steps;
    out << j.dump() << '\n';
    return out.str();
  }
  out << "goal " << g.name << " (agent " << agent << "), horizon " << o.horizon << ", model depth "
      << (o.model_depth < 0 ? o.horizon - 1 : o.model_depth) << "\n";
  out << (o.semantics == GoalSemantics::Within ? "P(goal within " : "P(goal holds after ")
      << o.horizon << " steps) = " << std::setprecision(10) << r.probability << "\n";
  out << "plan (own turns optimal, other agents most likely; expected outcome followed):\n";
  for (std::size_t k = 0; k < r.steps.size(); ++k) {
    const auto& s = r.steps[k];
    out << "  " << k + 1 << ". " << domain.spec().agents[static_cast<std::size_t>(s.agent)] << ": "
        << domain.action_text(s.action) << "  P(goal) after = " << std::setprecision(6) << s.value;
    if (s.agent != g.agent) out << "  P(chosen) = " << s.choice;
    out << "  -> " << domain.actions()[s.action].outcomes[s.outcome].label << "\n";
  }
  return out.str();
}

std::vector<StepRecord> run_agent(
    const Domain& domain, const AgentConfig& config, const std::vector<Event>& events,
    const std::string& events_file,
    const std::function<void(std::size_t, const std::string&)>& warn) {
  Agent agent(domain, config);
  std::vector<StepRecord> run{agent.initial_record()};
  for (std::size_t i = 0; i < events.size(); ++i) {
    try {
      run.push_back(agent.step(events[i]));
    } catch (const InvalidInput& e) {
      throw FormatError(SourceLocation{events_file, "", i + 1, 0}, e.what());
    }
    if (!run.back().skipped.empty() && warn) warn(i + 1, run.back().skipped);
  }
  return run;
}

std::string agent_timeline(const std::string& agent_name, const std::vector<StepRecord>& run) {
  std::string out;
  const std::string prefix = "{\"agent\":" + nlohmann::json(agent_name).dump() + ",";
  for (const auto& r : run) out += prefix + timeline_line(r).substr(1);
  return out;
}

namespace {

std::string time_axis_label(double unit_seconds) {
  if (unit_seconds == 60.0) return "time (minutes)";
  if (unit_seconds == 1.0) return "time (seconds)";
  std::ostringstream os;
  os << "time (units of " << unit_seconds << " s)";
  return os.str();
}

}  // namespace

void stage_run_charts(core::OutputBundle& bundle, const std::string& dir,
                      const std::vector<std::string>& names,
                      const std::vector<std::vector<StepRecord>>& runs, double unit_seconds) {
  if (names.size() != runs.size()) throw InvalidInput("stage_run_charts: one name per run");
  core::ChartSpec spec;  // every chart of the run shares the longest run's time axis
  spec.width = 960;
  spec.x = time_axis(last_time(runs), time_axis_label(unit_seconds));
  std::vector<std::vector<core::ChartPanel>> per_run;
  for (std::size_t k = 0; k < runs.size(); ++k) {  // per personality: Figs. 7.4, 7.5, 7.7, 7.8
    per_run.push_back(emotion_panels(names[k], runs[k]));
    core::ChartSpec s = spec;
    s.panels = per_run.back();
    s.title = names[k] + ": felt basic emotions";
    bundle.add(dir + "/" + names[k] + ".png", core::encode_png(core::draw_chart(s)));
  }
  // per emotion, one line per personality in one panel: Figs. 7.10, 7.11
  static const std::array<std::array<std::uint8_t, 3>, 6> kPalette{
      {{40, 40, 40}, {230, 120, 0}, {30, 90, 210}, {200, 40, 40}, {40, 160, 60}, {150, 60, 170}}};
  const auto& emotions = chart_emotions();
  for (std::size_t c = 0; c < emotions.size(); ++c) {
    core::ChartPanel panel = emotion_panels("", {}).at(c);
    panel.title = emotions[c].name;
    panel.height = 240;
    panel.series.clear();
    for (std::size_t k = 0; k < per_run.size(); ++k) {
      core::ChartSeries s = per_run[k][c].series.front();
      s.name = names[k];
      s.colour = kPalette[k % kPalette.size()];
      panel.series.push_back(std::move(s));
    }
    core::ChartSpec s = spec;
    s.panels = {panel};
    s.title = std::string(emotions[c].name) + ": one line per agent";
    bundle.add(dir + "/" + std::string(emotions[c].name) + ".png",
               core::encode_png(core::draw_chart(s)));
  }
}

}  // namespace emoface::parlee
