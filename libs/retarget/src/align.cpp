#include "emoface/retarget/align.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "emoface/core/errors.hpp"
#include "emoface/core/rng.hpp"
#include "kdtree.hpp"

namespace emoface::retarget {
namespace {
Eigen::Vector3d axis_vector(Axis a) {
  switch (a) {
    case Axis::PosX: return Eigen::Vector3d::UnitX();
    case Axis::NegX: return -Eigen::Vector3d::UnitX();
    case Axis::PosY: return Eigen::Vector3d::UnitY();
    case Axis::NegY: return -Eigen::Vector3d::UnitY();
    case Axis::PosZ: return Eigen::Vector3d::UnitZ();
    case Axis::NegZ: return -Eigen::Vector3d::UnitZ();
  }
  return Eigen::Vector3d::UnitY();
}

std::vector<char> used_vertices(const facemesh::Mesh& mesh) {
  std::vector<char> used(mesh.vertex_count(), 0);
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.faces(f, k);
      if (v < 0 || v >= mesh.vertices.rows()) throw InvalidInput("detect_landmarks: face " + std::to_string(f) + " has a vertex id out of range");
      used[static_cast<std::size_t>(v)] = 1;
    }
  return used;
}

int arg_best(const facemesh::Mesh& mesh, const std::vector<char>& used, const std::function<double(const Eigen::Vector3d&)>& score) {
  int best = -1;
  double best_score = -std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < mesh.vertices.rows(); ++i) {
    if (!used[static_cast<std::size_t>(i)]) continue;
    const double s = score(mesh.vertices.row(i));
    if (s > best_score) {
      best_score = s;
      best = static_cast<int>(i);
    }
  }
  return best;
}
}  // namespace

std::string to_string(Axis axis) {
  static const char* names[] = {"+x", "-x", "+y", "-y", "+z", "-z"};
  return names[static_cast<int>(axis)];
}

Axis axis_from_string(std::string_view name) {
  for (int i = 0; i < 6; ++i)
    if (to_string(static_cast<Axis>(i)) == name) return static_cast<Axis>(i);
  throw InvalidInput("unknown axis \"" + std::string(name) + "\" (expected +x, -x, +y, -y, +z or -z)");
}

std::string to_string(AlignMode mode) { return mode == AlignMode::Auto ? "auto" : "axes"; }

AlignMode align_mode_from_string(std::string_view name) {
  if (name == "auto") return AlignMode::Auto;
  if (name == "axes") return AlignMode::Axes;
  throw InvalidInput("unknown alignment mode \"" + std::string(name) + "\" (expected auto or axes)");
}

void AlignOptions::validate() const {
  if (up && front && std::abs(axis_vector(*up).dot(axis_vector(*front))) > 0.5)
    throw InvalidInput("AlignOptions: up (" + to_string(*up) + ") and front (" + to_string(*front) + ") must be perpendicular");
  if (mode == AlignMode::Axes && std::abs(axis_vector(up.value_or(Axis::PosY)).dot(axis_vector(front.value_or(Axis::PosZ)))) > 0.5)
    throw InvalidInput("AlignOptions: up and front must be perpendicular (defaults +y and +z)");
  if (samples < 200 || samples > 200000) throw InvalidInput("AlignOptions::samples must be in [200, 200000]");
  if (!(min_confidence >= 0.0 && min_confidence <= 1.0)) throw InvalidInput("AlignOptions::min_confidence must be in [0, 1]");
  if (!(snap_degrees >= 0.0 && snap_degrees <= 10.0)) throw InvalidInput("AlignOptions::snap_degrees must be in [0, 10]");
}

facemesh::Vertices Alignment::apply(const facemesh::Vertices& v) const {
  facemesh::Vertices out(v.rows(), 3);
  for (Eigen::Index i = 0; i < v.rows(); ++i) out.row(i) = apply(Eigen::Vector3d(v.row(i))).transpose();
  return out;
}

facemesh::Vertices Alignment::inverse(const facemesh::Vertices& v) const {
  facemesh::Vertices out(v.rows(), 3);
  for (Eigen::Index i = 0; i < v.rows(); ++i) out.row(i) = inverse(Eigen::Vector3d(v.row(i))).transpose();
  return out;
}

