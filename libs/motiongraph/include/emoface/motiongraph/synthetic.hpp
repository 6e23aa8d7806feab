#pragma once
// Synthetic labelled landmark database (CK+-like: 68 iBUG points, 640×490 pixels, neutral-to-peak,
// 30 fps) for tests, demos and the §7 evaluation. Expressions come from a LandmarkModel; the built-in
// ParametricLandmarkModel is a documented parametric face. The face-driven model (default
// face + fuzzyexpr + muscles, projected to 2D) plugs in through the same interface.
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "emoface/motiongraph/database.hpp"

namespace emoface::motiongraph {

/// A person: similarity pose in the image plus small shape offsets of the neutral face.
struct Identity {
  double scale = 1.0;     ///< relative face size, > 0
  double roll = 0.0;      ///< in-plane rotation, radians
  Eigen::Vector2d translation = Eigen::Vector2d::Zero();  ///< pixels from the image centre
  Eigen::MatrixXd shape;  ///< 68 by 2 neutral offsets (pixels) or empty (= none)
};

/// Maps an expression to 68 2D landmarks (iBUG-68 order, pixels, y down, 640×490 image).
class LandmarkModel {
 public:
  virtual ~LandmarkModel() = default;
  /// `intensity` in [0, 1]: 0 = neutral, 1 = full expression of `label`.
  virtual Eigen::MatrixXd landmarks(Label label, double intensity,
                                    const Identity& identity) const = 0;
};

/// Parametric iBUG-68 face: a neutral template of arcs and ellipses, and per label a sum of
/// FACS-action-unit displacement fields (EMFACS prototypes; see docs/motiongraph.md).
class ParametricLandmarkModel : public LandmarkModel {
 public:
  ParametricLandmarkModel();
  Eigen::MatrixXd landmarks(Label label, double intensity, const Identity& identity) const override;
  /// Template in face units (face width ≈ 0.94, centred, y down).
  const Eigen::MatrixXd& neutral_template() const { return neutral_; }
  /// Displacement field of a label at intensity 1, face units.
  const Eigen::MatrixXd& field(Label label) const;

 private:
  Eigen::MatrixXd neutral_;
  std::vector<Eigen::MatrixXd> fields_;  // per Label
};

/// φ+(x, Do) = exp(ln2·x/Do) − 1 (thesis §4.4 onset curve): 0 at x = 0, 1 at x = Do.
double onset_curve(double x, double onset_duration);

struct SyntheticOptions {
  std::uint64_t seed = 1;
  std::size_t sequences_per_label = 10;  ///< >= 1; 7 labels × 10 = 70 sequences (the paper's size)
  std::vector<Label> labels = {Label::Happiness, Label::Sadness, Label::Disgust, Label::Surprise,
                               Label::Anger,     Label::Fear,    Label::Contempt};
  std::size_t subjects = 20;             ///< distinct identities, >= 1 (paper: ~20 subjects)
  std::size_t min_frames = 10;           ///< neutral-to-peak length range (frames, >= 2)
  std::size_t max_frames = 30;           ///< CK+ sequences have 10–60 frames, mostly < 30
  double min_intensity = 0.6;            ///< peak intensity range, (0, 1]
  double max_intensity = 1.0;
  double scale_std = 0.05;               ///< identity size variation (relative)
  double shape_std = 2.0;                ///< identity shape offsets (pixels)
  double translation_std = 15.0;         ///< head position in the image (pixels)
  double roll_std = 0.03;                ///< head roll (radians)
  double noise_std = 0.4;                ///< per-frame landmark tracking noise (pixels)
  double frame_rate = 30.0;
  void validate() const;
};

/// Labelled neutral-to-peak sequences: intensity(frame i) = peak · φ+(i, n−1). Seeded; ids
/// "S<subject>_<n>" like CK+.
Database generate_synthetic_database(const LandmarkModel& model, const SyntheticOptions& options = {});
/// Sequences [block.first, block.second) of generate_synthetic_database (a shard's contiguous
/// block, core::Shard::block): the same sequences, bit for bit, as the whole database holds at
/// those indices. InvalidInput unless first <= second <= synthetic_sequence_count(options).
Database generate_synthetic_database(const LandmarkModel& model, const SyntheticOptions& options,
                                     std::pair<std::size_t, std::size_t> block);

/// Number of sequences generate_synthetic_database makes: sequences_per_label × labels.
std::size_t synthetic_sequence_count(const SyntheticOptions& options);
/// Sequence `index` (< synthetic_sequence_count) of generate_synthetic_database, computed alone (its
/// randomness comes from the stream of its index), so shards of a batch give the same sequences.
Sequence synthetic_sequence(const LandmarkModel& model, const SyntheticOptions& options, std::size_t index);

}  // namespace emoface::motiongraph
