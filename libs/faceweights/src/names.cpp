#include "emoface/faceweights/names.hpp"

#include <algorithm>
#include <cctype>

#include "emoface/core/errors.hpp"
#include "emoface/core/text.hpp"

namespace emoface::faceweights {
namespace {


bool ends_with(std::string_view s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}

}  // namespace

const std::vector<std::string>& arkit_names() {
  // Apple ARKit documentation, ARFaceAnchor.BlendShapeLocation: 52 locations, raw values.
  static const std::vector<std::string> names = {
      "browDown_L",       "browDown_R",       "browInnerUp",     "browOuterUp_L",
      "browOuterUp_R",    "cheekPuff",        "cheekSquint_L",   "cheekSquint_R",
      "eyeBlink_L",       "eyeBlink_R",       "eyeLookDown_L",   "eyeLookDown_R",
      "eyeLookIn_L",      "eyeLookIn_R",      "eyeLookOut_L",    "eyeLookOut_R",
      "eyeLookUp_L",      "eyeLookUp_R",      "eyeSquint_L",     "eyeSquint_R",
      "eyeWide_L",        "eyeWide_R",        "jawForward",      "jawLeft",
      "jawOpen",          "jawRight",         "mouthClose",      "mouthDimple_L",
      "mouthDimple_R",    "mouthFrown_L",     "mouthFrown_R",    "mouthFunnel",
      "mouthLeft",        "mouthLowerDown_L", "mouthLowerDown_R", "mouthPress_L",
      "mouthPress_R",     "mouthPucker",      "mouthRight",      "mouthRollLower",
      "mouthRollUpper",   "mouthShrugLower",  "mouthShrugUpper", "mouthSmile_L",
      "mouthSmile_R",     "mouthStretch_L",   "mouthStretch_R",  "mouthUpperUp_L",
      "mouthUpperUp_R",   "noseSneer_L",      "noseSneer_R",     "tongueOut"};
  return names;
}

std::string arkit_swift_name(std::string_view raw) {
  if (ends_with(raw, "_L")) return std::string(raw.substr(0, raw.size() - 2)) + "Left";
  if (ends_with(raw, "_R")) return std::string(raw.substr(0, raw.size() - 2)) + "Right";
  return std::string(raw);
}

std::string live_link_face_name(std::string_view raw) {
  std::string s = arkit_swift_name(raw);
  if (!s.empty()) s[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(s[0])));
  return s;
}

std::optional<std::string> arkit_raw_name(std::string_view any) {
  const std::string key = core::ascii_lower(any);
  for (const auto& raw : arkit_names()) {
    if (core::ascii_lower(raw) == key || core::ascii_lower(arkit_swift_name(raw)) == key)
      return raw;
  }
  return std::nullopt;
}

const std::vector<std::string>& live_link_face_columns() {
  // Live Link Face (Epic Games) CSV header after "Timecode,BlendShapeCount", as written by the app
  // and read by the public importers (e.g. the Blender Live Link Face add-on's LIVE_LINK_FACE_HEADER);
  // the same order is the value order of its version-6 UDP packets.
  static const std::vector<std::string> cols = {
      "EyeBlinkLeft",     "EyeLookDownLeft",  "EyeLookInLeft",    "EyeLookOutLeft",
      "EyeLookUpLeft",    "EyeSquintLeft",    "EyeWideLeft",      "EyeBlinkRight",
      "EyeLookDownRight", "EyeLookInRight",   "EyeLookOutRight",  "EyeLookUpRight",
      "EyeSquintRight",   "EyeWideRight",     "JawForward",       "JawRight",
      "JawLeft",          "JawOpen",          "MouthClose",       "MouthFunnel",
      "MouthPucker",      "MouthRight",       "MouthLeft",        "MouthSmileLeft",
      "MouthSmileRight",  "MouthFrownLeft",   "MouthFrownRight",  "MouthDimpleLeft",
      "MouthDimpleRight", "MouthStretchLeft", "MouthStretchRight", "MouthRollLower",
      "MouthRollUpper",   "MouthShrugLower",  "MouthShrugUpper",  "MouthPressLeft",
      "MouthPressRight",  "MouthLowerDownLeft", "MouthLowerDownRight", "MouthUpperUpLeft",
      "MouthUpperUpRight", "BrowDownLeft",    "BrowDownRight",    "BrowInnerUp",
      "BrowOuterUpLeft",  "BrowOuterUpRight", "CheekPuff",        "CheekSquintLeft",
      "CheekSquintRight", "NoseSneerLeft",    "NoseSneerRight",   "TongueOut",
      "HeadYaw",          "HeadPitch",        "HeadRoll",         "LeftEyeYaw",
      "LeftEyePitch",     "LeftEyeRoll",      "RightEyeYaw",      "RightEyePitch",
      "RightEyeRoll"};
  return cols;
}

const std::vector<int>& live_link_face_to_arkit() {
  static const std::vector<int> map = [] {
    std::vector<int> m;
    const auto& names = arkit_names();
    for (std::size_t i = 0; i < 52; ++i) {
      const auto raw = arkit_raw_name(live_link_face_columns()[i]);
      if (!raw) throw Error("live_link_face_to_arkit: internal name table mismatch");
      m.push_back(static_cast<int>(std::find(names.begin(), names.end(), *raw) - names.begin()));
    }
    return m;
  }();
  return map;
}

}  // namespace emoface::faceweights
