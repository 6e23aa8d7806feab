// A PLY file kept whole (ply_document.hpp).
#include "ply_document.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string_view>

#include "emoface/core/errors.hpp"

namespace emoface::facemesh::detail {
namespace {

constexpr std::size_t kMaxVertices = 50'000'000;  // as MeshDocument's OBJ/glTF limit
constexpr std::size_t kMaxPolygonCorners = 1000;

// PLY scalar types: 1 char, 2 uchar, 3 short, 4 ushort, 5 int, 6 uint, 7 float, 8 double.
int type_id(const std::string& t) {
  static const char* names[][2] = {{"char", "int8"},     {"uchar", "uint8"},   {"short", "int16"},
                                   {"ushort", "uint16"}, {"int", "int32"},     {"uint", "uint32"},
                                   {"float", "float32"}, {"double", "float64"}};
  for (int k = 0; k < 8; ++k) {
    if (t == names[k][0] || t == names[k][1]) return k + 1;
  }
  return 0;
}
std::size_t type_size(int t) { return t <= 2 ? 1 : t <= 4 ? 2 : t <= 7 ? 4 : 8; }
bool is_float(int t) { return t == 7 || t == 8; }
const char* type_name(int t) {
  static const char* names[] = {"?",   "char", "uchar", "short", "ushort",
                                "int", "uint", "float", "double"};
  return names[t >= 0 && t <= 8 ? t : 0];
}

struct Property {
  std::string name;
  int type = 0;        // item type
  int count_type = 0;  // list: the count's type, 0 = scalar
};
struct Element {
  std::string name;
  std::size_t count = 0;
  std::vector<Property> props;
};

struct Parser {
  Parser(PlyDocument& d, const std::string& p) : doc(d), path(p), t(d.text) {}
  PlyDocument& doc;
  const std::string& path;
  const std::string& t;
  std::size_t pos = 0, line = 1;

  [[noreturn]] void fail(std::size_t at_line, const std::string& message) const {
    SourceLocation where;
    where.file = path;
    where.line = at_line;
    throw FormatError(where, message);
  }
  // A data error: the line in ASCII, the byte offset in binary.
  [[noreturn]] void fail_here(const std::string& message) const {
    if (doc.encoding == PlyDocument::Encoding::Ascii) fail(line, message);
    fail(0, "at byte " + std::to_string(pos) + ": " + message);
  }

