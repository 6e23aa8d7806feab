#include "emoface/muscles/parameters.hpp"

#include <cmath>

#include "emoface/core/errors.hpp"

namespace emoface::muscles {

const std::array<std::string, 19>& muscle_type_names() {
  // thesis Table 2.1 order
  static const std::array<std::string, 19> names = {
      "zygomatic_major", "zygomatic_minor", "triangularis", "risorius", "depressor_labii", "mentalis",
      "orbicularis_oris_funneler", "orbicularis_oris_pressor", "frontalis_medialis", "frontalis_lateralis",
      "levator_labii_nasi", "levator_labii_superioris", "depressor_supercilii", "corrugator_supercilii",
      "depressor_glabellae", "levator_palpebrae_superioris", "orbicularis_oculi_palpebralis",
      "orbicularis_oculi_orbitalis", "masseter"};
  return names;
}

namespace {
bool unpaired(const std::string& n) {
  return n == "orbicularis_oris_funneler" || n == "orbicularis_oris_pressor" || n == "masseter";
}
}  // namespace

const std::vector<std::string>& side_parameter_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const auto& n : muscle_type_names()) {
      if (unpaired(n)) {
        out.push_back(n);
      } else {
        out.push_back(n + "_l");
        out.push_back(n + "_r");
      }
    }
    return out;
  }();
  return names;
}

const std::vector<std::string>& pose_parameter_names() {
  static const std::vector<std::string> names = {"eye_gaze_yaw", "eye_gaze_pitch", "head_yaw", "head_pitch", "head_roll"};
  return names;
}

const std::vector<std::string>& eyelid_parameter_names() {
  static const std::vector<std::string> names = {"eye_blink_l", "eye_blink_r"};
  return names;
}

const std::vector<std::string>& parameter_names() {
  static const std::vector<std::string> names = [] {
    auto out = side_parameter_names();
    for (const auto& n : pose_parameter_names()) out.push_back(n);
    for (const auto& n : eyelid_parameter_names()) out.push_back(n);
    return out;
  }();
  return names;
}

std::size_t parameter_index(std::string_view name) {
  const auto& names = parameter_names();
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return i;
  }
  throw InvalidInput("unknown face parameter '" + std::string(name) + "'");
}

void validate_parameter_vector(const std::vector<double>& values) {
  if (values.size() != kParameterCount) {
    throw InvalidInput("parameter vector needs " + std::to_string(kParameterCount) + " values, got " +
                       std::to_string(values.size()));
  }
  const auto& names = parameter_names();
  for (std::size_t i = 0; i < values.size(); ++i) {
    const double v = values[i];
    if (!std::isfinite(v)) throw InvalidInput("parameter " + names[i] + " is not finite");
    if (is_level_parameter(i)) {
      if (v < 0.0 || v > 1.0) throw InvalidInput("parameter " + names[i] + " = " + std::to_string(v) + " outside [0, 1]");
    } else if (std::abs(v) > 3.14159265358979323846) {
      throw InvalidInput("angle " + names[i] + " = " + std::to_string(v) + " outside [-pi, pi]");
    }
  }
}

std::vector<double> to_parameter_vector(const std::map<std::string, double>& named) {
  std::vector<double> values(kParameterCount, 0.0);
  for (const auto& [name, value] : named) values[parameter_index(name)] = value;
  validate_parameter_vector(values);
  return values;
}

}  // namespace emoface::muscles
