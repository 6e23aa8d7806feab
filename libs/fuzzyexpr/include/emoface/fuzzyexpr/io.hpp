#pragma once
// Rule-base files (format "emoface.fuzzyrules", version 1.x, JSON) and export to fuzzylite's FLL.
// The file layout is documented in docs/fuzzyexpr.md; data/fuzzyexpr/rules.json is the default.
#include <string>
#include <string_view>

#include "emoface/fuzzyexpr/engine.hpp"
#include "emoface/fuzzyexpr/rule_base.hpp"

namespace emoface::fuzzyexpr {

inline constexpr std::string_view kRuleFileKind = "fuzzyrules";

/// Parses and validates a rule-base document. Every problem (bad JSON, wrong envelope, unknown emotion,
/// muscle or set name, ill-formed or non-covering sets, wrong row length, pairs missing or repeated)
/// throws FormatError naming `file` and the JSON pointer of the offending field.
RuleBase parse_rule_base(std::string_view json_text, const std::string& file = "<rules>");
/// read_file + parse_rule_base (IoError if the file cannot be read).
RuleBase read_rule_base(const std::string& path);

/// The rule base as a version-1.0 document (parse_rule_base(to_json_text(r)) == r).
std::string to_json_text(const RuleBase& rules);
/// to_json_text written atomically.
void write_rule_base(const RuleBase& rules, const std::string& path);

struct FllOptions {
  /// Samples fuzzylite's Centroid defuzzifier integrates over the output range. ≥ 10.
  int centroid_resolution = 1000;
  std::string engine_name = "emoface_fuzzyexpr";
  /// How "−" cells are exported, as Engine reads them (ExpressionOptions::missing_rule): with
  /// NoContraction (the default) a "−" inside a row that has rules becomes a rule to the lowest
  /// output set; with NoRule it is left out.
  MissingRule missing_rule = MissingRule::NoContraction;
  void validate() const;
};

/// Exports the rule base as one fuzzylite 6 FLL engine: six input variables, 19 output variables
/// (default value 0 when no rule fires) and one rule block per mode — "single_<emotion>" for Tables
/// 6.1–6.6 and "blend_<first>_<second>" for each line of Table 6.7 — all disabled. Mode selection is not
/// fuzzy, so a fuzzylite user enables the one block that emoface's selection picks (see docs).
std::string to_fll(const RuleBase& rules, const FllOptions& options = {});

}  // namespace emoface::fuzzyexpr
