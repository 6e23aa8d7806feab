// emoface.rig reader/writer (JSON envelope kind "rig").
#include "emoface/facemesh/io.hpp"

#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/core/json_reader.hpp"
#include "emoface/facemesh/mesh_io.hpp"

namespace emoface::facemesh {
namespace {

using Json = nlohmann::ordered_json;

using core::JsonValue;

// Typed getters over core::JsonValue (located errors "FILE: at /pointer: message").
int integer(const JsonValue& v) {
  return static_cast<int>(
      v.integer(std::numeric_limits<int>::min(), std::numeric_limits<int>::max()));
}
Eigen::Vector3d vec3(const JsonValue& v) {
  v.expect_array(3);
  return {v[0].number(), v[1].number(), v[2].number()};
}
Eigen::Vector2d vec2(const JsonValue& v) {
  v.expect_array(2);
  return {v[0].number(), v[1].number()};
}
std::vector<int> ints(const JsonValue& v) {
  std::vector<int> out;
  for (const JsonValue& x : v.expect_array().items()) out.push_back(integer(x));
  return out;
}
std::vector<double> doubles(const JsonValue& v) {
  std::vector<double> out;
  for (const JsonValue& x : v.expect_array().items()) out.push_back(x.number());
  return out;
}
// An enum from its string, the parse error located at the value.
template <class Enum, class FromString>
Enum enum_value(const JsonValue& v, FromString from_string) {
  try {
    return from_string(v.string());
  } catch (const InvalidInput& e) {
    v.fail(e.what());
  }
}
// {"label": [vertex ids ...], ...}: every vertex exactly once.
template <class Enum, class FromString>
std::vector<Enum> labels(const JsonValue& v, std::size_t n, FromString from_string) {
  if (!v.is_object()) v.fail("expected an object of label -> vertex ids");
  std::vector<char> seen(n, 0);
  std::vector<Enum> out(n);
  for (const auto& [key, ids] : v.members()) {
    Enum label;
    try {
      label = from_string(key);
    } catch (const InvalidInput& e) {
      ids.fail(e.what());
    }
    const std::vector<JsonValue> items = ids.expect_array().items();
    for (const JsonValue& id : items) {
      const int vertex = integer(id);
      if (vertex < 0 || static_cast<std::size_t>(vertex) >= n)
        id.fail("vertex id " + std::to_string(vertex) + " out of range");
      if (seen[static_cast<std::size_t>(vertex)])
        id.fail("vertex " + std::to_string(vertex) + " listed twice");
      seen[static_cast<std::size_t>(vertex)] = 1;
      out[static_cast<std::size_t>(vertex)] = label;
    }
  }
  for (std::size_t i = 0; i < n; ++i)
    if (!seen[i]) v.fail("vertex " + std::to_string(i) + " has no label");
  return out;
}

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
  // The unknown-field rule of docs/formats.md: a newer 1.x may add fields; this and older minors
  // may not.
  const core::JsonReader reader(text, source, "rig", {kRigFormatMajor, kRigFormatMinor});
  const JsonValue doc = reader.root();
  doc.only_keys({"mesh", "vertex_count", "regions", "materials", "head_pivot", "lips", "jaw",
                 "eyes", "landmarks", "muscles", "frame", "parts"});
  Rig rig;
  rig.mesh_file = doc.at("mesh").string();
  rig.vertex_count = static_cast<std::size_t>(
      doc.at("vertex_count").integer(1, static_cast<std::int64_t>(kMaxVertices)));
  rig.regions = labels<Region>(doc.at("regions"), rig.vertex_count, region_from_string);
  rig.materials = labels<Material>(doc.at("materials"), rig.vertex_count, material_from_string);
  rig.head_pivot = vec3(doc.at("head_pivot"));

  const JsonValue lips = doc.at("lips");
  lips.only_keys({"control_points", "samples_around", "samples_across", "first_vertex", "centre",
                  "samples_in_mesh", "bound", "border_jaw"});
  for (const JsonValue& c : lips.at("control_points").expect_array().items())
    rig.lips.control_points.push_back(vec3(c));
  rig.lips.samples_around = integer(lips.at("samples_around"));
  rig.lips.samples_across = integer(lips.at("samples_across"));
  rig.lips.first_vertex = integer(lips.at("first_vertex"));
  rig.lips.centre = vec3(lips.at("centre"));
  // format 1.1 (absent in 1.0: the defaults)
  rig.lips.samples_in_mesh = lips.boolean_or("samples_in_mesh", true);
  if (const auto bound = lips.find("bound")) {
    if (bound->expect_array().size() > kMaxVertices) bound->fail("too many bound vertices");
    for (const JsonValue& j : bound->items()) {
      j.only_keys({"vertex", "u", "v", "offset", "weight"});
      LipBinding b;
      b.vertex = integer(j.at("vertex"));
      b.u = j.at("u").number();
      b.v = j.at("v").number();
      b.offset = vec3(j.at("offset"));
      b.weight = j.at("weight").number();
      rig.lips.bound.push_back(b);
    }
  }

