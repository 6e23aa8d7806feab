#pragma once
// Parameter names: the contract between channels and the face (ARCHITECTURE.md). The thesis
// (§4.3) calls muscles and eye/head controls alike "parameters".
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace emoface::channels {

/// The 19 muscles of thesis Table 2.1, in the thesis' numbering order (muscle k has index k−1).
const std::vector<std::string>& muscle_names();

/// True for the muscles that have a left and a right instance (all but orbicularis_oris_funneler,
/// orbicularis_oris_pressor and masseter).
bool is_paired_muscle(std::string_view muscle);

/// The 42 default parameters (muscles::parameter_names()): the 35 face parameters (each paired muscle
/// as <name>_l, <name>_r in Table 2.1 order, the unpaired ones by their name), then eye_gaze_yaw,
/// eye_gaze_pitch, head_yaw, head_pitch, head_roll (radians; + = subject's left / up), then
/// eye_blink_l, eye_blink_r (lid closure, AU45, [0, 1]).
const std::vector<std::string>& default_parameter_names();

/// True for the signed angle parameters (eye_gaze_* and head_*); all others are contractions in
/// [0,1].
bool is_signed_parameter(std::string_view name);

/// True if `name` is one of default_parameter_names().
bool is_known_parameter(std::string_view name);

/// The parameters that realise muscle `muscle` on the face: {muscle_l, muscle_r} or {muscle}.
/// Throws InvalidInput for an unknown muscle.
std::vector<std::string> muscle_parameters(std::string_view muscle);

/// The muscle a face parameter belongs to (strips _l/_r); empty for gaze/head or unknown names.
std::string parameter_muscle(std::string_view parameter);

}  // namespace emoface::channels
