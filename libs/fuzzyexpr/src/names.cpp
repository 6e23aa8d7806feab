#include "emoface/fuzzyexpr/names.hpp"

#include <cctype>
#include <string>

namespace emoface::fuzzyexpr {
namespace {

constexpr std::array<std::string_view, kEmotionCount> kEmotionNames = {
    "sadness", "happiness", "anger", "fear", "disgust", "surprise"};

constexpr std::array<std::string_view, kMuscleCount> kMuscleNames = {
    "zygomatic_major",
    "zygomatic_minor",
    "triangularis",
    "risorius",
    "depressor_labii",
    "mentalis",
    "orbicularis_oris_funneler",
    "orbicularis_oris_pressor",
    "frontalis_medialis",
    "frontalis_lateralis",
    "levator_labii_nasi",
    "levator_labii_superioris",
    "depressor_supercilii",
    "corrugator_supercilii",
    "depressor_glabellae",
    "levator_palpebrae_superioris",
    "orbicularis_oculi_palpebralis",
    "orbicularis_oculi_orbitalis",
    "masseter",
};

bool iequals(std::string_view a, std::string_view b) noexcept {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) != b[i]) return false;
  return true;
}

struct SideNames {
  std::array<std::string, kSideParameterCount> storage;
  std::array<std::string_view, kSideParameterCount> views;
  SideNames() {
    std::size_t k = 0;
    for (std::size_t i = 0; i < kMuscleCount; ++i) {
      if (is_paired(muscle_at(i))) {
        storage[k++] = std::string(kMuscleNames[i]) + "_l";
        storage[k++] = std::string(kMuscleNames[i]) + "_r";
      } else {
        storage[k++] = std::string(kMuscleNames[i]);
      }
    }
    for (std::size_t j = 0; j < kSideParameterCount; ++j) views[j] = storage[j];
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

bool is_paired(Muscle m) noexcept {
  return m != Muscle::OrbicularisOrisFunneler && m != Muscle::OrbicularisOrisPressor &&
         m != Muscle::Masseter;
}

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
