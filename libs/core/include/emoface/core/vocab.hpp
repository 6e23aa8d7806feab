#pragma once
// The one vocabulary of emoface (issue 18, item 2): the names of emotions, muscles and face
// parameters, defined once below the mesh-free libraries. fuzzyexpr (ESV/FMCV), channels (parameter
// tracks) and muscles (the face) all take their names from here; tests/vocab checks that they
// agree.
//
// Sources: the six emotions of the Emotion State Vector (thesis §6.1, §6.5, in ESV order); the 19
// muscles of thesis Table 2.1 (thesis number = index + 1); §4.3: every muscle has a left and a
// right instance except the two Orbicularis Oris parts and the Masseter, giving 35 side parameters;
// then the pose parameters (gaze and head, radians) and the eyelid parameters (FACS AU45) that
// emoface adds.
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace emoface::core {

inline constexpr std::size_t kEmotionCount = 6;
/// ESV order (thesis §6.5): sadness, happiness, anger, fear, disgust, surprise.
inline constexpr std::array<std::string_view, kEmotionCount> kEmotionNames = {
    "sadness", "happiness", "anger", "fear", "disgust", "surprise"};

inline constexpr std::size_t kMuscleCount = 19;
/// Thesis Table 2.1 order (muscle k has index k − 1).
inline constexpr std::array<std::string_view, kMuscleCount> kMuscleNames = {
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

/// False for the three muscles the face has once (orbicularis_oris_funneler,
/// orbicularis_oris_pressor, masseter; thesis §4.3), true for the other 16.
constexpr bool is_paired_muscle(std::size_t muscle_index) noexcept {
  return muscle_index != 6 && muscle_index != 7 && muscle_index != 18;
}
/// By name; false for unknown names.
bool is_paired_muscle(std::string_view muscle) noexcept;
std::optional<std::size_t> muscle_index(std::string_view muscle) noexcept;
std::optional<std::size_t> emotion_index(std::string_view emotion) noexcept;

/// 16 paired muscles × 2 + 3 unpaired.
inline constexpr std::size_t kSideParameterCount = 35;
/// Gaze and head angles (radians; + = subject's left / up; head_roll + = top towards subject's
/// right).
inline constexpr std::array<std::string_view, 5> kPoseParameterNames = {
    "eye_gaze_yaw", "eye_gaze_pitch", "head_yaw", "head_pitch", "head_roll"};
/// Lid closure beyond the muscles (FACS AU45), levels in [0, 1].
inline constexpr std::array<std::string_view, 2> kEyelidParameterNames = {"eye_blink_l",
                                                                          "eye_blink_r"};
inline constexpr std::size_t kParameterCount =
    kSideParameterCount + kPoseParameterNames.size() + kEyelidParameterNames.size();

/// The 35 side parameters: each muscle in Table 2.1 order as "<name>_l", "<name>_r" when paired, or
/// "<name>" when not.
const std::array<std::string, kSideParameterCount>& side_parameter_names() noexcept;
/// All 42: side, then pose, then eyelid parameters (the face's value vector order).
const std::vector<std::string>& parameter_names() noexcept;
/// Index in parameter_names(), or nothing.
std::optional<std::size_t> parameter_index(std::string_view name) noexcept;
/// True for the signed angles (pose parameters); all others are levels in [0, 1].
bool is_signed_parameter(std::string_view name) noexcept;

}  // namespace emoface::core
