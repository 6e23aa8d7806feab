#include "emoface/channels/parameters.hpp"

#include <algorithm>

#include "emoface/core/errors.hpp"

namespace emoface::channels {

// thesis Table 2.1 (muscle numbering 1–19, Appendix B)
const std::vector<std::string>& muscle_names() {
  static const std::vector<std::string> names = {
      "zygomatic_major",          "zygomatic_minor",
      "triangularis",             "risorius",
      "depressor_labii",          "mentalis",
      "orbicularis_oris_funneler", "orbicularis_oris_pressor",
      "frontalis_medialis",       "frontalis_lateralis",
      "levator_labii_nasi",       "levator_labii_superioris",
      "depressor_supercilii",     "corrugator_supercilii",
      "depressor_glabellae",      "levator_palpebrae_superioris",
      "orbicularis_oculi_palpebralis", "orbicularis_oculi_orbitalis",
      "masseter"};
  return names;
}

bool is_paired_muscle(std::string_view muscle) {
  // thesis §4.3: every muscle has a left and right instance except the two Orbicularis Oris and
  // the Masseter.
  return muscle != "orbicularis_oris_funneler" && muscle != "orbicularis_oris_pressor" &&
         muscle != "masseter";
}

const std::vector<std::string>& default_parameter_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const auto& m : muscle_names()) {
      for (auto& p : muscle_parameters(m)) out.push_back(std::move(p));
    }
    for (const char* extra : {"eye_gaze_yaw", "eye_gaze_pitch", "head_yaw", "head_pitch", "head_roll",
                              "eye_blink_l", "eye_blink_r"})
      out.emplace_back(extra);
    return out;
  }();
  return names;
}

bool is_signed_parameter(std::string_view name) {
  return name.rfind("eye_gaze_", 0) == 0 || name.rfind("head_", 0) == 0;
}

bool is_known_parameter(std::string_view name) {
  const auto& n = default_parameter_names();
  return std::find(n.begin(), n.end(), name) != n.end();
}

std::vector<std::string> muscle_parameters(std::string_view muscle) {
  const auto& m = muscle_names();
  if (std::find(m.begin(), m.end(), muscle) == m.end())
    throw InvalidInput("unknown muscle '" + std::string(muscle) + "'");
  if (!is_paired_muscle(muscle)) return {std::string(muscle)};
  return {std::string(muscle) + "_l", std::string(muscle) + "_r"};
}

std::string parameter_muscle(std::string_view parameter) {
  const auto& m = muscle_names();
  std::string_view base = parameter;
  if (base.size() > 2 && (base.substr(base.size() - 2) == "_l" || base.substr(base.size() - 2) == "_r"))
    base = base.substr(0, base.size() - 2);
  if (std::find(m.begin(), m.end(), base) != m.end() &&
      (base.size() != parameter.size()) == is_paired_muscle(base))
    return std::string(base);
  return {};
}

}  // namespace emoface::channels
