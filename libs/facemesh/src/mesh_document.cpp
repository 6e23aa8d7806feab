// A user's mesh file as a document (mesh_document.hpp): our own OBJ parser that keeps every line,
// glTF 2.0 through tinygltf (positions and normals rewritten in place), PLY/OFF through mesh_io.
#include "emoface/facemesh/mesh_document.hpp"

#include <tiny_gltf.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <map>
#include <set>
#include <string_view>
#include <tuple>
#include <unordered_map>

#include "document_companions.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/facemesh/mesh_io.hpp"
#include "gltf_buffers.hpp"
#include "ply_document.hpp"

namespace emoface::facemesh {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------------
// State

struct MeshDocument::Impl {
  MeshFormat format = MeshFormat::Obj;
  std::string path;
  Mesh tri;
  std::vector<int> polygon_of_triangle;
  std::size_t dropped = 0;
  std::vector<MeshGroup> groups;
  bool has_uvs = false;
  std::vector<Eigen::Vector3f> colors;
  std::vector<std::string> material_libraries;
  std::vector<MorphTarget> targets;                // glTF: the first mesh's own morph targets
  std::shared_ptr<const detail::PlyDocument> ply;  // PLY: the file, kept whole

  // OBJ: the file text and its logical lines (a line continued with '\' spans several physical lines).
  enum class LineKind { Other, Vertex, Normal };
  struct Line {
    std::size_t begin = 0, end = 0;  // span in text, terminator included
    std::string terminator;          // "\n", "\r\n" or "" (last line without one)
    LineKind kind = LineKind::Other;
    int index = -1;                  // vertex or normal id
  };
  std::string text;
  std::vector<Line> lines;
  std::vector<std::string> vertex_tail;  // per vertex: the text after its three coordinates
  std::vector<int> normal_line;          // per vn: index into lines
  std::vector<std::array<int, 3>> corner_normal;  // per triangle: vn id of each corner, −1 = none

  // glTF
  tinygltf::Model model;
  struct Primitive {
    int index = 0;           // in meshes[0].primitives
    int position = -1;       // accessor
    int normal = -1;         // accessor, −1 = none
    int vertex_offset = 0;   // first vertex in tri
    int vertex_count = 0;
    bool triangles = false;  // part of triangles()
  };
  std::vector<Primitive> primitives;
};

std::string to_string(MeshFormat format) {
  switch (format) {
    case MeshFormat::Obj: return "obj";
    case MeshFormat::Ply: return "ply";
    case MeshFormat::Off: return "off";
    case MeshFormat::Gltf: return "gltf";
    case MeshFormat::Glb: return "glb";
  }
  return "obj";
}

MeshFormat mesh_format_from_path(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".obj") return MeshFormat::Obj;
  if (ext == ".ply") return MeshFormat::Ply;
  if (ext == ".off") return MeshFormat::Off;
  if (ext == ".gltf") return MeshFormat::Gltf;
  if (ext == ".glb") return MeshFormat::Glb;
  throw InvalidInput("'" + path + "': unknown mesh format (use .obj, .ply, .off, .gltf or .glb)");
}

MeshDocument::MeshDocument() : impl_(std::make_unique<Impl>()) {}
MeshDocument::~MeshDocument() = default;
MeshDocument::MeshDocument(MeshDocument&&) noexcept = default;
MeshDocument& MeshDocument::operator=(MeshDocument&&) noexcept = default;
MeshDocument::MeshDocument(const MeshDocument& other) : impl_(std::make_unique<Impl>(*other.impl_)) {}
MeshDocument& MeshDocument::operator=(const MeshDocument& other) {
  if (this != &other) impl_ = std::make_unique<Impl>(*other.impl_);
  return *this;
}

MeshFormat MeshDocument::format() const { return impl_->format; }
const std::string& MeshDocument::path() const { return impl_->path; }
const Mesh& MeshDocument::triangles() const { return impl_->tri; }
const std::vector<int>& MeshDocument::polygon_of_triangle() const { return impl_->polygon_of_triangle; }
std::size_t MeshDocument::dropped_faces() const { return impl_->dropped; }
const std::vector<MeshGroup>& MeshDocument::groups() const { return impl_->groups; }
bool MeshDocument::has_uvs() const { return impl_->has_uvs; }
const std::vector<Eigen::Vector3f>& MeshDocument::vertex_colors() const { return impl_->colors; }
const std::vector<std::string>& MeshDocument::material_libraries() const { return impl_->material_libraries; }
const std::vector<MorphTarget>& MeshDocument::morph_targets() const { return impl_->targets; }