  // format 1.2 (absent before: derived by the solver)
  if (const auto border_jaw = lips.find("border_jaw")) rig.lips.border_jaw = doubles(*border_jaw);

  const JsonValue jaw = doc.at("jaw");
  jaw.only_keys({"pivot", "max_angle", "vertices", "weights"});
  rig.jaw.pivot = vec3(jaw.at("pivot"));
  rig.jaw.max_angle = jaw.at("max_angle").number();
  rig.jaw.vertices = ints(jaw.at("vertices"));
  rig.jaw.weights = doubles(jaw.at("weights"));

  const JsonValue eyes = doc.at("eyes").expect_array();
  if (eyes.size() != 2) eyes.fail("expected two eyes (right, left)");
  for (std::size_t e = 0; e < 2; ++e) {
    const JsonValue j = eyes[e];
    j.only_keys({"centre", "radius", "eyeball_vertices", "upper_lid", "upper_lid_weights",
                 "lower_lid", "lower_lid_weights", "close_angle", "open_angle", "yaw_limit",
                 "pitch_limit", "tighten_angle"});
    Eye& eye = rig.eyes[e];
    eye.centre = vec3(j.at("centre"));
    eye.radius = j.at("radius").number();
    eye.eyeball_vertices = ints(j.at("eyeball_vertices"));
    eye.upper_lid = ints(j.at("upper_lid"));
    eye.upper_lid_weights = doubles(j.at("upper_lid_weights"));
    eye.lower_lid = ints(j.at("lower_lid"));
    eye.lower_lid_weights = doubles(j.at("lower_lid_weights"));
    eye.close_angle = j.at("close_angle").number();
    eye.open_angle = j.at("open_angle").number();
    eye.yaw_limit = j.at("yaw_limit").number();
    eye.pitch_limit = j.at("pitch_limit").number();
    // format 1.3 (absent before: the tightener's angle is close_angle)
    if (const auto tighten = j.find("tighten_angle")) eye.tighten_angle = tighten->number();
  }
  const JsonValue landmarks = doc.at("landmarks");
  landmarks.only_keys({"ibug68", "retarget"});
  rig.ibug68 = ints(landmarks.at("ibug68"));
  const JsonValue named = landmarks.at("retarget");
  if (!named.is_object()) named.fail("expected an object name -> vertex id");
  for (const auto& [name, vertex] : named.members())
    rig.retarget_landmarks.push_back({name, integer(vertex)});

  for (const JsonValue& j : doc.at("muscles").expect_array().items()) {
    j.only_keys({"name", "parameter", "kind", "head", "tail", "omega", "rs", "rf", "semi_axes", "k",
                 "regions", "moves_lips", "wrinkle_count", "wrinkle_height"});
    MuscleSpec m;
    m.name = j.at("name").string();
    m.parameter = j.at("parameter").string();
    m.kind = enum_value<MuscleKind>(j.at("kind"), muscle_kind_from_string);
    m.head = vec3(j.at("head"));
    if (m.kind == MuscleKind::Vector) {
      m.tail = vec3(j.at("tail"));
      m.omega = j.at("omega").number();
      m.rs = j.at("rs").number();
      m.rf = j.at("rf").number();
    } else {
      m.semi_axes = vec2(j.at("semi_axes"));
    }
    m.k = j.at("k").number();
    for (const JsonValue& r : j.at("regions").expect_array().items())
      m.regions.push_back(enum_value<Region>(r, region_from_string));
    m.moves_lips = j.at("moves_lips").boolean();
    m.wrinkle_count = integer(j.at("wrinkle_count"));
    m.wrinkle_height = j.at("wrinkle_height").number();
    rig.muscles.push_back(std::move(m));
  }
  if (const auto f = doc.find("frame")) {
    f->only_keys({"scale", "rotation", "translation"});
    rig.frame.scale = f->at("scale").number();
    const JsonValue rot = f->at("rotation");
    if (!rot.is_array() || rot.size() != 3) rot.fail("expected 3 rows of 3 numbers");
    for (std::size_t i = 0; i < 3; ++i)
      rig.frame.rotation.row(static_cast<Eigen::Index>(i)) = vec3(rot[i]).transpose();
    rig.frame.translation = vec3(f->at("translation"));
  }
  if (const auto parts = doc.find("parts")) {
    for (const JsonValue& j : parts->expect_array().items()) {
      j.only_keys({"name", "kind", "side", "vertices"});
      Part part;
      part.name = j.at("name").string();
      part.kind = enum_value<PartKind>(j.at("kind"), part_kind_from_string);
      part.side = integer(j.at("side"));
      part.vertices = ints(j.at("vertices"));
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
  if (!rig.lips.border_jaw.empty()) lips["border_jaw"] = rig.lips.border_jaw;
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
    if (eye.tighten_angle) j["tighten_angle"] = *eye.tighten_angle;
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
