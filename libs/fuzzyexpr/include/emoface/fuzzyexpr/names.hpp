#pragma once
// The vocabulary of fuzzyexpr: the six emotions of the Emotion State Vector (ESV) and the 19 muscles of
// the Facial Muscle Contraction Vector (FMCV), thesis §6.5 and Table 2.1, plus the documented expansion of
// the 19 right-side muscles to the 35 left/right face parameters that the muscle model takes.
//
// Names are the contract between libraries and files: files always store names, never numbers. The
// thesis numbers muscles 1–19 (right side); thesis_number() gives that mapping.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

namespace emoface::fuzzyexpr {

/// The six basic emotions of the ESV, in ESV order (thesis §6.1, §6.5).
enum class Emotion : std::uint8_t { Sadness, Happiness, Anger, Fear, Disgust, Surprise };
inline constexpr std::size_t kEmotionCount = 6;

/// The 19 muscles of Table 2.1, in thesis order (thesis number = index + 1).
enum class Muscle : std::uint8_t {
  ZygomaticMajor,              // 1
  ZygomaticMinor,              // 2
  Triangularis,                // 3
  Risorius,                    // 4
  DepressorLabii,              // 5
  Mentalis,                    // 6
  OrbicularisOrisFunneler,     // 7  (unpaired: lip model)
  OrbicularisOrisPressor,      // 8  (unpaired: lip model)
  FrontalisMedialis,           // 9
  FrontalisLateralis,          // 10
  LevatorLabiiNasi,            // 11
  LevatorLabiiSuperioris,      // 12
  DepressorSupercilii,         // 13
  CorrugatorSupercilii,        // 14
  DepressorGlabellae,          // 15
  LevatorPalpebraeSuperioris,  // 16
  OrbicularisOculiPalpebralis, // 17 (eye closing)
  OrbicularisOculiOrbitalis,   // 18
  Masseter,                    // 19 (unpaired: jaw rotation)
};
inline constexpr std::size_t kMuscleCount = 19;
inline constexpr std::size_t kSideParameterCount = 35;

/// Emotion intensities in [0,1], indexed by Emotion.
using Esv = std::array<double, kEmotionCount>;
/// Muscle contraction levels in [0,1], indexed by Muscle.
using Fmcv = std::array<double, kMuscleCount>;
/// The 35 face parameters, in the order of side_parameter_names().
using SideParameters = std::array<double, kSideParameterCount>;

inline constexpr std::size_t index(Emotion e) noexcept { return static_cast<std::size_t>(e); }
inline constexpr std::size_t index(Muscle m) noexcept { return static_cast<std::size_t>(m); }
inline constexpr Emotion emotion_at(std::size_t i) noexcept { return static_cast<Emotion>(i); }
inline constexpr Muscle muscle_at(std::size_t i) noexcept { return static_cast<Muscle>(i); }

/// Lower-case snake_case names: "sadness", "zygomatic_major", ...
std::string_view to_string(Emotion e) noexcept;
std::string_view to_string(Muscle m) noexcept;
/// Case-insensitive lookup of a name; std::nullopt if unknown.
std::optional<Emotion> emotion_from_string(std::string_view name) noexcept;
std::optional<Muscle> muscle_from_string(std::string_view name) noexcept;

/// Thesis numbering (Table 2.1): 1 … 19.
inline constexpr int thesis_number(Muscle m) noexcept { return static_cast<int>(m) + 1; }

/// True for the 16 muscles that exist on both sides; false for the two Orbicularis Oris parts and the
/// masseter, which the face model has once.
bool is_paired(Muscle m) noexcept;

/// The 35 face parameter names, in muscle order; a paired muscle gives "<name>_l" then "<name>_r",
/// an unpaired one its plain name: zygomatic_major_l, zygomatic_major_r, …, orbicularis_oris_funneler,
/// orbicularis_oris_pressor, …, masseter.
const std::array<std::string_view, kSideParameterCount>& side_parameter_names() noexcept;

/// Expands an FMCV symmetrically: both sides of a paired muscle get its level (thesis §6.5 computes the
/// right side; emotional expressions are displayed symmetrically).
SideParameters expand_to_sides(const Fmcv& fmcv) noexcept;

}  // namespace emoface::fuzzyexpr
