#include "emoface/muscles/parameters.hpp"

#include <cmath>

#include "emoface/core/errors.hpp"
#include "emoface/core/vocab.hpp"

namespace emoface::muscles {

// Every name comes from the one vocabulary (emoface/core/vocab.hpp).
static_assert(kSideParameterCount == core::kSideParameterCount &&
              kParameterCount == core::kParameterCount);

const std::array<std::string, 19>& muscle_type_names() {
  static const std::array<std::string, 19> names = [] {
    std::array<std::string, 19> out;
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = std::string(core::kMuscleNames[i]);
    return out;
  }();
  return names;
}

const std::vector<std::string>& side_parameter_names() {
  static const std::vector<std::string> names(core::side_parameter_names().begin(),
                                              core::side_parameter_names().end());
  return names;
}

const std::vector<std::string>& pose_parameter_names() {
  static const std::vector<std::string> names(core::kPoseParameterNames.begin(),
                                              core::kPoseParameterNames.end());
  return names;
}

const std::vector<std::string>& eyelid_parameter_names() {
  static const std::vector<std::string> names(core::kEyelidParameterNames.begin(),
                                              core::kEyelidParameterNames.end());
  return names;
}

const std::vector<std::string>& parameter_names() { return core::parameter_names(); }

std::size_t parameter_index(std::string_view name) {
  if (auto i = core::parameter_index(name)) return *i;
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
