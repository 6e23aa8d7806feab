#pragma once
// What the parlee CLI prints and writes, as library calls (issue 18, item 4): the plan report (text
// or JSON), an agent run over an events file, the run's NDJSON timeline, and its charts staged into
// a core::OutputBundle (all files written or none).
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "emoface/core/bundle.hpp"
#include "emoface/parlee/agent.hpp"
#include "emoface/parlee/planner.hpp"

namespace emoface::parlee {

/// Index of the goal named `name` (empty: the first); InvalidInput if there is none.
std::size_t goal_index(const Domain& domain, const std::string& name);

/// The plan of `result` for goal `goal`: one JSON object and '\n' (goal, agent, horizon,
/// model_depth, semantics, probability, states_evaluated, plan steps), or the readable text.
std::string format_plan(const Domain& domain, std::size_t goal, const PlanOptions& options,
                        const PlanResult& result, bool json);

/// One agent over `events`: the initial record, then one per event. An event the agent cannot take
/// (InvalidInput) is a FormatError at `events_file` line i+1; an event its model does not allow is
/// skipped and reported through `warn` (the record's `skipped`).
std::vector<StepRecord> run_agent(
    const Domain& domain, const AgentConfig& config, const std::vector<Event>& events,
    const std::string& events_file,
    const std::function<void(std::size_t line, const std::string& why)>& warn = nullptr);

/// The NDJSON timeline lines of one run, each record prefixed with {"agent": name, …}.
std::string agent_timeline(const std::string& agent_name, const std::vector<StepRecord>& run);

/// The charts of several runs staged into `bundle` under `dir`: "<name>.png" per run (Figs. 7.4,
/// 7.5, 7.7, 7.8) and "<emotion>.png" per basic emotion with one line per run (Figs. 7.10, 7.11),
/// every chart on the longest run's time axis; `unit_seconds` labels it.
void stage_run_charts(core::OutputBundle& bundle, const std::string& dir,
                      const std::vector<std::string>& names,
                      const std::vector<std::vector<StepRecord>>& runs, double unit_seconds);

}  // namespace emoface::parlee
