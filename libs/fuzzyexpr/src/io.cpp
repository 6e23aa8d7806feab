#include "emoface/fuzzyexpr/io.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "emoface/core/io.hpp"
#include "emoface/core/json_reader.hpp"

namespace emoface::fuzzyexpr {
namespace {

using Json = nlohmann::ordered_json;
using core::JsonValue;
constexpr core::FormatVersion kVersion{1, 0};

// Reads the rule file through core::JsonReader: located errors, and the unknown-field rule of
// docs/formats.md (only_keys rejects unknown fields unless the file is of a newer minor version).
class Parser {
 public:
  std::vector<FuzzySet> sets(const JsonValue& j) const {
    std::vector<FuzzySet> out;
    for (const JsonValue& s : j.items()) {
      s.only_keys({"name", "shape", "points"});
      FuzzySet set;
      set.name = s.at("name").string();
      const JsonValue shape_value = s.at("shape");
      auto shape = set_shape_from_string(shape_value.string());
      if (!shape) shape_value.fail("unknown shape (expected \"triangle\" or \"trapezoid\")");
      set.shape = *shape;
      const JsonValue pts = s.at("points");
      const std::size_t want = set.shape == SetShape::Triangle ? 3 : 4;
      if (!pts.is_array() || pts.size() != want)
        pts.fail("expected " + std::to_string(want) + " numbers for a " +
                 std::string(to_string(set.shape)));
      double v[4];
      for (std::size_t k = 0; k < want; ++k) v[k] = pts[k].number();
      set.points = want == 3 ? std::array<double, 4>{v[0], v[1], v[1], v[2]}
                             : std::array<double, 4>{v[0], v[1], v[2], v[3]};
      try {
        set.validate();
      } catch (const InvalidInput& e) {
        pts.fail(e.what());
      }
      out.push_back(std::move(set));
    }
    if (out.size() < 2 || out.size() > 16) j.fail("need 2 to 16 fuzzy sets");
    std::set<std::string> names;
    for (std::size_t i = 0; i < out.size(); ++i)
      if (!names.insert(out[i].name).second)
        j[i].at("name").fail("duplicate set name \"" + out[i].name + "\"");
    return out;
  }

  static Emotion emotion(const JsonValue& j) {
    const std::string name = j.string();
    auto e = emotion_from_string(name);
    if (!e) j.fail("unknown emotion \"" + name + "\"");
    return *e;
  }
  static std::vector<Muscle> muscles(const JsonValue& j) {
    std::vector<Muscle> out;
    for (const JsonValue& item : j.items()) {
      const std::string name = item.string();
      auto m = muscle_from_string(name);
      if (!m) item.fail("unknown muscle \"" + name + "\"");
      out.push_back(*m);
    }
    return out;
  }

