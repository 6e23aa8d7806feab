// Mesh I/O through OpenMesh (the only place OpenMesh is used).
#include "emoface/facemesh/mesh_io.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/IO/importer/ImporterT.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/core/version.hpp"

namespace emoface::facemesh {
namespace {

struct Traits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  VertexAttributes(OpenMesh::Attributes::Status);
  FaceAttributes(OpenMesh::Attributes::Status);
  EdgeAttributes(OpenMesh::Attributes::Status);
  HalfedgeAttributes(OpenMesh::Attributes::Status);
};
using OmMesh = OpenMesh::PolyMesh_ArrayKernelT<Traits>;

std::string extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

bool known_extension(const std::string& ext) { return ext == ".obj" || ext == ".ply" || ext == ".off"; }

// OpenMesh reports problems on its own error stream; a library must not print, so mute it while we
// read and detect the problems ourselves (non-manifold faces are marked by the importer).
struct MuteOpenMesh {
  MuteOpenMesh() { ::omerr().disable(); ::omlog().disable(); }
  ~MuteOpenMesh() { ::omerr().enable(); ::omlog().enable(); }
};

// Records the polygons as the file gives them (reader vertex handles), before OpenMesh's halfedge
// structure splits the ones it cannot add (inconsistent winding) onto duplicated vertices.
class RecordingImporter : public OpenMesh::IO::ImporterT<OmMesh> {
 public:
  using Base = OpenMesh::IO::ImporterT<OmMesh>;
  explicit RecordingImporter(OmMesh& mesh) : Base(mesh) {}
  OpenMesh::VertexHandle add_vertex(const OpenMesh::Vec3f& p) override { return record(Base::add_vertex(p)); }
  OpenMesh::VertexHandle add_vertex(const OpenMesh::Vec3d& p) override { return record(Base::add_vertex(p)); }
  OpenMesh::VertexHandle add_vertex() override { return record(Base::add_vertex()); }
  OpenMesh::FaceHandle add_face(const OpenMesh::IO::BaseImporter::VHandles& ids) override {
    const auto fh = Base::add_face(ids);
    if (fh.is_valid()) {
      polygons.emplace_back();
      for (const auto& vh : ids) polygons.back().push_back(vh.idx());
    }
    return fh;
  }
  std::vector<int> reader_vertices;           // OpenMesh handles created by the file reader, in order
  std::vector<std::vector<int>> polygons;     // accepted polygons, reader handles
 private:
  OpenMesh::VertexHandle record(OpenMesh::VertexHandle vh) {
    reader_vertices.push_back(vh.idx());
    return vh;
  }
};

// OpenMesh 9's PLY header parser loops forever on some malformed headers (a missing "end_header", an
// unknown keyword, a property line without a type; found by fuzz_facemesh_mesh): the header is checked
// here, line by line, before OpenMesh sees the file.
void check_ply_header(const std::string& text, const SourceLocation& where) {
  static const char* types[] = {"char", "uchar", "short", "ushort", "int", "uint", "float", "double",
                                "int8", "uint8", "int16", "uint16", "int32", "uint32", "float32", "float64"};
  auto is_type = [](const std::string& t) {
    for (const char* k : types)
      if (t == k) return true;
    return false;
  };
  auto is_count = [](const std::string& t) {
    return !t.empty() && t.size() <= 12 && t.find_first_not_of("0123456789") == std::string::npos;
  };
  std::size_t pos = 0, line_no = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    ++line_no;
    std::string line = text.substr(pos, end - pos);
    pos = end + 1;
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t')) line.pop_back();
    std::vector<std::string> tok;
    for (std::size_t i = 0; i < line.size();) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
      std::size_t j = i;
      while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
      if (j > i) tok.push_back(line.substr(i, j - i));
      i = j;
    }
    SourceLocation at = where;
    at.line = line_no;
    bool ok = false;
    if (line_no == 1) {
      ok = line == "ply";
    } else if (tok.empty()) {
      ok = false;
    } else if (tok[0] == "end_header") {
      if (tok.size() == 1) return;
    } else if (tok[0] == "comment" || tok[0] == "obj_info") {
      ok = true;
    } else if (tok[0] == "format") {
      ok = tok.size() == 3 && (tok[1] == "ascii" || tok[1] == "binary_little_endian" || tok[1] == "binary_big_endian") && tok[2] == "1.0";
    } else if (tok[0] == "element") {
      // Every element takes at least one byte: a larger count is a lie that OpenMesh would allocate for.
      ok = tok.size() == 3 && is_count(tok[2]) && std::stoull(tok[2]) <= text.size();
    } else if (tok[0] == "property") {
      ok = (tok.size() == 3 && is_type(tok[1])) || (tok.size() == 5 && tok[1] == "list" && is_type(tok[2]) && is_type(tok[3]));
    }
    if (!ok) throw FormatError(at, "bad PLY header line \"" + line.substr(0, 80) + "\"");
  }
  throw FormatError(where, "PLY header has no end_header line");
}

