#pragma once
// Named parameters of a face (the contract with fuzzyexpr, channels and the CLIs).
// Muscle parameters are contraction levels in [0, 1]; angles are radians.
#include <array>
#include <cstddef>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace emoface::muscles {

/// The 19 muscle types of thesis Table 2.1, in table order (numbering 1–19 = index + 1).
const std::array<std::string, 19>& muscle_type_names();

/// The 35 side parameters: for each Table 2.1 muscle in order, "<name>_l","<name>_r" when paired, or
/// "<name>" for orbicularis_oris_funneler, orbicularis_oris_pressor and masseter (fuzzyexpr's
/// expand_to_sides order).
const std::vector<std::string>& side_parameter_names();

/// Extra named parameters: eye_gaze_yaw, eye_gaze_pitch (radians, both eyes, + = subject's left / up),
/// head_yaw (+ = subject's left), head_pitch (+ = up), head_roll (+ = top of the head towards the
/// subject's right, i.e. about +z out of the face).
const std::vector<std::string>& pose_parameter_names();

/// Eyelid closure beyond the muscles (FACS AU45, a blink): eye_blink_l, eye_blink_r, levels in [0, 1]
/// (1 = the upper lid meets the lower lid). Orbicularis oculi palpebralis stays the thesis' muscle
/// parameter; blinks and deliberate closure use these.
const std::vector<std::string>& eyelid_parameter_names();

/// All 42: side parameters, then pose parameters, then eyelid parameters. This is the order of
/// FaceSolver's value vector (indices 0–39 are those of the 40-parameter list of emoface ≤ 0.3).
const std::vector<std::string>& parameter_names();
inline constexpr std::size_t kSideParameterCount = 35;
inline constexpr std::size_t kPoseParameterCount = 5;
inline constexpr std::size_t kEyelidParameterCount = 2;
inline constexpr std::size_t kParameterCount = kSideParameterCount + kPoseParameterCount + kEyelidParameterCount;
/// True for the parameters that are levels in [0, 1] (muscles and eyelids); the others are angles.
inline constexpr bool is_level_parameter(std::size_t index) {
  return index < kSideParameterCount || index >= kSideParameterCount + kPoseParameterCount;
}

/// Index of a name in parameter_names(); throws InvalidInput for an unknown name.
std::size_t parameter_index(std::string_view name);

/// Named values -> full vector (missing names = 0). Throws InvalidInput for unknown names, NaN/inf,
/// or muscle levels outside [0, 1]. Angles must be finite and within [-π, π].
std::vector<double> to_parameter_vector(const std::map<std::string, double>& named);

/// Checks a full vector (size, finite, levels in [0, 1], angles in [-π, π]). Throws InvalidInput naming the parameter.
void validate_parameter_vector(const std::vector<double>& values);

}  // namespace emoface::muscles
