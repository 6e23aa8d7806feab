#pragma once
// Parameter frames for faceanim: one named parameter vector per frame, from
//   CSV with a header row (columns = parameter names; "time" in seconds optional; metadata columns
//       id, frame, index, label, name and the six emotion names are ignored — so emo2muscle's
//       35-column output, with or without its input columns, feeds straight in),
//   NDJSON (one object per line: {"time": t, "parameters": {name: value}} or a flat {name: value}),
//   JSON (a flat {name: value} object = one frame, or the envelope "emoface.params" 1.0 with
//       "fps" and "frames": [{"time": t, "parameters": {...}}]).
// Missing parameters are 0. Every error names the file and line/column or JSON pointer.
#include <string>
#include <string_view>
#include <vector>

namespace emoface::muscles {

struct ParameterFrame {
  double time = 0.0;           ///< seconds (from the file, else index / fps)
  std::vector<double> values;  ///< kParameterCount values in parameter_names() order
};

enum class FrameFormat { Csv, Ndjson, Json };
std::string to_string(FrameFormat format);
FrameFormat frame_format_from_string(std::string_view name);  ///< "csv", "ndjson", "json"
/// By extension: .csv, .ndjson/.jsonl, .json. Throws InvalidInput otherwise.
FrameFormat frame_format_from_path(const std::string& path);

struct FrameReadOptions {
  double fps = 25.0;                    ///< frame rate for files without times, (0, 1000]
  bool ignore_unknown_columns = false;  ///< unknown names are an error unless set
  void validate() const;
};

std::vector<ParameterFrame> parse_parameter_frames(std::string_view text, FrameFormat format, const std::string& source,
                                                   const FrameReadOptions& options = {});
std::vector<ParameterFrame> read_parameter_frames(const std::string& path, const FrameReadOptions& options = {});

/// CSV with header "time,<42 parameter names>" (round-trips through parse_parameter_frames).
std::string format_parameter_frames_csv(const std::vector<ParameterFrame>& frames);
/// JSON envelope "emoface.params" 1.0 (round-trips).
std::string format_parameter_frames_json(const std::vector<ParameterFrame>& frames, double fps);

}  // namespace emoface::muscles