  RuleBase parse(const JsonValue& doc) const {
    RuleBase r;
    doc.only_keys({"source", "input_sets", "output_sets", "single", "blend", "no_blend"});
    r.input_sets = sets(doc.at("input_sets"));
    r.output_sets = sets(doc.at("output_sets"));
    if (!covers_unit_interval(r.input_sets))
      doc.at("input_sets")
          .fail("the input sets do not cover [0, 1]: some intensity belongs to no set");
    for (const auto& [key, rows] : doc.at("single").members()) {
      auto e = emotion_from_string(key);
      if (!e) rows.fail("unknown emotion \"" + key + "\"");
      std::set<Muscle> seen;
      for (const JsonValue& jr : rows.items()) {
        jr.only_keys({"muscles", "levels"});
        RuleRow row;
        const JsonValue jm = jr.at("muscles");
        row.muscles = muscles(jm);
        if (row.muscles.empty()) jm.fail("a row must list at least one muscle");
        for (std::size_t k = 0; k < row.muscles.size(); ++k)
          if (!seen.insert(row.muscles[k]).second)
            jm[k].fail("muscle already has rules for " + key);
        const JsonValue lv = jr.at("levels");
        if (!lv.is_array() || lv.size() != r.input_sets.size())
          lv.fail("expected one level per input set (" + std::to_string(r.input_sets.size()) +
                  "), null for no rule");
        for (const JsonValue& level : lv.items()) {
          if (level.is_null()) {
            row.levels.push_back(kNoRule);
            continue;
          }
          const std::string name = level.string();
          int found = kNoRule;
          for (std::size_t o = 0; o < r.output_sets.size(); ++o)
            if (r.output_sets[o].name == name) found = static_cast<int>(o);
          if (found == kNoRule) level.fail("undefined output set \"" + name + "\"");
          row.levels.push_back(found);
        }
        r.single[index(*e)].push_back(std::move(row));
      }
    }
    std::set<std::pair<Emotion, Emotion>> pairs;
    auto add_pair = [&](Emotion a, Emotion b, const JsonValue& at) {
      if (a == b) at.fail("a pair needs two different emotions");
      auto key = std::minmax(a, b);
      if (!pairs.insert({key.first, key.second}).second)
        at.fail("emotion pair listed more than once (in blend or no_blend)");
    };
    for (const JsonValue& jb : doc.at("blend").items()) {
      jb.only_keys({"emotions", "first", "second"});
      const JsonValue em = jb.at("emotions");
      if (!em.is_array() || em.size() != 2) em.fail("expected two emotion names");
      BlendRule b;
      b.first = emotion(em[0]);
      b.second = emotion(em[1]);
      add_pair(b.first, b.second, em);
      const JsonValue first = jb.at("first"), second = jb.at("second");
      b.first_muscles = muscles(first);
      b.second_muscles = muscles(second);
      std::set<Muscle> seen;
      for (auto [list, where] :
           {std::pair{&b.first_muscles, &first}, std::pair{&b.second_muscles, &second}})
        for (std::size_t k = 0; k < list->size(); ++k)
          if (!seen.insert((*list)[k]).second)
            (*where)[k].fail("muscle assigned twice in this blend");
      r.blend.push_back(std::move(b));
    }
    if (auto nb = doc.find("no_blend")) {
      for (const JsonValue& pr : nb->items()) {
        if (!pr.is_array() || pr.size() != 2) pr.fail("expected two emotion names");
        Emotion a = emotion(pr[0]), b = emotion(pr[1]);
        add_pair(a, b, pr);
        r.no_blend.emplace_back(a, b);
      }
    }
    if (pairs.size() != kEmotionCount * (kEmotionCount - 1) / 2) {
      for (std::size_t a = 0; a < kEmotionCount; ++a)
        for (std::size_t b = a + 1; b < kEmotionCount; ++b)
          if (!pairs.count({emotion_at(a), emotion_at(b)}))
            doc.at("blend").fail("emotion pair " + std::string(to_string(emotion_at(a))) + "+" +
                                 std::string(to_string(emotion_at(b))) +
                                 " is in neither blend nor no_blend");
    }
    try {
      r.validate();  // anything the located checks above did not catch
    } catch (const InvalidInput& e) {
      doc.fail(e.what());
    }
    return r;
  }
};

Json sets_json(const std::vector<FuzzySet>& sets) {
  Json out = Json::array();
  for (const auto& s : sets) {
    Json j;
    j["name"] = s.name;
    j["shape"] = std::string(to_string(s.shape));
    if (s.shape == SetShape::Triangle)
      j["points"] = {s.points[0], s.points[1], s.points[3]};
    else
      j["points"] = {s.points[0], s.points[1], s.points[2], s.points[3]};
    out.push_back(j);
  }
  return out;
}

Json muscles_json(const std::vector<Muscle>& ms) {
  Json out = Json::array();
  for (Muscle m : ms) out.push_back(std::string(to_string(m)));
  return out;
}

}  // namespace

RuleBase parse_rule_base(std::string_view json_text, const std::string& file) {
  const core::JsonReader reader(json_text, file, kRuleFileKind, kVersion);
  return Parser().parse(reader.root());
}

RuleBase read_rule_base(const std::string& path) {
  return parse_rule_base(core::read_file(path, 16u << 20), path);
}

std::string to_json_text(const RuleBase& rules) {
  Json doc = core::make_envelope(kRuleFileKind, kVersion);
  doc["input_sets"] = sets_json(rules.input_sets);
  doc["output_sets"] = sets_json(rules.output_sets);
  Json single = Json::object();
  for (std::size_t e = 0; e < kEmotionCount; ++e) {
    if (rules.single[e].empty()) continue;
    Json rows = Json::array();
    for (const auto& row : rules.single[e]) {
      Json levels = Json::array();
      for (int l : row.levels)
        levels.push_back(l == kNoRule ? Json(nullptr) : Json(rules.output_sets[static_cast<std::size_t>(l)].name));
      rows.push_back({{"muscles", muscles_json(row.muscles)}, {"levels", levels}});
    }
    single[std::string(to_string(emotion_at(e)))] = rows;
  }
  doc["single"] = single;
  Json blend = Json::array();
  for (const auto& b : rules.blend)
    blend.push_back({{"emotions", {std::string(to_string(b.first)), std::string(to_string(b.second))}},
                     {"first", muscles_json(b.first_muscles)},
                     {"second", muscles_json(b.second_muscles)}});
  doc["blend"] = blend;
  Json nb = Json::array();
  for (const auto& [a, b] : rules.no_blend)
    nb.push_back({std::string(to_string(a)), std::string(to_string(b))});
  doc["no_blend"] = nb;
  return doc.dump(2) + "\n";
}

void write_rule_base(const RuleBase& rules, const std::string& path) {
  core::write_file_atomic(path, to_json_text(rules));
}

void FllOptions::validate() const {
  if (centroid_resolution < 10) throw InvalidInput("FllOptions.centroid_resolution must be >= 10");
  if (engine_name.empty() || engine_name.find_first_of(" \t\r\n") != std::string::npos)
    throw InvalidInput("FllOptions.engine_name must be a non-empty word");
}

namespace {

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string term(const FuzzySet& s) {
  const auto& p = s.points;
  if (s.shape == SetShape::Triangle)
    return "  term: " + s.name + " Triangle " + num(p[0]) + " " + num(p[1]) + " " + num(p[3]) + "\n";
  return "  term: " + s.name + " Trapezoid " + num(p[0]) + " " + num(p[1]) + " " + num(p[2]) + " " +
         num(p[3]) + "\n";
}

// "if <emotion> is <set> then m1 is X and m2 is X" for each input set of each row restricted to `mask`.
void rules_for(std::string& out, const RuleBase& r, Emotion e, std::uint32_t mask,
               MissingRule missing) {
  for (const auto& row : r.single[index(e)]) {
    std::vector<Muscle> ms;
    for (Muscle m : row.muscles)
      if (mask & (1u << index(m))) ms.push_back(m);
    if (ms.empty()) continue;
    const bool any = std::any_of(row.levels.begin(), row.levels.end(), [](int l) { return l != kNoRule; });
    for (std::size_t i = 0; i < row.levels.size(); ++i) {
      int level = row.levels[i];
      // "−: no contraction" (Table 6.1 caption): the lowest output set, as Engine reads it
      if (level == kNoRule && missing == MissingRule::NoContraction && any) level = 0;
      if (level == kNoRule) continue;
      out += "  rule: if " + std::string(to_string(e)) + " is " + r.input_sets[i].name + " then ";
      for (std::size_t k = 0; k < ms.size(); ++k) {
        if (k) out += " and ";
        out += std::string(to_string(ms[k])) + " is " +
               r.output_sets[static_cast<std::size_t>(level)].name;
      }
      out += "\n";
    }
  }
}

std::string block_header(const std::string& name) {
  return "RuleBlock: " + name +
         "\n  enabled: false\n  conjunction: Minimum\n  disjunction: Maximum\n  implication: "
         "Minimum\n  activation: General\n";
}

}  // namespace

std::string to_fll(const RuleBase& rules, const FllOptions& options) {
  options.validate();
  rules.validate();
  double lo = rules.output_sets.front().points[0], hi = rules.output_sets.front().points[3];
  for (const auto& s : rules.output_sets) {
    lo = std::min(lo, s.points[0]);
    hi = std::max(hi, s.points[3]);
  }
  std::string out = "#emoface " + std::string(core::make_envelope(kRuleFileKind, kVersion)["generator"]) +
                    ": thesis chapter 6 rule base. Enable exactly one rule block: the one emoface's\n"
                    "#mode selection picks (single_<emotion> or blend_<first>_<second>).\n";
  for (const auto& [a, b] : rules.no_blend)
    out += "#no blend rules for " + std::string(to_string(a)) + "+" + std::string(to_string(b)) +
           ": use single_<stronger>\n";
  out += "Engine: " + options.engine_name + "\n";
  for (std::size_t e = 0; e < kEmotionCount; ++e) {
    out += "InputVariable: " + std::string(to_string(emotion_at(e))) +
           "\n  enabled: true\n  range: 0.000 1.000\n  lock-range: false\n";
    for (const auto& s : rules.input_sets) out += term(s);
  }
  for (std::size_t m = 0; m < kMuscleCount; ++m) {
    out += "OutputVariable: " + std::string(to_string(muscle_at(m))) + "\n  enabled: true\n  range: " +
           num(lo) + " " + num(hi) +
           "\n  lock-range: false\n  aggregation: Maximum\n  defuzzifier: Centroid " +
           std::to_string(options.centroid_resolution) +
           "\n  default: 0.000\n  lock-previous: false\n";
    for (const auto& s : rules.output_sets) out += term(s);
  }
  const std::uint32_t all = (1u << kMuscleCount) - 1;
  for (std::size_t e = 0; e < kEmotionCount; ++e) {
    out += block_header("single_" + std::string(to_string(emotion_at(e))));
    rules_for(out, rules, emotion_at(e), all, options.missing_rule);
  }
  for (const auto& b : rules.blend) {
    out += block_header("blend_" + std::string(to_string(b.first)) + "_" + std::string(to_string(b.second)));
    std::uint32_t m1 = 0, m2 = 0;
    for (Muscle m : b.first_muscles) m1 |= 1u << index(m);
    for (Muscle m : b.second_muscles) m2 |= 1u << index(m);
    rules_for(out, rules, b.first, m1, options.missing_rule);
    rules_for(out, rules, b.second, m2, options.missing_rule);
  }
  return out;
}

}  // namespace emoface::fuzzyexpr
