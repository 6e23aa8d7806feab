#pragma once
// Weight tracks as files: parameter tracks written as ARKit / FACS / Live Link Face CSV (the shared
// writer behind emo2muscle, talkinghead, obie and mindmap), and ARKit weight tracks read back
// (faceanim --weights arkit).
//
//   arkit-csv      "# emoface x.y.z" stamp, header "time,<52 ARKit raw names>", one row per frame
//   facs-csv       the same with the FACS rows (AU1_L, …)
//   livelink-csv   Live Link Face's CSV: header "Timecode,BlendShapeCount,EyeBlinkLeft,…,TongueOut,
//                  HeadYaw,HeadPitch,HeadRoll,LeftEyeYaw,LeftEyePitch,LeftEyeRoll,RightEyeYaw,
//                  RightEyePitch,RightEyeRoll" (names.hpp), no stamp line (importers expect the header
//                  first), Timecode "HH:MM:SS:FF.fff" (FF = frame within the second at the integer
//                  frame rate, .fff = sub-frame), BlendShapeCount 61; angles in radians.
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "emoface/faceweights/weight_set.hpp"

namespace emoface::faceweights {

enum class TrackFormat { ArkitCsv, FacsCsv, LiveLinkFaceCsv };
std::string_view to_string(TrackFormat f) noexcept;  ///< "arkit-csv", "facs-csv", "livelink-csv"
std::optional<TrackFormat> track_format_from_string(std::string_view s) noexcept;

/// "HH:MM:SS:FF.fff" for `seconds` ≥ 0 at an integer frame rate `fps` (1–1000).
std::string live_link_timecode(double seconds, int fps);
/// Inverse of live_link_timecode (also "HH:MM:SS:FF" without sub-frame); nullopt if malformed or
/// a field is out of range (minutes/seconds ≥ 60, frame ≥ fps).
std::optional<double> parse_live_link_timecode(std::string_view text, int fps);

/// Formats parameter frames (`frames[i]` in `names` order, `times[i]` seconds, increasing) as
/// `format`. `fps` is the Live Link Face timecode rate (must be an integer there). Levels must be in
/// [0, 1] (Mapper::forward). Throws InvalidInput.
std::string format_weight_track(TrackFormat format, const std::vector<std::string>& names,
                                const std::vector<double>& times,
                                const std::vector<std::vector<double>>& frames, double fps,
                                int precision = 6);
void write_weight_track(const std::string& path, TrackFormat format,
                        const std::vector<std::string>& names, const std::vector<double>& times,
                        const std::vector<std::vector<double>>& frames, double fps);

/// A track of target weights read from CSV.
struct WeightTrack {
  std::vector<std::string> targets;           ///< the set's target names (set order)
  std::vector<double> times;                  ///< seconds, from the file's first row
  std::vector<std::vector<double>> weights;   ///< per frame, in `targets` order, each in [0, 1]
  /// Angles found in Live Link Face columns, per frame, by emoface parameter name: head_yaw,
  /// head_pitch, head_roll (HeadYaw/Pitch/Roll), eye_gaze_yaw, eye_gaze_pitch (the mean of the
  /// left and right eye columns). Empty if the file has none.
  std::vector<std::map<std::string, double>> pose;
};

struct WeightTrackReadOptions {
  double fps = 60.0;            ///< rate of Timecode columns and of files without a time column
  bool ignore_unknown_columns = false;
  void validate() const;
};

/// Reads a CSV whose header names every target of `set` (any ARKit spelling, case-insensitive, for
/// the arkit set), an optional time column ("time" in seconds or Live Link Face "Timecode"),
/// optional "BlendShapeCount" and Live Link Face angle columns. Errors are FormatError naming the
/// file, line and column: a missing target column, an unknown column, a repeated column, a
/// non-number, NaN/inf, a weight outside [0, 1], a row of the wrong length, no rows.
WeightTrack parse_weight_track(std::string_view text, const WeightSet& set, const std::string& file,
                               const WeightTrackReadOptions& options = {});
WeightTrack read_weight_track(const std::string& path, const WeightSet& set,
                              const WeightTrackReadOptions& options = {});

}  // namespace emoface::faceweights
