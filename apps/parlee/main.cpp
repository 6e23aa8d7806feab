// parlee — events → emotions with ParleE (thesis chapter 5) and Obie the football supporter (ch. 7).
#include <iostream>

#include "commands.hpp"
#include "emoface/cli/cli.hpp"

int main(int argc, char** argv) {
  using namespace emoface::parlee_app;
  CLI::App app{
      "parlee: probabilistic planning + OCC appraisal → emotion timelines (thesis ch. 5, 7).\n"
      "Examples:\n"
      "  parlee plan --domain data/parlee/rocket.domain --horizon 5\n"
      "  parlee run --domain data/parlee/football.domain --agent data/parlee/agents/neutral.json \\\n"
      "             --events data/parlee/match.ndjson --out timeline.ndjson --plot charts/\n"
      "  parlee interact --domain data/parlee/bread.domain --agent data/parlee/agents/bread_neutral.json",
      "parlee"};
  app.require_subcommand(1);

  PlanArgs plan;
  std::string problem;
  auto* p = app.add_subcommand("plan", "probability of achieving a goal within H steps and an optimal plan");
  p->add_option("--domain", plan.files, "domain file (thesis operator format or PPDDL)")->required()->expected(1);
  p->add_option("--problem", problem, "problem file (objects, initial state, goals)");
  p->add_option("--horizon", plan.horizon, "search depth H (turns)")->required()->check(CLI::Range(0, 64));
  p->add_option("--depth", plan.depth, "level d of the models of other agents (default H-1)")
      ->check(CLI::Range(-1, 64));
  p->add_option("--goal", plan.goal, "goal name (default: the first goal)");
  p->add_option("--semantics", plan.semantics, "within (default) or at_horizon");
  p->add_flag("--json", plan.json, "one JSON object instead of text");

  RunArgs run;
  auto* r = app.add_subcommand("run", "appraise a scripted event stream into an emotion timeline");
  r->add_option("--domain", run.files, "domain file")->required()->expected(1);
  r->add_option("--problem", problem, "problem file");
  r->add_option("--agent", run.agents, "agent file(s) (emoface.parlee_agent); repeat for several")->required();
  r->add_option("--events", run.events, "events, NDJSON {time, action, outcome}")->required();
  r->add_option("--out", run.out, "timeline NDJSON ('-' = stdout)")->required();
  r->add_option("--plot", run.plot_dir, "write PNG charts of fear, happiness, surprise, sadness here");
  r->add_option("--horizon", run.horizon, "override every agent's planning horizon H (turns)")
      ->check(CLI::Range(0, 64));
  r->add_option("--depth", run.depth, "override every agent's model depth d (-1 = H-1)")
      ->check(CLI::Range(-1, 64));

  InteractArgs inter;
  auto* i = app.add_subcommand("interact", "§5.9: you act in the domain, the agent responds and feels");
  i->add_option("--domain", inter.files, "domain file")->required()->expected(1);
  i->add_option("--problem", problem, "problem file");
  i->add_option("--agent", inter.agent, "agent file (default: neutral agent 'agent')");

  if (auto rc = emoface::cli::parse(app, argc, argv)) return *rc;
  return emoface::cli::run("parlee", [&]() {
    if (!problem.empty()) {
      plan.files.push_back(problem);
      run.files.push_back(problem);
      inter.files.push_back(problem);
    }
    if (*p) return plan_command(plan, std::cout);
    if (*r) return run_command(run);
    return interact_command(inter, std::cin, std::cout);
  });
}
