#include "emoface/fuzzyexpr/engine.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "emoface/core/errors.hpp"
#include "emoface/core/rng.hpp"

namespace emoface::fuzzyexpr {

// ---------------------------------------------------------------------------------------------------
// Enum names

namespace {
template <class E, std::size_t N>
std::optional<E> lookup(const std::array<std::string_view, N>& names, std::string_view s) {
  for (std::size_t i = 0; i < N; ++i)
    if (names[i] == s) return static_cast<E>(i);
  return std::nullopt;
}
constexpr std::array<std::string_view, 3> kModeNames = {"auto", "single", "blend"};
constexpr std::array<std::string_view, 2> kTieNames = {"fixed", "random"};
constexpr std::array<std::string_view, 2> kTransitionNames = {"crisp", "smooth"};
constexpr std::array<std::string_view, 2> kMissingNames = {"no_rule", "no_contraction"};
}  // namespace

std::string_view to_string(ExpressionMode v) noexcept { return kModeNames[static_cast<int>(v)]; }
std::string_view to_string(TieBreak v) noexcept { return kTieNames[static_cast<int>(v)]; }
std::string_view to_string(Transition v) noexcept { return kTransitionNames[static_cast<int>(v)]; }
std::string_view to_string(MissingRule v) noexcept { return kMissingNames[static_cast<int>(v)]; }
std::optional<ExpressionMode> expression_mode_from_string(std::string_view s) noexcept {
  return lookup<ExpressionMode>(kModeNames, s);
}
std::optional<TieBreak> tie_break_from_string(std::string_view s) noexcept {
  return lookup<TieBreak>(kTieNames, s);
}
std::optional<Transition> transition_from_string(std::string_view s) noexcept {
  return lookup<Transition>(kTransitionNames, s);
}
std::optional<MissingRule> missing_rule_from_string(std::string_view s) noexcept {
  return lookup<MissingRule>(kMissingNames, s);
}

void ExpressionOptions::validate() const {
  if (!(single_margin >= 0.0 && single_margin <= 1.0))
    throw InvalidInput("ExpressionOptions.single_margin must be in [0, 1]");
  if (!(transition_width > 0.0 && transition_width <= 1.0))
    throw InvalidInput("ExpressionOptions.transition_width must be in (0, 1]");
  if (transition == Transition::Smooth && mode == ExpressionMode::Auto &&
      transition_width > 2.0 * single_margin)
    throw InvalidInput(
        "ExpressionOptions.transition_width must be at most 2 * single_margin with a smooth "
        "transition, so the single/blend band stays away from equal intensities");
  std::array<bool, kEmotionCount> seen{};
  for (Emotion e : tie_order) {
    if (index(e) >= kEmotionCount || seen[index(e)])
      throw InvalidInput("ExpressionOptions.tie_order must list each emotion once");
    seen[index(e)] = true;
  }
}

// ---------------------------------------------------------------------------------------------------
// Compiled engine

namespace {

constexpr std::size_t kMaxSets = 16;

// One rule row restricted to a set of muscles: evaluate once, write to every muscle in `muscles`.
struct CompiledRow {
  Emotion emotion = Emotion::Sadness;
  std::array<std::int8_t, kMaxSets> levels{};  // output set per input set, or -1
  std::uint32_t muscles = 0;                   // bit i = Muscle i
};

struct Plan {
  std::vector<CompiledRow> rows;
  bool has_rules = true;  // false: a no-blend pair
};

inline double clamp01(double v) noexcept { return v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v); }

}  // namespace

struct Engine::Impl {
  RuleBase rules;
  ExpressionOptions options;
  std::size_t n_in = 0;
  std::size_t n_out = 0;
  std::array<Plan, kEmotionCount> single_plans;
  std::array<std::array<int, kEmotionCount>, kEmotionCount> pair_plan{};  // index into blend_plans
  std::vector<Plan> blend_plans;
  std::array<int, kEmotionCount> tie_rank{};  // position of each emotion in tie_order

