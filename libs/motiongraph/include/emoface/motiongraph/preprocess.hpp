#pragma once
// Database preprocessing before graph creation (paper §4, §7): reduced landmarks and regions,
// Procrustes alignment, sigmoid cleaning per landmark and sample, optional reversed copies.
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "emoface/motiongraph/curves.hpp"
#include "emoface/motiongraph/database.hpp"
#include "emoface/motiongraph/layout.hpp"

namespace emoface::motiongraph {

struct PreprocessOptions {
  bool align = true;            ///< Procrustes alignment (§4); off = raw coordinates
  bool clean = true;            ///< sigmoid fit per landmark displacement per sample (§4)
  bool append_reversed = true;  ///< append each sample's reversed copy (offset motion, §7)
  /// Reject samples that do not start neutral: (a) the first frame must be the farthest from the
  /// last within `neutral_start_tolerance` (relative, >= 0) plus `neutral_start_slack` (RMS landmark
  /// units, >= 0), and (b) the first frame, Procrustes-aligned, must be closer to the database's mean
  /// neutral than the last frame is, up to `neutral_mean_slack` (RMS landmark units, >= 0).
  bool check_neutral_start = true;
  double neutral_start_tolerance = 0.25;
  double neutral_start_slack = 1.0;
  double neutral_mean_slack = 0.25;
  /// A sample failing the neutral-start check is left out and named in PreprocessReport::skipped
  /// (`mgraph build --on-error skip`) instead of stopping the run; the mean neutral is then
  /// recomputed without it.
  bool skip_bad_samples = false;
  SigmoidFitOptions sigmoid;
  void validate() const;
};

/// One sample after preprocessing: per region, frames by (k_r·dimensions) displacements from the
/// sample's own first (neutral) pose, landmark-major, in the aligned frame.
struct PreparedSample {
  std::string id;
  std::string subject;
  Label label = Label::Neutral;
  std::size_t peak_frame = 0;  ///< index of the peak (last original frame)
  std::vector<Eigen::MatrixXd> displacement;  ///< one per region
  std::size_t frame_count() const { return displacement.empty() ? 0 : displacement[0].rows(); }
};

struct PreparedDatabase {
  int dimensions = 2;
  double frame_rate = 30.0;
  LandmarkLayout layout;
  /// Per region: the averaged aligned neutral pose, flattened 1 by (k_r·dimensions).
  std::vector<Eigen::RowVectorXd> neutral;
  std::vector<PreparedSample> samples;
};

struct PreprocessReport {
  std::size_t sigmoid_fits = 0;
  std::size_t sigmoid_not_converged = 0;
  double mean_fit_rms = 0.0;  ///< landmark units
  std::vector<std::string> skipped;  ///< with skip_bad_samples: one message per left-out sample
};

/// Runs the preprocessing. Throws InvalidInput for an invalid database (see validate()), a layout
/// that does not match its landmark count, no samples, or a sample that does not start neutral.
PreparedDatabase preprocess(const Database& db, const LandmarkLayout& layout,
                            const PreprocessOptions& options = {},
                            PreprocessReport* report = nullptr);

/// Similarity transform (scale, rotation, translation) that best maps `from` onto `to`
/// (both n by d, n >= 2), least squares (Umeyama 1991). Returns (d+1) by (d+1) homogeneous matrix.
Eigen::MatrixXd procrustes(const Eigen::MatrixXd& from, const Eigen::MatrixXd& to);

/// Applies a homogeneous transform from procrustes() to an n by d pose.
Eigen::MatrixXd apply_transform(const Eigen::MatrixXd& transform, const Eigen::MatrixXd& pose);

}  // namespace emoface::motiongraph