// OFF: the keyword line ([ST][C][N][4][n]OFF, optionally BINARY) and counts that fit the file; OpenMesh 9
// allocates for whatever counts a damaged header claims (found by fuzz_facemesh_mesh: 16 GB).
void check_off_header(const std::string& text, const SourceLocation& where) {
  std::size_t i = 0;
  auto next_token = [&]() {
    for (;;) {
      while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
      if (i < text.size() && text[i] == '#') {
        while (i < text.size() && text[i] != '\n') ++i;
        continue;
      }
      break;
    }
    if (i >= text.size()) return std::string();
    const std::size_t b = i;
    while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i]))) ++i;
    return text.substr(b, i - b);
  };
  std::string key = next_token();
  std::size_t k = 0;
  for (const char* prefix : {"ST", "C", "N", "4", "n"}) {
    const std::string p(prefix);
    if (key.compare(k, p.size(), p) == 0) k += p.size();
  }
  if (key.size() < 3 || key.compare(k, std::string::npos, "OFF") != 0)
    throw FormatError(where, "OFF file must start with the OFF keyword (got \"" + key.substr(0, 20) + "\")");
  const bool binary = text.compare(i, 7, " BINARY") == 0;
  if (binary) i += 7;
  if (key.find('4') != std::string::npos || key.find('n') != std::string::npos)
    throw FormatError(where, "4-D / n-D OFF files are not supported");
  // Binary OFF: OpenMesh trusts the binary counts and allocates for them (fuzzing found 16 GB requests);
  // their byte order is not fixed by any spec we can check, so binary OFF is refused.
  if (binary) throw FormatError(where, "binary OFF is not supported (use ASCII OFF, OBJ or PLY)");
  std::size_t counts[2] = {0, 0};
  for (auto& c : counts) {
    const std::string t = next_token();
    if (t.empty() || t.size() > 12 || t.find_first_not_of("0123456789") != std::string::npos)
      throw FormatError(where, "OFF header: bad vertex/face count \"" + t.substr(0, 20) + "\"");
    c = std::stoull(t);
  }
  // At least 6 bytes per ASCII vertex ("0 0 0\n") and 8 per triangle ("3 0 1 2\n").
  if (counts[0] * 6 > text.size() || counts[1] * 8 > text.size())
    throw FormatError(where, "OFF header declares " + std::to_string(counts[0]) + " vertices and " + std::to_string(counts[1]) +
                                 " faces, more than the file's " + std::to_string(text.size()) + " bytes can hold");
  // The body: OpenMesh trusts each face's vertex count (fuzzing found huge allocations), so every face
  // line is checked to start with a count in [3, 1000] followed by that many ids.
  next_token();  // edge count
  for (std::size_t v = 0; v <= counts[0]; ++v) {  // the rest of the counts line, then one line per vertex
    while (i < text.size() && text[i] != '\n') ++i;
    if (i < text.size()) ++i;
  }
  for (std::size_t f = 0; f < counts[1]; ++f) {
    const std::string n = next_token();
    if (n.empty() || n.size() > 4 || n.find_first_not_of("0123456789") != std::string::npos || std::stoul(n) < 3 ||
        std::stoul(n) > 1000)
      throw FormatError(where, "OFF face " + std::to_string(f) + ": bad vertex count \"" + n.substr(0, 20) + "\"");
    while (i < text.size() && text[i] != '\n') ++i;
  }
}