  std::vector<Element> header() {
    std::vector<Element> elements;
    bool format = false;
    for (std::size_t n = 1;; ++n) {
      if (pos >= t.size()) fail(n, "no end_header");
      std::size_t end = t.find('\n', pos);
      if (end == std::string::npos) fail(n, "no end_header");
      std::string_view l(t.data() + pos, end - pos);
      pos = end + 1;
      line = n + 1;
      while (!l.empty() && (l.back() == '\r' || l.back() == ' ' || l.back() == '\t'))
        l.remove_suffix(1);
      std::vector<std::string> tok;
      for (std::size_t i = 0; i < l.size();) {
        while (i < l.size() && (l[i] == ' ' || l[i] == '\t')) ++i;
        std::size_t j = i;
        while (j < l.size() && l[j] != ' ' && l[j] != '\t') ++j;
        if (j > i) tok.emplace_back(l.substr(i, j - i));
        i = j;
      }
      if (n == 1) {
        if (l != "ply") fail(1, "not a PLY file (the first line must be 'ply')");
        continue;
      }
      if (tok.empty()) fail(n, "empty header line");
      if (tok[0] == "comment" || tok[0] == "obj_info") continue;
      if (tok[0] == "end_header") break;
      if (tok[0] == "format") {
        if (tok.size() != 3 || tok[2] != "1.0") fail(n, "expected 'format <encoding> 1.0'");
        if (tok[1] == "ascii") {
          doc.encoding = PlyDocument::Encoding::Ascii;
        } else if (tok[1] == "binary_little_endian") {
          doc.encoding = PlyDocument::Encoding::BinaryLittle;
        } else if (tok[1] == "binary_big_endian") {
          doc.encoding = PlyDocument::Encoding::BinaryBig;
        } else {
          fail(n, "unknown PLY encoding '" + tok[1] + "'");
        }
        format = true;
      } else if (tok[0] == "element") {
        if (tok.size() != 3) fail(n, "expected 'element <name> <count>'");
        const std::string& c = tok[2];
        if (c.empty() || c.size() > 12 || c.find_first_not_of("0123456789") != std::string::npos)
          fail(n, "element " + tok[1] + ": bad count '" + c.substr(0, 20) + "'");
        elements.push_back({tok[1], static_cast<std::size_t>(std::stoull(c)), {}});
      } else if (tok[0] == "property") {
        if (elements.empty()) fail(n, "a property before any element");
        Property p;
        if (tok.size() == 5 && tok[1] == "list") {
          p.count_type = type_id(tok[2]);
          p.type = type_id(tok[3]);
          p.name = tok[4];
          if (p.count_type == 0 || is_float(p.count_type))
            fail(n, "list count type '" + tok[2] + "' is not an integer type");
        } else if (tok.size() == 3) {
          p.type = type_id(tok[1]);
          p.name = tok[2];
        } else {
          fail(n,
               "expected 'property <type> <name>' or 'property list <count type> <type> <name>'");
        }
        if (p.type == 0) fail(n, "unknown property type in '" + std::string(l) + "'");
        elements.back().props.push_back(p);
      } else {
        fail(n, "unknown header keyword '" + tok[0] + "'");
      }
    }
    if (!format) fail(2, "no format line");
    // every record takes at least a byte per number (binary: its size): refuse counts the rest of
    // the file cannot hold before allocating anything
    const std::size_t rest = t.size() - pos;
    for (const auto& e : elements) {
      std::size_t least = 0;
      for (const auto& p : e.props) {
        least += doc.encoding == PlyDocument::Encoding::Ascii
                     ? 2
                     : type_size(p.count_type ? p.count_type : p.type);
      }
      if (least == 0 && e.count > 0) fail(1, "element " + e.name + " has no properties");
      if (e.count > 0 && e.count > rest / least)
        fail(1, "element " + e.name + " declares " + std::to_string(e.count) +
                    " records, more than the " + std::to_string(rest) +
                    " bytes after the header can hold");
    }
    return elements;
  }

  // ASCII: the next token (its offset and length); fails at the end of the file.
  void skip_space() {
    while (pos < t.size() &&
           (t[pos] == ' ' || t[pos] == '\t' || t[pos] == '\r' || t[pos] == '\n')) {
      if (t[pos] == '\n') ++line;
      ++pos;
    }
  }
  PlySlot token(const char* what) {
    const std::size_t start_line = line;
    skip_space();
    if (pos >= t.size()) {
      line = start_line;  // the last line with content
      fail_here(std::string("file ends before ") + what + " (truncated)");
    }
    const std::size_t b = pos;
    while (pos < t.size() && !(t[pos] == ' ' || t[pos] == '\t' || t[pos] == '\r' || t[pos] == '\n'))
      ++pos;
    return {b, pos - b};
  }