std::vector<DetectedLandmark> detect_landmarks(const facemesh::Mesh& mesh, const std::vector<std::string>& names) {
  if (mesh.face_count() == 0) throw InvalidInput("detect_landmarks: the mesh has no faces");
  const auto used = used_vertices(mesh);
  // thesis §3.2.1: top of the head = highest y; tip of the nose = highest z.
  const int top = arg_best(mesh, used, [](const Eigen::Vector3d& p) { return p.y(); });
  const int nose = arg_best(mesh, used, [](const Eigen::Vector3d& p) { return p.z(); });
  const double h = mesh.vertices(top, 1) - mesh.vertices(nose, 1);
  if (!(h > 0.0)) throw InvalidInput("detect_landmarks: the nose tip (highest z) is not below the top of the head (highest y); check --up/--front");
  const double lo = mesh.vertices(nose, 1) - 0.4 * h, hi = mesh.vertices(nose, 1) + 0.6 * h;
  auto side = [&](double sign) {
    return arg_best(mesh, used, [&](const Eigen::Vector3d& p) {
      return p.y() >= lo && p.y() <= hi ? sign * p.x() : -std::numeric_limits<double>::infinity();
    });
  };
  std::vector<DetectedLandmark> out;
  for (const auto& name : names) {
    if (name == "top_of_head") out.push_back({name, top});
    else if (name == "nose_tip") out.push_back({name, nose});
    else if (name == "ear_r") out.push_back({name, side(-1.0)});  // +x is the subject's left (mesh.hpp)
    else if (name == "ear_l") out.push_back({name, side(1.0)});
    else throw InvalidInput("detect_landmarks: no heuristic for landmark \"" + name + "\"");
  }
  return out;
}

namespace {
facemesh::Vertices sample_surface_impl(const facemesh::Mesh& mesh, int count, std::uint64_t seed, std::vector<int>* faces);
}

facemesh::Vertices sample_surface(const facemesh::Mesh& mesh, int count, std::uint64_t seed) {
  return sample_surface_impl(mesh, count, seed, nullptr);
}

namespace {
facemesh::Vertices sample_surface_impl(const facemesh::Mesh& mesh, int count, std::uint64_t seed, std::vector<int>* faces) {
  if (count < 1) throw InvalidInput("sample_surface: count must be >= 1");
  const auto nv = mesh.vertices.rows();
  std::vector<double> cumulative(static_cast<std::size_t>(mesh.faces.rows()));
  double total = 0.0;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.faces(f, k);
      if (v < 0 || v >= nv) throw InvalidInput("sample_surface: face " + std::to_string(f) + " has a vertex id out of range");
      if (!mesh.vertices.row(v).allFinite()) throw InvalidInput("sample_surface: vertex " + std::to_string(v) + " has a NaN or infinite coordinate");
    }
    const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0));
    const double area = 0.5 * (Eigen::Vector3d(mesh.vertices.row(mesh.faces(f, 1))) - a).cross(Eigen::Vector3d(mesh.vertices.row(mesh.faces(f, 2))) - a).norm();
    total += area;
    cumulative[static_cast<std::size_t>(f)] = total;
  }
  if (!(total > 0.0) || !std::isfinite(total)) throw InvalidInput("sample_surface: the mesh has no surface area");
  core::Rng rng(seed, 0);
  facemesh::Vertices out(count, 3);
  for (int i = 0; i < count; ++i) {
    // Stratified over the cumulative area: one sample per 1/count of the total.
    const double u = (i + rng.uniform()) / count * total;
    const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), u);
    const auto f = static_cast<Eigen::Index>(std::min<std::ptrdiff_t>(it - cumulative.begin(), static_cast<std::ptrdiff_t>(cumulative.size()) - 1));
    const double r1 = std::sqrt(rng.uniform()), r2 = rng.uniform();
    out.row(i) = (1.0 - r1) * mesh.vertices.row(mesh.faces(f, 0)) + r1 * (1.0 - r2) * mesh.vertices.row(mesh.faces(f, 1)) +
                 r1 * r2 * mesh.vertices.row(mesh.faces(f, 2));
    if (faces) faces->push_back(static_cast<int>(f));
  }
  return out;
}

constexpr double kPi = 3.14159265358979323846;
constexpr double kKeep = 0.8;  // trimmed estimators keep the best 80 % of the correspondences
// Weight of the landmark cue against the chamfer cost (both in units of the RMS radius): a pose that
// puts the top of head or the nose tip a whole radius away from the source's costs 0.05, more than
// the chamfer difference between any two plausible poses (≈ 0.005-0.02 measured on the default face).
constexpr double kLandmarkWeight = 0.05;

