#pragma once
// The three `parlee` subcommands; main.cpp only parses arguments.
#include <iosfwd>
#include <string>
#include <vector>

namespace emoface::parlee_app {

struct PlanArgs {
  std::vector<std::string> files;  ///< domain, then optional problem
  int horizon = 3;
  int depth = -1;
  std::string goal;                ///< name; empty = first goal
  std::string semantics = "within";
  bool json = false;
};
int plan_command(const PlanArgs& args, std::ostream& out);

struct RunArgs {
  std::vector<std::string> files;
  std::vector<std::string> agents;
  std::string events;
  std::string out = "-";
  std::string plot_dir;
  int horizon = -1;  ///< overrides every agent's planning horizon; -1 = keep
  int depth = -2;    ///< overrides every agent's model depth; -2 = keep, -1 = H-1
};
int run_command(const RunArgs& args);

struct InteractArgs {
  std::vector<std::string> files;
  std::string agent;
};
int interact_command(const InteractArgs& args, std::istream& in, std::ostream& out);

}  // namespace emoface::parlee_app
