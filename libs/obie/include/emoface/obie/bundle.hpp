#pragma once
// The obie CLI's outputs as library calls (issue 18, item 4): every file of a run staged into one
// core::OutputBundle (all written or none), the one-screen summary, and the --key-moment syntax.
#include <string>
#include <vector>

#include "emoface/core/bundle.hpp"
#include "emoface/facemesh/io.hpp"
#include "emoface/obie/match.hpp"
#include "emoface/obie/pipeline.hpp"

namespace emoface::obie {

/// Which optional files a run writes besides the fixed ones.
struct OutputSelection {
  std::vector<std::string> weights;  ///< any of "arkit", "facs", "livelink" (→ arkit.csv, facs.csv,
                                     ///< livelink_face.csv)
  bool speech_wav = true;  ///< speech.wav (false when a VideoSink writes it)
};

/// Stages into `bundle`, in `out_dir`: timeline.ndjson, tracks.csv, the selected weight CSVs,
/// speech.wav, face.glb (when result.gltf_frames is not empty: the face's rig baked, the tracks'
/// weights at result.gltf_times), charts.png, key_moments.png (when there are key frames) and
/// summary.json. Appends the time of each stage to result.timings. InvalidInput for an unknown
/// weight format.
void stage_outputs(core::OutputBundle& bundle, const std::string& out_dir, ObieResult& result,
                   const MatchScript& match, const facemesh::Face& face,
                   const OutputSelection& selection);

/// The one-screen report after a run: goals, final score, peak emotions, utterances, frames, time
/// per stage and in total, and the `written` files (paths) of `out_dir`.
std::string console_summary(const ObieResult& result, const MatchScript& match,
                            const std::string& match_path, const ObieOptions& options,
                            double total_seconds, const std::string& out_dir,
                            const std::vector<std::string>& written);

/// "MINUTE[:LABEL]" (e.g. "12:the against team scores") → key moment; InvalidInput otherwise.
KeyMoment parse_key_moment(const std::string& text);

}  // namespace emoface::obie