double trimmed_mean(std::vector<double>& v) {
  if (v.empty()) return 0.0;
  const auto keep = std::max<std::size_t>(1, static_cast<std::size_t>(kKeep * static_cast<double>(v.size())));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(keep - 1), v.end());
  double sum = 0.0;
  for (std::size_t i = 0; i < keep; ++i) sum += v[i];
  return sum / static_cast<double>(keep);
}

// Threshold below which a distance belongs to the kept (best kKeep) part.
double trim_threshold(std::vector<double> v) {
  const auto keep = std::max<std::size_t>(1, static_cast<std::size_t>(kKeep * static_cast<double>(v.size())));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(keep - 1), v.end());
  return v[keep - 1];
}

struct Normalized {
  facemesh::Vertices points;   // (p − centroid) / rms
  facemesh::Vertices normals;  // unit normal of the sampled triangle (orientation irrelevant)
  Eigen::Vector3d centroid;
  double rms = 1.0;
};

// Distance used by every mismatch below: point-to-plane (tangent plane of the nearest sample) plus a
// small tangential part, so that the random spacing of the samples hardly counts (a perfectly matching
// surface scores ≈ 0 instead of ≈ the sample spacing).
double surface_gap(const Eigen::Vector3d& d, const Eigen::Vector3d& normal) {
  const double along = d.dot(normal);
  return std::sqrt(along * along + 0.05 * (d.squaredNorm() - along * along));
}

Normalized normalize_samples(const facemesh::Mesh& mesh, int count, std::uint64_t seed) {
  std::vector<int> faces;
  const facemesh::Vertices p = sample_surface_impl(mesh, count, seed, &faces);
  Normalized n;
  const facemesh::Vertices fn = facemesh::face_normals(mesh.vertices, mesh.faces);
  n.normals.resize(p.rows(), 3);
  for (Eigen::Index i = 0; i < p.rows(); ++i) n.normals.row(i) = fn.row(faces[static_cast<std::size_t>(i)]);
  n.centroid = p.colwise().mean().transpose();
  n.points = p.rowwise() - n.centroid.transpose();
  n.rms = std::sqrt(n.points.squaredNorm() / static_cast<double>(p.rows()));
  if (!(n.rms > 0.0) || !std::isfinite(n.rms)) throw InvalidInput("align: the mesh has no extent");
  n.points /= n.rms;
  return n;
}

struct Plane {
  Eigen::Vector3d normal;
  double offset = 0.0;  // normal·q = offset (normalised coordinates)
  double error = 0.0;   // trimmed mean mismatch of the reflected samples
};

// Mismatch of the samples reflected in `plane`; fills the kept correspondences when asked.
double reflection_error(const facemesh::Vertices& q, const facemesh::Vertices& normals, const detail::PointIndex& index,
                        const Plane& plane, int stride, std::vector<std::pair<int, int>>* pairs) {
  std::vector<double> dist;
  std::vector<std::pair<int, int>> all;
  for (Eigen::Index i = 0; i < q.rows(); i += stride) {
    const Eigen::Vector3d p = q.row(i);
    const Eigen::Vector3d r = p - 2.0 * (plane.normal.dot(p) - plane.offset) * plane.normal;
    double d2 = 0;
    const int j = index.nearest(r, d2);
    dist.push_back(surface_gap(r - Eigen::Vector3d(q.row(j)), normals.row(j)));
    all.emplace_back(static_cast<int>(i), j);
  }
  if (pairs) {
    const double t = trim_threshold(dist);
    pairs->clear();
    for (std::size_t k = 0; k < all.size(); ++k)
      if (dist[k] <= t) pairs->push_back(all[k]);
  }
  return trimmed_mean(dist);
}