std::size_t count_obj_faces(const std::string& text) {
  std::size_t declared_faces = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    std::size_t s = pos;
    while (s < end && (text[s] == ' ' || text[s] == '\t')) ++s;
    if (s + 1 < end && text[s] == 'f' && (text[s + 1] == ' ' || text[s + 1] == '\t')) ++declared_faces;
    pos = end + 1;
  }
  return declared_faces;
}

}  // namespace

Mesh read_mesh(const std::string& path, const MeshReadOptions& options, MeshReadReport* report) {
  if (!options.repair_orientation) {
    Mesh m = read_mesh(path);
    if (report) *report = MeshReadReport{};
    return m;
  }
  const std::string ext = extension(path);
  SourceLocation where;
  where.file = path;
  if (!known_extension(ext)) throw FormatError(where, "unknown mesh extension '" + ext + "' (use .obj, .ply or .off)");
  if (!std::filesystem::is_regular_file(path)) throw IoError(path + ": cannot open mesh file");
  const std::string text = core::read_file(path);
  if (ext == ".ply") check_ply_header(text, where);
  if (ext == ".off") check_off_header(text, where);
  OmMesh om;
  om.request_vertex_status();
  om.request_face_status();
  om.request_edge_status();
  RecordingImporter importer(om);
  bool ok = false;
  {
    MuteOpenMesh mute;
    OpenMesh::IO::Options opt;
    ok = OpenMesh::IO::IOManager().read(path, importer, opt);
  }
  if (!ok) throw FormatError(where, "OpenMesh could not parse the mesh");
  if (ext == ".obj") {
    const std::size_t declared = count_obj_faces(text);
    if (importer.polygons.size() != declared)
      throw FormatError(where, "the file declares " + std::to_string(declared) + " faces but only " +
                                   std::to_string(importer.polygons.size()) + " are valid (repeated or out-of-range vertex ids)");
  }
  std::vector<int> index(om.n_vertices(), -1);
  Mesh mesh;
  mesh.vertices.resize(static_cast<long>(importer.reader_vertices.size()), 3);
  for (std::size_t i = 0; i < importer.reader_vertices.size(); ++i) {
    const int h = importer.reader_vertices[i];
    index[static_cast<std::size_t>(h)] = static_cast<int>(i);
    const auto& p = om.point(OpenMesh::VertexHandle(h));
    mesh.vertices.row(static_cast<long>(i)) << p[0], p[1], p[2];
  }
  std::vector<std::array<int, 3>> tris;
  for (const auto& poly : importer.polygons)
    for (std::size_t k = 1; k + 1 < poly.size(); ++k)
      tris.push_back({index[static_cast<std::size_t>(poly[0])], index[static_cast<std::size_t>(poly[k])],
                      index[static_cast<std::size_t>(poly[k + 1])]});
  mesh.faces.resize(static_cast<long>(tris.size()), 3);
  for (std::size_t f = 0; f < tris.size(); ++f) mesh.faces.row(static_cast<long>(f)) << tris[f][0], tris[f][1], tris[f][2];
  if (mesh.faces.rows() == 0) throw FormatError(where, "mesh has no triangles");
  if (!mesh.vertices.allFinite()) validate_mesh(mesh, path);  // names the bad vertex
  OrientationReport orientation;
  try {
    orientation = orient_consistently(mesh);
  } catch (const InvalidInput& e) {
    throw FormatError(where, std::string(e.what()).substr(std::string("orient_consistently: ").size()));
  }
  validate_mesh(mesh, path);
  if (report) report->orientation = orientation;
  return mesh;
}