  void compile();
  CompiledRow compile_row(Emotion e, const RuleRow& row, std::uint32_t mask) const;

  // The input sets with positive membership at x (usually one or two) and their memberships.
  struct Active {
    std::size_t n = 0;
    std::uint8_t set[kMaxSets];
    double mu[kMaxSets];
  };
  void memberships(double x, Active& act) const noexcept {
    act.n = 0;
    for (std::size_t i = 0; i < n_in; ++i) {
      const double m = rules.input_sets[i].membership(x);
      if (m > 0.0) {
        act.set[act.n] = static_cast<std::uint8_t>(i);
        act.mu[act.n++] = m;
      }
    }
  }
  double level(const std::int8_t* levels, const Active& act) const noexcept;
  void run(const Plan& plan, const Esv& esv, Fmcv& out, double weight) const noexcept;
  Selection select(const Esv& esv, std::uint64_t row) const;
  bool ranks_before(const Esv& esv, std::size_t a, std::size_t b,
                    const std::array<int, kEmotionCount>& rank) const noexcept {
    return esv[a] > esv[b] || (esv[a] == esv[b] && rank[a] < rank[b]);
  }
  void smooth(const Esv& esv, Fmcv& out) const;
  void soft_single(const Esv& esv, const std::size_t* candidates, std::size_t n, Fmcv& out,
                   double weight) const;
};

CompiledRow Engine::Impl::compile_row(Emotion e, const RuleRow& row, std::uint32_t mask) const {
  CompiledRow c;
  c.emotion = e;
  c.levels.fill(-1);
  for (std::size_t i = 0; i < n_in; ++i) {
    int level = row.levels[i];
    if (level == kNoRule && options.missing_rule == MissingRule::NoContraction) {
      // A "−" cell inside a row that has rules: "no contraction", the lowest output set.
      bool any = std::any_of(row.levels.begin(), row.levels.end(), [](int l) { return l != kNoRule; });
      if (any) level = 0;
    }
    c.levels[i] = static_cast<std::int8_t>(level);
  }
  for (Muscle m : row.muscles)
    if (mask & (1u << index(m))) c.muscles |= 1u << index(m);
  return c;
}

void Engine::Impl::compile() {
  n_in = rules.input_sets.size();
  n_out = rules.output_sets.size();
  for (std::size_t r = 0; r < kEmotionCount; ++r) tie_rank[index(options.tie_order[r])] = static_cast<int>(r);
  const std::uint32_t all = (1u << kMuscleCount) - 1;
  for (std::size_t e = 0; e < kEmotionCount; ++e)
    for (const auto& row : rules.single[e])
      single_plans[e].rows.push_back(compile_row(emotion_at(e), row, all));
  for (auto& line : pair_plan) line.fill(-1);
  auto mask_of = [](const std::vector<Muscle>& ms) {
    std::uint32_t m = 0;
    for (Muscle x : ms) m |= 1u << index(x);
    return m;
  };
  for (const auto& b : rules.blend) {
    Plan plan;
    for (auto [emotion, muscles] : {std::pair{b.first, &b.first_muscles}, std::pair{b.second, &b.second_muscles}}) {
      const std::uint32_t mask = mask_of(*muscles);
      for (const auto& row : rules.single[index(emotion)]) {
        CompiledRow c = compile_row(emotion, row, mask);
        if (c.muscles) plan.rows.push_back(c);
      }
    }
    pair_plan[index(b.first)][index(b.second)] = pair_plan[index(b.second)][index(b.first)] =
        static_cast<int>(blend_plans.size());
    blend_plans.push_back(std::move(plan));
  }
  for (const auto& [a, b] : rules.no_blend) {
    Plan plan;
    plan.has_rules = false;
    pair_plan[index(a)][index(b)] = pair_plan[index(b)][index(a)] = static_cast<int>(blend_plans.size());
    blend_plans.push_back(std::move(plan));
  }
}

