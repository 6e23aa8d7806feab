#include "emoface/mindmotion/muscle_tracks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "emoface/core/errors.hpp"
#include "emoface/muscles/parameters.hpp"

namespace emoface::mindmotion {

Eigen::MatrixXd graph_neutral_ibug68(const motiongraph::MotionGraph& graph) {
  if (graph.dimensions != 2) throw InvalidInput("muscle tracks: only 2D motion graphs are supported");
  Eigen::MatrixXd out = Eigen::MatrixXd::Constant(68, 2, std::numeric_limits<double>::quiet_NaN());
  for (const auto& region : graph.regions)
    for (std::size_t i = 0; i < region.landmarks.size(); ++i) {
      const int id = region.landmarks[i];
      if (id < 0 || id >= 68) throw InvalidInput("muscle tracks: landmark id outside iBUG-68");
      out.row(id) << region.neutral(static_cast<Eigen::Index>(2 * i)), region.neutral(static_cast<Eigen::Index>(2 * i + 1));
    }
  return out;
}

std::vector<Eigen::MatrixXd> face_displacements(const motiongraph::MotionGraph& graph, const CharacterMotion& motion,
                                                const Eigen::MatrixXd& face_neutral) {
  const Eigen::MatrixXd neutral = graph_neutral_ibug68(graph);
  const std::vector<int> ids = graph.landmark_ids();
  std::vector<Eigen::MatrixXd> out;
  out.reserve(motion.frames.size());
  for (const auto& pose : motion.frames) {
    if (pose.rows() != static_cast<Eigen::Index>(ids.size()) || pose.cols() != 2)
      throw InvalidInput("muscle tracks: a frame does not match the graph's landmarks");
    Eigen::MatrixXd d = Eigen::MatrixXd::Constant(68, 2, std::numeric_limits<double>::quiet_NaN());
    for (std::size_t i = 0; i < ids.size(); ++i) d.row(ids[i]) = pose.row(static_cast<Eigen::Index>(i)) - neutral.row(ids[i]);
    // NaN rows stay NaN through the scaling.
    out.push_back(bridge::image_to_face(d, neutral, face_neutral));
  }
  return out;
}

std::vector<muscles::ParameterFrame> fit_muscle_tracks(const bridge::LandmarkFitter& fitter,
                                                       const motiongraph::MotionGraph& graph,
                                                       const CharacterMotion& motion, TrackFitSummary* summary) {
  const auto targets = face_displacements(graph, motion, fitter.neutral_landmarks());
  std::vector<bridge::FitReport> reports;
  const auto track = fitter.fit_track(targets, &reports);
  std::vector<muscles::ParameterFrame> frames;
  TrackFitSummary s;
  for (std::size_t k = 0; k < track.size(); ++k) {
    muscles::ParameterFrame f;
    f.time = static_cast<double>(k) / motion.frame_rate;
    f.values.assign(muscles::kParameterCount, 0.0);
    std::copy(track[k].begin(), track[k].end(), f.values.begin());
    frames.push_back(std::move(f));
    s.mean_rms += reports[k].rms_surrogate / static_cast<double>(track.size());
    s.max_rms = std::max(s.max_rms, reports[k].rms_surrogate);
    s.not_converged += reports[k].converged ? 0 : 1;
  }
  if (summary) *summary = s;
  return frames;
}

}  // namespace emoface::mindmotion
