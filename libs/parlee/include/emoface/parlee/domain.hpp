#pragma once
// ParleE planning domains (thesis §5.7.1, Fig. 5.4): probabilistic STRIPS operators, typed objects,
// facts, an initial state, agents taking turns, and goals with priority, importance and deadline.
//
// Two text formats parse into the same DomainSpec (docs/parlee.md, "Domain language"):
//  * the thesis' operator format, extended with declarations:
//      (types CARGO ROCKET PLACE AGENT)
//      (predicates (at 2) (in 2) (has-fuel 1))          ; name and arity
//      (objects (c1 CARGO) (r1 ROCKET) (london PLACE))
//      (agents pilot)                                   ; agents are objects; order = turn order
//      (turn is-acting)                                 ; optional: (is-acting X) marks X's turn
//      (operator LOAD (params (<o> CARGO) (<p> PLACE))
//        (preconds (at <o> <p>) (not (in <o> r1)))
//        (effects (0.9 loaded (in <o> r1) (del at <o> <p>)) (0.1)))
//      (initial (at c1 london))
//      (goal deliver (agent pilot) (priority 1) (importance 1.0) (deadline 0)
//        (facts (at c1 paris)))                         ; or (any-of (facts …) (facts …))
//  * a PPDDL subset: (define (domain N) (:types …) (:predicates …) (:action …)) and
//    (define (problem N) (:domain N) (:objects …) (:init …) (:goal (and …))).
// Outcome probabilities of an operator must each lie in [0,1] and sum to ≤ 1; the remainder is an
// implicit "nothing happens" outcome.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "emoface/core/errors.hpp"

namespace emoface::parlee {

/// A (possibly lifted) atom: predicate and arguments; an argument "<x>" or "?x" is a variable.
struct Atom {
  std::string predicate;
  std::vector<std::string> args;
  SourceLocation where;
};

struct OutcomeSpec {
  double probability = 0.0;  ///< in [0,1]
  std::string label;         ///< optional name ("goal"); empty = "case-<n>" (1-based)
  std::vector<Atom> add;
  std::vector<Atom> del;
  SourceLocation where;
};

struct OperatorSpec {
  std::string name;
  std::vector<std::string> param_vars;   ///< "<o>" / "?o"
  std::vector<std::string> param_types;  ///< type per parameter ("" = any object)
  std::vector<Atom> preconds;
  std::vector<Atom> negative_preconds;
  std::vector<OutcomeSpec> outcomes;     ///< explicit outcomes; remainder = no change
  SourceLocation where;
};

struct GoalSpec {
  std::string name;
  std::string agent;         ///< whose goal; empty = the first agent
  int priority = 0;          ///< higher is planned first (§5.7.4)
  double importance = 1.0;   ///< Import(goal) of §5.6.1, ≥ 0
  int deadline = 0;          ///< time (event clock) by which the goal must hold; 0 = none
  std::vector<std::vector<Atom>> alternatives;  ///< goal holds if all atoms of any alternative hold
  SourceLocation where;
};

struct ObjectSpec {
  std::string name;
  std::string type;
};

struct PredicateSpec {
  std::string name;
  std::size_t arity = 0;
};

/// Everything a domain (and problem) file declares, before grounding.
struct DomainSpec {
  std::string name;
  std::vector<std::string> types;
  std::vector<PredicateSpec> predicates;
  std::vector<ObjectSpec> objects;
  std::vector<std::string> agents;
  std::string turn_predicate;  ///< empty: the first agent always acts
  std::vector<OperatorSpec> operators;
  std::vector<Atom> initial;
  std::vector<GoalSpec> goals;
};

/// Parses thesis-format or PPDDL text and adds its declarations to `spec` (so a problem file can
/// extend a domain file). Throws FormatError (file:line:column) on malformed s-expressions,
/// truncated files, bad numbers, probabilities outside [0,1] or summing to more than 1, unknown
/// sections; names are checked by compile().
void parse_domain_text(const std::string& text, const std::string& file, DomainSpec& spec);

/// Reads and parses one or more files into one spec (domain first, then problem files).
DomainSpec read_domain_files(const std::vector<std::string>& files);

/// Writes a spec in the thesis format; parse_domain_text(write_domain_text(s)) gives back s.
std::string write_domain_text(const DomainSpec& spec);

/// A world state: the set of true ground facts as a bitset over Domain::facts().
struct State {
  std::vector<std::uint64_t> bits;
  bool has(std::size_t fact) const noexcept { return (bits[fact >> 6] >> (fact & 63)) & 1u; }
  void set(std::size_t fact) noexcept { bits[fact >> 6] |= std::uint64_t{1} << (fact & 63); }
  void reset(std::size_t fact) noexcept { bits[fact >> 6] &= ~(std::uint64_t{1} << (fact & 63)); }
  bool operator==(const State& o) const noexcept { return bits == o.bits; }
  bool operator!=(const State& o) const noexcept { return bits != o.bits; }
};

struct StateHash {
  std::size_t operator()(const State& s) const noexcept;
};

struct GroundOutcome {
  double probability = 0.0;
  std::string label;
  std::vector<std::uint32_t> add;
  std::vector<std::uint32_t> del;
};

struct GroundAction {
  std::size_t op = 0;                   ///< index into DomainSpec::operators
  std::vector<std::string> args;        ///< bound objects, parameter order
  int actor = -1;                       ///< agent index, -1 = any agent may take it
  std::vector<std::uint32_t> pre;       ///< facts that must hold (static ones removed)
  std::vector<std::uint32_t> pre_not;   ///< facts that must not hold
  std::vector<GroundOutcome> outcomes;  ///< includes the implicit no-change outcome if > 0
};

struct GroundGoal {
  std::string name;
  int agent = 0;
  int priority = 0;
  double importance = 1.0;
  int deadline = 0;
  std::vector<std::vector<std::uint32_t>> alternatives;
};

struct CompileOptions {
  std::size_t max_ground_actions = 200000;  ///< refuse bigger groundings (count, ≥ 1)
  std::size_t max_facts = 65536;            ///< refuse more ground facts (count, ≥ 1)
  void validate() const;
};

/// A grounded domain: facts numbered, operators instantiated over typed objects (bindings whose
/// static preconditions fail in the initial state are dropped), goals compiled.
class Domain {
 public:
  /// Grounds `spec`. Throws FormatError (with the declaration's location) for unknown
  /// predicates, objects, types or agents, wrong arities, unbound variables.
  explicit Domain(DomainSpec spec, CompileOptions options = {});