// Trimmed reflect-and-match refinement of a symmetry plane: the kept pairs (p, q ≈ mirror of p) give the
// normal as the principal direction of p − q and the offset as the mean of n·(p + q)/2.
Plane refine_plane(const facemesh::Vertices& q, const facemesh::Vertices& normals, const detail::PointIndex& index, Plane plane,
                   int stride) {
  std::vector<std::pair<int, int>> pairs;
  for (int it = 0; it < 8; ++it) {
    reflection_error(q, normals, index, plane, stride, &pairs);
    Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
    double offset = 0.0;
    for (const auto& [i, j] : pairs) {
      const Eigen::Vector3d d = q.row(i) - q.row(j);
      m += d * d.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(m);
    Eigen::Vector3d n = es.eigenvectors().col(2);
    if (!n.allFinite() || es.eigenvalues()(2) <= 0.0) break;
    if (n.dot(plane.normal) < 0) n = -n;
    for (const auto& [i, j] : pairs) offset += n.dot(0.5 * (Eigen::Vector3d(q.row(i)) + Eigen::Vector3d(q.row(j))));
    offset /= static_cast<double>(pairs.size());
    const bool converged = std::abs(n.dot(plane.normal)) > std::cos(1e-4) && std::abs(offset - plane.offset) < 1e-5;
    plane.normal = n;
    plane.offset = offset;
    if (converged) break;
  }
  plane.error = reflection_error(q, normals, index, plane, stride, nullptr);
  return plane;
}

// A pose inside the symmetry plane: thesis-frame (x, y, z) of a normalised target vector q with
// a = n·q, b = u·q, c = v·q is σ·(sgn·a, cosθ·b + sinθ·c, sgn·(−sinθ·b + cosθ·c)) + t.
struct Pose {
  int sgn = 1;
  double theta = 0.0;
  double scale = 1.0;
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  double cost = 0.0;
};

struct Frame {
  Eigen::Vector3d n, u, v;
  Eigen::Matrix3d rotation(const Pose& p) const {
    const Eigen::Vector3d y = std::cos(p.theta) * u + std::sin(p.theta) * v;
    const Eigen::Vector3d z = p.sgn * n.cross(y);
    Eigen::Matrix3d r;
    r.row(0) = y.cross(z).transpose();
    r.row(1) = y.transpose();
    r.row(2) = z.transpose();
    return r;
  }
};

struct Matcher {
  const facemesh::Vertices& target;  // normalised target samples
  const facemesh::Vertices& source;  // normalised source samples
  const facemesh::Vertices& target_normals;
  const facemesh::Vertices& source_normals;
  const detail::PointIndex& target_index;
  const detail::PointIndex& source_index;
  int stride;
  const facemesh::Vertices* target_vertices = nullptr;  // normalised used vertices of the target
  Eigen::Vector3d source_top = Eigen::Vector3d::Zero(), source_nose = Eigen::Vector3d::Zero();  // normalised
  double source_bottom = -std::numeric_limits<double>::infinity();  // lowest source sample − margin, normalised
  // Cue (thesis §3.2.1 read backwards): in the right pose the target's highest vertex (top of head)
  // and most forward vertex (nose tip) land where the source's are. Sum of both distances.
  double landmark_offset(const Eigen::Matrix3d& r, double scale, const Eigen::Vector3d& t) const {
    if (!target_vertices) return 0.0;
    const Eigen::RowVector3d ry = r.row(1), rz = r.row(2);
    Eigen::Index top = 0, nose = 0;
    (*target_vertices * ry.transpose()).maxCoeff(&top);
    (*target_vertices * rz.transpose()).maxCoeff(&nose);
    const Eigen::Vector3d top_t = scale * (r * target_vertices->row(top).transpose()) + t;
    const Eigen::Vector3d nose_t = scale * (r * target_vertices->row(nose).transpose()) + t;
    return (top_t - source_top).norm() + (nose_t - source_nose).norm();
  }
  // The source's face (front samples: nose, lips, eyes, chin) must find the target's surface: mean gap,
  // not trimmed, because the trimmed chamfer drops exactly these few distinctive points.
  std::vector<int> source_front{};
  double front_gap(const Eigen::Matrix3d& r, double scale, const Eigen::Vector3d& t) const {
    if (source_front.empty()) return 0.0;
    double sum = 0;
    for (int j : source_front) {
      double dd = 0;
      const Eigen::Vector3d x = r.transpose() * (source.row(j).transpose() - t) / scale;
      const int i = target_index.nearest(x, dd);
      sum += scale * surface_gap(x - Eigen::Vector3d(target.row(i)), target_normals.row(i));
    }
    return sum / static_cast<double>(source_front.size());
  }
  double total(const Eigen::Matrix3d& r, double scale, const Eigen::Vector3d& t) const {
    return cost(r, scale, t, nullptr) + front_gap(r, scale, t) + kLandmarkWeight * landmark_offset(r, scale, t);
  }
  // Two-sided trimmed chamfer cost; pairs (target sample, source sample) of the kept correspondences.
  double cost(const Eigen::Matrix3d& r, double scale, const Eigen::Vector3d& t, std::vector<std::pair<int, int>>* pairs) const {
    std::vector<double> d1, d2;
    std::vector<std::pair<int, int>> p1, p2;
    for (Eigen::Index i = 0; i < target.rows(); i += stride) {
      double dd = 0;
      const Eigen::Vector3d x = scale * (r * target.row(i).transpose()) + t;
      if (x.y() < source_bottom) continue;  // neck and shoulders below the source: not matched
      const int j = source_index.nearest(x, dd);
      d1.push_back(surface_gap(x - Eigen::Vector3d(source.row(j)), source_normals.row(j)));
      p1.emplace_back(static_cast<int>(i), j);
    }
    for (Eigen::Index j = 0; j < source.rows(); j += stride) {
      if (source(j, 1) < source_bottom) continue;
      double dd = 0;
      const Eigen::Vector3d x = r.transpose() * (source.row(j).transpose() - t) / scale;
      const int i = target_index.nearest(x, dd);
      d2.push_back(scale * surface_gap(x - Eigen::Vector3d(target.row(i)), target_normals.row(i)));
      p2.emplace_back(i, static_cast<int>(j));
    }
    if (d1.empty()) return std::numeric_limits<double>::infinity();
    if (pairs) {
      pairs->clear();
      const double t1 = trim_threshold(d1), t2 = trim_threshold(d2);
      for (std::size_t k = 0; k < p1.size(); ++k)
        if (d1[k] <= t1) pairs->push_back(p1[k]);
      for (std::size_t k = 0; k < p2.size(); ++k)
        if (d2[k] <= t2) pairs->push_back(p2[k]);
    }
    return 0.5 * (trimmed_mean(d1) + trimmed_mean(d2));
  }
};

// Trimmed ICP restricted to rotations about the plane normal (closed-form 2-D Procrustes in the plane,
// one shared scale, free translation).
Pose refine_pose(const Matcher& m, const Frame& f, Pose pose) {
  std::vector<std::pair<int, int>> pairs;
  for (int it = 0; it < 15; ++it) {
    m.cost(f.rotation(pose), pose.scale, pose.t, &pairs);
    const auto count = static_cast<double>(pairs.size());
    Eigen::Vector3d mean_w = Eigen::Vector3d::Zero(), mean_s = Eigen::Vector3d::Zero();
    for (const auto& [i, j] : pairs) {
      const Eigen::Vector3d q = m.target.row(i);
      mean_w += Eigen::Vector3d(f.n.dot(q), f.u.dot(q), f.v.dot(q)) / count;
      mean_s += Eigen::Vector3d(m.source.row(j)) / count;
    }
    double sxx = 0, sxy = 0, norm_w = 0;
    for (const auto& [i, j] : pairs) {
      const Eigen::Vector3d q = m.target.row(i);
      const Eigen::Vector3d w = Eigen::Vector3d(f.n.dot(q), f.u.dot(q), f.v.dot(q)) - mean_w;
      const Eigen::Vector3d s = Eigen::Vector3d(m.source.row(j)) - mean_s;
      // 2-D: h = (b, c) maps to k = (s_y, sgn·s_z) by a rotation by −θ.
      const Eigen::Vector2d h(w.y(), w.z()), k(s.y(), pose.sgn * s.z());
      sxx += h.dot(k);
      sxy += h.x() * k.y() - h.y() * k.x();
      norm_w += w.squaredNorm();
    }
    const double phi = std::atan2(sxy, sxx);
    const double theta = -phi;
    // Scale: Σ ŝ·R ŵ / Σ |ŵ|² with the new rotation.
    double num = 0;
    for (const auto& [i, j] : pairs) {
      const Eigen::Vector3d q = m.target.row(i);
      const Eigen::Vector3d w = Eigen::Vector3d(f.n.dot(q), f.u.dot(q), f.v.dot(q)) - mean_w;
      const Eigen::Vector3d s = Eigen::Vector3d(m.source.row(j)) - mean_s;
      const Eigen::Vector3d rw(pose.sgn * w.x(), std::cos(theta) * w.y() + std::sin(theta) * w.z(),
                               pose.sgn * (-std::sin(theta) * w.y() + std::cos(theta) * w.z()));
      num += s.dot(rw);
    }
    Pose next = pose;
    next.theta = theta;
    if (norm_w > 0 && num > 0) next.scale = num / norm_w;
    const Eigen::Vector3d rm(pose.sgn * mean_w.x(), std::cos(theta) * mean_w.y() + std::sin(theta) * mean_w.z(),
                             pose.sgn * (-std::sin(theta) * mean_w.y() + std::cos(theta) * mean_w.z()));
    next.t = mean_s - next.scale * rm;
    const bool converged = std::abs(std::remainder(next.theta - pose.theta, 2 * kPi)) < 1e-5 &&
                           std::abs(next.scale / pose.scale - 1) < 1e-5 && (next.t - pose.t).norm() < 1e-5;
    pose = next;
    if (converged) break;
  }
  pose.cost = m.total(f.rotation(pose), pose.scale, pose.t);
  return pose;
}

bool distinct(const Pose& a, const Pose& b) {
  return a.sgn != b.sgn || std::abs(std::remainder(a.theta - b.theta, 2 * kPi)) > kPi / 6;
}

std::string fmt(double v, int precision = 3) {
  std::ostringstream os;
  os.precision(precision);
  os << v;
  return os.str();
}

Eigen::Matrix3d axes_rotation(const AlignOptions& options) {
  const Eigen::Vector3d up = axis_vector(options.up.value_or(Axis::PosY)), front = axis_vector(options.front.value_or(Axis::PosZ));
  // Rows of R are the input axes that become x, y, z: y = up, z = front, x = y × z.
  Eigen::Matrix3d r;
  r.row(1) = up.transpose();
  r.row(2) = front.transpose();
  r.row(0) = up.cross(front).transpose();
  return r;
}

// Rotation input → thesis frame from the geometry (see align.hpp), with its report.
Eigen::Matrix3d auto_rotation(const facemesh::Mesh& target, const facemesh::Mesh& source, const Eigen::Vector3d& source_top,
                              const Eigen::Vector3d& source_nose, const AlignOptions& options, AlignReport& report,
                              Eigen::Vector3d& plane_point, Eigen::Vector3d& plane_normal) {
  const Normalized t = normalize_samples(target, options.samples, options.seed);
  // Flat or linear inputs (a plane, one triangle) have no second or third principal extent.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> pca(t.points.transpose() * t.points / static_cast<double>(t.points.rows()));
  const Eigen::Vector3d ev = pca.eigenvalues();  // ascending, sum 1
  if (!(ev(0) > 1e-6))
    throw InvalidInput("align: the mesh is flat (all its triangles lie in one plane or on one line): it cannot be a head");
  const detail::PointIndex target_index(t.points);
  const int stride = std::max(1, static_cast<int>(t.points.rows() / 1000));

  // 1. Symmetry plane: principal axes as candidate normals, refined; distinct planes compared.
  std::vector<Plane> planes;
  for (int k = 0; k < 3; ++k) {
    Plane raw{pca.eigenvectors().col(k), 0.0, 0.0};
    raw.error = reflection_error(t.points, t.normals, target_index, raw, stride, nullptr);
    planes.push_back(raw);
    planes.push_back(refine_plane(t.points, t.normals, target_index, raw, stride));
  }
  std::stable_sort(planes.begin(), planes.end(), [](const Plane& a, const Plane& b) { return a.error < b.error; });
  const Plane best_plane = planes.front();
  double second = std::numeric_limits<double>::infinity();
  for (const auto& p : planes)
    if (std::abs(p.normal.dot(best_plane.normal)) < std::cos(15.0 * kPi / 180.0)) {
      second = p.error;
      break;
    }
  report.symmetry_error = best_plane.error;
  report.symmetry_margin = std::isfinite(second) && second > 0 ? std::clamp(1.0 - best_plane.error / second, 0.0, 1.0) : 1.0;

  // 2. In-plane pose against the source.
  const Normalized s = normalize_samples(source, options.samples, options.seed);
  const detail::PointIndex source_index(s.points);
  Frame f;
  f.n = best_plane.normal.normalized();
  Eigen::Vector3d seed_axis = pca.eigenvectors().col(2);
  if (std::abs(seed_axis.dot(f.n)) > 0.9) seed_axis = pca.eigenvectors().col(1);
  f.u = (seed_axis - seed_axis.dot(f.n) * f.n).normalized();
  f.v = f.n.cross(f.u);
  const auto used = used_vertices(target);
  facemesh::Vertices target_vertices(std::count(used.begin(), used.end(), 1), 3);
  for (Eigen::Index i = 0, k = 0; i < target.vertices.rows(); ++i)
    if (used[static_cast<std::size_t>(i)]) target_vertices.row(k++) = (target.vertices.row(i) - t.centroid.transpose()) / t.rms;
  Matcher coarse{t.points, s.points, t.normals, s.normals, target_index, source_index, std::max(1, static_cast<int>(t.points.rows() / 400))};
  coarse.target_vertices = &target_vertices;
  coarse.source_top = (source_top - s.centroid) / s.rms;
  coarse.source_nose = (source_nose - s.centroid) / s.rms;
  // Front of the source face: samples in front of the centroid (z > 0.3 RMS radii) no lower than the
  // nose tip minus one radius (no neck).
  for (Eigen::Index j = 0; j < s.points.rows(); j += coarse.stride)
    if (s.points(j, 2) > 0.3 && s.points(j, 1) > coarse.source_nose.y() - 1.0) coarse.source_front.push_back(static_cast<int>(j));
  coarse.source_bottom = s.points.col(1).minCoeff() - 0.1;
  Matcher fine = coarse;
  fine.stride = stride;
  const std::optional<Eigen::Vector3d> hint_up = options.up ? std::optional<Eigen::Vector3d>(axis_vector(*options.up)) : std::nullopt;
  const std::optional<Eigen::Vector3d> hint_front = options.front ? std::optional<Eigen::Vector3d>(axis_vector(*options.front)) : std::nullopt;
  report.hints_used = hint_up || hint_front;
  std::vector<Pose> poses;
  for (int sgn : {1, -1})
    for (int step = 0; step < 72; ++step) {
      Pose p;
      p.sgn = sgn;
      p.theta = 2 * kPi * step / 72;
      const Eigen::Matrix3d r = f.rotation(p);
      if (hint_up && r.row(1).dot(*hint_up) < 0.5) continue;
      if (hint_front && r.row(2).dot(*hint_front) < 0.5) continue;
      p.cost = coarse.total(r, 1.0, Eigen::Vector3d::Zero());
      poses.push_back(p);
    }
  if (poses.empty()) throw InvalidInput("align: no pose agrees with the up/front hints within 60 degrees of the symmetry plane found; check --up/--front or use --align axes");
  std::stable_sort(poses.begin(), poses.end(), [](const Pose& a, const Pose& b) { return a.cost < b.cost; });
  std::vector<Pose> seeds;
  for (const auto& p : poses) {
    if (std::all_of(seeds.begin(), seeds.end(), [&](const Pose& q) { return distinct(p, q); })) seeds.push_back(p);
    if (seeds.size() == 4) break;
  }
  std::vector<Pose> refined;
  for (const auto& p : seeds) refined.push_back(refine_pose(fine, f, p));
  std::stable_sort(refined.begin(), refined.end(), [](const Pose& a, const Pose& b) { return a.cost < b.cost; });
  const Pose best = refined.front();
  double runner_up = std::numeric_limits<double>::infinity();
  // The margin compares with the best grossly different pose (facing the other way or ≥ 60° apart):
  // the up/down and front/back decision. Poses 30-60° apart are mere ICP local minima; if no refined pose
  // is that different, the coarse table provides one.
  auto gross = [&](const Pose& p) { return p.sgn != best.sgn || std::abs(std::remainder(p.theta - best.theta, 2 * kPi)) >= kPi / 3; };
  for (const auto& p : refined)
    if (gross(p)) {
      runner_up = p.cost;
      break;
    }
  if (!std::isfinite(runner_up))
    for (const auto& p : poses)
      if (gross(p)) {
        runner_up = refine_pose(fine, f, p).cost;
        break;
      }
  report.match_cost = best.cost;
  report.landmark_offset = fine.landmark_offset(f.rotation(best), best.scale, best.t);
  // No grossly different pose left: only possible when the hints excluded them, so the hints decided.
  report.orientation_margin = std::isfinite(runner_up) && runner_up > 0 ? std::clamp(1.0 - best.cost / runner_up, 0.0, 1.0)
                                                                        : (report.hints_used ? 1.0 : 0.0);
  const Eigen::Matrix3d r = f.rotation(best);
  plane_normal = f.n;
  plane_point = t.centroid + t.rms * best_plane.offset * f.n;
  return r;
}
}  // namespace

