#pragma once
// Weight-space motion graphs on the face (issue 19 item 2): ARKit-52 weight sequences as
// motion-graph training data, and synthesized weight motion driving the muscle face exactly through
// faceweights' parameter ↔ ARKit mapping (no landmark fit).
//
//   * arkit_layout(): the paper's regions (§4, fig. 3) over the ARKit channels;
//   * generate_weight_database(): the face-driven synthetic database in weight space — label →
//     fuzzyexpr → 35 side parameters (FaceLandmarkModel::side_parameters) → ARKit weights
//     (faceweights::Mapper::forward), per-subject gains, tracking noise;
//   * Live Link Face CSV takes (faceweights/tracks.hpp reads and writes the format) → weight takes
//     (motiongraph::TrackedFrames with dimensions 1), trimmed and labelled by
//     motiongraph::capture_database like landmark takes; generate_weight_takes() writes examples;
//   * weight_parameters(): synthesized weight frames → face parameters by Mapper::inverse.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "emoface/bridge/face_landmark_model.hpp"
#include "emoface/faceweights/mapper.hpp"
#include "emoface/motiongraph/capture.hpp"
#include "emoface/motiongraph/graph.hpp"
#include "emoface/motiongraph/layout.hpp"
#include "emoface/muscles/io.hpp"

namespace emoface::bridge {

/// Regions over the 52 ARKit channels (faceweights::arkit_names() order): eyes (eyeBlink, eyeLook,
/// eyeSquint, eyeWide; 14), brows (5), nose (noseSneer; 2), mouth (mouth*; 23), cheeks+jaw (cheek*,
/// jaw*; 7). tongueOut is left out: emoface's face has no tongue muscle
/// (data/faceweights/arkit.json).
motiongraph::LandmarkLayout arkit_layout();

/// The ARKit mapper on muscles::parameter_names() (the 42 face parameters).
const faceweights::Mapper& arkit_mapper();

/// ARKit weights (52, arkit_names() order) of the face-driven expression of `label` at `intensity`
/// in [0, 1]: Mapper::forward of FaceLandmarkModel::side_parameters (pose and gaze parameters 0).
std::vector<double> expression_weights(const FaceLandmarkModel& face, motiongraph::Label label,
                                       double intensity);

struct WeightDatabaseOptions {
  /// Sequences, labels, subjects, lengths, intensities, frame rate and seed as for the landmark
  /// database (the pixel fields — scale, shape, translation, roll, noise — are not used).
  motiongraph::SyntheticOptions database;
  double gain_std = 0.1;  ///< per-subject, per-channel gain ~ N(1, gain_std), >= 0 (people differ)
  double noise_std =
      0.01;  ///< per-frame tracking noise (weight units), >= 0; results clamped to [0, 1]
  void validate() const;
};

/// The synthetic database in weight space: dimensions 1, 52 channels, same sequence ids, subjects,
/// labels, lengths and φ+ onsets as motiongraph::generate_synthetic_database with the same options.
/// Deterministic for the seed.
motiongraph::Database generate_weight_database(const FaceLandmarkModel& face,
                                               const WeightDatabaseOptions& options = {});

/// A Live Link Face / ARKit CSV take (faceweights::parse_weight_track with the built-in arkit set)
/// as a weight take: frames 52 by 1, confidence 1, success 1 (the app records neither), no labels
/// (use a side file). `fps` is the Timecode rate. FormatError names the file, line and column.
motiongraph::TrackedFrames parse_live_link_take(std::string_view text, const std::string& file,
                                                double fps = 60.0, const std::string& id = "");
motiongraph::TrackedFrames read_live_link_take(const std::string& path, double fps = 60.0);
/// The take as Live Link Face CSV at integer `fps` (weights must be in [0, 1]).
std::string live_link_csv(const motiongraph::TrackedFrames& take, double fps);

/// Synthesized frames of an ARKit weight graph as a 52-channel weight take (channels outside the
/// graph's regions 0, values clamped to [0, 1], time = index / frame rate), e.g. for live_link_csv.
/// Throws InvalidInput for a landmark graph or frames that do not match it.
motiongraph::TrackedFrames weight_take(const motiongraph::MotionGraph& graph,
                                       const std::vector<motiongraph::Pose>& frames,
                                       const std::string& id);

struct WeightTakeOptions {
  WeightDatabaseOptions database;
  std::size_t rest_frames = 12;  ///< frames at rest before, between and after expressions, >= 1
  std::size_t hold_frames = 6;   ///< frames holding the peak, >= 0
  void validate() const;
};

/// Long weight takes, one per subject: each of its sequences of generate_weight_database played as
/// rest → onset → hold → offset (the onset reversed) → rest, with tracking noise at rest and hold
/// and a per-frame label column (`neutral` at rest; kept in memory — Live Link files carry no
/// labels, write a side table with weight_take_labels()). Deterministic for the seed.
std::vector<motiongraph::TrackedFrames> generate_weight_takes(
    const FaceLandmarkModel& face, const WeightTakeOptions& options = {});

/// The side table (take, segment, label) of takes with label columns, from the same trimming
/// capture_database does (each segment gets the label at its peak frame; neutral segments are left
/// out).
motiongraph::LabelTable weight_take_labels(const std::vector<motiongraph::TrackedFrames>& takes,
                                           const motiongraph::TrimOptions& trimming = {});

struct WeightDriveReport {
  std::size_t frames = 0;
  double max_weight_error = 0.0;  ///< max |forward(fitted) − synthesized| over frames and channels
  std::size_t not_converged = 0;
  std::vector<std::string> unrepresented;  ///< channels with weight but no muscle (tongueOut)
};

/// Synthesized weight frames of a weight graph over the ARKit channels → face parameter frames
/// (muscles::parameter_names() order, time = index / frame rate): Mapper::inverse per frame, warm
/// started from the previous one. Exact where the weights are in the range of the mapping (weights
/// made by the mapping, e.g. the generated databases); the report gives the largest weight error.
/// Throws InvalidInput for a landmark graph or a graph whose channels are not ARKit-52.
std::vector<muscles::ParameterFrame> weight_parameters(const motiongraph::MotionGraph& graph,
                                                       const std::vector<motiongraph::Pose>& frames,
                                                       WeightDriveReport* report = nullptr);

}  // namespace emoface::bridge
