#include "commands.hpp"

#include <iomanip>
#include <iostream>

#include "emoface/cli/cli.hpp"
#include "emoface/core/bundle.hpp"
#include "emoface/core/io.hpp"
#include "emoface/parlee/agent.hpp"
#include "emoface/parlee/io.hpp"
#include "emoface/parlee/report.hpp"

namespace emoface::parlee_app {
using namespace emoface::parlee;

int plan_command(const PlanArgs& a, std::ostream& out) {
  const Domain domain(read_domain_files(a.files));
  const std::size_t goal = goal_index(domain, a.goal);
  PlanOptions o;
  o.horizon = a.horizon;
  o.model_depth = a.depth;
  o.semantics = goal_semantics_from_string(a.semantics);
  Planner planner(domain, o);
  out << format_plan(domain, goal, o, planner.plan(goal, domain.initial_state()), a.json);
  return cli::kExitOk;
}

// Every agent over the events; the timeline (stdout or a file) and the charts are written together,
// or nothing is (core::OutputBundle).
int run_command(const RunArgs& a) {
  const Domain domain(read_domain_files(a.files));
  const std::vector<Event> events = read_events_file(a.events);
  std::string timeline =
      core::ndjson_header("parlee.timeline", {1, 1});  // 1.1: skipped, active, shown
  std::vector<std::string> names;
  std::vector<std::vector<StepRecord>> runs;
  double unit_seconds = 0.0;
  for (const auto& file : a.agents) {
    AgentConfig config = read_agent_file(file);
    if (unit_seconds == 0.0) unit_seconds = config.time_unit_seconds;
    if (a.horizon >= 0) config.planning.horizon = a.horizon;
    if (a.depth >= -1) config.planning.model_depth = a.depth;
    runs.push_back(
        run_agent(domain, config, events, a.events, [&](std::size_t line, const std::string& why) {
          std::cerr << "parlee: warning: " << a.events << ":" << line << ": agent " << config.name
                    << ": skipped: " << why << "\n";
        }));
    timeline += agent_timeline(config.name, runs.back());
    names.push_back(config.name);
  }
  core::OutputBundle bundle;
  bundle.add(a.out, timeline);
  if (!a.plot_dir.empty()) stage_run_charts(bundle, a.plot_dir, names, runs, unit_seconds);
  bundle.commit();
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