  // One number of type `type`: its value and where it is.
  double number(int type, const std::string& what, PlySlot& slot) {
    if (doc.encoding == PlyDocument::Encoding::Ascii) {
      slot = token(what.c_str());
      const char* b = t.data() + slot.offset;
      const char* e = b + slot.length;
      if (is_float(type)) {
        double x = 0.0;
        if (*b == '+') ++b;
        const auto r = std::from_chars(b, e, x);
        if (r.ec == std::errc::result_out_of_range) fail_here(what + " out of range");
        if (r.ec != std::errc() || r.ptr != e)
          fail_here("expected a number for " + what + ", got '" +
                    std::string(t, slot.offset, std::min<std::size_t>(slot.length, 20)) + "'");
        return x;
      }
      long long i = 0;
      if (*b == '+') ++b;
      const auto r = std::from_chars(b, e, i);
      if (r.ec != std::errc() || r.ptr != e)
        fail_here("expected an integer for " + what + ", got '" +
                  std::string(t, slot.offset, std::min<std::size_t>(slot.length, 20)) + "'");
      const std::size_t bits = 8 * type_size(type);
      const bool is_signed = type == 1 || type == 3 || type == 5;
      const long long lo = is_signed ? -(1LL << (bits - 1)) : 0;
      const long long hi =
          is_signed ? (1LL << (bits - 1)) - 1 : static_cast<long long>((1ULL << bits) - 1);
      if (i < lo || i > hi)
        fail_here(what + " " + std::to_string(i) + " out of range for " + type_name(type));
      return static_cast<double>(i);
    }
    const std::size_t n = type_size(type);
    if (n > t.size() - pos) fail_here("file ends inside " + what + " (truncated)");
    slot = {pos, n};
    unsigned char b[8];
    std::memcpy(b, t.data() + pos, n);
    pos += n;
    if (doc.encoding == PlyDocument::Encoding::BinaryBig) std::reverse(b, b + n);
    switch (type) {
      case 1:
        return static_cast<std::int8_t>(b[0]);
      case 2:
        return b[0];
      case 3: {
        std::int16_t v;
        std::memcpy(&v, b, 2);
        return v;
      }
      case 4: {
        std::uint16_t v;
        std::memcpy(&v, b, 2);
        return v;
      }
      case 5: {
        std::int32_t v;
        std::memcpy(&v, b, 4);
        return v;
      }
      case 6: {
        std::uint32_t v;
        std::memcpy(&v, b, 4);
        return v;
      }
      case 7: {
        float v;
        std::memcpy(&v, b, 4);
        return v;
      }
      default: {
        double v;
        std::memcpy(&v, b, 8);
        return v;
      }
    }
  }

