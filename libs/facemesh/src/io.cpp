// emoface.rig reader/writer (JSON envelope kind "rig").
#include "emoface/facemesh/io.hpp"

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

#include <nlohmann/json.hpp>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/facemesh/mesh_io.hpp"

namespace emoface::facemesh {
namespace {

using Json = nlohmann::ordered_json;

struct Reader {
  const std::string& source;

  [[noreturn]] void fail(const std::string& pointer, const std::string& message) const {
    SourceLocation where;
    where.file = source;
    where.json_pointer = pointer;
    throw FormatError(where, message);
  }
  const Json& field(const Json& obj, const char* key, const std::string& p) const {
    if (!obj.is_object()) fail(p, "expected an object");
    auto it = obj.find(key);
    if (it == obj.end()) fail(p + "/" + key, "missing field");
    return *it;
  }
  double number(const Json& j, const std::string& p) const {
    if (!j.is_number()) fail(p, "expected a number");
    const double x = j.get<double>();
    if (!std::isfinite(x)) fail(p, "not a finite number");
    return x;
  }
  int integer(const Json& j, const std::string& p) const {
    if (!j.is_number_integer()) fail(p, "expected an integer");
    if (j.is_number_unsigned()) {
      const auto u = j.get<std::uint64_t>();
      if (u > static_cast<std::uint64_t>(std::numeric_limits<int>::max())) fail(p, "integer out of range");
      return static_cast<int>(u);
    }
    const auto i = j.get<std::int64_t>();
    if (i < std::numeric_limits<int>::min() || i > std::numeric_limits<int>::max()) fail(p, "integer out of range");
    return static_cast<int>(i);
  }
  std::string string(const Json& j, const std::string& p) const {
    if (!j.is_string()) fail(p, "expected a string");
    return j.get<std::string>();
  }
  bool boolean(const Json& j, const std::string& p) const {
    if (!j.is_boolean()) fail(p, "expected true or false");
    return j.get<bool>();
  }
  const Json& array(const Json& j, const std::string& p) const {
    if (!j.is_array()) fail(p, "expected an array");
    return j;
  }
  Eigen::Vector3d vec3(const Json& j, const std::string& p) const {
    if (!j.is_array() || j.size() != 3) fail(p, "expected an array of 3 numbers");
    return {number(j[0], p + "/0"), number(j[1], p + "/1"), number(j[2], p + "/2")};
  }
  Eigen::Vector2d vec2(const Json& j, const std::string& p) const {
    if (!j.is_array() || j.size() != 2) fail(p, "expected an array of 2 numbers");
    return {number(j[0], p + "/0"), number(j[1], p + "/1")};
  }
  std::vector<int> ints(const Json& j, const std::string& p) const {
    array(j, p);
    std::vector<int> out;
    out.reserve(j.size());
    for (std::size_t i = 0; i < j.size(); ++i) out.push_back(integer(j[i], p + "/" + std::to_string(i)));
    return out;
  }
  std::vector<double> doubles(const Json& j, const std::string& p) const {
    array(j, p);
    std::vector<double> out;
    out.reserve(j.size());
    for (std::size_t i = 0; i < j.size(); ++i) out.push_back(number(j[i], p + "/" + std::to_string(i)));
    return out;
  }
  template <class Enum, class FromString>
  std::vector<Enum> labels(const Json& j, const std::string& p, std::size_t n, FromString from_string) const {
    // {"label": [vertex ids ...], ...}: every vertex exactly once.
    if (!j.is_object()) fail(p, "expected an object of label -> vertex ids");
    std::vector<int> seen(n, -1);
    std::vector<Enum> out(n);
    for (auto it = j.begin(); it != j.end(); ++it) {
      const std::string q = p + "/" + core::json_pointer_token(it.key());
      Enum label;
      try {
        label = from_string(it.key());
      } catch (const InvalidInput& e) {
        fail(q, e.what());
      }
      const auto ids = ints(it.value(), q);
      for (std::size_t i = 0; i < ids.size(); ++i) {
        const int v = ids[i];
        if (v < 0 || static_cast<std::size_t>(v) >= n) fail(q + "/" + std::to_string(i), "vertex id " + std::to_string(v) + " out of range");
        if (seen[static_cast<std::size_t>(v)] >= 0) fail(q + "/" + std::to_string(i), "vertex " + std::to_string(v) + " listed twice");
        seen[static_cast<std::size_t>(v)] = 1;
        out[static_cast<std::size_t>(v)] = label;
      }
    }
    for (std::size_t v = 0; v < n; ++v) {
      if (seen[v] < 0) fail(p, "vertex " + std::to_string(v) + " has no label");
    }
    return out;
  }
};

Json vec(const Eigen::Vector3d& v) { return Json::array({v.x(), v.y(), v.z()}); }

template <class Enum>
Json label_sets(const std::vector<Enum>& labels, int count) {
  Json out = Json::object();
  std::vector<std::vector<int>> sets(static_cast<std::size_t>(count));
  for (std::size_t v = 0; v < labels.size(); ++v) sets[static_cast<std::size_t>(labels[v])].push_back(static_cast<int>(v));
  for (int i = 0; i < count; ++i) {
    if (!sets[static_cast<std::size_t>(i)].empty()) out[to_string(static_cast<Enum>(i))] = sets[static_cast<std::size_t>(i)];
  }
  return out;
}

constexpr std::size_t kMaxVertices = 10'000'000;  // bounds the memory a hostile file can make us allocate

}  // namespace

Rig parse_rig(std::string_view text, const std::string& source) {
  const Json doc = core::parse_json(text, source);
  core::check_envelope(doc, "rig", {kRigFormatMajor, kRigFormatMinor}, source);
  const Reader r{source};
  Rig rig;
  rig.mesh_file = r.string(r.field(doc, "mesh", ""), "/mesh");
  const int nv = r.integer(r.field(doc, "vertex_count", ""), "/vertex_count");
  if (nv <= 0 || static_cast<std::size_t>(nv) > kMaxVertices) r.fail("/vertex_count", "must be in [1, 10000000]");
  rig.vertex_count = static_cast<std::size_t>(nv);
  rig.regions = r.labels<Region>(r.field(doc, "regions", ""), "/regions", rig.vertex_count, region_from_string);
  rig.materials = r.labels<Material>(r.field(doc, "materials", ""), "/materials", rig.vertex_count, material_from_string);
  rig.head_pivot = r.vec3(r.field(doc, "head_pivot", ""), "/head_pivot");

  const Json& lips = r.field(doc, "lips", "");
  const Json& cps = r.array(r.field(lips, "control_points", "/lips"), "/lips/control_points");
  for (std::size_t i = 0; i < cps.size(); ++i) rig.lips.control_points.push_back(r.vec3(cps[i], "/lips/control_points/" + std::to_string(i)));
  rig.lips.samples_around = r.integer(r.field(lips, "samples_around", "/lips"), "/lips/samples_around");
  rig.lips.samples_across = r.integer(r.field(lips, "samples_across", "/lips"), "/lips/samples_across");
  rig.lips.first_vertex = r.integer(r.field(lips, "first_vertex", "/lips"), "/lips/first_vertex");
  rig.lips.centre = r.vec3(r.field(lips, "centre", "/lips"), "/lips/centre");
  // format 1.1 (absent in 1.0: the defaults)
  if (lips.contains("samples_in_mesh")) rig.lips.samples_in_mesh = r.boolean(lips["samples_in_mesh"], "/lips/samples_in_mesh");
  if (lips.contains("bound")) {
    const Json& bound = r.array(lips["bound"], "/lips/bound");
    if (bound.size() > kMaxVertices) r.fail("/lips/bound", "too many bound vertices");
    rig.lips.bound.reserve(bound.size());
    for (std::size_t i = 0; i < bound.size(); ++i) {
      const std::string p = "/lips/bound/" + std::to_string(i);
      const Json& j = bound[i];
      LipBinding b;
      b.vertex = r.integer(r.field(j, "vertex", p), p + "/vertex");
      b.u = r.number(r.field(j, "u", p), p + "/u");
      b.v = r.number(r.field(j, "v", p), p + "/v");
      b.offset = r.vec3(r.field(j, "offset", p), p + "/offset");
      b.weight = r.number(r.field(j, "weight", p), p + "/weight");
      rig.lips.bound.push_back(b);
    }
  }

  const Json& jaw = r.field(doc, "jaw", "");
  rig.jaw.pivot = r.vec3(r.field(jaw, "pivot", "/jaw"), "/jaw/pivot");
  rig.jaw.max_angle = r.number(r.field(jaw, "max_angle", "/jaw"), "/jaw/max_angle");
  rig.jaw.vertices = r.ints(r.field(jaw, "vertices", "/jaw"), "/jaw/vertices");
  rig.jaw.weights = r.doubles(r.field(jaw, "weights", "/jaw"), "/jaw/weights");

  const Json& eyes = r.array(r.field(doc, "eyes", ""), "/eyes");
  if (eyes.size() != 2) r.fail("/eyes", "expected two eyes (right, left)");
  for (std::size_t e = 0; e < 2; ++e) {
    const std::string p = "/eyes/" + std::to_string(e);
    const Json& j = eyes[e];
    Eye& eye = rig.eyes[e];
    eye.centre = r.vec3(r.field(j, "centre", p), p + "/centre");
    eye.radius = r.number(r.field(j, "radius", p), p + "/radius");
    eye.eyeball_vertices = r.ints(r.field(j, "eyeball_vertices", p), p + "/eyeball_vertices");
    eye.upper_lid = r.ints(r.field(j, "upper_lid", p), p + "/upper_lid");
    eye.upper_lid_weights = r.doubles(r.field(j, "upper_lid_weights", p), p + "/upper_lid_weights");
    eye.lower_lid = r.ints(r.field(j, "lower_lid", p), p + "/lower_lid");
    eye.lower_lid_weights = r.doubles(r.field(j, "lower_lid_weights", p), p + "/lower_lid_weights");
    eye.close_angle = r.number(r.field(j, "close_angle", p), p + "/close_angle");
    eye.open_angle = r.number(r.field(j, "open_angle", p), p + "/open_angle");
    eye.yaw_limit = r.number(r.field(j, "yaw_limit", p), p + "/yaw_limit");
    eye.pitch_limit = r.number(r.field(j, "pitch_limit", p), p + "/pitch_limit");
  }
  const Json& landmarks = r.field(doc, "landmarks", "");
  rig.ibug68 = r.ints(r.field(landmarks, "ibug68", "/landmarks"), "/landmarks/ibug68");
  const Json& named = r.field(landmarks, "retarget", "/landmarks");
  if (!named.is_object()) r.fail("/landmarks/retarget", "expected an object name -> vertex id");
  for (auto it = named.begin(); it != named.end(); ++it) {
    rig.retarget_landmarks.push_back({it.key(), r.integer(it.value(), "/landmarks/retarget/" + core::json_pointer_token(it.key()))});
  }
  const Json& muscles = r.array(r.field(doc, "muscles", ""), "/muscles");
  for (std::size_t i = 0; i < muscles.size(); ++i) {
    const std::string p = "/muscles/" + std::to_string(i);
    const Json& j = muscles[i];
    MuscleSpec m;
    m.name = r.string(r.field(j, "name", p), p + "/name");
    m.parameter = r.string(r.field(j, "parameter", p), p + "/parameter");
    try {
      m.kind = muscle_kind_from_string(r.string(r.field(j, "kind", p), p + "/kind"));
    } catch (const InvalidInput& e) {
      r.fail(p + "/kind", e.what());
    }
    m.head = r.vec3(r.field(j, "head", p), p + "/head");
    if (m.kind == MuscleKind::Vector) {
      m.tail = r.vec3(r.field(j, "tail", p), p + "/tail");
      m.omega = r.number(r.field(j, "omega", p), p + "/omega");
      m.rs = r.number(r.field(j, "rs", p), p + "/rs");
      m.rf = r.number(r.field(j, "rf", p), p + "/rf");
    } else {
      m.semi_axes = r.vec2(r.field(j, "semi_axes", p), p + "/semi_axes");
    }
    m.k = r.number(r.field(j, "k", p), p + "/k");
    const Json& regs = r.array(r.field(j, "regions", p), p + "/regions");
    for (std::size_t k = 0; k < regs.size(); ++k) {
      const std::string q = p + "/regions/" + std::to_string(k);
      try {
        m.regions.push_back(region_from_string(r.string(regs[k], q)));
      } catch (const InvalidInput& e) {
        r.fail(q, e.what());
      }
    }
    m.moves_lips = r.boolean(r.field(j, "moves_lips", p), p + "/moves_lips");
    m.wrinkle_count = r.integer(r.field(j, "wrinkle_count", p), p + "/wrinkle_count");
    m.wrinkle_height = r.number(r.field(j, "wrinkle_height", p), p + "/wrinkle_height");
    rig.muscles.push_back(std::move(m));
  }
  if (doc.contains("frame")) {
    const Json& f = doc["frame"];
    rig.frame.scale = r.number(r.field(f, "scale", "/frame"), "/frame/scale");
    const Json& rot = r.field(f, "rotation", "/frame");
    if (!rot.is_array() || rot.size() != 3) r.fail("/frame/rotation", "expected 3 rows of 3 numbers");
    for (int i = 0; i < 3; ++i) rig.frame.rotation.row(i) = r.vec3(rot[static_cast<std::size_t>(i)], "/frame/rotation/" + std::to_string(i)).transpose();
    rig.frame.translation = r.vec3(r.field(f, "translation", "/frame"), "/frame/translation");
  }
  if (doc.contains("parts")) {
    const Json& parts = r.array(doc["parts"], "/parts");
    for (std::size_t i = 0; i < parts.size(); ++i) {
      const std::string p = "/parts/" + std::to_string(i);
      const Json& j = parts[i];
      Part part;
      part.name = r.string(r.field(j, "name", p), p + "/name");
      try {
        part.kind = part_kind_from_string(r.string(r.field(j, "kind", p), p + "/kind"));
      } catch (const InvalidInput& e) {
        r.fail(p + "/kind", e.what());
      }
      part.side = r.integer(r.field(j, "side", p), p + "/side");
      part.vertices = r.ints(r.field(j, "vertices", p), p + "/vertices");
      rig.parts.push_back(std::move(part));
    }
  }
  validate_rig(rig, source);
  return rig;
}

std::string format_rig(const Rig& rig) {
  Json doc = core::make_envelope("rig", {kRigFormatMajor, kRigFormatMinor});
  doc["mesh"] = rig.mesh_file;
  doc["vertex_count"] = rig.vertex_count;
  doc["regions"] = label_sets(rig.regions, kRegionCount);
  doc["materials"] = label_sets(rig.materials, kMaterialCount);
  doc["head_pivot"] = vec(rig.head_pivot);
  Json lips;
  Json cps = Json::array();
  for (const auto& c : rig.lips.control_points) cps.push_back(vec(c));
  lips["control_points"] = cps;
  lips["samples_around"] = rig.lips.samples_around;
  lips["samples_across"] = rig.lips.samples_across;
  lips["first_vertex"] = rig.lips.first_vertex;
  lips["centre"] = vec(rig.lips.centre);
  if (!rig.lips.samples_in_mesh) lips["samples_in_mesh"] = false;
  if (!rig.lips.bound.empty()) {
    Json bound = Json::array();
    for (const auto& b : rig.lips.bound) {
      Json j;
      j["vertex"] = b.vertex;
      j["u"] = b.u;
      j["v"] = b.v;
      j["offset"] = vec(b.offset);
      j["weight"] = b.weight;
      bound.push_back(j);
    }
    lips["bound"] = bound;
  }
  doc["lips"] = lips;
  Json jaw;
  jaw["pivot"] = vec(rig.jaw.pivot);
  jaw["max_angle"] = rig.jaw.max_angle;
  jaw["vertices"] = rig.jaw.vertices;
  jaw["weights"] = rig.jaw.weights;
  doc["jaw"] = jaw;
  Json eyes = Json::array();
  for (const auto& eye : rig.eyes) {
    Json j;
    j["centre"] = vec(eye.centre);
    j["radius"] = eye.radius;
    j["eyeball_vertices"] = eye.eyeball_vertices;
    j["upper_lid"] = eye.upper_lid;
    j["upper_lid_weights"] = eye.upper_lid_weights;
    j["lower_lid"] = eye.lower_lid;
    j["lower_lid_weights"] = eye.lower_lid_weights;
    j["close_angle"] = eye.close_angle;
    j["open_angle"] = eye.open_angle;
    j["yaw_limit"] = eye.yaw_limit;
    j["pitch_limit"] = eye.pitch_limit;
    eyes.push_back(j);
  }
  doc["eyes"] = eyes;
  Json landmarks;
  landmarks["ibug68"] = rig.ibug68;
  Json named = Json::object();
  for (const auto& l : rig.retarget_landmarks) named[l.name] = l.vertex;
  landmarks["retarget"] = named;
  doc["landmarks"] = landmarks;
  Json muscles = Json::array();
  for (const auto& m : rig.muscles) {
    Json j;
    j["name"] = m.name;
    j["parameter"] = m.parameter;
    j["kind"] = to_string(m.kind);
    j["head"] = vec(m.head);
    if (m.kind == MuscleKind::Vector) {
      j["tail"] = vec(m.tail);
      j["omega"] = m.omega;
      j["rs"] = m.rs;
      j["rf"] = m.rf;
    } else {
      j["semi_axes"] = Json::array({m.semi_axes.x(), m.semi_axes.y()});
    }
    j["k"] = m.k;
    Json regs = Json::array();
    for (auto reg : m.regions) regs.push_back(to_string(reg));
    j["regions"] = regs;
    j["moves_lips"] = m.moves_lips;
    j["wrinkle_count"] = m.wrinkle_count;
    j["wrinkle_height"] = m.wrinkle_height;
    muscles.push_back(j);
  }
  doc["muscles"] = muscles;
  // format 1.1: written only when they differ from the 1.0 defaults
  if (!rig.frame.is_identity()) {
    Json f;
    f["scale"] = rig.frame.scale;
    Json rot = Json::array();
    for (int i = 0; i < 3; ++i) rot.push_back(vec(rig.frame.rotation.row(i).transpose()));
    f["rotation"] = rot;
    f["translation"] = vec(rig.frame.translation);
    doc["frame"] = f;
  }
  if (!rig.parts.empty()) {
    Json parts = Json::array();
    for (const auto& part : rig.parts) {
      Json j;
      j["name"] = part.name;
      j["kind"] = to_string(part.kind);
      j["side"] = part.side;
      j["vertices"] = part.vertices;
      parts.push_back(j);
    }
    doc["parts"] = parts;
  }
  return doc.dump(1) + "\n";
}

Rig read_rig(const std::string& path) { return parse_rig(core::read_file(path), path); }

void write_rig(const std::string& path, const Rig& rig) {
  validate_rig(rig, path);
  core::write_file_atomic(path, format_rig(rig));
}

std::string frame_format(const Face& face) {
  if (!face.document) return "obj";
  switch (face.document->format()) {
    case MeshFormat::Gltf:
    case MeshFormat::Glb:
      return "glb";
    case MeshFormat::Ply:
      return "ply";
    case MeshFormat::Obj:
    case MeshFormat::Off:
      return "obj";
  }
  return "obj";
}

Face load_face(const std::string& rig_path) {
  Face face;
  face.rig = read_rig(rig_path);
  const auto dir = std::filesystem::path(rig_path).parent_path();
  const std::string mesh_path = (dir / face.rig.mesh_file).string();
  SourceLocation where;
  where.file = rig_path;
  where.json_pointer = "/mesh";
  if (face.rig.mesh_file.empty() || !std::filesystem::is_regular_file(mesh_path)) {
    throw FormatError(where, "referenced mesh '" + mesh_path + "' does not exist");
  }
  MeshFormat format;
  try {
    format = mesh_format_from_path(mesh_path);
  } catch (const InvalidInput& e) {
    throw FormatError(where, e.what());
  }
  if (format == MeshFormat::Off) {
    face.mesh = read_mesh(mesh_path);
  } else {
    auto document = std::make_shared<MeshDocument>(read_mesh_document(mesh_path));
    face.mesh = document->triangles();
    validate_mesh(face.mesh, mesh_path);
    face.document = std::move(document);
  }
  if (!face.rig.frame.is_identity()) {  // the mesh file is in its own frame; the Face lives in the rig's
    for (long v = 0; v < face.mesh.vertices.rows(); ++v) {
      face.mesh.vertices.row(v) = face.rig.frame.to_rig(face.mesh.vertices.row(v).transpose()).transpose();
    }
  }
  if (face.mesh.vertex_count() != face.rig.vertex_count) {
    throw FormatError(where, "mesh '" + mesh_path + "' has " + std::to_string(face.mesh.vertex_count()) +
                                 " vertices, the rig expects " + std::to_string(face.rig.vertex_count));
  }
  return face;
}

Vertices to_mesh_frame(const Rig& rig, const Vertices& positions, const Vertices* original) {
  if (rig.frame.is_identity()) return positions;
  if (original && original->rows() != positions.rows()) throw InvalidInput("to_mesh_frame: original has another vertex count");
  Vertices out(positions.rows(), 3);
  for (long v = 0; v < positions.rows(); ++v) {
    const Eigen::Vector3d p = positions.row(v).transpose();
    if (original) {
      const Eigen::Vector3d o = original->row(v).transpose();
      const Eigen::Vector3d r = rig.frame.to_rig(o);
      if (r.x() == p.x() && r.y() == p.y() && r.z() == p.z()) {
        out.row(v) = o.transpose();
        continue;
      }
    }
    out.row(v) = rig.frame.to_mesh(p).transpose();
  }
  return out;
}

void write_face_mesh(const std::string& path, const Face& face, const Vertices& positions) {
  if (positions.rows() != face.mesh.vertices.rows()) throw InvalidInput("write_face_mesh: positions and face differ in vertex count");
  const MeshFormat format = mesh_format_from_path(path);
  const bool gltf = format == MeshFormat::Gltf || format == MeshFormat::Glb;
  const auto* doc = face.document.get();
  const bool doc_fits = doc && doc->triangles().vertices.rows() == positions.rows() && doc->triangles().faces == face.mesh.faces;
  const bool doc_gltf = doc_fits && (doc->format() == MeshFormat::Gltf || doc->format() == MeshFormat::Glb);
  const Vertices file = to_mesh_frame(face.rig, positions, doc_fits ? &doc->triangles().vertices : nullptr);
  const bool same_kind = doc_fits && doc->format() == format &&
                         (format == MeshFormat::Obj || format == MeshFormat::Ply);
  if (same_kind || (doc_gltf && gltf)) {
    doc->write(path, file);
  } else if (gltf) {
    throw InvalidInput("'" + path + "': a .gltf/.glb mesh file needs a face whose mesh is a glTF document");
  } else {
    write_mesh(path, Mesh{file, face.mesh.faces});
  }
}

void save_face(const std::string& rig_path, const Face& face) {
  if (face.rig.mesh_file.empty()) throw InvalidInput("save_face: rig.mesh_file is empty");
  if (face.mesh.vertex_count() != face.rig.vertex_count) throw InvalidInput("save_face: mesh and rig disagree on the vertex count");
  const auto dir = std::filesystem::path(rig_path).parent_path();
  write_face_mesh((dir / face.rig.mesh_file).string(), face, face.mesh.vertices);
  write_rig(rig_path, face.rig);
}

}  // namespace emoface::facemesh