// Mamdani inference for one output variable (thesis §6.4.2): the activation of output set o is the max
// over the rules concluding o of their firing strength (single antecedent: μ_i(x)); each set is clipped
// at its activation (min implication), the clipped sets are max-aggregated and defuzzified by COA.
double Engine::Impl::level(const std::int8_t* levels, const Active& act) const noexcept {
  ClippedSet clips[kMaxSets];  // uninitialised aggregate array: only the first n are used
  std::size_t n = 0;
  for (std::size_t k = 0; k < act.n; ++k) {
    const int o = levels[act.set[k]];
    if (o < 0) continue;
    const double h = act.mu[k];
    std::size_t j = 0;
    while (j < n && clips[j].set != &rules.output_sets[static_cast<std::size_t>(o)]) ++j;
    if (j == n)
      clips[n++] = {&rules.output_sets[static_cast<std::size_t>(o)], h};
    else if (h > clips[j].height)
      clips[j].height = h;  // two rules conclude the same set: max (thesis §6.4.2, ∨ = max)
  }
  if (n == 0) return 0.0;  // no rule fires: the muscle is not contracted
  return clamp01(centre_of_area(clips, n).centroid);
}

void Engine::Impl::run(const Plan& plan, const Esv& esv, Fmcv& out, double weight) const noexcept {
  Active mu[kEmotionCount];
  std::uint32_t have = 0;
  // At a given intensity only the consequents of the active input sets matter, so rows that agree on
  // them (common: "vs s m b vb" and "vs s s b vb" between High and VeryHigh) share one inference.
  struct Memo {
    std::uint32_t emotion_key;
    double value;
  } memo[16];
  std::size_t n_memo = 0;
  for (const auto& row : plan.rows) {
    const std::size_t e = index(row.emotion);
    if (!(have & (1u << e))) {
      memberships(esv[e], mu[e]);
      have |= 1u << e;
    }
    const Active& act = mu[e];
    double v = -1.0;
    std::uint32_t key = 0;
    const bool memoisable = act.n <= 3;
    if (memoisable) {
      key = static_cast<std::uint32_t>(e) << 24;
      for (std::size_t k = 0; k < act.n; ++k)
        key |= static_cast<std::uint32_t>(static_cast<std::uint8_t>(row.levels[act.set[k]] + 1)) << (8 * k);
      for (std::size_t j = 0; j < n_memo; ++j)
        if (memo[j].emotion_key == key) v = memo[j].value;
    }
    if (v < 0.0) {
      v = level(row.levels.data(), act);
      if (memoisable && n_memo < 16) memo[n_memo++] = {key, v};
    }
    v *= weight;
    for (std::uint32_t bits = row.muscles; bits; bits &= bits - 1)
      out[static_cast<std::size_t>(__builtin_ctz(bits))] += v;
  }
}

Selection Engine::Impl::select(const Esv& esv, std::uint64_t row) const {
  std::array<int, kEmotionCount> rank = tie_rank;
  auto top3 = [&](std::size_t& a, std::size_t& b, std::size_t& c) {
    a = b = c = kEmotionCount;
    for (std::size_t i = 0; i < kEmotionCount; ++i) {
      if (a == kEmotionCount || ranks_before(esv, i, a, rank)) {
        c = b;
        b = a;
        a = i;
      } else if (b == kEmotionCount || ranks_before(esv, i, b, rank)) {
        c = b;
        b = i;
      } else if (c == kEmotionCount || ranks_before(esv, i, c, rank)) {
        c = i;
      }
    }
  };
  std::size_t a, b, c;
  top3(a, b, c);
  if (options.tie_break == TieBreak::Random && (esv[a] == esv[b] || esv[b] == esv[c])) {
    // Thesis §6.5: tied emotions are chosen at random. A random permutation decides the ties.
    core::Rng rng(options.seed, row);
    std::array<int, kEmotionCount> perm{0, 1, 2, 3, 4, 5};
    for (std::size_t i = kEmotionCount - 1; i > 0; --i)
      std::swap(perm[i], perm[rng.uniform_int(i + 1)]);
    rank = perm;
    top3(a, b, c);
  }
  Selection s;
  s.first = emotion_at(a);
  s.second = emotion_at(b);
  // Auto: thesis §6.5 (e1 − e2 > margin), and single whenever only one emotion is present (e2 = 0):
  // a lone weak emotion has no partner to blend with, and the blend with a zero-intensity partner
  // would drop its characteristic muscles (sadness 0.4 alone would move no brow; issue 14).
  const bool single = options.mode == ExpressionMode::Single ||
                      (options.mode == ExpressionMode::Auto &&
                       (esv[a] - esv[b] > options.single_margin || esv[b] == 0.0));
  s.mode = single ? ExpressionMode::Single : ExpressionMode::Blend;
  s.pair_has_rules = blend_plans[static_cast<std::size_t>(pair_plan[a][b])].has_rules;
  return s;
}

