#include "emoface/facemesh/rig.hpp"

#include <cmath>
#include <set>
#include <string>
#include <vector>

#include <Eigen/LU>

#include "emoface/core/errors.hpp"

namespace emoface::facemesh {
namespace {

constexpr const char* kRegionNames[kRegionCount] = {
    "right_lower_face", "right_middle_face", "right_lower_eyelid", "right_upper_eyelid",
    "right_upper_face", "left_lower_face",   "left_middle_face",   "left_lower_eyelid",
    "left_upper_eyelid", "left_upper_face",  "rest"};
constexpr const char* kMaterialNames[] = {"skin", "lip", "eye_white", "iris", "pupil", "brow", "hair",
                                          "mouth_interior", "teeth", "tongue", "lash"};
constexpr const char* kKindNames[] = {"vector", "sphincter"};
constexpr const char* kPartKindNames[] = {"head",        "eyeball", "upper_teeth", "lower_teeth",
                                          "tongue",      "lashes",  "brows",       "other"};

template <std::size_t N>
int find_name(const char* const (&names)[N], std::string_view name) {
  for (std::size_t i = 0; i < N; ++i) {
    if (name == names[i]) return static_cast<int>(i);
  }
  return -1;
}

struct Checker {
  const std::string& source;
  [[noreturn]] void fail(const std::string& pointer, const std::string& message) const {
    SourceLocation where;
    where.file = source;
    where.json_pointer = pointer;
    throw FormatError(where, message);
  }
  void finite(const Eigen::Vector3d& v, const std::string& pointer) const {
    if (!v.allFinite()) fail(pointer, "non-finite coordinate");
  }
  void number(double x, double lo, double hi, const std::string& pointer) const {
    if (!std::isfinite(x) || x < lo || x > hi) {
      fail(pointer, "value " + std::to_string(x) + " outside [" + std::to_string(lo) + ", " +
                        std::to_string(hi) + "]");
    }
  }
  void ids(const std::vector<int>& list, std::size_t n, const std::string& pointer) const {
    for (std::size_t i = 0; i < list.size(); ++i) {
      if (list[i] < 0 || static_cast<std::size_t>(list[i]) >= n) {
        fail(pointer + "/" + std::to_string(i),
             "vertex id " + std::to_string(list[i]) + " out of range (mesh has " + std::to_string(n) + ")");
      }
    }
  }
  void weights(const std::vector<int>& list, const std::vector<double>& w, const std::string& pointer) const {
    if (w.size() != list.size()) fail(pointer, "needs one weight per vertex");
    for (std::size_t i = 0; i < w.size(); ++i) number(w[i], 0.0, 1.0, pointer + "/" + std::to_string(i));
  }
};

}  // namespace

std::string to_string(Region region) { return kRegionNames[static_cast<int>(region)]; }
Region region_from_string(std::string_view name) {
  const int i = find_name(kRegionNames, name);
  if (i < 0) throw InvalidInput("unknown region '" + std::string(name) + "'");
  return static_cast<Region>(i);
}
std::string to_string(Material material) { return kMaterialNames[static_cast<int>(material)]; }
Material material_from_string(std::string_view name) {
  const int i = find_name(kMaterialNames, name);
  if (i < 0) throw InvalidInput("unknown material '" + std::string(name) + "'");
  return static_cast<Material>(i);
}
std::string to_string(MuscleKind kind) { return kKindNames[static_cast<int>(kind)]; }
MuscleKind muscle_kind_from_string(std::string_view name) {
  const int i = find_name(kKindNames, name);
  if (i < 0) throw InvalidInput("unknown muscle kind '" + std::string(name) + "'");
  return static_cast<MuscleKind>(i);
}

std::string to_string(PartKind kind) { return kPartKindNames[static_cast<int>(kind)]; }
PartKind part_kind_from_string(std::string_view name) {
  const int i = find_name(kPartKindNames, name);
  if (i < 0) throw InvalidInput("unknown part kind '" + std::string(name) + "'");
  return static_cast<PartKind>(i);
}

void validate_rig(const Rig& rig, const std::string& source) {
  const Checker c{source};
  const std::size_t n = rig.vertex_count;
  if (n == 0) c.fail("/vertex_count", "must be positive");
  if (rig.regions.size() != n) c.fail("/regions", "needs one region per vertex");
  if (rig.materials.size() != n) c.fail("/materials", "needs one material per vertex");
  // Lips.
  const auto& lips = rig.lips;
  if (!lips.control_points.empty() &&
      lips.control_points.size() != static_cast<std::size_t>(LipGrid::kAround * LipGrid::kAcross)) {
    c.fail("/lips/control_points", "needs 24x6 = 144 control points (or none: a face without the lip model)");
  }
  for (std::size_t i = 0; i < lips.control_points.size(); ++i) {
    c.finite(lips.control_points[i], "/lips/control_points/" + std::to_string(i));
  }
  if (lips.samples_around < LipGrid::kAround || lips.samples_around > 1024) c.fail("/lips/samples_around", "must be in [24, 1024]");
  if (lips.samples_across < LipGrid::kAcross || lips.samples_across > 256) c.fail("/lips/samples_across", "must be in [6, 256]");
  const long long lip_end = static_cast<long long>(lips.first_vertex) +
                            static_cast<long long>(lips.samples_around) * lips.samples_across;
  const bool grid_in_mesh = !lips.control_points.empty() && lips.samples_in_mesh;
  if (grid_in_mesh && (lips.first_vertex < 0 || lip_end > static_cast<long long>(n))) {
    c.fail("/lips/first_vertex", "lip samples exceed the mesh");
  }
  c.finite(lips.centre, "/lips/centre");
  if (!lips.bound.empty() && lips.control_points.empty()) c.fail("/lips/bound", "bound vertices need the lip control points");
  if (!lips.border_jaw.empty()) {
    if (lips.control_points.empty())
      c.fail("/lips/border_jaw", "border jaw weights need the lip control points");
    if (lips.border_jaw.size() != static_cast<std::size_t>(LipGrid::kAround)) {
      c.fail("/lips/border_jaw", "needs 24 weights (one per border control point) or none");
    }
    for (std::size_t i = 0; i < lips.border_jaw.size(); ++i)
      c.number(lips.border_jaw[i], 0.0, 1.0, "/lips/border_jaw/" + std::to_string(i));
  }
  {
    std::vector<char> seen(n, 0);
    for (std::size_t i = 0; i < lips.bound.size(); ++i) {
      const auto& b = lips.bound[i];
      const std::string p = "/lips/bound/" + std::to_string(i);
      if (b.vertex < 0 || static_cast<std::size_t>(b.vertex) >= n) {
        c.fail(p + "/vertex", "vertex id " + std::to_string(b.vertex) + " out of range (mesh has " + std::to_string(n) + ")");
      }
      if (seen[static_cast<std::size_t>(b.vertex)]) c.fail(p + "/vertex", "vertex " + std::to_string(b.vertex) + " bound twice");
      seen[static_cast<std::size_t>(b.vertex)] = 1;
      if (grid_in_mesh && b.vertex >= lips.first_vertex && b.vertex < lip_end) {
        c.fail(p + "/vertex", "vertex " + std::to_string(b.vertex) + " is also a lip grid sample");
      }
      if (!(std::isfinite(b.u) && b.u >= 0.0 && b.u < 1.0)) c.fail(p + "/u", "u must be in [0, 1)");
      c.number(b.v, 0.0, 1.0, p + "/v");
      c.number(b.weight, 0.0, 1.0, p + "/weight");
      c.finite(b.offset, p + "/offset");
    }
  }
  // Frame (mesh file -> rig): scale > 0, a proper rotation.
  {
    const auto& f = rig.frame;
    if (!(std::isfinite(f.scale) && f.scale > 0.0)) c.fail("/frame/scale", "scale must be a finite number > 0");
    if (!f.rotation.allFinite()) c.fail("/frame/rotation", "non-finite rotation");
    const double ortho = (f.rotation.transpose() * f.rotation - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
    if (!(ortho <= 1e-6)) c.fail("/frame/rotation", "not orthonormal (|R^T R - I| = " + std::to_string(ortho) + ")");
    if (!(std::abs(f.rotation.determinant() - 1.0) <= 1e-6)) c.fail("/frame/rotation", "not a proper rotation (det != +1)");
    c.finite(f.translation, "/frame/translation");
  }
  // Parts.
  for (std::size_t i = 0; i < rig.parts.size(); ++i) {
    const auto& part = rig.parts[i];
    const std::string p = "/parts/" + std::to_string(i);
    if (part.name.empty()) c.fail(p + "/name", "empty part name");
    if (part.side < -1 || part.side > 1) c.fail(p + "/side", "side must be -1 (none), 0 (right) or 1 (left)");
    c.ids(part.vertices, n, p + "/vertices");
    for (std::size_t k = 1; k < part.vertices.size(); ++k) {
      if (part.vertices[k] <= part.vertices[k - 1]) c.fail(p + "/vertices/" + std::to_string(k), "vertex ids must be ascending and unique");
    }
  }
  // Jaw.
  c.finite(rig.jaw.pivot, "/jaw/pivot");
  c.number(rig.jaw.max_angle, 0.0, 1.5707963267948966, "/jaw/max_angle");
  c.ids(rig.jaw.vertices, n, "/jaw/vertices");
  c.weights(rig.jaw.vertices, rig.jaw.weights, "/jaw/weights");
  c.finite(rig.head_pivot, "/head_pivot");
  for (int e = 0; e < 2; ++e) {
    const auto& eye = rig.eyes[static_cast<std::size_t>(e)];
    const std::string p = "/eyes/" + std::to_string(e);
    c.finite(eye.centre, p + "/centre");
    c.number(eye.radius, 1e-6, 1.0, p + "/radius");
    c.ids(eye.eyeball_vertices, n, p + "/eyeball_vertices");
    c.ids(eye.upper_lid, n, p + "/upper_lid");
    c.ids(eye.lower_lid, n, p + "/lower_lid");
    c.weights(eye.upper_lid, eye.upper_lid_weights, p + "/upper_lid_weights");
    c.weights(eye.lower_lid, eye.lower_lid_weights, p + "/lower_lid_weights");
    c.number(eye.close_angle, 0.0, 3.14159, p + "/close_angle");
    c.number(eye.open_angle, 0.0, 3.14159, p + "/open_angle");
    if (eye.tighten_angle) c.number(*eye.tighten_angle, 0.0, eye.close_angle, p + "/tighten_angle");
    c.number(eye.yaw_limit, 1e-6, 1.5707963267948966, p + "/yaw_limit");
    c.number(eye.pitch_limit, 1e-6, 1.5707963267948966, p + "/pitch_limit");
  }
  if (!rig.ibug68.empty() && rig.ibug68.size() != 68) c.fail("/landmarks/ibug68", "needs exactly 68 landmarks");
  c.ids(rig.ibug68, n, "/landmarks/ibug68");
  for (std::size_t i = 0; i < rig.retarget_landmarks.size(); ++i) {
    const auto& l = rig.retarget_landmarks[i];
    const std::string p = "/landmarks/retarget/" + l.name;
    if (l.name.empty()) c.fail(p, "empty landmark name");
    if (l.vertex < 0 || static_cast<std::size_t>(l.vertex) >= n) c.fail(p, "vertex id " + std::to_string(l.vertex) + " out of range");
  }
  std::set<std::string> names;
  for (std::size_t i = 0; i < rig.muscles.size(); ++i) {
    const auto& m = rig.muscles[i];
    const std::string p = "/muscles/" + std::to_string(i);
    if (m.name.empty()) c.fail(p + "/name", "empty muscle name");
    if (!names.insert(m.name).second) c.fail(p + "/name", "duplicate muscle name '" + m.name + "'");
    if (m.parameter.empty()) c.fail(p + "/parameter", "empty parameter name");
    c.finite(m.head, p + "/head");
    c.finite(m.tail, p + "/tail");
    c.number(m.k, 0.0, 1.0, p + "/k");
    c.number(m.wrinkle_height, 0.0, 0.1, p + "/wrinkle_height");
    if (m.wrinkle_count < 0 || m.wrinkle_count > 100) c.fail(p + "/wrinkle_count", "must be in [0, 100]");
    if (m.regions.empty()) c.fail(p + "/regions", "a muscle needs at least one region");
    if (m.kind == MuscleKind::Vector) {
      if (!((m.tail - m.head).norm() > 1e-9)) c.fail(p + "/tail", "zero-length muscle (head == tail)");
      c.number(m.omega, 1e-6, 3.14159, p + "/omega");
      c.number(m.rs, 1e-9, 10.0, p + "/rs");
      c.number(m.rf, 1e-9, 10.0, p + "/rf");
      if (!(m.rs < m.rf)) c.fail(p + "/rs", "needs Rs < Rf");
    } else {
      if (!(m.semi_axes.allFinite() && m.semi_axes.minCoeff() > 1e-9)) c.fail(p + "/semi_axes", "sphincter semi-axes must be > 0");
    }
  }
}

std::array<std::vector<int>, kRegionCount> region_vertices(const Rig& rig) {
  std::array<std::vector<int>, kRegionCount> out;
  for (std::size_t v = 0; v < rig.regions.size(); ++v) {
    out[static_cast<std::size_t>(rig.regions[v])].push_back(static_cast<int>(v));
  }
  return out;
}

}  // namespace emoface::facemesh
