#pragma once
// Weight sets: named targets (FACS action units, ARKit blend shapes) as linear functions of the named
// emoface face parameters — data, not code (data/faceweights/*.json, format docs/formats.md).
//
//   target weight = clamp( Σ_terms weight · input , 0, 1 )
//   input "<parameter>"  : a level parameter in [0, 1] (muscles, eye_blink_*)
//   input "<parameter>+" : max(0,  angle) / range   (signed angle parameters: eye_gaze_*, head_*)
//   input "<parameter>-" : max(0, −angle) / range   clamped to [0, 1]; range from WeightSet::ranges
// A target without terms has no muscle in emoface (e.g. tongueOut); its note says why.
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace emoface::faceweights {

struct Term {
  std::string input;    ///< parameter name, or "<name>+" / "<name>-" for a half of a signed angle
  double weight = 0.0;  ///< finite, |weight| ≤ 10
};

struct Target {
  std::string name;                  ///< e.g. "mouthSmile_L", "AU12_L"; unique within a set
  std::vector<Term> terms;           ///< empty = no muscle (see note)
  std::string facs;                  ///< the FACS action unit(s) it corresponds to, e.g. "AU12"
  std::vector<std::string> sources;  ///< ids into WeightSet::sources
  std::string note;                  ///< free text; required when terms is empty
};

struct Source {
  std::string id;
  std::string citation;
};

struct WeightSet {
  std::string set;                       ///< "arkit", "facs" or a user's name
  std::string naming;                    ///< "arkit" (target names are ARKit shapes) or "facs"/other
  std::string description;
  std::map<std::string, double> ranges;  ///< radians per signed parameter used with +/-; > 0
  std::vector<Source> sources;
  std::vector<Target> targets;

  /// Index of a target by name. With naming "arkit" any ARKit spelling is accepted (names.hpp);
  /// otherwise the match is case-insensitive. nullopt if absent.
  std::optional<std::size_t> find(std::string_view name) const;
  std::vector<std::string> target_names() const;
  /// Checks the invariants listed above (unique names, known source ids, finite weights, ranges for
  /// every signed input, a note on every target without terms). Throws InvalidInput.
  void validate() const;
};

inline constexpr const char* kWeightSetKind = "faceweights";  ///< format "emoface.faceweights"
inline constexpr int kWeightSetMajor = 1;
inline constexpr int kWeightSetMinor = 0;

/// Parses an "emoface.faceweights" 1.x document. Errors are FormatError naming `file` and the JSON
/// pointer of the offending field.
WeightSet parse_weight_set(std::string_view text, const std::string& file);
WeightSet read_weight_set(const std::string& path);
/// JSON text of the set (round-trips through parse_weight_set).
std::string format_weight_set(const WeightSet& set);
void write_weight_set(const std::string& path, const WeightSet& set);

/// The built-in sets compiled from data/faceweights/: "arkit" and "facs". Throws InvalidInput naming
/// the known sets for any other name.
const WeightSet& builtin_weight_set(std::string_view name);
std::vector<std::string> builtin_weight_set_names();

}  // namespace emoface::faceweights
