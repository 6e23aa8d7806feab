#pragma once
// Labelled landmark sequences: the input of motion-graph building (paper §4: a dynamic 2D/3D sparse
// database of neutral-to-peak samples with expression labels, e.g. CK/CK+) and the output of synthesis.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace emoface::motiongraph {

/// Expression labels of CK/CK+ (paper §4): the seven emotions plus neutral.
enum class Label { Neutral, Happiness, Sadness, Disgust, Surprise, Anger, Fear, Contempt };

/// All labels in enum order.
const std::vector<Label>& all_labels();
/// "neutral", "happiness", ... (lower case).
std::string to_string(Label label);
/// Inverse of to_string. Throws InvalidInput for an unknown name.
Label label_from_string(std::string_view name);

/// One pose: landmark_count by dimensions (2 or 3), row i = landmark i; pixels (2D) or the
/// database's length unit (3D). Weight space (issue 19 item 2): dimensions 1, row i = the weight of
/// channel i (an ARKit blend shape or FACS action unit, in [0, 1]); "landmark" then means channel.
using Pose = Eigen::MatrixXd;

/// One labelled sequence. Samples start at a neutral pose; the last frame is the peak (CK+ layout).
struct Sequence {
  std::string id;       ///< unique within a database, e.g. "S005_001"
  std::string subject;  ///< person id, e.g. "S005"; may be empty
  Label label = Label::Neutral;
  std::vector<Pose> frames;  ///< each landmark_count by dimensions
};

/// A set of sequences sharing landmark count, dimensionality and frame rate.
struct Database {
  int dimensions = 2;              ///< 2 or 3 (landmarks), 1 (weight space: one value per channel)
  std::size_t landmark_count = 0;  ///< landmarks per pose (68 for CK+)
  double frame_rate = 30.0;        ///< frames per second, > 0 (CK+ was recorded at 30 fps)
  /// Optional: for each landmark, its index in the source layout (e.g. iBUG-68), when the poses hold a
  /// subset (synthesized output holds the reduced set). Empty means 0..landmark_count-1.
  std::vector<int> landmark_ids;
  std::vector<Sequence> sequences;
};

/// Checks shapes and values: dimensions 1|2|3, landmark_count > 0, frame_rate > 0, unique non-empty ids,
/// every frame landmark_count by dimensions, finite coordinates, at least `min_frames` frames per
/// sequence, landmark_ids empty or of size landmark_count. Throws InvalidInput naming the sequence and
/// frame.
void validate(const Database& db, std::size_t min_frames = 2);

}  // namespace emoface::motiongraph
