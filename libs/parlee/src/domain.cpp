#include "emoface/parlee/domain.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <unordered_map>

#include "emoface/core/io.hpp"
#include "emoface/core/text.hpp"
#include "sexpr.hpp"

namespace emoface::parlee {
namespace {

using detail::SNode;

[[noreturn]] void fail(const std::string& file, const SNode& at, const std::string& msg) {
  throw FormatError(SourceLocation{file, "", at.line, at.column}, msg);
}
[[noreturn]] void fail_at(const SourceLocation& at, const std::string& msg) { throw FormatError(at, msg); }

SourceLocation loc(const std::string& file, const SNode& n) { return {file, "", n.line, n.column}; }

const std::string& sym(const std::string& file, const SNode& n, const char* what) {
  if (n.is_list) fail(file, n, std::string("expected ") + what + ", found a list");
  return n.atom;
}

double number(const std::string& file, const SNode& n, const char* what) {
  const std::string& s = sym(file, n, what);
  // The locale-free parser of every emoface reader; "inf"/"nan" are numbers, but not finite ones.
  const std::optional<double> v = core::parse_number(s, true);
  if (!v) fail(file, n, std::string("expected ") + what + ", found '" + s + "'");
  if (!std::isfinite(*v)) fail(file, n, std::string(what) + " is not finite");
  return *v;
}

int integer(const std::string& file, const SNode& n, const char* what) {
  const double v = number(file, n, what);
  if (v != std::floor(v) || std::fabs(v) > 1e9) fail(file, n, std::string(what) + " must be an integer");
  return static_cast<int>(v);
}


bool is_var(const std::string& s) {
  return (s.size() >= 3 && s.front() == '<' && s.back() == '>') || (s.size() >= 2 && s[0] == '?');
}

Atom atom_from(const std::string& file, const SNode& n, std::size_t skip = 0) {
  if (!n.is_list || n.items.size() <= skip) fail(file, n, "expected an atom like (pred arg …)");
  Atom a;
  a.where = loc(file, n);
  a.predicate = sym(file, n.items[skip], "a predicate name");
  for (std::size_t i = skip + 1; i < n.items.size(); ++i) a.args.push_back(sym(file, n.items[i], "an argument"));
  return a;
}

// ---------------------------------------------------------------- thesis format
void parse_outcome(const std::string& file, const SNode& n, OperatorSpec& op) {
  if (!n.is_list || n.items.empty()) fail(file, n, "expected an outcome (probability effects…)");
  OutcomeSpec out;
  out.where = loc(file, n);
  out.probability = number(file, n.items[0], "an outcome probability");
  if (out.probability < 0.0 || out.probability > 1.0) fail(file, n.items[0], "outcome probability outside [0,1]");
  std::size_t i = 1;
  if (i < n.items.size() && !n.items[i].is_list) out.label = n.items[i++].atom;
  for (; i < n.items.size(); ++i) {
    const SNode& e = n.items[i];
    if (!e.is_list || e.items.empty()) fail(file, e, "expected an effect (pred …) or (del pred …)");
    const std::string head =
        e.items[0].is_list ? std::string() : core::ascii_lower(e.items[0].atom);
    if (head == "del") {
      if (e.items.size() >= 2 && e.items[1].is_list) out.del.push_back(atom_from(file, e.items[1]));
      else out.del.push_back(atom_from(file, e, 1));
    } else if (head == "add" && e.items.size() == 2 && e.items[1].is_list) {
      out.add.push_back(atom_from(file, e.items[1]));
    } else {
      out.add.push_back(atom_from(file, e));
    }
  }
  op.outcomes.push_back(std::move(out));
}

void check_outcome_sum(const std::string& file, const SNode& at, const OperatorSpec& op) {
  double sum = 0.0;
  for (const auto& o : op.outcomes) sum += o.probability;
  if (sum > 1.0 + 1e-9) {
    std::ostringstream msg;
    msg << "outcome probabilities of '" << op.name << "' sum to " << sum << " > 1";
    fail(file, at, msg.str());
  }
}

void parse_operator(const std::string& file, const SNode& n, DomainSpec& spec) {
  if (n.items.size() < 2) fail(file, n, "operator without a name");
  OperatorSpec op;
  op.where = loc(file, n);
  op.name = sym(file, n.items[1], "an operator name");
  for (std::size_t i = 2; i < n.items.size(); ++i) {
    const SNode& sec = n.items[i];
    if (!sec.is_list || sec.items.empty()) fail(file, sec, "expected (params …), (preconds …) or (effects …)");
    const std::string head = core::ascii_lower(sym(file, sec.items[0], "a section name"));
    if (head == "params") {
      for (std::size_t k = 1; k < sec.items.size(); ++k) {
        const SNode& p = sec.items[k];
        if (!p.is_list || p.items.empty() || p.items.size() > 2) fail(file, p, "expected a parameter (<var> TYPE)");
        const std::string& v = sym(file, p.items[0], "a variable");
        if (!is_var(v)) fail(file, p.items[0], "parameter '" + v + "' is not a variable (<name> or ?name)");
        op.param_vars.push_back(v);
        op.param_types.push_back(p.items.size() == 2 ? sym(file, p.items[1], "a type") : std::string());
      }
    } else if (head == "preconds") {
      for (std::size_t k = 1; k < sec.items.size(); ++k) {
        const SNode& p = sec.items[k];
        if (p.is_list && p.items.size() == 2 && !p.items[0].is_list &&
            core::ascii_lower(p.items[0].atom) == "not")
          op.negative_preconds.push_back(atom_from(file, p.items[1]));
        else
          op.preconds.push_back(atom_from(file, p));
      }
    } else if (head == "effects") {
      for (std::size_t k = 1; k < sec.items.size(); ++k) parse_outcome(file, sec.items[k], op);
      check_outcome_sum(file, sec, op);
    } else {
      fail(file, sec, "unknown operator section '" + head + "'");
    }
  }
  spec.operators.push_back(std::move(op));
}

std::vector<Atom> parse_fact_list(const std::string& file, const SNode& n, std::size_t from) {
  std::vector<Atom> out;
  for (std::size_t k = from; k < n.items.size(); ++k) out.push_back(atom_from(file, n.items[k]));
  return out;
}

void parse_goal(const std::string& file, const SNode& n, DomainSpec& spec) {
  if (n.items.size() < 2) fail(file, n, "goal without a name");
  GoalSpec g;
  g.where = loc(file, n);
  g.name = sym(file, n.items[1], "a goal name");
  for (std::size_t i = 2; i < n.items.size(); ++i) {
    const SNode& sec = n.items[i];
    if (!sec.is_list || sec.items.empty()) fail(file, sec, "expected a goal section");
    const std::string head = core::ascii_lower(sym(file, sec.items[0], "a section name"));
    auto one = [&]() -> const SNode& {
      if (sec.items.size() != 2) fail(file, sec, "(" + head + " …) takes one value");
      return sec.items[1];
    };
    if (head == "agent") g.agent = sym(file, one(), "an agent");
    else if (head == "priority") g.priority = integer(file, one(), "a priority");
    else if (head == "importance") {
      g.importance = number(file, one(), "an importance");
      if (g.importance < 0.0 || g.importance > 1e6) fail(file, sec, "importance must be in [0, 1e6]");
    } else if (head == "deadline") {
      g.deadline = integer(file, one(), "a deadline");
      if (g.deadline < 0) fail(file, sec, "deadline must be ≥ 0");
    } else if (head == "facts") {
      g.alternatives.push_back(parse_fact_list(file, sec, 1));
    } else if (head == "any-of") {
      for (std::size_t k = 1; k < sec.items.size(); ++k) {
        const SNode& f = sec.items[k];
        if (!f.is_list || f.items.empty() || f.items[0].is_list ||
            core::ascii_lower(f.items[0].atom) != "facts")
          fail(file, f, "any-of takes (facts …) alternatives");
        g.alternatives.push_back(parse_fact_list(file, f, 1));
      }
    } else {
      fail(file, sec, "unknown goal section '" + head + "'");
    }
  }
  if (g.alternatives.empty()) fail(file, n, "goal '" + g.name + "' has no (facts …)");
  spec.goals.push_back(std::move(g));
}

void parse_thesis_form(const std::string& file, const SNode& n, DomainSpec& spec) {
  const std::string head = core::ascii_lower(sym(file, n.items[0], "a form name"));
  if (head == "domain") {
    if (n.items.size() != 2) fail(file, n, "(domain NAME)");
    spec.name = sym(file, n.items[1], "a domain name");
  } else if (head == "types") {
    for (std::size_t i = 1; i < n.items.size(); ++i) spec.types.push_back(sym(file, n.items[i], "a type"));
  } else if (head == "predicates") {
    for (std::size_t i = 1; i < n.items.size(); ++i) {
      const SNode& p = n.items[i];
      if (!p.is_list || p.items.size() != 2) fail(file, p, "expected (name arity)");
      const int arity = integer(file, p.items[1], "an arity");
      if (arity < 0 || arity > 16) fail(file, p.items[1], "arity must be in [0,16]");
      spec.predicates.push_back({sym(file, p.items[0], "a predicate"), static_cast<std::size_t>(arity)});
    }
  } else if (head == "objects") {
    for (std::size_t i = 1; i < n.items.size(); ++i) {
      const SNode& p = n.items[i];
      if (p.is_list) {
        if (p.items.empty() || p.items.size() > 2) fail(file, p, "expected (object TYPE)");
        spec.objects.push_back({sym(file, p.items[0], "an object"),
                                p.items.size() == 2 ? sym(file, p.items[1], "a type") : std::string()});
      } else {
        spec.objects.push_back({p.atom, std::string()});
      }
    }
  } else if (head == "agents") {
    for (std::size_t i = 1; i < n.items.size(); ++i) spec.agents.push_back(sym(file, n.items[i], "an agent"));
  } else if (head == "turn") {
    if (n.items.size() != 2) fail(file, n, "(turn PREDICATE)");
    spec.turn_predicate = sym(file, n.items[1], "a predicate");
  } else if (head == "operator") {
    parse_operator(file, n, spec);
  } else if (head == "initial") {
    auto facts = parse_fact_list(file, n, 1);
    spec.initial.insert(spec.initial.end(), facts.begin(), facts.end());
  } else if (head == "goal") {
    parse_goal(file, n, spec);
  } else {
    fail(file, n, "unknown form '" + head + "'");
  }
}

// ---------------------------------------------------------------- PPDDL subset
// typed list: a b - T c - U d  → (name, type)
std::vector<std::pair<std::string, std::string>> typed_list(const std::string& file, const SNode& n,
                                                             std::size_t from) {
  std::vector<std::pair<std::string, std::string>> out;
  std::size_t pending = 0;
  for (std::size_t i = from; i < n.items.size(); ++i) {
    const std::string& s = sym(file, n.items[i], "a name");
    if (s == "-") {
      if (i + 1 >= n.items.size()) fail(file, n.items[i], "'-' without a type");
      const std::string& t = sym(file, n.items[i + 1], "a type");
      for (std::size_t k = out.size() - pending; k < out.size(); ++k) out[k].second = t;
      pending = 0;
      ++i;
    } else {
      out.emplace_back(s, std::string());
      ++pending;
    }
  }
  return out;
}

bool head_is(const SNode& n, const char* h) {
  return n.is_list && !n.items.empty() && !n.items[0].is_list &&
         core::ascii_lower(n.items[0].atom) == h;
}

// Conjunction of literals: (and l…) or a literal.
void ppddl_literals(const std::string& file, const SNode& n, std::vector<Atom>& pos, std::vector<Atom>& neg) {
  if (head_is(n, "and")) {
    for (std::size_t i = 1; i < n.items.size(); ++i) ppddl_literals(file, n.items[i], pos, neg);
  } else if (head_is(n, "not")) {
    if (n.items.size() != 2) fail(file, n, "(not ATOM)");
    neg.push_back(atom_from(file, n.items[1]));
  } else {
    pos.push_back(atom_from(file, n));
  }
}

void ppddl_effect(const std::string& file, const SNode& n, OperatorSpec& op) {
  std::vector<Atom> det_add, det_del;
  const SNode* prob = nullptr;
  auto visit = [&](const SNode& e) {
    if (head_is(e, "probabilistic")) {
      if (prob) fail(file, e, "only one probabilistic effect per action is supported");
      prob = &e;
    } else {
      ppddl_literals(file, e, det_add, det_del);
    }
  };
  if (head_is(n, "and")) {
    for (std::size_t i = 1; i < n.items.size(); ++i) visit(n.items[i]);
  } else {
    visit(n);
  }
  double sum = 0.0;
  if (prob) {
    if ((prob->items.size() - 1) % 2 != 0) fail(file, *prob, "probabilistic takes probability/effect pairs");
    for (std::size_t i = 1; i + 1 < prob->items.size(); i += 2) {
      OutcomeSpec out;
      out.where = loc(file, prob->items[i]);
      out.probability = number(file, prob->items[i], "an outcome probability");
      if (out.probability < 0.0 || out.probability > 1.0) fail(file, prob->items[i], "outcome probability outside [0,1]");
      ppddl_literals(file, prob->items[i + 1], out.add, out.del);
      out.add.insert(out.add.end(), det_add.begin(), det_add.end());
      out.del.insert(out.del.end(), det_del.begin(), det_del.end());
      sum += out.probability;
      op.outcomes.push_back(std::move(out));
    }
    check_outcome_sum(file, *prob, op);
  }
  if ((!det_add.empty() || !det_del.empty()) && sum < 1.0 - 1e-12) {
    OutcomeSpec rest;
    rest.where = loc(file, n);
    rest.probability = 1.0 - sum;
    rest.add = det_add;
    rest.del = det_del;
    op.outcomes.push_back(std::move(rest));
  }
}

void parse_ppddl(const std::string& file, const SNode& n, DomainSpec& spec) {
  if (n.items.size() < 2 || !n.items[1].is_list || n.items[1].items.size() != 2)
    fail(file, n, "expected (define (domain NAME) …) or (define (problem NAME) …)");
  const std::string kind = core::ascii_lower(sym(file, n.items[1].items[0], "domain or problem"));
  if (kind != "domain" && kind != "problem") fail(file, n.items[1], "expected (domain NAME) or (problem NAME)");
  if (kind == "domain") spec.name = sym(file, n.items[1].items[1], "a name");
  for (std::size_t i = 2; i < n.items.size(); ++i) {
    const SNode& sec = n.items[i];
    if (!sec.is_list || sec.items.empty()) fail(file, sec, "expected a (:section …)");
    const std::string head = core::ascii_lower(sym(file, sec.items[0], "a section name"));
    if (head == ":requirements" || head == ":domain") {
      continue;
    } else if (head == ":types") {
      for (auto& [name, parent] : typed_list(file, sec, 1)) spec.types.push_back(name);
    } else if (head == ":predicates") {
      for (std::size_t k = 1; k < sec.items.size(); ++k) {
        const SNode& p = sec.items[k];
        if (!p.is_list || p.items.empty()) fail(file, p, "expected (pred ?x - type …)");
        spec.predicates.push_back({sym(file, p.items[0], "a predicate"), typed_list(file, p, 1).size()});
      }
    } else if (head == ":constants" || head == ":objects") {
      for (auto& [name, type] : typed_list(file, sec, 1)) spec.objects.push_back({name, type});
    } else if (head == ":agents") {
      for (std::size_t k = 1; k < sec.items.size(); ++k) spec.agents.push_back(sym(file, sec.items[k], "an agent"));
    } else if (head == ":turn") {
      if (sec.items.size() != 2) fail(file, sec, "(:turn PREDICATE)");
      spec.turn_predicate = sym(file, sec.items[1], "a predicate");
    } else if (head == ":init") {
      auto facts = parse_fact_list(file, sec, 1);
      spec.initial.insert(spec.initial.end(), facts.begin(), facts.end());
    } else if (head == ":goal") {
      if (sec.items.size() != 2) fail(file, sec, "(:goal FORMULA)");
      GoalSpec g;
      g.where = loc(file, sec);
      g.name = spec.name.empty() ? "goal" : "goal" + std::to_string(spec.goals.size());
      std::vector<Atom> pos, neg;
      ppddl_literals(file, sec.items[1], pos, neg);
      if (!neg.empty()) fail(file, sec, "negative goals are not supported");
      g.alternatives.push_back(std::move(pos));
      spec.goals.push_back(std::move(g));
    } else if (head == ":action") {
      if (sec.items.size() < 2) fail(file, sec, "action without a name");
      OperatorSpec op;
      op.where = loc(file, sec);
      op.name = sym(file, sec.items[1], "an action name");
      for (std::size_t k = 2; k < sec.items.size(); ++k) {
        const std::string key = core::ascii_lower(sym(file, sec.items[k], "a keyword"));
        if (k + 1 >= sec.items.size()) fail(file, sec.items[k], "keyword '" + key + "' without a value");
        const SNode& v = sec.items[++k];
        if (key == ":parameters") {
          if (!v.is_list) fail(file, v, "expected a parameter list");
          for (auto& [name, type] : typed_list(file, v, 0)) {
            if (!is_var(name)) fail(file, v, "parameter '" + name + "' is not a ?variable");
            op.param_vars.push_back(name);
            op.param_types.push_back(type);
          }
        } else if (key == ":precondition") {
          ppddl_literals(file, v, op.preconds, op.negative_preconds);
        } else if (key == ":effect") {
          ppddl_effect(file, v, op);
        } else {
          fail(file, sec.items[k - 1], "unknown action keyword '" + key + "'");
        }
      }
      spec.operators.push_back(std::move(op));
    } else {
      fail(file, sec, "unknown PPDDL section '" + head + "'");
    }
  }
}

std::string atom_text(const std::string& pred, const std::vector<std::string>& args) {
  std::string s = "(" + pred;
  for (const auto& a : args) s += " " + a;
  return s + ")";
}

std::string fmt_num(double v) {
  std::ostringstream o;
  o.precision(17);
  o << v;
  return o.str();
}

}  // namespace

void parse_domain_text(const std::string& text, const std::string& file, DomainSpec& spec) {
  const auto forms = detail::parse_sexprs(text, file);
  for (const auto& n : forms) {
    if (n.items.empty() || n.items[0].is_list) fail(file, n, "expected a named form");
    if (core::ascii_lower(n.items[0].atom) == "define")
      parse_ppddl(file, n, spec);
    else parse_thesis_form(file, n, spec);
  }
}

DomainSpec read_domain_files(const std::vector<std::string>& files) {
  DomainSpec spec;
  for (const auto& f : files) parse_domain_text(core::read_file(f, std::size_t{16} << 20), f, spec);
  return spec;
}

std::string write_domain_text(const DomainSpec& spec) {
  std::ostringstream out;
  if (!spec.name.empty()) out << "(domain " << spec.name << ")\n";
  if (!spec.types.empty()) {
    out << "(types";
    for (const auto& t : spec.types) out << ' ' << t;
    out << ")\n";
  }
  out << "(predicates";
  for (const auto& p : spec.predicates) out << " (" << p.name << ' ' << p.arity << ')';
  out << ")\n(objects";
  for (const auto& ob : spec.objects) {
    if (ob.type.empty()) out << ' ' << ob.name;
    else out << " (" << ob.name << ' ' << ob.type << ')';
  }
  out << ")\n";
  if (!spec.agents.empty()) {
    out << "(agents";
    for (const auto& a : spec.agents) out << ' ' << a;
    out << ")\n";
  }
  if (!spec.turn_predicate.empty()) out << "(turn " << spec.turn_predicate << ")\n";
  for (const auto& op : spec.operators) {
    out << "(operator " << op.name << "\n  (params";
    for (std::size_t i = 0; i < op.param_vars.size(); ++i) {
      out << " (" << op.param_vars[i];
      if (!op.param_types[i].empty()) out << ' ' << op.param_types[i];
      out << ')';
    }
    out << ")\n  (preconds";
    for (const auto& a : op.preconds) out << ' ' << atom_text(a.predicate, a.args);
    for (const auto& a : op.negative_preconds) out << " (not " << atom_text(a.predicate, a.args) << ')';
    out << ")\n  (effects";
    for (const auto& oc : op.outcomes) {
      out << "\n    (" << fmt_num(oc.probability);
      if (!oc.label.empty()) out << ' ' << oc.label;
      for (const auto& a : oc.add) out << ' ' << atom_text(a.predicate, a.args);
      for (const auto& a : oc.del) out << " (del " << atom_text(a.predicate, a.args) << ')';
      out << ')';
    }
    out << "))\n";
  }
  if (!spec.initial.empty()) {
    out << "(initial";
    for (const auto& a : spec.initial) out << ' ' << atom_text(a.predicate, a.args);
    out << ")\n";
  }
  for (const auto& g : spec.goals) {
    out << "(goal " << g.name;
    if (!g.agent.empty()) out << " (agent " << g.agent << ')';
    out << " (priority " << g.priority << ") (importance " << fmt_num(g.importance) << ") (deadline "
        << g.deadline << ")\n  (any-of";
    for (const auto& alt : g.alternatives) {
      out << " (facts";
      for (const auto& a : alt) out << ' ' << atom_text(a.predicate, a.args);
      out << ')';
    }
    out << "))\n";
  }
  return out.str();
}

// ---------------------------------------------------------------- grounding

std::size_t StateHash::operator()(const State& s) const noexcept {
  std::uint64_t h = 1469598103934665603ull;
  for (std::uint64_t w : s.bits) {
    h ^= w + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
    h *= 1099511628211ull;
  }
  return static_cast<std::size_t>(h);
}

void CompileOptions::validate() const {
  if (max_ground_actions < 1) throw InvalidInput("CompileOptions::max_ground_actions must be ≥ 1");
  if (max_facts < 1) throw InvalidInput("CompileOptions::max_facts must be ≥ 1");
}

Domain::Domain(DomainSpec spec, CompileOptions options) : spec_(std::move(spec)) {
  options.validate();
  if (spec_.agents.empty()) spec_.agents.push_back("self");
  // types
  std::set<std::string> types(spec_.types.begin(), spec_.types.end());
  std::map<std::string, std::size_t> arity;
  for (const auto& p : spec_.predicates)
    if (!arity.emplace(p.name, p.arity).second) throw FormatError({}, "predicate '" + p.name + "' declared twice");
  std::map<std::string, std::string> object_type;
  for (const auto& ob : spec_.objects) {
    if (!ob.type.empty() && !types.empty() && !types.count(ob.type))
      throw FormatError({}, "object '" + ob.name + "' has unknown type '" + ob.type + "'");
    if (!object_type.emplace(ob.name, ob.type).second) throw FormatError({}, "object '" + ob.name + "' declared twice");
  }
  {
    std::set<std::string> ops, goals;
    for (const auto& op : spec_.operators)
      if (!ops.insert(op.name).second) fail_at(op.where, "operator '" + op.name + "' declared twice");
    for (const auto& g : spec_.goals)
      if (!goals.insert(g.name).second) fail_at(g.where, "goal '" + g.name + "' declared twice");
  }
  {
    std::set<std::string> seen;
    for (const auto& a : spec_.agents) {
      if (!seen.insert(a).second) throw FormatError({}, "agent '" + a + "' declared twice");
      if (!object_type.count(a)) {
        const std::string t = types.count("AGENT") ? "AGENT" : "";
        spec_.objects.push_back({a, t});
        object_type[a] = t;
      }
    }
  }
  if (!spec_.turn_predicate.empty()) {
    auto it = arity.find(spec_.turn_predicate);
    if (it == arity.end() || it->second != 1)
      throw FormatError({}, "turn predicate '" + spec_.turn_predicate + "' must be a declared predicate of arity 1");
  }
  auto check_atom = [&](const Atom& a, const std::vector<std::string>* vars) {
    auto it = arity.find(a.predicate);
    if (it == arity.end()) fail_at(a.where, "unknown predicate '" + a.predicate + "'");
    if (it->second != a.args.size())
      fail_at(a.where, "predicate '" + a.predicate + "' takes " + std::to_string(it->second) + " arguments, got " +
                           std::to_string(a.args.size()));
    for (const auto& arg : a.args) {
      if (is_var(arg)) {
        if (!vars || std::find(vars->begin(), vars->end(), arg) == vars->end())
          fail_at(a.where, "unbound variable '" + arg + "'");
      } else if (!object_type.count(arg)) {
        fail_at(a.where, "unknown object '" + arg + "'");
      }
    }
  };
  // static predicates: never in any effect
  std::set<std::string> dynamic;
  if (!spec_.turn_predicate.empty()) dynamic.insert(spec_.turn_predicate);
  for (const auto& op : spec_.operators) {
    for (const auto& o : op.outcomes) {
      for (const auto& a : o.add) dynamic.insert(a.predicate);
      for (const auto& a : o.del) dynamic.insert(a.predicate);
    }
  }
  std::set<std::string> init_text;
  for (const auto& a : spec_.initial) {
    check_atom(a, nullptr);
    init_text.insert(atom_text(a.predicate, a.args));
  }
  std::unordered_map<std::string, std::uint32_t> ids;
  auto fact = [&](const std::string& text) -> std::uint32_t {
    auto it = ids.find(text);
    if (it != ids.end()) return it->second;
    if (facts_.size() >= options.max_facts)
      throw FormatError({}, "more than " + std::to_string(options.max_facts) + " ground facts");
    const auto id = static_cast<std::uint32_t>(facts_.size());
    facts_.push_back(text);
    ids.emplace(text, id);
    return id;
  };
  for (const auto& a : spec_.initial) fact(atom_text(a.predicate, a.args));
  turn_fact_.assign(spec_.agents.size(), -1);
  if (!spec_.turn_predicate.empty())
    for (std::size_t i = 0; i < spec_.agents.size(); ++i)
      turn_fact_[i] = fact(atom_text(spec_.turn_predicate, {spec_.agents[i]}));

  std::vector<std::string> all_objects;
  for (const auto& ob : spec_.objects) all_objects.push_back(ob.name);
  for (std::size_t oi = 0; oi < spec_.operators.size(); ++oi) {
    const OperatorSpec& op = spec_.operators[oi];
    {
      std::set<std::string> seen;
      for (const auto& v : op.param_vars)
        if (!seen.insert(v).second) fail_at(op.where, "parameter '" + v + "' declared twice");
    }
    for (const auto& t : op.param_types)
      if (!t.empty() && !types.empty() && !types.count(t)) fail_at(op.where, "unknown type '" + t + "'");
    for (const auto& a : op.preconds) check_atom(a, &op.param_vars);
    for (const auto& a : op.negative_preconds) check_atom(a, &op.param_vars);
    for (const auto& o : op.outcomes) {
      for (const auto& a : o.add) check_atom(a, &op.param_vars);
      for (const auto& a : o.del) check_atom(a, &op.param_vars);
    }
    std::vector<std::vector<std::string>> domains;
    for (const auto& t : op.param_types) {
      std::vector<std::string> d;
      for (const auto& ob : spec_.objects)
        if (t.empty() || ob.type == t) d.push_back(ob.name);
      domains.push_back(std::move(d));
    }
    const std::size_t np = domains.size();
    std::vector<std::size_t> idx(np, 0);
    bool empty = std::any_of(domains.begin(), domains.end(), [](const auto& d) { return d.empty(); });
    std::vector<std::string> binding(np);
    auto bind = [&](const Atom& a) {
      std::vector<std::string> args;
      for (const auto& x : a.args) {
        if (is_var(x)) {
          const auto k = static_cast<std::size_t>(
              std::find(op.param_vars.begin(), op.param_vars.end(), x) - op.param_vars.begin());
          args.push_back(binding[k]);
        } else {
          args.push_back(x);
        }
      }
      return atom_text(a.predicate, args);
    };
    double explicit_sum = 0.0;
    for (const auto& o : op.outcomes) explicit_sum += o.probability;
    std::size_t enumerated = 0;
    while (!empty) {
      if (++enumerated > options.max_ground_actions * 64)
        fail_at(op.where, "grounding of '" + op.name + "' is too large");
      for (std::size_t k = 0; k < np; ++k) binding[k] = domains[k][idx[k]];
      bool ok = true;
      GroundAction g;
      g.op = oi;
      g.args = binding;
      for (const auto& a : op.preconds) {
        const std::string t = bind(a);
        if (!dynamic.count(a.predicate)) {
          if (!init_text.count(t)) { ok = false; break; }
        } else {
          g.pre.push_back(fact(t));
          if (a.predicate == spec_.turn_predicate) {
            const std::string& who = is_var(a.args[0]) ? binding[static_cast<std::size_t>(
                std::find(op.param_vars.begin(), op.param_vars.end(), a.args[0]) - op.param_vars.begin())] : a.args[0];
            const int ag = agent_index(who);
            if (ag < 0) fail_at(a.where, "turn predicate argument is not an agent");
            g.actor = ag;
          }
        }
      }
      if (ok) {
        for (const auto& a : op.negative_preconds) {
          const std::string t = bind(a);
          if (!dynamic.count(a.predicate)) {
            if (init_text.count(t)) { ok = false; break; }
          } else {
            g.pre_not.push_back(fact(t));
          }
        }
      }
      if (ok) {
        for (std::size_t k = 0; k < op.outcomes.size(); ++k) {
          const auto& o = op.outcomes[k];
          GroundOutcome go;
          go.probability = o.probability;
          go.label = o.label.empty() ? "case-" + std::to_string(k + 1) : o.label;
          for (const auto& a : o.add) go.add.push_back(fact(bind(a)));
          for (const auto& a : o.del) go.del.push_back(fact(bind(a)));
          g.outcomes.push_back(std::move(go));
        }
        if (explicit_sum < 1.0 - 1e-12) {
          GroundOutcome rest;
          rest.probability = 1.0 - explicit_sum;
          rest.label = "nothing";
          g.outcomes.push_back(std::move(rest));
        }
        if (actions_.size() >= options.max_ground_actions)
          fail_at(op.where, "more than " + std::to_string(options.max_ground_actions) + " ground actions");
        actions_.push_back(std::move(g));
      }
      std::size_t k = np;
      while (k > 0) {
        --k;
        if (++idx[k] < domains[k].size()) break;
        idx[k] = 0;
        if (k == 0) { empty = true; break; }
      }
      if (np == 0) break;
    }
  }
  for (const auto& g : spec_.goals) {
    GroundGoal gg;
    gg.name = g.name;
    gg.agent = g.agent.empty() ? 0 : agent_index(g.agent);
    if (gg.agent < 0) fail_at(g.where, "goal '" + g.name + "' names unknown agent '" + g.agent + "'");
    gg.priority = g.priority;
    gg.importance = g.importance;
    gg.deadline = g.deadline;
    for (const auto& alt : g.alternatives) {
      std::vector<std::uint32_t> ids_alt;
      for (const auto& a : alt) {
        check_atom(a, nullptr);
        ids_alt.push_back(fact(atom_text(a.predicate, a.args)));
      }
      gg.alternatives.push_back(std::move(ids_alt));
    }
    goals_.push_back(std::move(gg));
  }
  words_ = std::max<std::size_t>(1, (facts_.size() + 63) / 64);
  initial_ = empty_state();
  for (const auto& a : spec_.initial) initial_.set(ids.at(atom_text(a.predicate, a.args)));
  for (const auto& [text, id] : ids) fact_index_.emplace_back(text, id);
  std::sort(fact_index_.begin(), fact_index_.end());
}

int Domain::agent_index(const std::string& name) const {
  for (std::size_t i = 0; i < spec_.agents.size(); ++i)
    if (spec_.agents[i] == name) return static_cast<int>(i);
  return -1;
}

State Domain::empty_state() const {
  State s;
  s.bits.assign(words_, 0);
  return s;
}

long Domain::fact_id(const std::string& text) const {
  auto it = std::lower_bound(fact_index_.begin(), fact_index_.end(), std::make_pair(text, std::uint32_t{0}));
  if (it != fact_index_.end() && it->first == text) return static_cast<long>(it->second);
  return -1;
}

int Domain::turn(const State& s) const noexcept {
  for (std::size_t i = 0; i < turn_fact_.size(); ++i)
    if (turn_fact_[i] >= 0 && s.has(static_cast<std::size_t>(turn_fact_[i]))) return static_cast<int>(i);
  return 0;
}

bool Domain::applicable(const GroundAction& a, const State& s) const noexcept {
  for (auto f : a.pre)
    if (!s.has(f)) return false;
  for (auto f : a.pre_not)
    if (s.has(f)) return false;
  return true;
}

std::vector<std::size_t> Domain::applicable_actions(const State& s) const {
  std::vector<std::size_t> out;
  const int who = turn(s);
  for (std::size_t i = 0; i < actions_.size(); ++i) {
    const auto& a = actions_[i];
    if ((a.actor < 0 || a.actor == who) && applicable(a, s)) out.push_back(i);
  }
  return out;
}

State Domain::pass_turn(const State& s) const {
  State t = s;
  if (spec_.turn_predicate.empty() || spec_.agents.size() < 2) return t;
  const int who = turn(s);
  const std::size_t next = (static_cast<std::size_t>(who) + 1) % spec_.agents.size();
  if (turn_fact_[static_cast<std::size_t>(who)] >= 0) t.reset(static_cast<std::size_t>(turn_fact_[static_cast<std::size_t>(who)]));
  t.set(static_cast<std::size_t>(turn_fact_[next]));
  return t;
}

State Domain::apply(const State& s, std::size_t action, std::size_t outcome) const {
  if (action >= actions_.size() || outcome >= actions_[action].outcomes.size())
    throw InvalidInput("Domain::apply: action or outcome index out of range");
  State t = pass_turn(s);
  const auto& o = actions_[action].outcomes[outcome];
  for (auto f : o.del) t.reset(f);
  for (auto f : o.add) t.set(f);
  return t;
}

bool Domain::goal_holds(std::size_t goal, const State& s) const noexcept {
  for (const auto& alt : goals_[goal].alternatives) {
    bool all = true;
    for (auto f : alt)
      if (!s.has(f)) { all = false; break; }
    if (all) return true;
  }
  return false;
}

std::string Domain::action_text(std::size_t action) const {
  const auto& a = actions_.at(action);
  return atom_text(spec_.operators[a.op].name, a.args);
}

long Domain::find_action(const std::string& text, const std::vector<std::size_t>& candidates) const {
  std::vector<std::string> words;
  {
    std::string cur;
    for (char c : text) {
      if (c == '(' || c == ')' || std::isspace(static_cast<unsigned char>(c))) {
        if (!cur.empty()) words.push_back(cur);
        cur.clear();
      } else {
        cur.push_back(c);
      }
    }
    if (!cur.empty()) words.push_back(cur);
  }
  if (words.empty()) return -1;
  long found = -1;
  for (std::size_t c : candidates) {
    const auto& a = actions_.at(c);
    if (core::ascii_lower(spec_.operators[a.op].name) != core::ascii_lower(words[0]) ||
        words.size() - 1 > a.args.size())
      continue;
    bool match = true;
    for (std::size_t k = 1; k < words.size(); ++k)
      if (a.args[k - 1] != words[k]) { match = false; break; }
    if (!match) continue;
    if (found >= 0) return -2;
    found = static_cast<long>(c);
  }
  return found;
}

std::string Domain::state_text(const State& s) const {
  std::vector<std::string> parts;
  for (std::size_t i = 0; i < facts_.size(); ++i)
    if (s.has(i)) parts.push_back(facts_[i]);
  std::sort(parts.begin(), parts.end());
  std::string out;
  for (const auto& p : parts) out += (out.empty() ? "" : " ") + p;
  return out;
}

void Domain::set_outcome_probabilities(std::size_t op, const std::vector<double>& p) {
  if (op >= spec_.operators.size()) throw InvalidInput("set_outcome_probabilities: operator out of range");
  double sum = 0.0;
  for (double v : p) {
    if (!(v >= 0.0 && v <= 1.0)) throw InvalidInput("set_outcome_probabilities: probability outside [0,1]");
    sum += v;
  }
  if (std::fabs(sum - 1.0) > 1e-9) throw InvalidInput("set_outcome_probabilities: probabilities must sum to 1");
  for (auto& a : actions_) {
    if (a.op != op) continue;
    if (a.outcomes.size() != p.size()) throw InvalidInput("set_outcome_probabilities: wrong number of outcomes");
    for (std::size_t k = 0; k < p.size(); ++k) a.outcomes[k].probability = p[k];
  }
}

}  // namespace emoface::parlee
