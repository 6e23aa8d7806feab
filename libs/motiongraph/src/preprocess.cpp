#include "emoface/motiongraph/preprocess.hpp"

#include <cmath>

#include <Eigen/Dense>

#include "emoface/core/errors.hpp"
#include "flat.hpp"

namespace emoface::motiongraph {

void PreprocessOptions::validate() const {
  if (!(neutral_start_tolerance >= 0.0) || !std::isfinite(neutral_start_tolerance))
    throw InvalidInput("preprocess: neutral_start_tolerance must be >= 0");
  if (!(neutral_start_slack >= 0.0) || !std::isfinite(neutral_start_slack))
    throw InvalidInput("preprocess: neutral_start_slack must be >= 0");
  if (!(neutral_mean_slack >= 0.0) || !std::isfinite(neutral_mean_slack))
    throw InvalidInput("preprocess: neutral_mean_slack must be >= 0");
  sigmoid.validate();
}

// Umeyama (1991) least-squares similarity transform, as used for Procrustes analysis (paper §4).
Eigen::MatrixXd procrustes(const Eigen::MatrixXd& from, const Eigen::MatrixXd& to) {
  if (from.rows() != to.rows() || from.cols() != to.cols() || from.rows() < 2)
    throw InvalidInput("procrustes: need two n by d point sets of equal shape, n >= 2");
  const Eigen::Index d = from.cols();
  const Eigen::RowVectorXd mf = from.colwise().mean(), mt = to.colwise().mean();
  const Eigen::MatrixXd a = from.rowwise() - mf, b = to.rowwise() - mt;
  const double var = a.squaredNorm() / static_cast<double>(from.rows());
  Eigen::MatrixXd t = Eigen::MatrixXd::Identity(d + 1, d + 1);
  if (var <= 0.0) {  // degenerate: translation only
    t.topRightCorner(d, 1) = (mt - mf).transpose();
    return t;
  }
  const Eigen::MatrixXd cov = b.transpose() * a / static_cast<double>(from.rows());
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(cov, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::VectorXd s = Eigen::VectorXd::Ones(d);
  if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0) s[d - 1] = -1.0;
  const Eigen::MatrixXd r = svd.matrixU() * s.asDiagonal() * svd.matrixV().transpose();
  const double scale = (svd.singularValues().array() * s.array()).sum() / var;
  t.topLeftCorner(d, d) = scale * r;
  t.topRightCorner(d, 1) = mt.transpose() - scale * r * mf.transpose();
  return t;
}

Eigen::MatrixXd apply_transform(const Eigen::MatrixXd& transform, const Eigen::MatrixXd& pose) {
  const Eigen::Index d = pose.cols();
  if (transform.rows() != d + 1 || transform.cols() != d + 1)
    throw InvalidInput("apply_transform: transform size does not match the pose dimensions");
  Eigen::MatrixXd out = pose * transform.topLeftCorner(d, d).transpose();
  const Eigen::RowVectorXd shift = transform.topRightCorner(d, 1).transpose();
  out.rowwise() += shift;
  return out;
}

namespace {

using detail::flatten;

Eigen::MatrixXd rows_of(const Eigen::MatrixXd& pose, const std::vector<int>& idx) {
  Eigen::MatrixXd out(static_cast<Eigen::Index>(idx.size()), pose.cols());
  for (std::size_t i = 0; i < idx.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = pose.row(idx[i]);
  return out;
}

double rms_size(const Eigen::MatrixXd& centred) {
  return std::sqrt(centred.squaredNorm() / static_cast<double>(centred.rows()));
}

// Generalised Procrustes mean of the neutral poses (all centred at the origin), scaled to their
// average size so the result stays in the database's units.
Eigen::MatrixXd mean_neutral(const std::vector<Eigen::MatrixXd>& neutrals, bool align) {
  Eigen::MatrixXd mean = Eigen::MatrixXd::Zero(neutrals[0].rows(), neutrals[0].cols());
  for (const auto& n : neutrals) mean += n;
  mean /= static_cast<double>(neutrals.size());
  if (!align) return mean;
  double size = 0.0;
  for (const auto& n : neutrals) size += rms_size(n);
  size /= static_cast<double>(neutrals.size());
  Eigen::MatrixXd ref = neutrals[0];
  for (int it = 0; it < 5; ++it) {
    Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(ref.rows(), ref.cols());
    for (const auto& n : neutrals) sum += apply_transform(procrustes(n, ref), n);
    ref = sum / static_cast<double>(neutrals.size());
    ref = ref.rowwise() - ref.colwise().mean();
    const double s = rms_size(ref);
    if (s > 0.0) ref *= size / s;
  }
  return ref;
}

}  // namespace

PreparedDatabase preprocess(const Database& db, const LandmarkLayout& layout,
                            const PreprocessOptions& options, PreprocessReport* report) {
  options.validate();
  validate(db, 2);
  layout.validate();
  if (layout.source_landmark_count != db.landmark_count)
    throw InvalidInput("preprocess: the layout is for " +
                       std::to_string(layout.source_landmark_count) +
                       " landmarks, the database has " + std::to_string(db.landmark_count));
  if (db.sequences.empty()) throw InvalidInput("preprocess: the database has no sequences");

  PreparedDatabase out;
  out.dimensions = db.dimensions;
  out.frame_rate = db.frame_rate;
  out.layout = layout;
  const std::size_t nr = layout.regions.size();
  const std::vector<int> reduced = layout.reduced_landmarks();

  // Weight space (dimensions 1, issue 19 item 2): weights are already in the face's own frame —
  // no translation, no Procrustes alignment; the neutral is the plain mean of the first frames.
  const bool weights = db.dimensions == 1;
  const bool align = options.align && !weights;
  // Neutral-based translation (§4): each sample's first pose centred at the origin.
  std::vector<Eigen::RowVectorXd> shift(db.sequences.size());
  std::vector<Eigen::MatrixXd> neutrals;
  for (std::size_t s = 0; s < db.sequences.size(); ++s) {
    shift[s] = weights ? Eigen::RowVectorXd::Zero(1).eval()
                       : db.sequences[s].frames[0].colwise().mean().eval();
    neutrals.push_back(db.sequences[s].frames[0].rowwise() - shift[s]);
  }
  const Eigen::MatrixXd mean = mean_neutral(neutrals, align);
  for (const Region& r : layout.regions) out.neutral.push_back(flatten(rows_of(mean, r.landmarks)));

  PreprocessReport rep;
  double rms_sum = 0.0;
  std::vector<char> bad(db.sequences.size(), 0);
  for (std::size_t s = 0; s < db.sequences.size(); ++s) {
    const Sequence& seq = db.sequences[s];
    const std::size_t n = seq.frames.size();
    try {
    // Sequences must start neutral: the first frame is (about) the farthest from the peak.
    if (options.check_neutral_start && seq.label != Label::Neutral) {
      const Eigen::MatrixXd last = rows_of(seq.frames[n - 1], reduced);
      auto rms_to_last = [&](std::size_t f) {
        return rms_size(rows_of(seq.frames[f], reduced) - last);
      };
      const double first = rms_to_last(0);
      for (std::size_t f = 1; f < n; ++f)
        if (rms_to_last(f) > (1.0 + options.neutral_start_tolerance) * first +
                                 options.neutral_start_slack)
          throw InvalidInput("preprocess: sequence \"" + seq.id + "\" does not start neutral (frame " +
                             std::to_string(f) + " is farther from the peak than frame 0)");
      // ... and its first frame is closer to the database's mean neutral than its last frame.
      const Eigen::MatrixXd to_mean =
          weights ? Eigen::MatrixXd::Identity(2, 2).eval() : procrustes(neutrals[s], mean);
      auto rms_to_mean = [&](std::size_t f) {
        const Eigen::MatrixXd p = apply_transform(to_mean, seq.frames[f].rowwise() - shift[s]);
        return rms_size(rows_of(p, reduced) - rows_of(mean, reduced));
      };
      if (rms_to_mean(0) > rms_to_mean(n - 1) + options.neutral_mean_slack)
        throw InvalidInput("preprocess: sequence \"" + seq.id +
                           "\" does not start neutral (its last frame is closer to the mean neutral pose)");
    }
    } catch (const InvalidInput& e) {
      if (!options.skip_bad_samples) throw;
      rep.skipped.push_back(e.what());
      bad[s] = 1;
      continue;
    }
    PreparedSample ps;
    ps.id = seq.id;
    ps.subject = seq.subject;
    ps.label = seq.label;
    ps.peak_frame = n - 1;
    const std::size_t total = options.append_reversed ? 2 * n - 1 : n;
    for (std::size_t r = 0; r < nr; ++r) {
      const Region& reg = layout.regions[r];
      const std::vector<int>& markers = reg.alignment.empty() ? reg.landmarks : reg.alignment;
      // Regional Procrustes between samples (§4): the sample's neutral markers onto the mean's.
      Eigen::MatrixXd transform = Eigen::MatrixXd::Identity(db.dimensions + 1, db.dimensions + 1);
      if (align) transform = procrustes(rows_of(neutrals[s], markers), rows_of(mean, markers));
      const Eigen::Index k = static_cast<Eigen::Index>(reg.landmarks.size());
      Eigen::MatrixXd disp(static_cast<Eigen::Index>(n), k * db.dimensions);
      Eigen::RowVectorXd first;
      for (std::size_t f = 0; f < n; ++f) {
        Eigen::MatrixXd pose = rows_of(seq.frames[f], reg.landmarks).rowwise() - shift[s];
        const Eigen::RowVectorXd flat = flatten(apply_transform(transform, pose));
        if (f == 0) first = flat;
        disp.row(static_cast<Eigen::Index>(f)) = flat - first;
      }
      // Cleaning (§4): sigmoid fitted to each landmark's displacement, least squares.
      if (options.clean && n >= 3) {
        Eigen::VectorXd times(static_cast<Eigen::Index>(n));
        for (std::size_t f = 0; f < n; ++f) times[static_cast<Eigen::Index>(f)] = static_cast<double>(f);
        for (Eigen::Index l = 0; l < k; ++l) {
          const Eigen::MatrixXd y = disp.middleCols(l * db.dimensions, db.dimensions);
          SigmoidFitReport fr;
          const SigmoidCurve c = fit_sigmoid(y, options.sigmoid, &fr);
          ++rep.sigmoid_fits;
          if (!fr.converged) ++rep.sigmoid_not_converged;
          rms_sum += fr.rms;
          Eigen::MatrixXd fitted = c.evaluate(times);
          fitted = fitted.rowwise() - fitted.row(0);
          disp.middleCols(l * db.dimensions, db.dimensions) = fitted;
        }
      }
      if (options.append_reversed) {  // §7: offsets by appending the sample's reversed copy
        Eigen::MatrixXd both(static_cast<Eigen::Index>(total), disp.cols());
        both.topRows(static_cast<Eigen::Index>(n)) = disp;
        for (std::size_t f = n; f < total; ++f)
          both.row(static_cast<Eigen::Index>(f)) = disp.row(static_cast<Eigen::Index>(2 * (n - 1) - f));
        disp = both;
      }
      ps.displacement.push_back(std::move(disp));
    }
    out.samples.push_back(std::move(ps));
  }
  rep.mean_fit_rms = rep.sigmoid_fits ? rms_sum / static_cast<double>(rep.sigmoid_fits) : 0.0;
  if (!rep.skipped.empty()) {
    // The mean neutral included the left-out samples: start again without them.
    Database kept = db;
    kept.sequences.clear();
    for (std::size_t s = 0; s < db.sequences.size(); ++s)
      if (!bad[s]) kept.sequences.push_back(db.sequences[s]);
    PreprocessReport again;
    PreparedDatabase result = preprocess(kept, layout, options, &again);
    again.skipped.insert(again.skipped.begin(), rep.skipped.begin(), rep.skipped.end());
    if (report) *report = std::move(again);
    return result;
  }
  if (report) *report = rep;
  return out;
}

}  // namespace emoface::motiongraph
