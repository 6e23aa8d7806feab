#include "emoface/core/bounded_lm.hpp"

#include <array>
#include <utility>

namespace emoface::core {

void BoundedLmOptions::validate() const {
  if (max_iterations < 1) throw InvalidInput("BoundedLmOptions: max_iterations must be >= 1");
  if (!(function_tolerance >= 0.0 && function_tolerance < 1.0))
    throw InvalidInput("BoundedLmOptions: function_tolerance must be in [0, 1)");
  if (!(gradient_tolerance >= 0.0) || !std::isfinite(gradient_tolerance))
    throw InvalidInput("BoundedLmOptions: gradient_tolerance must be finite and >= 0");
  if (!(parameter_tolerance >= 0.0) || !std::isfinite(parameter_tolerance))
    throw InvalidInput("BoundedLmOptions: parameter_tolerance must be finite and >= 0");
  if (!(initial_damping > 0.0) || !std::isfinite(initial_damping))
    throw InvalidInput("BoundedLmOptions: initial_damping must be finite and > 0");
  if (!(min_relative_decrease >= 0.0 && min_relative_decrease < 1.0))
    throw InvalidInput("BoundedLmOptions: min_relative_decrease must be in [0, 1)");
}

namespace {
constexpr std::array<std::pair<BoundedLmStatus, const char*>, 6> kStatusNames{{
    {BoundedLmStatus::FunctionTolerance, "function_tolerance"},
    {BoundedLmStatus::GradientTolerance, "gradient_tolerance"},
    {BoundedLmStatus::ParameterTolerance, "parameter_tolerance"},
    {BoundedLmStatus::MaxIterations, "max_iterations"},
    {BoundedLmStatus::DampingTooLarge, "damping_too_large"},
    {BoundedLmStatus::Failure, "failure"},
}};
}  // namespace

std::string to_string(BoundedLmStatus status) {
  for (const auto& [s, name] : kStatusNames)
    if (s == status) return name;
  return "unknown";
}

BoundedLmStatus bounded_lm_status_from_string(const std::string& name) {
  std::string known;
  for (const auto& [s, n] : kStatusNames) {
    if (name == n) return s;
    known += (known.empty() ? "" : ", ") + std::string(n);
  }
  throw InvalidInput("unknown bounded LM status \"" + name + "\" (known: " + known + ")");
}

}  // namespace emoface::core
