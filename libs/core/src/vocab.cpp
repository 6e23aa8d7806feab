#include "emoface/core/vocab.hpp"

namespace emoface::core {

std::optional<std::size_t> muscle_index(std::string_view muscle) noexcept {
  for (std::size_t i = 0; i < kMuscleCount; ++i)
    if (kMuscleNames[i] == muscle) return i;
  return std::nullopt;
}

std::optional<std::size_t> emotion_index(std::string_view emotion) noexcept {
  for (std::size_t i = 0; i < kEmotionCount; ++i)
    if (kEmotionNames[i] == emotion) return i;
  return std::nullopt;
}

bool is_paired_muscle(std::string_view muscle) noexcept {
  auto i = muscle_index(muscle);
  return i && is_paired_muscle(*i);
}

const std::array<std::string, kSideParameterCount>& side_parameter_names() noexcept {
  static const std::array<std::string, kSideParameterCount> names = [] {
    std::array<std::string, kSideParameterCount> out;
    std::size_t k = 0;
    for (std::size_t i = 0; i < kMuscleCount; ++i) {
      const std::string base(kMuscleNames[i]);
      if (is_paired_muscle(i)) {
        out[k++] = base + "_l";
        out[k++] = base + "_r";
      } else {
        out[k++] = base;
      }
    }
    return out;
  }();
  return names;
}

const std::vector<std::string>& parameter_names() noexcept {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out(side_parameter_names().begin(), side_parameter_names().end());
    for (std::string_view n : kPoseParameterNames) out.emplace_back(n);
    for (std::string_view n : kEyelidParameterNames) out.emplace_back(n);
    return out;
  }();
  return names;
}

std::optional<std::size_t> parameter_index(std::string_view name) noexcept {
  const auto& names = parameter_names();
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return i;
  return std::nullopt;
}

bool is_signed_parameter(std::string_view name) noexcept {
  for (std::string_view n : kPoseParameterNames)
    if (n == name) return true;
  return false;
}

}  // namespace emoface::core