Alignment align_to_frame(const facemesh::Mesh& target, const facemesh::Mesh& source, const Eigen::Vector3d& source_top,
                         const Eigen::Vector3d& source_nose, const AlignOptions& options) {
  options.validate();
  if (target.face_count() == 0) throw InvalidInput("align: the target mesh has no faces");
  if (!target.vertices.allFinite()) throw InvalidInput("align: the target mesh has a NaN or infinite coordinate");
  Alignment a;
  Eigen::Vector3d plane_point = Eigen::Vector3d::Zero(), plane_normal = Eigen::Vector3d::Zero();
  if (options.mode == AlignMode::Axes) {
    a.rotation = axes_rotation(options);
  } else {
    a.rotation = auto_rotation(target, source, source_top, source_nose, options, a.report, plane_point, plane_normal);
  }
  a.report.method = options.mode;
  if (options.mode == AlignMode::Auto && options.snap_degrees > 0) {
    // Scans are usually stored axis-aligned: within snap_degrees of one of the 24 axis-aligned frames,
    // take that frame exactly.
    for (int up = 0; up < 6; ++up)
      for (int front = 0; front < 6; ++front) {
        const Eigen::Vector3d u = axis_vector(static_cast<Axis>(up)), f = axis_vector(static_cast<Axis>(front));
        if (std::abs(u.dot(f)) > 0.5) continue;
        Eigen::Matrix3d r;
        r.row(0) = u.cross(f).transpose();
        r.row(1) = u.transpose();
        r.row(2) = f.transpose();
        if (Eigen::AngleAxisd(r * a.rotation.transpose()).angle() * 180.0 / kPi < options.snap_degrees) {
          a.rotation = r;
          a.report.snapped = true;
        }
      }
  }
  const Eigen::AngleAxisd aa(a.rotation);
  a.report.axis = aa.axis();
  a.report.angle_deg = aa.angle() * 180.0 / kPi;
  facemesh::Mesh rotated = target;
  rotated.vertices = a.apply(target.vertices);
  const auto lm = detect_landmarks(rotated, {"top_of_head", "nose_tip"});
  const Eigen::Vector3d top = rotated.vertices.row(lm[0].vertex), nose = rotated.vertices.row(lm[1].vertex);
  if (options.mode == AlignMode::Auto) {
    // Cues: nose tip and top of head near the symmetry plane (x = const in the frame).
    const double plane_x = (a.rotation * plane_point).x();
    const auto used = used_vertices(rotated);
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (Eigen::Index i = 0; i < rotated.vertices.rows(); ++i)
      if (used[static_cast<std::size_t>(i)]) {
        lo = std::min(lo, rotated.vertices(i, 0));
        hi = std::max(hi, rotated.vertices(i, 0));
      }
    const double width = hi - lo;
    auto& r = a.report;
    r.nose_on_plane = std::abs(nose.x() - plane_x) <= 0.1 * width;
    r.top_on_plane = std::abs(top.x() - plane_x) <= 0.1 * width;
    r.confidence = std::clamp(std::min(r.symmetry_margin, 2.0 * r.orientation_margin), 0.0, 1.0);
    if (!r.nose_on_plane) r.confidence *= 0.5;
    if (!r.top_on_plane) r.confidence *= 0.5;
    r.message = std::string(r.snapped ? "snapped to the axis-aligned frame; " : "") + "symmetry plane: mismatch " + fmt(r.symmetry_error) + " (margin " + fmt(r.symmetry_margin, 2) +
                "); up/front by matching the source: cost " + fmt(r.match_cost) + " (margin " + fmt(r.orientation_margin, 2) +
                "), top of head and nose tip " + fmt(r.landmark_offset, 2) + " radii from the source's" + (r.hints_used ? ", restricted by the up/front hints" : "") + "; nose tip " +
                (r.nose_on_plane ? "on" : "OFF") + " the plane, top of head " + (r.top_on_plane ? "on" : "OFF") + " the plane";
  } else {
    a.report.message = "axes given: up " + to_string(options.up.value_or(Axis::PosY)) + ", front " + to_string(options.front.value_or(Axis::PosZ));
  }
  place_in_frame(a, target, source_top, source_nose, options.scale);
  return a;
}

void place_in_frame(Alignment& a, const facemesh::Mesh& target, const Eigen::Vector3d& source_top,
                    const Eigen::Vector3d& source_nose, bool scale) {
  facemesh::Mesh rotated = target;
  rotated.vertices = target.vertices * a.rotation.transpose();
  const auto lm = detect_landmarks(rotated, {"top_of_head", "nose_tip"});
  const Eigen::Vector3d top = rotated.vertices.row(lm[0].vertex), nose = rotated.vertices.row(lm[1].vertex);
  const double source_h = source_top.y() - source_nose.y();
  if (!(source_h > 0.0)) throw InvalidInput("align_to_frame: the source nose tip is not below its top of head");
  a.scale = scale ? source_h / (top.y() - nose.y()) : 1.0;
  if (!std::isfinite(a.scale) || !(a.scale > 0.0)) throw InvalidInput("align_to_frame: degenerate target (cannot determine its scale)");
  a.translation = Eigen::Vector3d(source_top.x() - a.scale * top.x(), source_top.y() - a.scale * top.y(),
                                  source_nose.z() - a.scale * nose.z());
}

}  // namespace emoface::retarget