namespace {
// Cross-fade weight: 0 at x <= -w/2, 1 at x >= w/2, linear in between.
inline double ramp(double x, double w) noexcept { return clamp01(0.5 + x / w); }
}  // namespace

// Soft choice of the strongest among `candidates`: each gets ramp(e_k − max of the others), normalised.
void Engine::Impl::soft_single(const Esv& esv, const std::size_t* candidates, std::size_t n,
                               Fmcv& out, double weight) const {
  double r[kEmotionCount];
  double total = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    double best_other = -1.0;
    for (std::size_t j = 0; j < n; ++j)
      if (j != i) best_other = std::max(best_other, esv[candidates[j]]);
    r[i] = ramp(esv[candidates[i]] - best_other, options.transition_width);
    total += r[i];
  }
  for (std::size_t i = 0; i < n; ++i)
    if (r[i] > 0.0) run(single_plans[candidates[i]], esv, out, weight * r[i] / total);
}

// Transition::Smooth: a convex combination of the crisp interpretations whose weights are continuous
// functions of the ESV and vanish wherever an interpretation's identity could change (docs/fuzzyexpr.md).
void Engine::Impl::smooth(const Esv& esv, Fmcv& out) const {
  const double w = options.transition_width;
  std::array<double, kEmotionCount> sorted;
  std::copy(esv.begin(), esv.end(), sorted.begin());
  std::sort(sorted.begin(), sorted.end(), std::greater<double>());
  static constexpr std::size_t kAll[kEmotionCount] = {0, 1, 2, 3, 4, 5};
  double s;  // weight of the single interpretation
  switch (options.mode) {
    case ExpressionMode::Single: s = 1.0; break;
    case ExpressionMode::Blend: s = 0.0; break;
    // the margin fades in as the second emotion rises from 0 to w, so that a lone emotion is single
    // (as in the crisp selection) and the weight stays continuous in the ESV
    default:
      s = ramp(sorted[0] - sorted[1] - options.single_margin * std::min(1.0, sorted[1] / w), w);
  }
  if (s > 0.0) soft_single(esv, kAll, kEmotionCount, out, s);
  if (s >= 1.0) return;
  // Pair weights: how clearly {i, j} are the two strongest.
  double pw[kEmotionCount][kEmotionCount] = {};
  double total = 0.0;
  for (std::size_t i = 0; i < kEmotionCount; ++i)
    for (std::size_t j = i + 1; j < kEmotionCount; ++j) {
      double rest = 0.0;
      for (std::size_t k = 0; k < kEmotionCount; ++k)
        if (k != i && k != j) rest = std::max(rest, esv[k]);
      pw[i][j] = ramp(std::min(esv[i], esv[j]) - rest, w);
      total += pw[i][j];
    }
  for (std::size_t i = 0; i < kEmotionCount; ++i)
    for (std::size_t j = i + 1; j < kEmotionCount; ++j) {
      if (pw[i][j] <= 0.0) continue;
      const double weight = (1.0 - s) * pw[i][j] / total;
      const Plan& plan = blend_plans[static_cast<std::size_t>(pair_plan[i][j])];
      if (plan.has_rules) {
        run(plan, esv, out, weight);
      } else {
        const std::size_t pair[2] = {i, j};
        soft_single(esv, pair, 2, out, weight);
      }
    }
}

