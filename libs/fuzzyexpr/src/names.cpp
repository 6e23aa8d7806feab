#include "emoface/fuzzyexpr/names.hpp"

#include <cctype>
#include <string>

#include "emoface/core/vocab.hpp"

namespace emoface::fuzzyexpr {
namespace {

// The names come from the one vocabulary (emoface/core/vocab.hpp); the enums here number them.
static_assert(kEmotionCount == core::kEmotionCount && kMuscleCount == core::kMuscleCount &&
              kSideParameterCount == core::kSideParameterCount);
constexpr const auto& kEmotionNames = core::kEmotionNames;
constexpr const auto& kMuscleNames = core::kMuscleNames;

bool iequals(std::string_view a, std::string_view b) noexcept {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) != b[i]) return false;
  return true;
}

struct SideNames {
  std::array<std::string_view, kSideParameterCount> views;
  SideNames() {
    for (std::size_t j = 0; j < kSideParameterCount; ++j)
      views[j] = core::side_parameter_names()[j];
  }
};

}  // namespace

std::string_view to_string(Emotion e) noexcept { return kEmotionNames[index(e)]; }
std::string_view to_string(Muscle m) noexcept { return kMuscleNames[index(m)]; }

std::optional<Emotion> emotion_from_string(std::string_view name) noexcept {
  for (std::size_t i = 0; i < kEmotionCount; ++i)
    if (iequals(name, kEmotionNames[i])) return emotion_at(i);
  return std::nullopt;
}

std::optional<Muscle> muscle_from_string(std::string_view name) noexcept {
  for (std::size_t i = 0; i < kMuscleCount; ++i)
    if (iequals(name, kMuscleNames[i])) return muscle_at(i);
  return std::nullopt;
}

bool is_paired(Muscle m) noexcept { return core::is_paired_muscle(index(m)); }

const std::array<std::string_view, kSideParameterCount>& side_parameter_names() noexcept {
  static const SideNames names;
  return names.views;
}

SideParameters expand_to_sides(const Fmcv& fmcv) noexcept {
  SideParameters out{};
  std::size_t k = 0;
  for (std::size_t i = 0; i < kMuscleCount; ++i) {
    out[k++] = fmcv[i];
    if (is_paired(muscle_at(i))) out[k++] = fmcv[i];
  }
  return out;
}

}  // namespace emoface::fuzzyexpr