namespace {

constexpr std::size_t kMaxElements = 50'000'000;  // vertices / triangles a document may hold

bool is_degenerate(const Vertices& v, int a, int b, int c) {
  if (a == b || b == c || a == c) return true;
  const Eigen::Vector3d pa = v.row(a).transpose();
  const Eigen::Vector3d n = (Eigen::Vector3d(v.row(b).transpose()) - pa).cross(Eigen::Vector3d(v.row(c).transpose()) - pa);
  return !(n.squaredNorm() > 0.0);
}

// Edges shared by more than two triangles of one group: returns the offending triangle or −1.
int overshared_edge(const Faces& faces, const std::vector<int>& group_faces) {
  std::unordered_map<std::uint64_t, int> count;
  count.reserve(group_faces.size() * 3);
  for (int f : group_faces) {
    for (int k = 0; k < 3; ++k) {
      const auto a = static_cast<std::uint32_t>(faces(f, k)), b = static_cast<std::uint32_t>(faces(f, (k + 1) % 3));
      const std::uint64_t key = (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
      if (++count[key] > 2) return f;
    }
  }
  return -1;
}

std::string format_double(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

std::string format_float(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.9g", x);
  return buf;
}

bool same_bits(const double* a, const double* b) { return std::memcmp(a, b, 3 * sizeof(double)) == 0; }

// ---------------------------------------------------------------------------------------------------
// OBJ

struct ObjParser {
  explicit ObjParser(MeshDocument::Impl& d) : doc(d) {}
  MeshDocument::Impl& doc;
  std::size_t line_no = 0;  // 1-based physical line of the current logical line's start

  [[noreturn]] void fail(const std::string& message) const {
    SourceLocation where;
    where.file = doc.path;
    where.line = line_no;
    throw FormatError(where, message);
  }

  double number(std::string_view token, const char* what) const {
    double x = 0.0;
    const char* b = token.data();
    const char* e = b + token.size();
    if (!token.empty() && *b == '+') ++b;  // from_chars does not take a leading '+'
    const auto r = std::from_chars(b, e, x);
    if (r.ec == std::errc::result_out_of_range) fail(std::string(what) + " '" + std::string(token) + "' out of range");
    if (r.ec != std::errc() || r.ptr != e) fail(std::string("expected a number for ") + what + ", got '" + std::string(token) + "'");
    if (!std::isfinite(x)) fail(std::string(what) + " is not finite ('" + std::string(token) + "')");
    return x;
  }

  // 1-based or negative (relative to `count` defined so far) OBJ index -> 0-based; `limit`: −1 = check later
  long index(std::string_view token, long count, const char* what) const {
    long long i = 0;
    const auto r = std::from_chars(token.data(), token.data() + token.size(), i);
    if (r.ec != std::errc() || r.ptr != token.data() + token.size() || token.empty()) {
      fail(std::string("bad ") + what + " index '" + std::string(token) + "'");
    }
    if (i == 0) fail(std::string(what) + " index 0 (OBJ indices start at 1)");
    if (i < 0) {
      if (-i > count) fail(std::string(what) + " index " + std::to_string(i) + " refers before the first " + what);
      return static_cast<long>(count + i);
    }
    if (i > static_cast<long long>(kMaxElements)) fail(std::string(what) + " index " + std::to_string(i) + " out of range");
    return static_cast<long>(i - 1);
  }

  void parse() {
    const std::string& t = doc.text;
    std::vector<double> xyz;
    std::vector<Eigen::Vector3f> colors;
    std::size_t colored = 0;
    long vt_count = 0, vn_count = 0;
    // faces: per polygon its corners (v, vt, vn) and the physical line for errors
    struct Corner {
      long v, vt, vn;
    };
    std::vector<Corner> corners;
    struct Polygon {
      std::size_t first, count, line;
      int group;
    };
    std::vector<Polygon> polygons;
    std::string object, group, material;
    std::map<std::tuple<std::string, std::string, std::string>, int> group_ids;
    int current_group = -1;
    auto group_id = [&]() {
      if (current_group >= 0) return current_group;
      const auto key = std::make_tuple(object, group, material);
      auto it = group_ids.find(key);
      if (it == group_ids.end()) {
        it = group_ids.emplace(key, static_cast<int>(doc.groups.size())).first;
        doc.groups.push_back({object, group, material, {}});
      }
      return current_group = it->second;
    };

    std::size_t pos = 0, physical = 0;
    std::vector<std::string_view> tokens;
    std::string joined;
    while (pos < t.size()) {
      MeshDocument::Impl::Line line;
      line.begin = pos;
      line_no = physical + 1;
      joined.clear();
      // gather the physical lines of this logical line ('\' at the end continues it)
      for (;;) {
        const std::size_t nl = t.find('\n', pos);
        const std::size_t stop = nl == std::string::npos ? t.size() : nl;
        std::size_t content_end = stop;
        if (content_end > pos && t[content_end - 1] == '\r') --content_end;
        ++physical;
        line.terminator = nl == std::string::npos ? std::string() : t.substr(content_end, nl + 1 - content_end);
        const std::string_view piece(t.data() + pos, content_end - pos);
        pos = nl == std::string::npos ? t.size() : nl + 1;
        if (!piece.empty() && piece.back() == '\\' && pos < t.size()) {
          joined.append(piece.substr(0, piece.size() - 1));
          joined.push_back(' ');
          continue;
        }
        joined.append(piece);
        break;
      }
      line.end = pos;
      // tokens
      tokens.clear();
      {
        std::size_t i = 0;
        const std::size_t cut = joined.find('#');
        const std::size_t n = cut == std::string::npos ? joined.size() : cut;
        while (i < n) {
          while (i < n && (joined[i] == ' ' || joined[i] == '\t' || joined[i] == '\r' || joined[i] == '\f' || joined[i] == '\v')) ++i;
          const std::size_t s = i;
          while (i < n && !(joined[i] == ' ' || joined[i] == '\t' || joined[i] == '\r' || joined[i] == '\f' || joined[i] == '\v')) ++i;
          if (i > s) tokens.emplace_back(joined.data() + s, i - s);
        }
      }
      if (!tokens.empty()) {
        const std::string_view key = tokens[0];
        if (key == "v") {
          const std::size_t n = tokens.size() - 1;
          if (n != 3 && n != 4 && n != 6 && n != 7) fail("a vertex needs x y z [w] or x y z r g b [a], got " + std::to_string(n) + " numbers");
          if (xyz.size() / 3 >= kMaxElements) fail("too many vertices");
          for (int k = 1; k <= 3; ++k) xyz.push_back(number(tokens[static_cast<std::size_t>(k)], "vertex coordinate"));
          Eigen::Vector3f c(1.0f, 1.0f, 1.0f);
          if (n >= 6) {
            for (int k = 0; k < 3; ++k) c[k] = static_cast<float>(number(tokens[static_cast<std::size_t>(4 + k)], "vertex colour"));
            ++colored;
          } else if (n == 4) {
            number(tokens[4], "vertex w");
          }
          if (n == 7) number(tokens[7], "vertex alpha");
          colors.push_back(c);
          line.kind = MeshDocument::Impl::LineKind::Vertex;
          line.index = static_cast<int>(xyz.size() / 3 - 1);
          // the text after the third coordinate (colours, trailing comment), kept verbatim on rewrite
          const std::size_t after = static_cast<std::size_t>(tokens[3].data() + tokens[3].size() - joined.data());
          doc.vertex_tail.push_back(joined.substr(after));
        } else if (key == "vt") {
          if (tokens.size() < 2 || tokens.size() > 4) fail("a texture coordinate needs 1 to 3 numbers");
          for (std::size_t k = 1; k < tokens.size(); ++k) number(tokens[k], "texture coordinate");
          ++vt_count;
        } else if (key == "vn") {
          if (tokens.size() != 4) fail("a normal needs 3 numbers");
          for (std::size_t k = 1; k < 4; ++k) number(tokens[k], "normal coordinate");
          line.kind = MeshDocument::Impl::LineKind::Normal;
          line.index = static_cast<int>(vn_count++);
          doc.normal_line.push_back(static_cast<int>(doc.lines.size()));
        } else if (key == "f" || key == "fo") {
          if (tokens.size() < 4) fail("a face needs at least 3 corners");
          const std::size_t first = corners.size();
          for (std::size_t k = 1; k < tokens.size(); ++k) {
            const std::string_view c = tokens[k];
            const std::size_t s1 = c.find('/');
            Corner corner{-1, -1, -1};
            corner.v = index(c.substr(0, s1), static_cast<long>(xyz.size() / 3), "vertex");
            if (s1 != std::string_view::npos) {
              const std::size_t s2 = c.find('/', s1 + 1);
              const std::string_view vt = c.substr(s1 + 1, s2 == std::string_view::npos ? std::string_view::npos : s2 - s1 - 1);
              if (!vt.empty()) corner.vt = index(vt, vt_count, "texture coordinate");
              if (s2 != std::string_view::npos) corner.vn = index(c.substr(s2 + 1), vn_count, "normal");
              if (s2 == std::string_view::npos && vt.empty()) fail("bad face corner '" + std::string(c) + "'");
            }
            if (corner.vt >= 0 && corner.vt >= vt_count) fail("texture coordinate index " + std::to_string(corner.vt + 1) + " out of range");
            if (corner.vn >= 0 && corner.vn >= vn_count) fail("normal index " + std::to_string(corner.vn + 1) + " out of range");
            if (corner.vt >= 0) doc.has_uvs = true;
            corners.push_back(corner);
          }
          if (polygons.size() >= kMaxElements) fail("too many faces");
          polygons.push_back({first, corners.size() - first, line_no, group_id()});
        } else if (key == "o") {
          object = joined_rest(tokens, joined);
          current_group = -1;
        } else if (key == "g") {
          group = joined_rest(tokens, joined);
          current_group = -1;
        } else if (key == "usemtl") {
          material = joined_rest(tokens, joined);
          current_group = -1;
        } else if (key == "mtllib") {
          for (std::size_t k = 1; k < tokens.size(); ++k) doc.material_libraries.emplace_back(tokens[k]);
        }
        // s, l, p, vp, cstype, ... and unknown statements: kept verbatim, not interpreted
      }
      doc.lines.push_back(line);
    }

    // vertices
    const std::size_t nv = xyz.size() / 3;
    doc.tri.vertices.resize(static_cast<long>(nv), 3);
    std::copy(xyz.begin(), xyz.end(), doc.tri.vertices.data());
    if (colored == nv && nv > 0) doc.colors = std::move(colors);
    // triangles (fan), with their polygon, group and corner normals
    std::vector<std::array<int, 3>> faces;
    for (std::size_t p = 0; p < polygons.size(); ++p) {
      const Polygon& poly = polygons[p];
      for (std::size_t k = 0; k < poly.count; ++k) {
        if (corners[poly.first + k].v >= static_cast<long>(nv)) {
          line_no = poly.line;
          fail("vertex index " + std::to_string(corners[poly.first + k].v + 1) + " out of range (" + std::to_string(nv) + " vertices)");
        }
      }
      for (std::size_t k = 1; k + 1 < poly.count; ++k) {
        const Corner& a = corners[poly.first];
        const Corner& b = corners[poly.first + k];
        const Corner& c = corners[poly.first + k + 1];
        if (is_degenerate(doc.tri.vertices, static_cast<int>(a.v), static_cast<int>(b.v), static_cast<int>(c.v))) {
          ++doc.dropped;
          continue;
        }
        doc.groups[static_cast<std::size_t>(poly.group)].faces.push_back(static_cast<int>(faces.size()));
        faces.push_back({static_cast<int>(a.v), static_cast<int>(b.v), static_cast<int>(c.v)});
        doc.corner_normal.push_back({static_cast<int>(a.vn), static_cast<int>(b.vn), static_cast<int>(c.vn)});
        doc.polygon_of_triangle.push_back(static_cast<int>(p));
        triangle_line_.push_back(poly.line);
      }
    }
    if (faces.empty()) {
      line_no = 0;
      fail(polygons.empty() ? "no faces" : "no non-degenerate triangle");
    }
    doc.tri.faces.resize(static_cast<long>(faces.size()), 3);
    for (std::size_t f = 0; f < faces.size(); ++f) {
      for (int k = 0; k < 3; ++k) doc.tri.faces(static_cast<long>(f), k) = faces[f][static_cast<std::size_t>(k)];
    }
    // empty groups (a usemtl followed by no face) are dropped
    doc.groups.erase(std::remove_if(doc.groups.begin(), doc.groups.end(), [](const MeshGroup& g) { return g.faces.empty(); }),
                     doc.groups.end());
    for (const auto& g : doc.groups) {
      const int f = overshared_edge(doc.tri.faces, g.faces);
      if (f >= 0) {
        line_no = triangle_line_[static_cast<std::size_t>(f)];
        fail("an edge of this face is shared by more than two triangles (non-manifold)");
      }
    }
  }

  static std::string joined_rest(const std::vector<std::string_view>& tokens, const std::string& joined) {
    if (tokens.size() < 2) return {};
    const std::size_t b = static_cast<std::size_t>(tokens[1].data() - joined.data());
    const std::size_t e = static_cast<std::size_t>(tokens.back().data() + tokens.back().size() - joined.data());
    return joined.substr(b, e - b);
  }

  std::vector<std::size_t> triangle_line_;
};

void read_obj(MeshDocument::Impl& doc) {
  doc.text = core::read_file(doc.path);
  ObjParser parser(doc);
  parser.parse();
}

// Area-weighted normals of the vn entries whose triangles moved; nullopt-like flag per vn.
void write_obj(const MeshDocument::Impl& doc, const std::string& path, const Vertices& positions, bool recompute_normals) {
  const Vertices& old = doc.tri.vertices;
  const long nv = old.rows();
  std::vector<char> moved(static_cast<std::size_t>(nv), 0);
  for (long v = 0; v < nv; ++v) moved[static_cast<std::size_t>(v)] = !same_bits(old.data() + 3 * v, positions.data() + 3 * v);
  const std::size_t nn = doc.normal_line.size();
  std::vector<Eigen::Vector3d> normal(nn, Eigen::Vector3d::Zero());
  std::vector<char> dirty(nn, 0);
  if (recompute_normals && nn > 0) {
    const Faces& F = doc.tri.faces;
    for (long f = 0; f < F.rows(); ++f) {
      const auto& cn = doc.corner_normal[static_cast<std::size_t>(f)];
      const bool any_moved = moved[static_cast<std::size_t>(F(f, 0))] || moved[static_cast<std::size_t>(F(f, 1))] || moved[static_cast<std::size_t>(F(f, 2))];
      const Eigen::Vector3d a = positions.row(F(f, 0)).transpose();
      const Eigen::Vector3d n = (Eigen::Vector3d(positions.row(F(f, 1)).transpose()) - a).cross(Eigen::Vector3d(positions.row(F(f, 2)).transpose()) - a);
      for (int k = 0; k < 3; ++k) {
        if (cn[static_cast<std::size_t>(k)] < 0) continue;
        const auto i = static_cast<std::size_t>(cn[static_cast<std::size_t>(k)]);
        normal[i] += n;  // |cross| = 2·area: area-weighted
        if (any_moved) dirty[i] = 1;
      }
    }
  }
  std::string out;
  out.reserve(doc.text.size() + doc.text.size() / 4);
  const std::string& t = doc.text;
  for (const auto& line : doc.lines) {
    if (line.kind == MeshDocument::Impl::LineKind::Vertex && moved[static_cast<std::size_t>(line.index)]) {
      const double* p = positions.data() + 3 * line.index;
      out += "v " + format_double(p[0]) + " " + format_double(p[1]) + " " + format_double(p[2]);
      out += doc.vertex_tail[static_cast<std::size_t>(line.index)];
      out += line.terminator;
    } else if (line.kind == MeshDocument::Impl::LineKind::Normal && dirty[static_cast<std::size_t>(line.index)] &&
               normal[static_cast<std::size_t>(line.index)].norm() > 0.0) {
      const Eigen::Vector3d n = normal[static_cast<std::size_t>(line.index)].normalized();
      out += "vn " + format_float(n.x()) + " " + format_float(n.y()) + " " + format_float(n.z()) + line.terminator;
    } else {
      out.append(t, line.begin, line.end - line.begin);
    }
  }
  core::write_file_atomic(path, out);
}

void copy_material_libraries(const MeshDocument& document, const std::string& path) {
  const fs::path from_dir = fs::path(document.path()).parent_path();
  const fs::path to_dir = fs::path(path).parent_path();
  std::error_code ec;
  if (fs::equivalent(from_dir.empty() ? "." : from_dir, to_dir.empty() ? "." : to_dir, ec)) return;
  // the .mtl files and their textures (a missing one is the user's; the OBJ still reads)
  for (const auto& file : document.companion_files().files) {
    const fs::path dst = to_dir / file.path;
    fs::create_directories(dst.parent_path(), ec);
    core::write_file_atomic(dst.string(), file.bytes);
  }
}

// ---------------------------------------------------------------------------------------------------
// PLY (ply_document.hpp: our parser keeps every element and property)

void read_ply(MeshDocument::Impl& doc) {
  auto ply =
      std::make_shared<detail::PlyDocument>(detail::parse_ply(core::read_file(doc.path), doc.path));
  const std::size_t nv = ply->xyz.size() / 3;
  doc.tri.vertices.resize(static_cast<long>(nv), 3);
  std::copy(ply->xyz.begin(), ply->xyz.end(), doc.tri.vertices.data());
  std::vector<std::array<int, 3>> faces;
  std::vector<std::size_t> line_of;
  MeshGroup group;
  for (std::size_t p = 0; p < ply->polygons.size(); ++p) {
    const auto& poly = ply->polygons[p];
    for (std::size_t k = 1; k + 1 < poly.size(); ++k) {
      if (is_degenerate(doc.tri.vertices, poly[0], poly[k], poly[k + 1])) {
        ++doc.dropped;
        continue;
      }
      group.faces.push_back(static_cast<int>(faces.size()));
      faces.push_back({poly[0], poly[k], poly[k + 1]});
      doc.polygon_of_triangle.push_back(static_cast<int>(p));
      line_of.push_back(ply->polygon_line[p]);
    }
  }
  SourceLocation where;
  where.file = doc.path;
  if (faces.empty())
    throw FormatError(where, ply->polygons.empty() ? "no faces" : "no non-degenerate triangle");
  doc.tri.faces.resize(static_cast<long>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    for (int k = 0; k < 3; ++k)
      doc.tri.faces(static_cast<long>(f), k) = faces[f][static_cast<std::size_t>(k)];
  }
  const int bad = overshared_edge(doc.tri.faces, group.faces);
  if (bad >= 0) {
    where.line = line_of[static_cast<std::size_t>(bad)];
    throw FormatError(
        where, "face " + std::to_string(doc.polygon_of_triangle[static_cast<std::size_t>(bad)]) +
                   ": an edge shared by more than two triangles (non-manifold)");
  }
  doc.groups.push_back(std::move(group));
  doc.colors = ply->colors;
  doc.ply = std::move(ply);
}

void write_ply_document(const MeshDocument::Impl& doc, const std::string& path,
                        const Vertices& positions, bool recompute_normals) {
  const Vertices& old = doc.tri.vertices;
  std::vector<char> dirty(static_cast<std::size_t>(old.rows()), 0);
  Vertices normals;
  if (recompute_normals && doc.ply->has_normals) {
    normals = vertex_normals(positions, doc.tri.faces);
    const Faces& F = doc.tri.faces;
    for (long f = 0; f < F.rows(); ++f) {
      bool moved = false;
      for (int k = 0; k < 3; ++k)
        moved = moved || !same_bits(old.data() + 3 * F(f, k), positions.data() + 3 * F(f, k));
      if (!moved) continue;
      for (int k = 0; k < 3; ++k) dirty[static_cast<std::size_t>(F(f, k))] = 1;
    }
  }
  core::write_file_atomic(path, detail::write_ply(*doc.ply, positions, normals, dirty));
}

// ---------------------------------------------------------------------------------------------------
// glTF

struct GltfReader {
  explicit GltfReader(MeshDocument::Impl& d) : doc(d) {}
  MeshDocument::Impl& doc;
  [[noreturn]] void fail(const std::string& pointer, const std::string& message) const {
    SourceLocation where;
    where.file = doc.path;
    where.json_pointer = pointer;
    throw FormatError(where, message);
  }

  static std::size_t component_size(int type) {
    switch (type) {
      case TINYGLTF_COMPONENT_TYPE_BYTE:
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
      case TINYGLTF_COMPONENT_TYPE_SHORT:
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
      case TINYGLTF_COMPONENT_TYPE_INT:
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
      default: return 0;
    }
  }
  static int components(int type) {
    switch (type) {
      case TINYGLTF_TYPE_SCALAR: return 1;
      case TINYGLTF_TYPE_VEC2: return 2;
      case TINYGLTF_TYPE_VEC3: return 3;
      case TINYGLTF_TYPE_VEC4: return 4;
      default: return 0;
    }
  }

  std::string accessor_pointer(int accessor) const {
    return "/accessors/" + std::to_string(accessor);
  }

  const tinygltf::Accessor& accessor_at(int accessor) const {
    if (accessor < 0 || static_cast<std::size_t>(accessor) >= doc.model.accessors.size())
      fail(accessor_pointer(accessor), "no such accessor");
    return doc.model.accessors[static_cast<std::size_t>(accessor)];
  }

  // The bytes of buffer view `index` (bounds checked against its buffer); `what` names the
  // referrer.
  const tinygltf::BufferView& buffer_view(int index, const std::string& what) const {
    if (index < 0 || static_cast<std::size_t>(index) >= doc.model.bufferViews.size())
      fail(what, "buffer view " + std::to_string(index) + " missing or out of range");
    const auto& bv = doc.model.bufferViews[static_cast<std::size_t>(index)];
    const std::string bp = "/bufferViews/" + std::to_string(index);
    if (bv.buffer < 0 || static_cast<std::size_t>(bv.buffer) >= doc.model.buffers.size())
      fail(bp + "/buffer", "out of range");
    const auto& buffer = doc.model.buffers[static_cast<std::size_t>(bv.buffer)];
    if (bv.byteOffset > buffer.data.size() || bv.byteLength > buffer.data.size() - bv.byteOffset)
      fail(bp, "exceeds its buffer");
    return bv;
  }

  // Where element i of a dense accessor lives; checks every bound before anything is read or
  // allocated. A sparse accessor, or one without a buffer view (zeros), has no such place: refused
  // here (read them with elements(); the writer makes them dense first, dense_copy).
  struct View {
    const unsigned char* base = nullptr;
    unsigned char* mutable_base = nullptr;
    std::size_t stride = 0, count = 0, element = 0;
    int component_type = 0, components = 0;
    bool normalized = false;
  };
  View view(int accessor) const {
    const std::string p = accessor_pointer(accessor);
    const auto& a = accessor_at(accessor);
    if (a.sparse.isSparse) fail(p + "/sparse", "a sparse accessor has no dense storage");
    return base_view(accessor);
  }
  // The accessor's base storage (its buffer view), sparse or not.
  View base_view(int accessor) const {
    const std::string p = accessor_pointer(accessor);
    const auto& a = accessor_at(accessor);
    View v;
    v.component_type = a.componentType;
    v.components = components(a.type);
    const std::size_t cs = component_size(a.componentType);
    if (cs == 0 || v.components == 0) fail(p, "unsupported component type or type");
    v.element = cs * static_cast<std::size_t>(v.components);
    v.count = a.count;
    v.normalized = a.normalized;
    if (a.count > kMaxElements) fail(p + "/count", "count " + std::to_string(a.count) + " too large");
    if (a.bufferView == -1) return v;  // no buffer view: zeros (glTF 2.0 §3.6.2.3), base == nullptr
    const auto& bv = buffer_view(a.bufferView, p + "/bufferView");
    auto& buffer =
        const_cast<tinygltf::Buffer&>(doc.model.buffers[static_cast<std::size_t>(bv.buffer)]);
    v.stride = bv.byteStride ? bv.byteStride : v.element;
    if (v.stride < v.element)
      fail("/bufferViews/" + std::to_string(a.bufferView) + "/byteStride",
           "smaller than the element");
    if (a.count > 0) {
      const std::size_t need = a.byteOffset + v.stride * (a.count - 1) + v.element;
      if (a.byteOffset > bv.byteLength || need > bv.byteLength) fail(p + "/count", "count " + std::to_string(a.count) + " exceeds its buffer view");
    }
    v.mutable_base = buffer.data.data() + bv.byteOffset + a.byteOffset;
    v.base = v.mutable_base;
    return v;
  }

  static double component(const View& v, std::size_t i, int k) {
    return component_at(
        v.base + i * v.stride +
            static_cast<std::size_t>(k) * (v.element / static_cast<std::size_t>(v.components)),
        v.component_type, v.normalized);
  }
  // One component; normalised integers mapped as glTF 2.0 §3.11 ("Animations": c / (2^n − 1),
  // signed max(c / (2^(n−1) − 1), −1)), the same mapping the spec gives for vertex attributes.
  static double component_at(const unsigned char* p, int type, bool normalized) {
    switch (type) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: {
        float f;
        std::memcpy(&f, p, 4);
        return f;
      }
      case TINYGLTF_COMPONENT_TYPE_BYTE: {
        const auto c = static_cast<std::int8_t>(*p);
        return normalized ? std::max(c / 127.0, -1.0) : c;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return normalized ? *p / 255.0 : *p;
      case TINYGLTF_COMPONENT_TYPE_SHORT: {
        std::int16_t s;
        std::memcpy(&s, p, 2);
        return normalized ? std::max(s / 32767.0, -1.0) : s;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        std::uint16_t s;
        std::memcpy(&s, p, 2);
        return normalized ? s / 65535.0 : s;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        std::uint32_t s;
        std::memcpy(&s, p, 4);
        return s;
      }
      default: return std::numeric_limits<double>::quiet_NaN();
    }
  }

  // An accessor's elements as numbers (count × components, row-major), dense or sparse: glTF 2.0
  // §3.6.2.3 "Sparse accessors": the base buffer view (zeros without one), then sparse.count
  // elements replaced, at indices (UNSIGNED_BYTE/SHORT/INT, strictly increasing, < count) read from
  // sparse.indices, by the tightly packed values of sparse.values. Every bound is checked before
  // reading; errors name the accessor's JSON pointer.
  struct Elements {
    std::vector<double> data;
    std::size_t count = 0;
    int components = 0, component_type = 0;
    bool normalized = false, sparse = false;
    double at(std::size_t i, int k) const {
      return data[i * static_cast<std::size_t>(components) + static_cast<std::size_t>(k)];
    }
  };
  Elements elements(int accessor) const {
    const std::string p = accessor_pointer(accessor);
    const auto& a = accessor_at(accessor);
    const View v = base_view(accessor);
    Elements e;
    e.count = v.count;
    e.components = v.components;
    e.component_type = v.component_type;
    e.normalized = v.normalized;
    e.sparse = a.sparse.isSparse;
    const auto nc = static_cast<std::size_t>(v.components);
    e.data.assign(v.count * nc, 0.0);
    if (v.base) {
      for (std::size_t i = 0; i < v.count; ++i) {
        for (int k = 0; k < v.components; ++k)
          e.data[i * nc + static_cast<std::size_t>(k)] = component(v, i, k);
      }
    }
    if (!a.sparse.isSparse) return e;
    const auto& s = a.sparse;
    const std::string sp = p + "/sparse";
    if (s.count < 1) fail(sp + "/count", "must be at least 1, got " + std::to_string(s.count));
    if (static_cast<std::size_t>(s.count) > a.count)
      fail(sp + "/count",
           std::to_string(s.count) + " exceeds the accessor's count " + std::to_string(a.count));
    const auto n = static_cast<std::size_t>(s.count);
    const int it = s.indices.componentType;
    if (it != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        it != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT && it != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
      fail(sp + "/indices/componentType",
           "must be UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT, got " + std::to_string(it));
    // the indices and values views: tightly packed (no byteStride), inside their views
    auto packed_span = [&](int view_index, int offset, std::size_t bytes,
                           const std::string& where) {
      const auto& bv = buffer_view(view_index, where + "/bufferView");
      if (bv.byteStride != 0)
        fail(where + "/bufferView", "a sparse accessor's buffer view must not have a byteStride");
      if (offset < 0 || static_cast<std::size_t>(offset) > bv.byteLength ||
          bytes > bv.byteLength - static_cast<std::size_t>(offset))
        fail(where, std::to_string(n) + " sparse elements exceed buffer view " +
                        std::to_string(view_index));
      return doc.model.buffers[static_cast<std::size_t>(bv.buffer)].data.data() + bv.byteOffset +
             static_cast<std::size_t>(offset);
    };
    const std::size_t isize = component_size(it);
    const unsigned char* idx =
        packed_span(s.indices.bufferView, s.indices.byteOffset, n * isize, sp + "/indices");
    const unsigned char* val =
        packed_span(s.values.bufferView, s.values.byteOffset, n * v.element, sp + "/values");
    const std::size_t cs = v.element / nc;
    double previous = -1.0;
    for (std::size_t j = 0; j < n; ++j) {
      const double i = component_at(idx + j * isize, it, false);
      if (!(i > previous))
        fail(sp + "/indices", "index " + std::to_string(static_cast<long long>(i)) + " at " +
                                  std::to_string(j) + " is not above the one before (" +
                                  std::to_string(static_cast<long long>(previous)) +
                                  "): sparse indices must strictly increase");
      if (i >= static_cast<double>(a.count))
        fail(sp + "/indices", "index " + std::to_string(static_cast<long long>(i)) + " at " +
                                  std::to_string(j) + " out of range (count " +
                                  std::to_string(a.count) + ")");
      previous = i;
      const auto row = static_cast<std::size_t>(i);
      for (std::size_t k = 0; k < nc; ++k)
        e.data[row * nc + k] =
            component_at(val + j * v.element + k * cs, v.component_type, v.normalized);
    }
    return e;
  }

  // A per-vertex attribute: `count` elements of one of `types` (component types), VEC<n> for n in
  // [min_components, max_components], every number finite.
  Elements attribute(int accessor, const std::string& name, std::size_t count,
                     std::initializer_list<int> types, int min_components,
                     int max_components) const {
    const std::string p = accessor_pointer(accessor);
    Elements e = elements(accessor);
    bool type_ok = false;
    for (int t : types) type_ok = type_ok || t == e.component_type;
    if (!type_ok || e.components < min_components || e.components > max_components)
      fail(p, name + ": unsupported component type " + std::to_string(e.component_type) +
                  " or type VEC" + std::to_string(e.components));
    if (e.component_type != TINYGLTF_COMPONENT_TYPE_FLOAT && !e.normalized)
      fail(p + "/normalized", name + ": integer components must be normalized");
    if (e.count != count)
      fail(p + "/count", name + ": " + std::to_string(e.count) + " elements for " +
                             std::to_string(count) + " vertices");
    for (std::size_t i = 0; i < e.data.size(); ++i) {
      if (!std::isfinite(e.data[i]))
        fail(p, name + ": element " + std::to_string(i / static_cast<std::size_t>(e.components)) +
                    " is not finite");
    }
    return e;
  }

  void read() {
    tinygltf::TinyGLTF loader;
    // images are kept as they are (uri, data URI or buffer view), never decoded: the raw bytes of a
    // data URI are kept to be written back as a data URI (save_gltf)
    loader.SetImageLoader([](tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                             const unsigned char* bytes, int size, void*) {
      if (image->uri.empty() && image->bufferView < 0 && bytes && size > 0) image->image.assign(bytes, bytes + size);
      image->as_is = true;
      return true;
    },
                          nullptr);
    std::string err, warn;
    if (!fs::is_regular_file(doc.path)) throw IoError("cannot read '" + doc.path + "'");
    const bool ok = doc.format == MeshFormat::Glb ? loader.LoadBinaryFromFile(&doc.model, &err, &warn, doc.path)
                                                  : loader.LoadASCIIFromFile(&doc.model, &err, &warn, doc.path);
    if (!ok) fail("", "not a valid glTF 2.0 file: " + (err.empty() ? warn : err));
    if (doc.model.meshes.empty()) fail("/meshes", "no mesh");
    const auto& mesh = doc.model.meshes[0];
    std::map<int, int> offset_of;  // position accessor -> vertex offset (primitives may share one)
    std::vector<double> xyz;
    std::vector<Eigen::Vector3f> colors;
    bool all_colored = true;
    std::vector<std::array<int, 3>> faces;
    int polygon = 0;
    for (std::size_t k = 0; k < mesh.primitives.size(); ++k) {
      const auto& prim = mesh.primitives[k];
      const std::string p = "/meshes/0/primitives/" + std::to_string(k);
      MeshDocument::Impl::Primitive info;
      info.index = static_cast<int>(k);
      auto pos = prim.attributes.find("POSITION");
      if (pos == prim.attributes.end()) fail(p + "/attributes", "no POSITION");
      info.position = pos->second;
      const Elements pv = elements(info.position);
      if (pv.component_type != TINYGLTF_COMPONENT_TYPE_FLOAT || pv.components != 3) fail("/accessors/" + std::to_string(info.position), "POSITION must be float VEC3");
      auto nrm = prim.attributes.find("NORMAL");
      if (nrm != prim.attributes.end()) {
        attribute(nrm->second, "NORMAL", pv.count, {TINYGLTF_COMPONENT_TYPE_FLOAT}, 3, 3);
        info.normal = nrm->second;
      }
      for (const auto& [name, id] : prim.attributes) {  // UVs: checked, kept as they are
        if (name.rfind("TEXCOORD_", 0) == 0)
          attribute(id, name, pv.count,
                    {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                     TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                    2, 2);
      }
      if (prim.targets.size() != mesh.primitives[0].targets.size())
        fail(p + "/targets", std::to_string(prim.targets.size()) +
                                 " morph targets, primitive 0 has " +
                                 std::to_string(mesh.primitives[0].targets.size()) +
                                 " (every primitive of a mesh has the same targets)");
      info.vertex_count = static_cast<int>(pv.count);
      info.triangles = prim.mode == TINYGLTF_MODE_TRIANGLES || prim.mode == -1;
      auto known = offset_of.find(info.position);
      if (known != offset_of.end()) {
        info.vertex_offset = known->second;
      } else {
        info.vertex_offset = static_cast<int>(xyz.size() / 3);
        if (xyz.size() / 3 + pv.count > kMaxElements) fail(p, "too many vertices");
        offset_of[info.position] = info.vertex_offset;
        for (std::size_t i = 0; i < pv.count; ++i) {
          for (int c = 0; c < 3; ++c) {
            const double x = pv.at(i, c);
            if (!std::isfinite(x)) fail("/accessors/" + std::to_string(info.position), "vertex " + std::to_string(i) + " is not finite");
            xyz.push_back(x);
          }
        }
        auto col = prim.attributes.find("COLOR_0");
        if (col != prim.attributes.end()) {
          const Elements cv =
              attribute(col->second, "COLOR_0", pv.count,
                        {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                         TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                        3, 4);
          for (std::size_t i = 0; i < cv.count; ++i) {
            colors.emplace_back(static_cast<float>(cv.at(i, 0)), static_cast<float>(cv.at(i, 1)),
                                static_cast<float>(cv.at(i, 2)));
          }
        } else {
          all_colored = false;
          colors.resize(xyz.size() / 3, Eigen::Vector3f::Ones());
        }
        // morph targets (glTF 2.0 §3.7.2.2): POSITION / NORMAL deltas, dense or sparse, checked and
        // read; other target attributes (TANGENT, ...) are kept in the file, not read
        for (std::size_t t = 0; t < prim.targets.size(); ++t) {
          for (const auto& [name, id] : prim.targets[t]) {
            if (name != "POSITION" && name != "NORMAL") continue;
            Elements d = attribute(id, "morph target " + std::to_string(t) + " " + name, pv.count,
                                   {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
                                    TINYGLTF_COMPONENT_TYPE_SHORT},
                                   3, 3);
            pending_targets_.push_back({t, name == "NORMAL", info.vertex_offset, std::move(d)});
          }
        }
      }
      if (prim.attributes.count("TEXCOORD_0")) doc.has_uvs = true;
      doc.primitives.push_back(info);
      if (!info.triangles) continue;  // lines, points, strips: kept in the file, not in triangles()
      MeshGroup group;
      group.object = mesh.name;
      group.group = "primitive_" + std::to_string(k);
      if (prim.material >= 0 && static_cast<std::size_t>(prim.material) < doc.model.materials.size()) {
        group.material = doc.model.materials[static_cast<std::size_t>(prim.material)].name;
      }
      std::vector<long> ids;
      if (prim.indices >= 0) {
        const Elements iv = elements(prim.indices);
        if (iv.components != 1 || (iv.component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                                   iv.component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
                                   iv.component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)) {
          fail("/accessors/" + std::to_string(prim.indices), "indices must be unsigned scalars");
        }
        ids.reserve(iv.count);
        for (std::size_t i = 0; i < iv.count; ++i) {
          const auto id = static_cast<long>(iv.at(i, 0));
          if (id >= static_cast<long>(pv.count)) fail("/accessors/" + std::to_string(prim.indices), "index " + std::to_string(id) + " at " + std::to_string(i) + " out of range (" + std::to_string(pv.count) + " vertices)");
          ids.push_back(id);
        }
      } else {
        for (std::size_t i = 0; i < pv.count; ++i) ids.push_back(static_cast<long>(i));
      }
      if (ids.size() % 3 != 0) fail(p + "/indices", "triangle list length not a multiple of 3");
      for (std::size_t i = 0; i + 2 < ids.size(); i += 3, ++polygon) {
        const int a = info.vertex_offset + static_cast<int>(ids[i]);
        const int b = info.vertex_offset + static_cast<int>(ids[i + 1]);
        const int c = info.vertex_offset + static_cast<int>(ids[i + 2]);
        pending_.push_back({a, b, c, polygon});
      }
      pending_groups_.push_back({group, pending_.size()});
    }
    const std::size_t nv = xyz.size() / 3;
    doc.tri.vertices.resize(static_cast<long>(nv), 3);
    std::copy(xyz.begin(), xyz.end(), doc.tri.vertices.data());
    if (all_colored && nv > 0) doc.colors = std::move(colors);
    const std::size_t n_targets = mesh.primitives.empty() ? 0 : mesh.primitives[0].targets.size();
    std::vector<std::string> names;
    if (mesh.extras.IsObject() && mesh.extras.Has("targetNames") &&
        mesh.extras.Get("targetNames").IsArray()) {
      const auto& tn = mesh.extras.Get("targetNames");
      for (std::size_t t = 0; t < tn.ArrayLen(); ++t)
        names.push_back(tn.Get(static_cast<int>(t)).IsString()
                            ? tn.Get(static_cast<int>(t)).Get<std::string>()
                            : std::string());
    }
    doc.targets.resize(n_targets);
    for (std::size_t t = 0; t < n_targets; ++t) {
      doc.targets[t].name =
          t < names.size() && !names[t].empty() ? names[t] : "target_" + std::to_string(t);
      doc.targets[t].position_deltas = Vertices::Zero(static_cast<long>(nv), 3);
    }
    for (const auto& pt : pending_targets_) {
      auto& target = doc.targets[pt.target];
      Vertices& m = pt.normal ? target.normal_deltas : target.position_deltas;
      if (m.rows() == 0) m = Vertices::Zero(static_cast<long>(nv), 3);
      for (std::size_t i = 0; i < pt.deltas.count; ++i) {
        for (int k = 0; k < 3; ++k)
          m(pt.vertex_offset + static_cast<long>(i), k) = pt.deltas.at(i, k);
      }
    }
    std::size_t start = 0;
    for (auto& [group, end] : pending_groups_) {
      for (std::size_t i = start; i < end; ++i) {
        const auto& t = pending_[i];
        if (is_degenerate(doc.tri.vertices, t[0], t[1], t[2])) {
          ++doc.dropped;
          continue;
        }
        group.faces.push_back(static_cast<int>(faces.size()));
        faces.push_back({t[0], t[1], t[2]});
        doc.polygon_of_triangle.push_back(t[3]);
      }
      start = end;
      if (!group.faces.empty()) doc.groups.push_back(group);
    }
    if (faces.empty()) fail("/meshes/0", "no non-degenerate triangle in the first mesh");
    doc.tri.faces.resize(static_cast<long>(faces.size()), 3);
    for (std::size_t f = 0; f < faces.size(); ++f) {
      for (int k = 0; k < 3; ++k) doc.tri.faces(static_cast<long>(f), k) = faces[f][static_cast<std::size_t>(k)];
    }
    for (const auto& g : doc.groups) {
      const int f = overshared_edge(doc.tri.faces, g.faces);
      if (f >= 0) {
        fail("/meshes/0/primitives/" + g.group.substr(10), "triangle " + std::to_string(doc.polygon_of_triangle[static_cast<std::size_t>(f)]) +
                                                            ": an edge shared by more than two triangles (non-manifold)");
      }
    }
  }

  struct PendingTarget {
    std::size_t target;
    bool normal;
    int vertex_offset;
    Elements deltas;
  };
  std::vector<PendingTarget> pending_targets_;
  std::vector<std::array<int, 4>> pending_;
  std::vector<std::pair<MeshGroup, std::size_t>> pending_groups_;
};

void write_floats(unsigned char* base, std::size_t stride, std::size_t i, const float xyz[3]) {
  std::memcpy(base + i * stride, xyz, 3 * sizeof(float));
}

// A model with POSITION (and NORMAL) of the first mesh replaced; min/max updated.
// New float VEC3 rows for an accessor. A dense accessor is written in place; a sparse one (or one
// without a buffer view) whose rows change becomes dense: a new buffer view with every row, the
// sparse object dropped (an unchanged one stays as it is). `rows(i, f)` fills row i, returns false
// to keep the accessor's own row. Returns false when nothing was written.
template <class Rows>
bool rewrite_vec3(tinygltf::Model& model, const GltfReader& reader, int accessor, std::size_t count,
                  Rows rows) {
  auto& a = model.accessors[static_cast<std::size_t>(accessor)];
  if (!a.sparse.isSparse && a.bufferView != -1) {
    const auto v = reader.view(accessor);
    float f[3];
    for (std::size_t i = 0; i < count; ++i) {
      if (rows(i, f)) write_floats(v.mutable_base, v.stride, i, f);
    }
    return true;
  }
  const GltfReader::Elements e = reader.elements(accessor);
  std::vector<float> packed(count * 3);
  bool changed = false;
  for (std::size_t i = 0; i < count; ++i) {
    float f[3];
    const bool set = rows(i, f);
    for (int k = 0; k < 3; ++k) {
      const auto old = static_cast<float>(e.at(i, k));
      packed[3 * i + static_cast<std::size_t>(k)] = set ? f[k] : old;
      changed = changed || (set && std::memcmp(&f[k], &old, 4) != 0);
    }
  }
  if (!changed) return false;
  if (model.buffers.empty()) model.buffers.emplace_back();
  a.bufferView =
      detail::add_view(model, packed.data(), packed.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER);
  a.byteOffset = 0;
  a.sparse.isSparse = false;
  a.sparse.count = 0;
  return true;
}

// A model with POSITION (and NORMAL) of the first mesh replaced; min/max updated.
tinygltf::Model updated_model(const MeshDocument::Impl& doc, const Vertices& positions, bool recompute_normals) {
  tinygltf::Model model = doc.model;
  MeshDocument::Impl copy_view;  // GltfReader needs an Impl; point it at the copy's buffers
  copy_view.path = doc.path;
  std::swap(copy_view.model, model);
  const GltfReader reader(copy_view);
  const Vertices normals = recompute_normals ? vertex_normals(positions, doc.tri.faces) : Vertices();
  std::map<int, bool> done;
  for (const auto& prim : doc.primitives) {
    if (done[prim.position]) continue;
    done[prim.position] = true;
    std::vector<double> lo(3, std::numeric_limits<double>::infinity()), hi(3, -std::numeric_limits<double>::infinity());
    const auto count = static_cast<std::size_t>(prim.vertex_count);
    const bool written =
        rewrite_vec3(copy_view.model, reader, prim.position, count, [&](std::size_t i, float* p) {
          for (int k = 0; k < 3; ++k) {
            p[k] = static_cast<float>(positions(prim.vertex_offset + static_cast<long>(i), k));
            lo[static_cast<std::size_t>(k)] =
                std::min(lo[static_cast<std::size_t>(k)], static_cast<double>(p[k]));
            hi[static_cast<std::size_t>(k)] =
                std::max(hi[static_cast<std::size_t>(k)], static_cast<double>(p[k]));
          }
          return true;
        });
    auto& a = copy_view.model.accessors[static_cast<std::size_t>(prim.position)];
    if (written && prim.vertex_count > 0) a.minValues = lo, a.maxValues = hi;
    if (recompute_normals && prim.normal >= 0) {
      rewrite_vec3(copy_view.model, reader, prim.normal, count, [&](std::size_t i, float* f) {
        const Eigen::Vector3d n =
            normals.row(prim.vertex_offset + static_cast<long>(i)).transpose();
        if (!(n.squaredNorm() > 0.0)) return false;  // a vertex of no triangle: keep its normal
        for (int k = 0; k < 3; ++k) f[k] = static_cast<float>(n[k]);
        return true;
      });
    }
  }
  return std::move(copy_view.model);
}

}  // namespace

namespace detail {
// The image files a copy of a glTF document needs (MeshDocument::companion_files): every image with
// a file uri (not a data URI, not a buffer view) at the same path relative to the copy, when that
// path stays inside the document's directory; one leaving it (absolute, `..`) or missing is a
// warning and not copied (the copy names it as the input did; nothing lands outside the output).
Companions gltf_image_companions(const MeshDocument::Impl& doc) {
  Companions out;
  const fs::path from_dir = fs::path(doc.path).parent_path();
  std::set<std::string> taken;
  for (const auto& image : doc.model.images) {
    if (image.uri.empty() || image.uri.rfind("data:", 0) == 0) continue;
    const fs::path rel(image.uri);
    const fs::path n = rel.lexically_normal();
    if (rel.is_absolute() || rel.has_root_name() || rel.has_root_directory() || n.empty() ||
        *n.begin() == ".." || !n.has_filename()) {
      out.warnings.push_back(
          "image '" + image.uri +
          "' lies outside the mesh's directory: not copied (the copy names it as the input did)");
      continue;
    }
    const fs::path src = from_dir / rel;
    if (!fs::is_regular_file(src)) {
      out.warnings.push_back("image '" + image.uri + "' not found: not copied");
      continue;
    }
    if (!taken.insert(n.generic_string()).second) continue;  // named by two images
    out.files.push_back({n.generic_string(), core::read_file(src.string())});
  }
  return out;
}
}  // namespace detail

namespace {

std::string base64(const std::vector<unsigned char>& bytes) {
  static const char* const kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t b0 = bytes[i], b1 = i + 1 < bytes.size() ? bytes[i + 1] : 0, b2 = i + 2 < bytes.size() ? bytes[i + 2] : 0;
    const std::uint32_t w = (b0 << 16) | (b1 << 8) | b2;
    out += kAlphabet[(w >> 18) & 63];
    out += kAlphabet[(w >> 12) & 63];
    out += i + 1 < bytes.size() ? kAlphabet[(w >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kAlphabet[w & 63] : '=';
  }
  return out;
}

void save_gltf(const MeshDocument::Impl& doc, tinygltf::Model& model, const std::string& path,
               bool copy_images = true) {
  MeshFormat out = mesh_format_from_path(path);
  if (out != MeshFormat::Gltf && out != MeshFormat::Glb) throw InvalidInput("'" + path + "': a glTF document is written as .gltf or .glb");
  const bool binary = out == MeshFormat::Glb;
  // images with a file uri stay files: copied beside the output (data URIs and buffer views travel
  // along), only those inside the document's directory (detail::gltf_image_companions)
  const fs::path from_dir = fs::path(doc.path).parent_path(), to_dir = fs::path(path).parent_path();
  std::error_code ec;
  const bool same_dir = fs::equivalent(from_dir.empty() ? "." : from_dir, to_dir.empty() ? "." : to_dir, ec);
  if (copy_images && !same_dir) {
    for (const auto& file : detail::gltf_image_companions(doc).files) {
      fs::create_directories((to_dir / file.path).parent_path(), ec);
      core::write_file_atomic((to_dir / file.path).string(), file.bytes);
    }
  }
  // buffers always embedded (data URI in .gltf, the BIN chunk in .glb): the output stands alone
  for (auto& b : model.buffers) b.uri.clear();
  // a .glb carries embedded images in its BIN chunk (a data URI inside a GLB is discouraged: the
  // glTF-Validator's DATA_URI_GLB warning); PNG and JPEG recognised by their signature
  if (binary) {
    if (model.buffers.empty()) model.buffers.emplace_back();
    for (auto& image : model.images) {
      if (!image.uri.empty() || image.bufferView >= 0 || image.image.size() < 4) continue;
      const auto& b = image.image;
      std::string mime = image.mimeType;
      if (mime.empty() && b[0] == 0x89 && b[1] == 'P' && b[2] == 'N' && b[3] == 'G')
        mime = "image/png";
      if (mime.empty() && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF) mime = "image/jpeg";
      if (mime.empty()) continue;  // unknown kind: stays a data URI
      image.bufferView = detail::add_view(model, b.data(), b.size(), 0);
      image.mimeType = mime;
      image.image.clear();
    }
  }
  tinygltf::TinyGLTF writer;
  // a data-URI image goes back as the same data URI; false keeps an image's original uri
  writer.SetImageWriter([](const std::string*, const std::string*, const tinygltf::Image* image, bool, std::string* out_uri,
                           void*) {
    if (!image->uri.empty() || image->image.empty()) return false;
    *out_uri = "data:" + (image->mimeType.empty() ? std::string("application/octet-stream") : image->mimeType) + ";base64," +
               base64(image->image);
    return true;
  },
                        nullptr);
  const std::string tmp = path + ".part" + fs::path(path).extension().string();
  if (!writer.WriteGltfSceneToFile(&model, tmp, false, true, !binary, binary)) {
    fs::remove(tmp, ec);
    throw IoError("cannot write '" + path + "'");
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw IoError("cannot write '" + path + "': " + ec.message());
  }
}

void check_positions(const MeshDocument::Impl& doc, const Vertices& positions, const char* who) {
  if (positions.rows() != doc.tri.vertices.rows()) {
    throw InvalidInput(std::string(who) + ": " + std::to_string(positions.rows()) + " positions for a document of " +
                       std::to_string(doc.tri.vertices.rows()) + " vertices");
  }
  if (!positions.allFinite()) throw InvalidInput(std::string(who) + ": non-finite position");
}

}  // namespace

void MeshDocument::write(const std::string& path, const Vertices& positions, bool recompute_normals,
                         bool copy_materials) const {
  const Impl& doc = *impl_;
  check_positions(doc, positions, "MeshDocument::write");
  switch (doc.format) {
    case MeshFormat::Obj:
      if (mesh_format_from_path(path) != MeshFormat::Obj) throw InvalidInput("'" + path + "': an OBJ document is written as .obj");
      write_obj(doc, path, positions, recompute_normals);
      if (copy_materials) copy_material_libraries(*this, path);
      return;
    case MeshFormat::Ply:
      if (mesh_format_from_path(path) == MeshFormat::Ply) {
        write_ply_document(doc, path, positions, recompute_normals);
        return;
      }
      write_mesh(path, Mesh{positions, doc.tri.faces});
      return;
    case MeshFormat::Off:
      write_mesh(path, Mesh{positions, doc.tri.faces});
      return;
    case MeshFormat::Gltf:
    case MeshFormat::Glb: {
      tinygltf::Model model = updated_model(doc, positions, recompute_normals);
      save_gltf(doc, model, path, copy_materials);
      return;
    }
  }
}

void DocumentTargetsOptions::validate() const {
  if (!(sparse_epsilon >= 0.0) || !std::isfinite(sparse_epsilon))
    throw InvalidInput("DocumentTargetsOptions: sparse_epsilon must be finite and >= 0");
  if (clash_suffix.empty()) throw InvalidInput("DocumentTargetsOptions: empty clash_suffix");
}

void MeshDocument::write_gltf_with_targets(const std::string& path, const std::vector<std::string>& names,
                                           const std::vector<Vertices>& deltas) const {
  if (names.size() != deltas.size())
    throw InvalidInput("write_gltf_with_targets: one name per target needed");
  std::vector<MorphTarget> targets;
  for (std::size_t t = 0; t < names.size(); ++t) targets.push_back({names[t], deltas[t], {}});
  DocumentTargetsOptions options;
  options.sparse = false;
  write_gltf_with_targets(path, targets, {}, options);
}

namespace {

std::vector<float> packed(const Vertices& v, int first, int count) {
  std::vector<float> out(static_cast<std::size_t>(count) * 3);
  for (int i = 0; i < count; ++i) {
    for (int k = 0; k < 3; ++k)
      out[static_cast<std::size_t>(3 * i + k)] = static_cast<float>(v(first + i, k));
  }
  return out;
}

void check_animation(const WeightAnimation& a, std::size_t targets) {
  const std::string who = "write_gltf_with_targets: animation '" + a.name + "'";
  if (a.times.empty() || a.weights.size() != a.times.size())
    throw InvalidInput(who + " needs one weight vector per key");
  for (std::size_t i = 0; i < a.times.size(); ++i) {
    if (!std::isfinite(a.times[i]) || a.times[i] < 0.0 || (i > 0 && !(a.times[i] > a.times[i - 1])))
      throw InvalidInput(who + ": times must be finite, >= 0 and increasing (key " +
                         std::to_string(i) + ")");
    if (a.weights[i].size() != targets)
      throw InvalidInput(who + ": key " + std::to_string(i) + " has " +
                         std::to_string(a.weights[i].size()) + " weights for " +
                         std::to_string(targets) + " added targets");
    for (double w : a.weights[i]) {
      if (!std::isfinite(w))
        throw InvalidInput(who + ": key " + std::to_string(i) + ": weight not finite");
    }
  }
}

}  // namespace

DocumentTargetsReport MeshDocument::write_gltf_with_targets(
    const std::string& path, const std::vector<MorphTarget>& targets,
    const std::vector<WeightAnimation>& animations, const DocumentTargetsOptions& options) const {
  const Impl& doc = *impl_;
  options.validate();
  if (doc.format != MeshFormat::Gltf && doc.format != MeshFormat::Glb) {
    throw InvalidInput("write_gltf_with_targets: '" + doc.path + "' is not a glTF document");
  }
  for (const auto& t : targets) {
    if (t.name.empty()) throw InvalidInput("write_gltf_with_targets: empty target name");
    check_positions(doc, t.position_deltas, "write_gltf_with_targets");
    if (t.normal_deltas.rows() != 0)
      check_positions(doc, t.normal_deltas, "write_gltf_with_targets (normals)");
  }
  for (const auto& a : animations) check_animation(a, targets.size());
  tinygltf::Model model = doc.model;
  auto& mesh = model.meshes[0];
  DocumentTargetsReport report;
  const std::size_t existing = mesh.primitives.empty() ? 0 : mesh.primitives[0].targets.size();
  report.existing_targets = existing;
  if (model.buffers.empty()) model.buffers.emplace_back();
  // extras.targetNames: existing names (or placeholders for unnamed targets), then the new ones
  tinygltf::Value::Object extras = mesh.extras.IsObject()
                                       ? mesh.extras.Get<tinygltf::Value::Object>()
                                       : tinygltf::Value::Object();
  tinygltf::Value::Array target_names;
  if (extras.count("targetNames") && extras["targetNames"].IsArray())
    target_names = extras["targetNames"].Get<tinygltf::Value::Array>();
  while (target_names.size() < existing)
    target_names.emplace_back(std::string("target_") + std::to_string(target_names.size()));
  target_names.resize(existing);
  std::set<std::string> used;
  for (const auto& n : target_names) {
    if (n.IsString()) used.insert(n.Get<std::string>());
  }
  for (const auto& t : targets) {
    std::string name = t.name;
    if (used.count(name)) {
      name = t.name + options.clash_suffix;
      for (int k = 2; used.count(name); ++k)
        name = t.name + options.clash_suffix + std::to_string(k);
    }
    used.insert(name);
    report.names.push_back(name);
    target_names.emplace_back(name);
  }
  // NORMAL deltas only where the primitive has NORMAL and its own targets carry NORMAL too
  for (const auto& prim : doc.primitives) {
    auto& p = mesh.primitives[static_cast<std::size_t>(prim.index)];
    bool normals = p.attributes.count("NORMAL") > 0;
    for (const auto& own : p.targets) normals = normals && own.count("NORMAL") > 0;
    for (const auto& t : targets) {
      std::map<std::string, int> attrs;
      bool sparse = false;
      attrs["POSITION"] =
          detail::add_delta(model, packed(t.position_deltas, prim.vertex_offset, prim.vertex_count),
                            options.sparse_epsilon, true, options.sparse, sparse);
      ++(sparse ? report.sparse_accessors : report.dense_accessors);
      if (normals && t.normal_deltas.rows() != 0) {
        attrs["NORMAL"] =
            detail::add_delta(model, packed(t.normal_deltas, prim.vertex_offset, prim.vertex_count),
                              options.sparse_epsilon, false, options.sparse, sparse);
        ++(sparse ? report.sparse_accessors : report.dense_accessors);
      }
      p.targets.push_back(attrs);
    }
  }
  std::vector<double> defaults = mesh.weights;
  defaults.resize(existing, 0.0);
  if (!mesh.weights.empty() || existing == 0) mesh.weights.resize(existing + targets.size(), 0.0);
  extras["targetNames"] = tinygltf::Value(target_names);
  mesh.extras = tinygltf::Value(extras);
  // animations: one weights channel per node holding the first mesh (a skinned node too)
  std::vector<int> nodes;
  for (std::size_t n = 0; n < model.nodes.size(); ++n) {
    if (model.nodes[n].mesh == 0) nodes.push_back(static_cast<int>(n));
  }
  if (!animations.empty() && nodes.empty())
    throw InvalidInput("write_gltf_with_targets: '" + doc.path +
                       "': no node holds the first mesh, nothing to animate");
  report.animated_nodes = animations.empty() ? 0 : nodes.size();
  for (const auto& a : animations) {
    tinygltf::Animation anim;
    anim.name = a.name;
    std::vector<float> t(a.times.begin(), a.times.end());
    const int tv = detail::add_view(model, t.data(), t.size() * 4, 0);
    const int ta = detail::add_accessor(model, tv, TINYGLTF_COMPONENT_TYPE_FLOAT, t.size(),
                                        TINYGLTF_TYPE_SCALAR, {static_cast<double>(t.front())},
                                        {static_cast<double>(t.back())});
    std::vector<float> w;
    w.reserve(a.times.size() * (existing + targets.size()));
    for (const auto& key : a.weights) {
      for (double x : defaults) w.push_back(static_cast<float>(x));
      for (double x : key) w.push_back(static_cast<float>(x));
    }
    const int wv = detail::add_view(model, w.data(), w.size() * 4, 0);
    tinygltf::AnimationSampler s;
    s.input = ta;
    s.output = detail::add_accessor(model, wv, TINYGLTF_COMPONENT_TYPE_FLOAT, w.size(),
                                    TINYGLTF_TYPE_SCALAR);
    s.interpolation = "LINEAR";
    anim.samplers.push_back(s);
    for (int node : nodes) {
      tinygltf::AnimationChannel c;
      c.sampler = 0;
      c.target_node = node;
      c.target_path = "weights";
      anim.channels.push_back(c);
    }
    model.animations.push_back(anim);
  }
  save_gltf(doc, model, path);
  return report;
}

MeshDocument read_mesh_document(const std::string& path) {
  MeshDocument document;
  MeshDocument::Impl& doc = *document.impl_;
  doc.path = path;
  try {
    doc.format = mesh_format_from_path(path);
  } catch (const InvalidInput& e) {
    SourceLocation where;
    where.file = path;
    throw FormatError(where, e.what());
  }
  switch (doc.format) {
    case MeshFormat::Obj: read_obj(doc); break;
    case MeshFormat::Ply:
      read_ply(doc);
      break;
    case MeshFormat::Off:
      doc.tri = read_mesh(path);
      doc.polygon_of_triangle.resize(doc.tri.face_count());
      for (std::size_t f = 0; f < doc.tri.face_count(); ++f) doc.polygon_of_triangle[f] = static_cast<int>(f);
      doc.groups.push_back({"", "", "", std::vector<int>(doc.polygon_of_triangle)});
      break;
    case MeshFormat::Gltf:
    case MeshFormat::Glb: {
      GltfReader reader(doc);
      reader.read();
      break;
    }
  }
  return document;
}

MeshDocument parse_obj_document(std::string text, const std::string& source) {
  MeshDocument document;
  MeshDocument::Impl& doc = *document.impl_;
  doc.path = source;
  doc.format = MeshFormat::Obj;
  doc.text = std::move(text);
  ObjParser parser(doc);
  parser.parse();
  return document;
}

}  // namespace emoface::facemesh