  const DomainSpec& spec() const noexcept { return spec_; }
  const std::vector<std::string>& facts() const noexcept { return facts_; }  ///< "(at c1 paris)"
  const std::vector<GroundAction>& actions() const noexcept { return actions_; }
  const std::vector<GroundGoal>& goals() const noexcept { return goals_; }
  std::size_t agent_count() const noexcept { return spec_.agents.size(); }
  int agent_index(const std::string& name) const;  ///< -1 if unknown
  const State& initial_state() const noexcept { return initial_; }
  State empty_state() const;

  /// Fact id of a ground atom text "(at c1 paris)"; -1 if not a fact of this domain.
  long fact_id(const std::string& text) const;
  /// The agent whose turn it is in `s` (index into spec().agents).
  int turn(const State& s) const noexcept;
  bool applicable(const GroundAction& a, const State& s) const noexcept;
  /// Indices of the actions the agent on turn may take in `s`.
  std::vector<std::size_t> applicable_actions(const State& s) const;
  /// Successor of `s` under outcome `k` of action `a` (delete, then add; then the turn passes).
  State apply(const State& s, std::size_t action, std::size_t outcome) const;
  /// The state after the agent on turn passes without acting.
  State pass_turn(const State& s) const;
  bool goal_holds(std::size_t goal, const State& s) const noexcept;

  /// "(load c1 r1 london)".
  std::string action_text(std::size_t action) const;
  /// Parses "(load c1 r1 london)" (a prefix of the arguments is enough when unambiguous among
  /// `candidates`); -1 if no candidate matches, -2 if several do.
  long find_action(const std::string& text, const std::vector<std::size_t>& candidates) const;
  /// "(at c1 london) (in c2 r1)".
  std::string state_text(const State& s) const;

  /// Replaces the outcome probabilities of every ground action of operator `op` (learning, §5.8).
  /// `probabilities` has one entry per ground outcome, each in [0,1], summing to 1 ± 1e-9.
  void set_outcome_probabilities(std::size_t op, const std::vector<double>& probabilities);

 private:
  DomainSpec spec_;
  std::vector<std::string> facts_;
  std::vector<GroundAction> actions_;
  std::vector<GroundGoal> goals_;
  State initial_;
  std::vector<long> turn_fact_;  ///< per agent: fact id of (turn agent) or -1
  std::size_t words_ = 1;
  std::vector<std::pair<std::string, std::uint32_t>> fact_index_;  ///< sorted for lookup
};

}  // namespace emoface::parlee