// ---------------------------------------------------------------------------------------------------

Engine::Engine(RuleBase rules, ExpressionOptions options) {
  rules.validate();
  options.validate();
  auto impl = std::make_shared<Impl>();
  impl->rules = std::move(rules);
  impl->options = options;
  impl->compile();
  impl_ = std::move(impl);
}

const RuleBase& Engine::rules() const noexcept { return impl_->rules; }
const ExpressionOptions& Engine::options() const noexcept { return impl_->options; }

namespace {
void check_esv(const Esv& esv) {
  for (std::size_t i = 0; i < kEmotionCount; ++i)
    if (!(esv[i] >= 0.0 && esv[i] <= 1.0))
      throw InvalidInput("ESV intensity of " + std::string(to_string(emotion_at(i))) +
                         " must be in [0, 1], got " + std::to_string(esv[i]));
}
void check_intensity(double x, Emotion e) {
  if (!(x >= 0.0 && x <= 1.0))
    throw InvalidInput("intensity of " + std::string(to_string(e)) + " must be in [0, 1], got " +
                       std::to_string(x));
}
}  // namespace

Selection Engine::select(const Esv& esv, std::uint64_t row) const {
  check_esv(esv);
  return impl_->select(esv, row);
}

Fmcv Engine::convert(const Esv& esv, std::uint64_t row) const {
  check_esv(esv);
  Fmcv out{};
  const Impl& m = *impl_;
  if (m.options.transition == Transition::Smooth) {
    m.smooth(esv, out);
  } else {
    const Selection s = m.select(esv, row);
    if (s.mode == ExpressionMode::Single || !s.pair_has_rules)
      m.run(m.single_plans[index(s.first)], esv, out, 1.0);
    else
      m.run(m.blend_plans[static_cast<std::size_t>(m.pair_plan[index(s.first)][index(s.second)])],
            esv, out, 1.0);
    return out;  // crisp: every level is already a clamped centre of area
  }
  for (double& v : out) v = clamp01(v);  // smooth: guard the weighted sum against rounding
  return out;
}

Fmcv Engine::single(Emotion emotion, double intensity) const {
  check_intensity(intensity, emotion);
  Esv esv{};
  esv[index(emotion)] = intensity;
  Fmcv out{};
  impl_->run(impl_->single_plans[index(emotion)], esv, out, 1.0);
  return out;
}

Fmcv Engine::blend(Emotion a, double intensity_a, Emotion b, double intensity_b) const {
  check_intensity(intensity_a, a);
  check_intensity(intensity_b, b);
  if (a == b) throw InvalidInput("Engine::blend needs two different emotions");
  Esv esv{};
  esv[index(a)] = intensity_a;
  esv[index(b)] = intensity_b;
  const Impl& m = *impl_;
  Fmcv out{};
  const Plan& plan = m.blend_plans[static_cast<std::size_t>(m.pair_plan[index(a)][index(b)])];
  if (plan.has_rules) {
    m.run(plan, esv, out, 1.0);
  } else {
    const bool a_first = m.ranks_before(esv, index(a), index(b), m.tie_rank);
    m.run(m.single_plans[index(a_first ? a : b)], esv, out, 1.0);
  }
  return out;
}

double Engine::row_level(const RuleRow& row, double intensity) const noexcept {
  const Impl& m = *impl_;
  if (row.levels.size() != m.n_in) return 0.0;
  Impl::Active mu;
  m.memberships(intensity, mu);
  const CompiledRow c = m.compile_row(Emotion::Sadness, row, 0);
  return m.level(c.levels.data(), mu);
}

std::function<SideParameters(const Esv&)> side_parameter_function(RuleBase rules) {
  auto engine = std::make_shared<const Engine>(std::move(rules));
  return [engine](const Esv& esv) { return expand_to_sides(engine->convert(esv)); };
}

}  // namespace emoface::fuzzyexpr
