#pragma once
// Names of the ARKit-52 blend shapes and the Live Link Face columns.
//
// Three spellings of one ARKit shape are in use:
//   raw value    "eyeBlink_L"     ARFaceAnchor.BlendShapeLocation(rawValue:), the dictionary keys ARKit
//                                 delivers (Apple ARKit documentation) — emoface's canonical spelling;
//   Swift name   "eyeBlinkLeft"   the Swift/Objective-C constant (ARBlendShapeLocationEyeBlinkLeft);
//   Live Link    "EyeBlinkLeft"   the Live Link Face CSV column (the Swift name capitalised).
// Readers accept all three, case-insensitively; writers write the raw value (or the Live Link Face
// column in Live Link Face files). _L / _R = the subject's own left / right (emoface's _l / _r).
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace emoface::faceweights {

/// The 52 ARKit raw values in Apple's documentation order (alphabetical by Swift name).
const std::vector<std::string>& arkit_names();

/// "eyeBlink_L" → "eyeBlinkLeft"; names without a side suffix are unchanged.
std::string arkit_swift_name(std::string_view raw);

/// "eyeBlink_L" → "EyeBlinkLeft" (the Live Link Face CSV column).
std::string live_link_face_name(std::string_view raw);

/// The raw value for any of the three spellings (case-insensitive), or nullopt.
std::optional<std::string> arkit_raw_name(std::string_view any);

/// The 61 values of a Live Link Face frame after "Timecode,BlendShapeCount": the 52 shapes in Live
/// Link Face order (EyeBlinkLeft, EyeLookDownLeft, …, TongueOut), then HeadYaw, HeadPitch, HeadRoll,
/// LeftEyeYaw, LeftEyePitch, LeftEyeRoll, RightEyeYaw, RightEyePitch, RightEyeRoll.
const std::vector<std::string>& live_link_face_columns();

/// For each of the first 52 live_link_face_columns(), its index in arkit_names().
const std::vector<int>& live_link_face_to_arkit();

}  // namespace emoface::faceweights
