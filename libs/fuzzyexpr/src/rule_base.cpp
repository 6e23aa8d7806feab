#include "emoface/fuzzyexpr/rule_base.hpp"

#include <algorithm>
#include <set>
#include <string>

#include "emoface/core/errors.hpp"

namespace emoface::fuzzyexpr {
namespace {

void validate_sets(const std::vector<FuzzySet>& sets, const char* what) {
  if (sets.size() < 2 || sets.size() > 16)
    throw InvalidInput(std::string(what) + ": need 2 to 16 fuzzy sets, got " +
                       std::to_string(sets.size()));
  std::set<std::string> names;
  for (const auto& s : sets) {
    if (s.name.empty()) throw InvalidInput(std::string(what) + ": a fuzzy set has an empty name");
    if (!names.insert(s.name).second)
      throw InvalidInput(std::string(what) + ": duplicate fuzzy set name \"" + s.name + "\"");
    s.validate();
  }
}

std::string pair_name(Emotion a, Emotion b) {
  return std::string(to_string(a)) + "+" + std::string(to_string(b));
}

}  // namespace

void RuleBase::validate() const {
  validate_sets(input_sets, "input sets");
  validate_sets(output_sets, "output sets");
  if (!covers_unit_interval(input_sets))
    throw InvalidInput("input sets do not cover [0, 1]: some intensity belongs to no set");
  for (std::size_t e = 0; e < kEmotionCount; ++e) {
    std::set<Muscle> seen;
    for (const auto& row : single[e]) {
      const std::string where = "single rules of " + std::string(to_string(emotion_at(e)));
      if (row.muscles.empty()) throw InvalidInput(where + ": a row lists no muscles");
      if (row.levels.size() != input_sets.size())
        throw InvalidInput(where + ": a row has " + std::to_string(row.levels.size()) +
                           " levels, expected one per input set (" +
                           std::to_string(input_sets.size()) + ")");
      for (int level : row.levels)
        if (level != kNoRule && (level < 0 || level >= static_cast<int>(output_sets.size())))
          throw InvalidInput(where + ": level index " + std::to_string(level) + " out of range");
      for (Muscle m : row.muscles)
        if (!seen.insert(m).second)
          throw InvalidInput(where + ": muscle " + std::string(to_string(m)) + " appears twice");
    }
  }
  std::set<std::pair<Emotion, Emotion>> pairs;
  auto add_pair = [&](Emotion a, Emotion b) {
    if (a == b) throw InvalidInput("blend pair " + pair_name(a, b) + " names one emotion twice");
    auto key = std::minmax(a, b);
    if (!pairs.insert({key.first, key.second}).second)
      throw InvalidInput("emotion pair " + pair_name(a, b) + " is listed more than once");
  };
  for (const auto& rule : blend) {
    add_pair(rule.first, rule.second);
    std::set<Muscle> seen;
    for (const auto* list : {&rule.first_muscles, &rule.second_muscles})
      for (Muscle m : *list)
        if (!seen.insert(m).second)
          throw InvalidInput("blend " + pair_name(rule.first, rule.second) + ": muscle " +
                             std::string(to_string(m)) + " is assigned twice");
  }
  for (const auto& [a, b] : no_blend) add_pair(a, b);
  if (pairs.size() != kEmotionCount * (kEmotionCount - 1) / 2)
    throw InvalidInput("every one of the 15 emotion pairs must be listed in blend or no_blend; " +
                       std::to_string(pairs.size()) + " are");
}

const RuleRow* RuleBase::row_for(Emotion emotion, Muscle muscle) const noexcept {
  for (const auto& row : single[index(emotion)])
    if (std::find(row.muscles.begin(), row.muscles.end(), muscle) != row.muscles.end()) return &row;
  return nullptr;
}

}  // namespace emoface::fuzzyexpr
