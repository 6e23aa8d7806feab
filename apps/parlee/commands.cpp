#include "commands.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "emoface/cli/cli.hpp"
#include "emoface/core/io.hpp"
#include "emoface/parlee/agent.hpp"
#include "emoface/parlee/chart.hpp"
#include "emoface/parlee/io.hpp"

namespace emoface::parlee_app {
using namespace emoface::parlee;

int plan_command(const PlanArgs& a, std::ostream& out) {
  const Domain domain(read_domain_files(a.files));
  if (domain.goals().empty()) throw InvalidInput("the domain declares no goal");
  std::size_t goal = 0;
  if (!a.goal.empty()) {
    goal = domain.goals().size();
    for (std::size_t g = 0; g < domain.goals().size(); ++g)
      if (domain.goals()[g].name == a.goal) goal = g;
    if (goal == domain.goals().size()) throw InvalidInput("no goal named '" + a.goal + "'");
  }
  PlanOptions o;
  o.horizon = a.horizon;
  o.model_depth = a.depth;
  o.semantics = goal_semantics_from_string(a.semantics);
  Planner planner(domain, o);
  const PlanResult r = planner.plan(goal, domain.initial_state());
  const auto& g = domain.goals()[goal];
  const std::string& agent = domain.spec().agents[static_cast<std::size_t>(g.agent)];
  if (a.json) {
    nlohmann::ordered_json j;
    j["goal"] = g.name;
    j["agent"] = agent;
    j["horizon"] = o.horizon;
    j["model_depth"] = o.model_depth;
    j["semantics"] = a.semantics;
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
    return cli::kExitOk;
  }
  out << "goal " << g.name << " (agent " << agent << "), horizon " << o.horizon << ", model depth "
      << (o.model_depth < 0 ? o.horizon - 1 : o.model_depth) << "\n";
  out << (o.semantics == GoalSemantics::Within ? "P(goal within " : "P(goal holds after ") << o.horizon
      << " steps) = " << std::setprecision(10) << r.probability << "\n";
  out << "plan (own turns optimal, other agents most likely; expected outcome followed):\n";
  for (std::size_t k = 0; k < r.steps.size(); ++k) {
    const auto& s = r.steps[k];
    out << "  " << k + 1 << ". " << domain.spec().agents[static_cast<std::size_t>(s.agent)] << ": "
        << domain.action_text(s.action) << "  P(goal) after = " << std::setprecision(6) << s.value;
    if (s.agent != g.agent) out << "  P(chosen) = " << s.choice;
    out << "  -> " << domain.actions()[s.action].outcomes[s.outcome].label << "\n";
  }
  return cli::kExitOk;
}

namespace {

std::string time_axis_label(double unit_seconds) {
  if (unit_seconds == 60.0) return "time (minutes)";
  if (unit_seconds == 1.0) return "time (seconds)";
  std::ostringstream os;
  os << "time (units of " << unit_seconds << " s)";
  return os.str();
}

void plot_runs(const std::string& dir, const std::vector<std::string>& names,
               const std::vector<std::vector<StepRecord>>& runs, double unit_seconds) {
  std::filesystem::create_directories(dir);
  ChartOptions options;  // x_max: every chart of the run shares the longest run's axis
  options.x_max = 10;
  for (const auto& run : runs)
    for (const auto& r : run) options.x_max = std::max(options.x_max, r.time);
  options.x_max = std::ceil(options.x_max / 10) * 10;
  options.x_label = time_axis_label(unit_seconds);
  options.y_label = "intensity";
  std::vector<std::vector<ChartPanel>> per_run;
  for (std::size_t k = 0; k < runs.size(); ++k) {  // per personality: Figs. 7.4, 7.5, 7.7, 7.8
    per_run.push_back(emotion_panels(names[k], runs[k]));
    ChartOptions o = options;
    o.title = names[k] + ": felt basic emotions";
    core::write_file_atomic(dir + "/" + names[k] + ".png", render_chart(per_run.back(), o));
  }
  // per emotion, one line per personality in one panel: Figs. 7.10, 7.11
  static const std::array<std::array<std::uint8_t, 3>, 6> kPalette{
      {{40, 40, 40}, {230, 120, 0}, {30, 90, 210}, {200, 40, 40}, {40, 160, 60}, {150, 60, 170}}};
  const auto& emotions = chart_emotions();
  for (std::size_t c = 0; c < emotions.size(); ++c) {
    ChartPanel panel{std::string(emotions[c].name), {}, 1.0};
    for (std::size_t k = 0; k < per_run.size(); ++k) {
      ChartSeries s = per_run[k][c].series.front();
      s.name = names[k];
      s.rgb = kPalette[k % kPalette.size()];
      panel.series.push_back(std::move(s));
    }
    ChartOptions o = options;
    o.panel_height = 240;
    o.title = std::string(emotions[c].name) + ": one line per agent";
    core::write_file_atomic(dir + "/" + std::string(emotions[c].name) + ".png",
                            render_chart({panel}, o));
  }
}

}  // namespace

int run_command(const RunArgs& a) {
  const Domain domain(read_domain_files(a.files));
  const std::vector<Event> events = read_events_file(a.events);
  cli::Output out(a.out);  // writes devices and FIFOs directly, regular files atomically
  out.write(core::ndjson_header("parlee.timeline", {1, 1}));  // 1.1: skipped, active, shown
  std::vector<std::string> names;
  std::vector<std::vector<StepRecord>> runs;
  double unit_seconds = 0.0;
  for (const auto& file : a.agents) {
    AgentConfig config = read_agent_file(file);
    if (unit_seconds == 0.0) unit_seconds = config.time_unit_seconds;
    if (a.horizon >= 0) config.planning.horizon = a.horizon;
    if (a.depth >= -1) config.planning.model_depth = a.depth;
    Agent agent(domain, config);
    std::vector<StepRecord> run{agent.initial_record()};
    for (std::size_t i = 0; i < events.size(); ++i) {
      try {
        run.push_back(agent.step(events[i]));
      } catch (const InvalidInput& e) {
        throw FormatError(SourceLocation{a.events, "", i + 1, 0}, e.what());
      }
      if (!run.back().skipped.empty())  // the agent's model does not allow it: reported, skipped
        std::cerr << "parlee: warning: " << a.events << ":" << i + 1 << ": agent " << config.name
                  << ": skipped: " << run.back().skipped << "\n";
    }
    for (const auto& r : run) {
      std::string line = timeline_line(r);
      out.write("{\"agent\":" + nlohmann::json(config.name).dump() + "," + line.substr(1));
    }
    names.push_back(config.name);
    runs.push_back(std::move(run));
  }
  out.commit();
  if (!a.plot_dir.empty()) plot_runs(a.plot_dir, names, runs, unit_seconds);
  return cli::kExitOk;
}

int interact_command(const InteractArgs& a, std::istream& in, std::ostream& out) {
  const Domain domain(read_domain_files(a.files));
  AgentConfig config = a.agent.empty() ? AgentConfig{} : read_agent_file(a.agent);
  if (config.self.empty()) config.self = "agent";
  Agent agent(domain, config);
  double time = 0;
  for (;;) {
    out << "FACT: " << domain.state_text(agent.state()) << "\n\nChoose an action: (-1 to exit)\n0: No Action\n";
    const auto options = agent.applicable();
    for (std::size_t k = 0; k < options.size(); ++k) out << k + 1 << ": " << options[k] << "\n";
    out << "You choose: " << std::flush;
    long choice = 0;
    std::string line;
    if (!std::getline(in, line)) break;
    try {
      choice = std::stol(line);
    } catch (const std::exception&) {
      out << "\nplease type a number\n";
      continue;
    }
    if (choice < 0) break;
    if (static_cast<std::size_t>(choice) > options.size()) {
      out << "\nno such action\n";
      continue;
    }
    Event e;
    e.time = ++time;
    e.action = choice == 0 ? "" : options[static_cast<std::size_t>(choice - 1)];
    const StepRecord r = agent.step(e);
    out << "\n";
    for (const auto& act : r.actions) {
      if (act.action == "pass") continue;
      out << (act.actor == config.self ? "Agent" : "You") << " did: " << act.action << "\n" << act.outcome
          << " (with probability of " << std::setprecision(3) << 100.0 * act.p_event
          << " %) happened; effects: " << act.effects << "\n";
    }
    out << "Emotions:";
    for (std::size_t i = 0; i < kEmotionCount; ++i)
      if (r.emotions[i] >= 0.005) out << ' ' << to_string(static_cast<Emotion>(i)) << '=' << std::setprecision(2) << r.emotions[i];
    out << "\n\n";
  }
  return cli::kExitOk;
}

}  // namespace emoface::parlee_app