Mesh read_mesh(const std::string& path) {
  const std::string ext = extension(path);
  SourceLocation where;
  where.file = path;
  if (!known_extension(ext)) throw FormatError(where, "unknown mesh extension '" + ext + "' (use .obj, .ply or .off)");
  if (!std::filesystem::is_regular_file(path)) throw IoError(path + ": cannot open mesh file");
  // Count the faces the file declares for OBJ/OFF so that faces OpenMesh silently drops (repeated or
  // out-of-range ids) are reported instead of lost.
  std::size_t declared_faces = 0;
  bool counted = false;
  const std::string text = core::read_file(path);
  if (ext == ".ply") check_ply_header(text, where);
  if (ext == ".off") check_off_header(text, where);
  if (ext == ".obj") {
    counted = true;
    declared_faces = count_obj_faces(text);
  }
  OmMesh om;
  om.request_vertex_status();
  om.request_face_status();
  bool ok = false;
  {
    MuteOpenMesh mute;
    OpenMesh::IO::Options opt;
    ok = OpenMesh::IO::read_mesh(om, path, opt);
  }
  if (!ok) throw FormatError(where, "OpenMesh could not parse the mesh");
  if (counted && om.n_faces() != declared_faces) {
    throw FormatError(where, "the file declares " + std::to_string(declared_faces) + " faces but only " +
                                 std::to_string(om.n_faces()) +
                                 " are valid (repeated or out-of-range vertex ids)");
  }
  Mesh mesh;
  mesh.vertices.resize(static_cast<long>(om.n_vertices()), 3);
  for (auto vh : om.vertices()) {
    const auto& p = om.point(vh);
    mesh.vertices.row(vh.idx()) << p[0], p[1], p[2];
  }
  std::vector<std::array<int, 3>> tris;
  for (auto fh : om.faces()) {
    if (om.status(fh).fixed_nonmanifold()) {
      where.line = static_cast<std::size_t>(fh.idx()) + 1;
      throw FormatError(where, "face " + std::to_string(fh.idx()) + " is non-manifold");
    }
    std::vector<int> ids;
    for (auto vh : om.fv_range(fh)) ids.push_back(vh.idx());
    for (std::size_t k = 1; k + 1 < ids.size(); ++k) tris.push_back({ids[0], ids[k], ids[k + 1]});
  }
  mesh.faces.resize(static_cast<long>(tris.size()), 3);
  for (std::size_t f = 0; f < tris.size(); ++f) {
    mesh.faces.row(static_cast<long>(f)) << tris[f][0], tris[f][1], tris[f][2];
  }
  validate_mesh(mesh, path);
  return mesh;
}

void write_mesh(const std::string& path, const Mesh& mesh) {
  const std::string ext = extension(path);
  if (!known_extension(ext)) throw InvalidInput("write_mesh: unknown extension '" + ext + "' (use .obj, .ply or .off)");
  // Written by hand for OBJ/OFF/PLY ASCII (simple, exact "%.9g" text, atomic); OpenMesh is used to
  // read, which accepts far more variants than we write.
  std::string out;
  out.reserve(mesh.vertex_count() * 40 + mesh.face_count() * 20);
  char buf[128];
  const long nv = mesh.vertices.rows(), nf = mesh.faces.rows();
  if (ext == ".off") {
    out += "OFF\n" + std::to_string(nv) + " " + std::to_string(nf) + " 0\n";
  } else if (ext == ".ply") {
    out += "ply\nformat ascii 1.0\ncomment " + std::string(emoface::kGenerator) + "\nelement vertex " + std::to_string(nv) +
           "\nproperty double x\nproperty double y\nproperty double z\nelement face " + std::to_string(nf) +
           "\nproperty list uchar int vertex_indices\nend_header\n";
  } else {
    out += "# " + std::string(emoface::kGenerator) + "\n";
  }
  for (long v = 0; v < nv; ++v) {
    std::snprintf(buf, sizeof buf, ext == ".obj" ? "v %.9g %.9g %.9g\n" : "%.9g %.9g %.9g\n",
                  mesh.vertices(v, 0), mesh.vertices(v, 1), mesh.vertices(v, 2));
    out += buf;
  }
  for (long f = 0; f < nf; ++f) {
    if (ext == ".obj") {
      std::snprintf(buf, sizeof buf, "f %d %d %d\n", mesh.faces(f, 0) + 1, mesh.faces(f, 1) + 1, mesh.faces(f, 2) + 1);
    } else {
      std::snprintf(buf, sizeof buf, "3 %d %d %d\n", mesh.faces(f, 0), mesh.faces(f, 1), mesh.faces(f, 2));
    }
    out += buf;
  }
  core::write_file_atomic(path, out);
}

}  // namespace emoface::facemesh
