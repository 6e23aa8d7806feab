#pragma once
// Face-tracking captures as motion-graph training data (issue 19, item 1; paper §4 builds its
// graphs from captured CK+ landmark sequences):
//   * readers and writers of OpenFace 2.0 FeatureExtraction CSV and of MediaPipe face-landmarker
//     results (one JSON object per frame), both giving the 68 iBUG landmarks per frame;
//   * clean_frames: confidence/success filtering, short gaps interpolated, long gaps split the
//   take;
//   * stabilise_head: per-frame similarity alignment onto the take's rest pose on stable landmarks;
//   * find_segments: automatic trimming of long takes into neutral-to-peak segments (onset
//   detection
//     on the landmark displacement magnitude, docs/motiongraph.md "Captures");
//   * capture_database: all of it, with labels from a per-frame column or a side file.
// Formats and where real files come from: docs/motiongraph.md. Everything is mesh-free.
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "emoface/motiongraph/database.hpp"
#include "emoface/motiongraph/io.hpp"
#include "emoface/motiongraph/synthetic.hpp"

namespace emoface::motiongraph {

/// One tracker's per-frame output for one take, unfiltered.
struct TrackedFrames {
  std::string id;                   ///< take id (file stem by default)
  /// Of `frames`: 2 (pixels) or 3; 1 = a weight take (issue 19 item 2: each frame one column of
  /// channel weights, e.g. the ARKit-52 of a Live Link Face CSV, read by bridge/weight_space.hpp).
  /// Weight takes are filtered and trimmed like landmark takes but never stabilised.
  int dimensions = 2;
  std::vector<double> times;        ///< seconds, strictly increasing
  std::vector<double> confidence;   ///< per frame, [0, 1]
  std::vector<char> success;        ///< per frame, 0 or 1 (the tracker found the face)
  std::vector<Pose> frames;         ///< per frame, 68 iBUG landmarks by `dimensions` (or
                                    ///< channels by 1)
  std::vector<std::string> labels;  ///< per frame (a label column), or empty
  std::vector<std::string>
      au_names;  ///< OpenFace action-unit columns (AU01_r, …, AU45_c), or empty
  std::vector<std::vector<double>> au;  ///< per frame, in au_names order
  std::size_t size() const noexcept { return frames.size(); }
  void validate() const;  ///< sizes and values; throws InvalidInput
};

// ---- OpenFace 2.0 -------------------------------------------------------------------------------

struct OpenFaceReadOptions {
  bool use_3d = false;       ///< read X_i, Y_i, Z_i (millimetres) instead of x_i, y_i (pixels)
  int face_id = 0;           ///< rows of other faces (FaceLandmarkVidMulti) are ignored, >= 0
  std::string label_column;  ///< a column holding a label per frame ("" = none)
  void validate() const;
};

/// OpenFace 2.0 FeatureExtraction CSV (header "frame, face_id, timestamp, confidence, success, …,
/// x_0, …, x_67, y_0, …, y_67, [X_0 … Z_67,] …, AU01_r, …, AU45_c"; names may carry the spaces
/// OpenFace writes after commas; `face_id` is optional; other columns are ignored). Errors are
/// FormatError "file:line:field: message": a missing or repeated column, a row of the wrong length,
/// a non-number, NaN/inf, |coordinate| > 1e6, confidence outside [0, 1], success not 0/1,
/// timestamps not increasing, no rows.
TrackedFrames parse_openface_csv(std::string_view text, const std::string& file,
                                 const OpenFaceReadOptions& options = {});
TrackedFrames read_openface_csv(const std::string& path, const OpenFaceReadOptions& options = {});
/// The columns frame (1-based), face_id, timestamp, confidence, success, x_/y_ (2D takes) or
/// X_/Y_/Z_ (3D takes), the AU columns and, when the take has labels, `label`; ", " separators as
/// OpenFace writes them. Reads back equal (round trip) with label_column "label".
std::string openface_csv(const TrackedFrames& take);

// ---- MediaPipe face landmarker ------------------------------------------------------------------

/// MediaPipe's 478 face-landmarker points → iBUG-68: for each iBUG point (0-based) one or two
/// MediaPipe indices whose mean is the point. The table is
/// data/motiongraph/mediapipe478_ibug68.json (compiled in); its source is cited there and in
/// docs/motiongraph.md.
const std::vector<std::vector<int>>& mediapipe_to_ibug68();

struct MediaPipeReadOptions {
  double image_width = 640.0;   ///< pixels: x is normalised by the image width, (0, 1e5]
  double image_height = 490.0;  ///< pixels: y is normalised by the image height, (0, 1e5]
  bool use_z = false;           ///< 3D: z × image_width (MediaPipe's z has about x's scale)
  void validate() const;
};

/// MediaPipe face-landmarker results, one JSON object per line (`#` lines and blank lines skipped):
/// {"timestamp_ms": 33.3, "face_landmarks": [[{"x": 0.51, "y": 0.42, "z": -0.03}, … 478 …]],
///  "label": "happiness"} — the fields of the Tasks API's FaceLandmarkerResult (face_landmarks, one
/// list per face; the first face is used), plus our optional `label`; other fields
/// (face_blendshapes, facial_transformation_matrixes) are ignored. A frame with no face gets
/// success 0. Errors are FormatError naming the file, line and JSON pointer: not an object, a
/// missing field, a face without 478 points, a non-number, NaN/inf, |x|, |y|, |z| > 100, timestamps
/// not increasing.
TrackedFrames parse_mediapipe_ndjson(std::string_view text, const std::string& file,
                                     const MediaPipeReadOptions& options = {});
TrackedFrames read_mediapipe_ndjson(const std::string& path,
                                    const MediaPipeReadOptions& options = {});

/// One frame of 478 normalised MediaPipe points (478 by 3) that the correspondence maps exactly
/// back to `ibug` (68 by 2 pixels, or 68 by 3 with z in pixels): points of one-index iBUG points
/// take the point, pairs are set so that their mean is the point, the other points take the
/// landmarks' centroid (they carry no information for emoface). For the example generator and
/// tests.
Eigen::MatrixXd mediapipe_points_from_ibug68(const Pose& ibug,
                                             const MediaPipeReadOptions& options = {});
/// Writes frames of 478 normalised points (each 478 by 3; empty = no face) as
/// parse_mediapipe_ndjson reads them; `labels` may be empty.
std::string mediapipe_ndjson(const std::vector<double>& times,
                             const std::vector<Eigen::MatrixXd>& points,
                             const std::vector<std::string>& labels = {});
/// An iBUG-68 take (2 or 3 dimensions, pixels) as MediaPipe NDJSON: each frame through
/// mediapipe_points_from_ibug68 (with `options`), a failed frame (success 0) without a face, the
/// take's labels kept.
std::string mediapipe_ndjson(const TrackedFrames& take, const MediaPipeReadOptions& options = {});

// ---- Cleaning, stabilisation, trimming ----------------------------------------------------------

struct FrameFilterOptions {
  double min_confidence = 0.75;  ///< frames below are dropped, [0, 1]
  bool require_success = true;   ///< frames with success 0 are dropped
  /// Runs of at most this many dropped frames are filled by linear interpolation between their
  /// neighbours; a longer run ends the part (the take is split), [0, 1000].
  std::size_t max_gap = 3;
  std::size_t min_frames = 4;  ///< parts shorter than this are discarded, >= 2
  void validate() const;
};

/// The take's usable parts: dropped frames interpolated or splitting the take (parts are named
/// "<id>" when the take stays whole, else "<id>.p<k>"). Every returned frame has success 1.
std::vector<TrackedFrames> clean_frames(const TrackedFrames& take,
                                        const FrameFilterOptions& options = {});

struct StabiliseOptions {
  /// Stable landmarks (iBUG, 0-based) that define the head pose: the outer and inner eye corners
  /// and the nose bridge by default — they move little with expressions.
  std::vector<int> anchors = {27, 28, 29, 30, 36, 39, 42, 45};
  std::size_t reference_frames =
      5;  ///< the reference is the per-landmark median of the first frames, >= 1
  void validate() const;
};

/// Removes rigid head motion: every frame is mapped by the similarity transform (scale, rotation,
/// translation; Umeyama 1991) that best maps its anchors onto the reference frame's anchors.
/// Returns the per-frame RMS anchor residual after alignment (landmark units).
std::vector<double> stabilise_head(TrackedFrames& take, const StabiliseOptions& options = {});

struct TrimOptions {
  std::size_t reference_frames = 5;  ///< rest reference: median of the first frames, >= 1
  /// Thresholds on the displacement magnitude above its moving baseline, e(t) = m(t) − b(t), as
  /// fractions of the rest pose's outer-eye-corner distance (iBUG 36–45): an episode is a run with
  /// e > low that reaches e > high. 0 < low < high <= 1.
  double low = 0.006;
  double high = 0.015;
  /// The same thresholds for weight takes (dimensions 1: ARKit/FACS weights in [0, 1], issue 19
  /// item 2), in weight units: e > weight_low reaching e > weight_high. 0 < low < high <= 1.
  /// Live Link Face weights jitter by about ±0.01 at rest; an expression moves its top quarter of
  /// channels by 0.1–0.6 (docs/motiongraph.md "Weight space").
  double weight_low = 0.03;
  double weight_high = 0.08;
  /// The baseline b(t) is the minimum of m within ±baseline_window seconds, (0, 600]: it follows
  /// slow drift of the rest pose but not an onset (CK+ onsets last < 1 s).
  double baseline_window = 1.5;
  /// m(t) is the RMS displacement of the most displaced `top_fraction` of the 68 landmarks, (0, 1]
  /// (1 = all landmarks; 0.25 keeps a one-sided smile from being diluted by the still face).
  double top_fraction = 0.25;
  std::size_t min_frames = 4;  ///< shorter neutral-to-peak segments are dropped, >= 2
  void validate() const;
};

/// A neutral-to-peak segment of a take: frames [first, peak] (indices into the take).
struct TakeSegment {
  std::size_t first = 0;
  std::size_t peak = 0;
};

/// Onset detection on displacement magnitude (docs/motiongraph.md "Captures"): m(t) = RMS distance
/// to the rest reference of the top_fraction most displaced landmarks, smoothed by a centred
/// 3-frame mean; e(t) = m(t) minus its moving minimum; each episode's segment starts at the last
/// frame before it (at rest) and ends at its largest e. `magnitude` receives e when not null.
std::vector<TakeSegment> find_segments(const TrackedFrames& take, const TrimOptions& options = {},
                                       std::vector<double>* magnitude = nullptr);

/// Labels from a side file: CSV with header "take,segment,label", `segment` a 0-based segment index
/// or `*` (every segment of the take). FormatError names the file, line and field.
struct LabelTable {
  std::map<std::pair<std::string, std::string>, Label> entries;  ///< (take, segment or "*") → label
};
LabelTable parse_label_table(std::string_view text, const std::string& file);
LabelTable read_label_table(const std::string& path);
std::string label_table_csv(const LabelTable& table);
/// The side file of takes that carry a label column (the example generator's): for each take, the
/// segments the default options find (clean_frames, stabilise_head, find_segments, in that order,
/// segment k counted over the take's parts) labelled with the take's label at the segment's peak
/// frame; neutral peaks are left out. InvalidInput for a take without a label column or an unknown
/// label.
LabelTable segment_label_table(const std::vector<TrackedFrames>& takes);

struct CaptureOptions {
  FrameFilterOptions filter;
  bool stabilise = true;
  StabiliseOptions stabilisation;
  bool trim = true;  ///< find_segments; off = every part is one neutral-to-peak sequence
  TrimOptions trimming;
  OnError on_error = OnError::Stop;  ///< a segment without a label, a take without usable frames
  void validate() const;
};

/// Takes → labelled landmark database (one sequence per segment, id "<part>/<k>", subject = take
/// id). A segment's label comes from the side table (take, k) or (take, *), else from the take's
/// label column at the segment's peak frame; a segment whose label is neutral or missing is an
/// error (Stop) or skipped and reported (Skip). All takes must share dimensions and frame rate
/// (within 5 %); the database's frame rate is the median frame rate. Throws InvalidInput /
/// FormatError.
Database capture_database(const std::vector<TrackedFrames>& takes,
                          const CaptureOptions& options = {}, const LabelTable* labels = nullptr,
                          ReadReport* report = nullptr);

// ---- Example generator --------------------------------------------------------------------------

struct CaptureExampleOptions {
  SyntheticOptions database;     ///< the sequences (identities, onsets, noise) of the takes
  std::size_t rest_frames = 12;  ///< frames at rest before, between and after expressions, >= 1
  std::size_t hold_frames = 6;   ///< frames holding the peak, >= 0
  double head_roll = 0.04;       ///< amplitude of the slow head roll (radians), [0, 0.5]
  double head_shift = 6.0;       ///< amplitude of the slow head translation (pixels), [0, 100]
  double head_scale = 0.02;      ///< amplitude of the slow size change (relative), [0, 0.3]
  /// Every this many rest frames one frame is a tracking failure (success 0, confidence 0.1,
  /// landmarks zero as OpenFace writes them); 0 = none.
  std::size_t dropout_every = 7;
  void validate() const;
};

/// Long takes from `model`: one per subject, each sequence of the synthetic database played as rest
/// → onset → hold → offset (the onset reversed) → rest, with slow rigid head motion and tracking
/// dropouts, and a per-frame label column (the sequence's label, `neutral` at rest). Deterministic
/// for the options' seed.
std::vector<TrackedFrames> generate_capture_takes(const LandmarkModel& model,
                                                  const CaptureExampleOptions& options = {});

}  // namespace emoface::motiongraph
