#include "emoface/channels/parameters.hpp"

#include <algorithm>

#include "emoface/core/errors.hpp"
#include "emoface/core/vocab.hpp"

namespace emoface::channels {

// Names from the one vocabulary (emoface/core/vocab.hpp): thesis Table 2.1 and §4.3.
const std::vector<std::string>& muscle_names() {
  static const std::vector<std::string> names(core::kMuscleNames.begin(), core::kMuscleNames.end());
  return names;
}

bool is_paired_muscle(std::string_view muscle) {
  // Unknown names count as paired, as before (muscle_parameters rejects them).
  auto i = core::muscle_index(muscle);
  return !i || core::is_paired_muscle(*i);
}

const std::vector<std::string>& default_parameter_names() { return core::parameter_names(); }

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