  void parse() {
    const std::vector<Element> elements = header();
    const Element* vertex = nullptr;
    const Element* face = nullptr;
    for (const auto& e : elements) {
      if (e.name == "vertex" && !vertex) vertex = &e;
      if (e.name == "face" && !face) face = &e;
    }
    if (!vertex) fail(1, "no vertex element");
    if (!face) fail(1, "no face element");
    if (vertex->count > kMaxVertices)
      fail(1, "too many vertices (" + std::to_string(vertex->count) + ")");
    // the vertex properties we read
    static const char* slot_names[6] = {"x", "y", "z", "nx", "ny", "nz"};
    std::array<int, 6> slot_prop;
    slot_prop.fill(-1);
    std::array<int, 4> color_prop{-1, -1, -1, -1};
    for (std::size_t k = 0; k < vertex->props.size(); ++k) {
      const Property& p = vertex->props[k];
      bool used = false;
      for (int s = 0; s < 6; ++s) {
        if (p.name == slot_names[s] && slot_prop[static_cast<std::size_t>(s)] < 0 &&
            !p.count_type) {
          slot_prop[static_cast<std::size_t>(s)] = static_cast<int>(k);
          used = true;
        }
      }
      static const char* color_names[4] = {"red", "green", "blue", "alpha"};
      for (int c = 0; c < 4; ++c) {
        if ((p.name == color_names[c] || p.name == std::string("diffuse_") + color_names[c]) &&
            color_prop[static_cast<std::size_t>(c)] < 0) {
          if (p.count_type || !(p.type == 2 || p.type == 4 || is_float(p.type)))
            fail(1, "vertex colour property " + p.name + ": type " + type_name(p.type) +
                        " not supported (uchar, ushort, float or double)");
          color_prop[static_cast<std::size_t>(c)] = static_cast<int>(k);
          used = true;
        }
      }
      if (!used) doc.kept_properties.push_back(p.name);
    }
    for (int s = 0; s < 3; ++s) {
      const int k = slot_prop[static_cast<std::size_t>(s)];
      if (k < 0) fail(1, std::string("the vertex element has no ") + slot_names[s] + " property");
      if (!is_float(vertex->props[static_cast<std::size_t>(k)].type))
        fail(1, std::string("vertex property ") + slot_names[s] + " is " +
                    type_name(vertex->props[static_cast<std::size_t>(k)].type) +
                    " (positions must be float or double)");
    }
    doc.has_normals = true;
    for (int s = 3; s < 6; ++s) {
      const int k = slot_prop[static_cast<std::size_t>(s)];
      doc.has_normals =
          doc.has_normals && k >= 0 && is_float(vertex->props[static_cast<std::size_t>(k)].type);
    }
    if (!doc.has_normals) {
      for (int s = 3; s < 6; ++s) {
        if (slot_prop[static_cast<std::size_t>(s)] >= 0)
          doc.kept_properties.push_back(slot_names[s]);
        slot_prop[static_cast<std::size_t>(s)] = -1;  // kept as they are, never rewritten
      }
    }
    const bool colored = color_prop[0] >= 0 && color_prop[1] >= 0 && color_prop[2] >= 0;
    if (!colored && (color_prop[0] >= 0 || color_prop[1] >= 0 || color_prop[2] >= 0))
      fail(1, "vertex colours need red, green and blue");
    for (int s = 0; s < 6; ++s) {
      const int k = slot_prop[static_cast<std::size_t>(s)];
      doc.slot_type[static_cast<std::size_t>(s)] =
          k >= 0 ? vertex->props[static_cast<std::size_t>(k)].type : 0;
    }
    int index_list = -1;
    for (std::size_t k = 0; k < face->props.size(); ++k) {
      const Property& p = face->props[k];
      if ((p.name == "vertex_indices" || p.name == "vertex_index") && index_list < 0) {
        if (!p.count_type) fail(1, "face property " + p.name + " must be a list");
        if (is_float(p.type))
          fail(1,
               "face property " + p.name + ": indices must be integers, not " + type_name(p.type));
        index_list = static_cast<int>(k);
      }
    }
    if (index_list < 0) fail(1, "the face element has no vertex_indices list");

    const std::size_t nv = vertex->count;
    doc.xyz.reserve(nv * 3);
    doc.slots.resize(nv);
    if (colored) doc.colors.reserve(nv);
    for (const auto& e : elements) {
      const bool is_vertex = &e == vertex, is_face = &e == face;
      for (std::size_t r = 0; r < e.count; ++r) {
        if (doc.encoding == PlyDocument::Encoding::Ascii) skip_space();
        const std::size_t record_line = line;
        Eigen::Vector4f color(1, 1, 1, 1);
        for (std::size_t k = 0; k < e.props.size(); ++k) {
          const Property& p = e.props[k];
          const std::string what = e.name + " " + std::to_string(r) + " " + p.name;
          PlySlot slot;
          if (!p.count_type) {
            const double x = number(p.type, what, slot);
            if (!is_vertex) continue;
            for (int s = 0; s < 6; ++s) {
              if (slot_prop[static_cast<std::size_t>(s)] != static_cast<int>(k)) continue;
              if (!std::isfinite(x)) fail_here(what + " is not finite");
              doc.slots[r][static_cast<std::size_t>(s)] = slot;
              if (s < 3) doc.xyz.push_back(x);
            }
            for (int c = 0; c < 4; ++c) {
              if (color_prop[static_cast<std::size_t>(c)] != static_cast<int>(k)) continue;
              const double v = p.type == 2 ? x / 255.0 : p.type == 4 ? x / 65535.0 : x;
              if (!(v >= 0.0 && v <= 1.0))
                fail_here(what + " = " + std::to_string(x) +
                          " out of range (float colours are 0 to 1)");
              color[c] = static_cast<float>(v);
            }
            continue;
          }
          const double count = number(p.count_type, what + " count", slot);
          if (count < 0) fail_here(what + ": negative list count");
          const auto n = static_cast<std::size_t>(count);
          const std::size_t least =
              doc.encoding == PlyDocument::Encoding::Ascii ? 2 : type_size(p.type);
          if (n > (t.size() - pos) / least + 1)
            fail_here(what + ": list of " + std::to_string(n) + " beyond the end of the file");
          const bool indices = is_face && static_cast<int>(k) == index_list;
          if (indices && (n < 3 || n > kMaxPolygonCorners))
            fail_here("face " + std::to_string(r) + " has " + std::to_string(n) +
                      " vertices (3 to " + std::to_string(kMaxPolygonCorners) + ")");
          std::vector<int> poly;
          for (std::size_t i = 0; i < n; ++i) {
            const double v = number(p.type, what + " item " + std::to_string(i), slot);
            if (!indices) continue;
            if (v < 0 || v >= static_cast<double>(nv))
              fail_here("face " + std::to_string(r) + ": vertex index " +
                        std::to_string(static_cast<long long>(v)) + " out of range (" +
                        std::to_string(nv) + " vertices)");
            poly.push_back(static_cast<int>(v));
          }
          if (indices) {
            doc.polygons.push_back(std::move(poly));
            doc.polygon_line.push_back(doc.encoding == PlyDocument::Encoding::Ascii ? record_line
                                                                                    : 0);
          }
        }
        if (is_vertex && colored) doc.colors.emplace_back(color[0], color[1], color[2]);
      }
    }
  }
};

void append_number(std::string& out, const PlyDocument& doc, int type, double x) {
  if (doc.encoding == PlyDocument::Encoding::Ascii) {
    char buf[40];
    std::snprintf(buf, sizeof buf, type == 7 ? "%.9g" : "%.17g",
                  type == 7 ? static_cast<double>(static_cast<float>(x)) : x);
    out += buf;
    return;
  }
  unsigned char b[8];
  std::size_t n = 8;
  if (type == 7) {
    const auto f = static_cast<float>(x);
    std::memcpy(b, &f, 4);
    n = 4;
  } else {
    std::memcpy(b, &x, 8);
  }
  if (doc.encoding == PlyDocument::Encoding::BinaryBig) std::reverse(b, b + n);
  out.append(reinterpret_cast<const char*>(b), n);
}

}  // namespace

PlyDocument parse_ply(std::string text, const std::string& path) {
  PlyDocument doc;
  doc.text = std::move(text);
  Parser parser(doc, path);
  parser.parse();
  return doc;
}

std::string write_ply(const PlyDocument& doc, const Vertices& positions, const Vertices& normals,
                      const std::vector<char>& dirty) {
  struct Patch {
    PlySlot slot;
    int type;
    double value;
  };
  std::vector<Patch> patches;
  const std::size_t nv = doc.slots.size();
  for (std::size_t v = 0; v < nv; ++v) {
    const auto row = static_cast<long>(v);
    bool moved = false;
    for (int k = 0; k < 3; ++k) {
      const double a = positions(row, k), b = doc.xyz[3 * v + static_cast<std::size_t>(k)];
      moved = moved || std::memcmp(&a, &b, sizeof a) != 0;
    }
    if (moved) {
      for (int k = 0; k < 3; ++k)
        patches.push_back({doc.slots[v][static_cast<std::size_t>(k)],
                           doc.slot_type[static_cast<std::size_t>(k)], positions(row, k)});
    }
    if (doc.has_normals && normals.rows() == positions.rows() && dirty[v] &&
        normals.row(row).squaredNorm() > 0.0) {
      for (int k = 0; k < 3; ++k)
        patches.push_back({doc.slots[v][static_cast<std::size_t>(3 + k)],
                           doc.slot_type[static_cast<std::size_t>(3 + k)], normals(row, k)});
    }
  }
  std::sort(patches.begin(), patches.end(),
            [](const Patch& a, const Patch& b) { return a.slot.offset < b.slot.offset; });
  std::string out;
  out.reserve(doc.text.size() + patches.size() * 8);
  std::size_t at = 0;
  for (const auto& p : patches) {
    out.append(doc.text, at, p.slot.offset - at);
    append_number(out, doc, p.type, p.value);
    at = p.slot.offset + p.slot.length;
  }
  out.append(doc.text, at, std::string::npos);
  return out;
}

}  // namespace emoface::facemesh::detail
