#include "emoface/bridge/face_landmark_model.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "emoface/core/errors.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/fuzzyexpr/names.hpp"
#include "emoface/muscles/parameters.hpp"

namespace emoface::bridge {

namespace mg = motiongraph;

namespace {

constexpr Eigen::Index kLandmarks = 68;

muscles::FaceSolver default_solver() {
  facemesh::Face face = facemesh::make_generic_face();
  return muscles::FaceSolver(std::move(face.mesh), std::move(face.rig));
}

// The fuzzyexpr emotion of a motion-graph label (the six of the ESV; thesis §6.1).
std::optional<fuzzyexpr::Emotion> emotion_of(mg::Label label) {
  switch (label) {
    case mg::Label::Happiness:
      return fuzzyexpr::Emotion::Happiness;
    case mg::Label::Sadness:
      return fuzzyexpr::Emotion::Sadness;
    case mg::Label::Disgust:
      return fuzzyexpr::Emotion::Disgust;
    case mg::Label::Surprise:
      return fuzzyexpr::Emotion::Surprise;
    case mg::Label::Anger:
      return fuzzyexpr::Emotion::Anger;
    case mg::Label::Fear:
      return fuzzyexpr::Emotion::Fear;
    default:
      return std::nullopt;
  }
}

void check_intensity(double intensity) {
  if (!(intensity >= 0.0 && intensity <= 1.0))
    throw InvalidInput("face landmark model: intensity must be in [0, 1]");
}

}  // namespace

std::string_view to_string(Projection p) noexcept {
  return p == Projection::Perspective ? "perspective" : "orthographic";
}

std::optional<Projection> projection_from_string(std::string_view name) noexcept {
  if (name == "perspective") return Projection::Perspective;
  if (name == "orthographic") return Projection::Orthographic;
  return std::nullopt;
}

void FaceLandmarkModelOptions::validate() const {
  if (!(camera_distance >= 0.2 && camera_distance <= 100.0))
    throw InvalidInput("FaceLandmarkModelOptions: camera_distance must be in [0.2, 100] m");
  if (!(face_size_px > 0.0 && face_size_px <= 1000.0))
    throw InvalidInput("FaceLandmarkModelOptions: face_size_px must be in (0, 1000]");
  if (!centre_px.allFinite())
    throw InvalidInput("FaceLandmarkModelOptions: centre_px must be finite");
}

// Contempt: EMFACS prototype AU12 + AU14, unilateral (Ekman & Friesen; CK+ criteria, Lucey et al.
// 2010). Table 2.1 has no buccinator (AU14), so the corner tightening is the risorius pulling the
// corner back plus a little Orbicularis Oris pressing; AU12 is the zygomatic major. Weights chosen
// so the raised corner moves about as far as in motiongraph's parametric contempt
// (docs/motiongraph.md).
std::vector<double> contempt_parameters(double intensity) {
  check_intensity(intensity);
  std::vector<double> side(muscles::kSideParameterCount, 0.0);
  side[muscles::parameter_index("zygomatic_major_l")] = 0.7 * intensity;
  side[muscles::parameter_index("risorius_l")] = intensity;
  side[muscles::parameter_index("orbicularis_oris_pressor")] = 0.3 * intensity;
  return side;
}

FaceLandmarkModel::FaceLandmarkModel(FaceLandmarkModelOptions options)
    : FaceLandmarkModel(default_solver(), fuzzyexpr::Engine(), std::move(options)) {}

FaceLandmarkModel::FaceLandmarkModel(muscles::FaceSolver solver, fuzzyexpr::Engine engine,
                                     FaceLandmarkModelOptions options)
    : solver_(std::move(solver)), engine_(std::move(engine)), options_(std::move(options)) {
  options_.validate();
  const std::vector<int>& ids = solver_.rig().ibug68;
  if (ids.size() != static_cast<std::size_t>(kLandmarks))
    throw InvalidInput("face landmark model: the rig has no 68 iBUG landmarks");
  const facemesh::Vertices& v = solver_.neutral().vertices;
  neutral_.resize(kLandmarks, 3);
  for (Eigen::Index i = 0; i < kLandmarks; ++i) {
    const int id = ids[static_cast<std::size_t>(i)];
    if (id < 0 || id >= v.rows())
      throw InvalidInput("face landmark model: iBUG landmark " + std::to_string(i) +
                         " is not a vertex of the mesh");
    neutral_.row(i) = v.row(id);
  }
  centroid_ = neutral_.colwise().mean().transpose();
  // Scale and centre the camera image of the neutral face (computed with unit scale first).
  pixels_per_unit_ = 1.0;
  offset_.setZero();
  const Eigen::MatrixXd raw = project_raw(neutral_);
  const Eigen::RowVector2d c = raw.colwise().mean();
  const double rms = std::sqrt((raw.rowwise() - c).rowwise().squaredNorm().mean());
  if (!(rms > 0.0)) throw InvalidInput("face landmark model: the neutral landmarks are degenerate");
  pixels_per_unit_ = options_.face_size_px / rms;
  offset_ = options_.centre_px - pixels_per_unit_ * c.transpose();
}

std::vector<double> FaceLandmarkModel::side_parameters(mg::Label label, double intensity) const {
  check_intensity(intensity);
  if (label == mg::Label::Contempt) return contempt_parameters(intensity);
  std::vector<double> side(muscles::kSideParameterCount, 0.0);
  const auto emotion = emotion_of(label);
  if (!emotion || intensity == 0.0) return side;  // neutral: no contraction
  fuzzyexpr::Esv esv{};
  esv[fuzzyexpr::index(*emotion)] = intensity;
  const fuzzyexpr::SideParameters s = fuzzyexpr::expand_to_sides(engine_.convert(esv));
  // fuzzyexpr's side order is muscles' (both follow Table 2.1; checked in the tests).
  for (std::size_t j = 0; j < s.size(); ++j) side[j] = s[j];
  return side;
}

Eigen::MatrixXd FaceLandmarkModel::landmarks_3d(mg::Label label, double intensity) const {
  const std::vector<double> side = side_parameters(label, intensity);
  bool rest = true;
  for (double x : side) rest = rest && x == 0.0;
  if (rest) return neutral_;
  std::vector<double> values(muscles::kParameterCount, 0.0);
  std::copy(side.begin(), side.end(), values.begin());
  muscles::Deformation d;
  solver_.deform(values, d);
  const std::vector<int>& ids = solver_.rig().ibug68;
  Eigen::MatrixXd out(kLandmarks, 3);
  for (Eigen::Index i = 0; i < kLandmarks; ++i)
    out.row(i) = d.vertices.row(ids[static_cast<std::size_t>(i)]);
  return out;
}

// Camera on the face's +z axis through the neutral centroid, looking at −z, image x = face x (the
// subject's left appears on the image right, as in a frontal video), image y = −face y.
Eigen::MatrixXd FaceLandmarkModel::project_raw(const Eigen::MatrixXd& p) const {
  Eigen::MatrixXd px(p.rows(), 2);
  const double d = options_.camera_distance;
  for (Eigen::Index i = 0; i < p.rows(); ++i) {
    const Eigen::Vector3d q = p.row(i).transpose() - centroid_;
    double k = 1.0;
    if (options_.projection == Projection::Perspective) {
      const double depth = d - q.z();
      if (!(depth > 1e-6))
        throw NumericalError("face landmark model: a landmark is behind the camera");
      k = d / depth;  // 1 at the centroid's depth
    }
    px(i, 0) = pixels_per_unit_ * k * q.x();
    px(i, 1) = -pixels_per_unit_ * k * q.y();
  }
  px.rowwise() += offset_.transpose();
  return px;
}

Eigen::MatrixXd FaceLandmarkModel::project(const Eigen::MatrixXd& landmarks_3d,
                                           const mg::Identity& identity) const {
  if (landmarks_3d.rows() != kLandmarks || landmarks_3d.cols() != 3)
    throw InvalidInput("face landmark model: expected 68 by 3 landmarks");
  if (!landmarks_3d.allFinite())
    throw InvalidInput("face landmark model: landmarks must be finite");
  if (!(identity.scale > 0.0) || !std::isfinite(identity.scale))
    throw InvalidInput("face landmark model: identity scale must be > 0");
  if (!std::isfinite(identity.roll) || !identity.translation.allFinite())
    throw InvalidInput("face landmark model: identity roll and translation must be finite");
  if (identity.shape.size() != 0 &&
      (identity.shape.rows() != kLandmarks || identity.shape.cols() != 2))
    throw InvalidInput("face landmark model: identity shape must be 68 by 2");
  // The identity transform of motiongraph::ParametricLandmarkModel (which turns about its template
  // origin, 27 px above the centroid): scale and roll about the face centre, then translation and
  // per-person shape offsets.
  Eigen::MatrixXd rel = project_raw(landmarks_3d);
  rel.rowwise() -= options_.centre_px.transpose();
  const double c = std::cos(identity.roll), s = std::sin(identity.roll);
  Eigen::Matrix2d rot;
  rot << c, -s, s, c;
  Eigen::MatrixXd px = (rel * rot.transpose()) * identity.scale;
  px.rowwise() += (options_.centre_px + identity.translation).transpose();
  if (identity.shape.size() != 0) px += identity.shape;
  return px;
}

Eigen::MatrixXd FaceLandmarkModel::landmarks(mg::Label label, double intensity,
                                             const mg::Identity& identity) const {
  return project(landmarks_3d(label, intensity), identity);
}

}  // namespace emoface::bridge
