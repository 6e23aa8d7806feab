// The files that go with a copy of a document (mesh_document.hpp, MeshDocument::companion_files):
// an OBJ's material libraries and every texture they reference; a glTF's image files
// (detail::gltf_image_companions, mesh_document.cpp).
#include <algorithm>
#include <cctype>
#include <charconv>
#include <filesystem>
#include <map>
#include <set>
#include <string_view>

#include "document_companions.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/facemesh/mesh_document.hpp"

namespace emoface::facemesh {
namespace {

namespace fs = std::filesystem;

// A relative path that stays inside its directory once normalised ("a/../b.png" yes, "../b.png"
// no).
bool stays_inside(const fs::path& p) {
  if (p.empty() || p.is_absolute() || p.has_root_name() || p.has_root_directory()) return false;
  const fs::path n = p.lexically_normal();
  return !n.empty() && *n.begin() != ".." && n != ".";
}

bool is_number(std::string_view t) {
  double x = 0.0;
  const char* b = t.data();
  if (!t.empty() && *b == '+') ++b;
  const auto r = std::from_chars(b, t.data() + t.size(), x);
  return r.ec == std::errc() && r.ptr == t.data() + t.size();
}

// The texture statements of the MTL format (Wavefront "MTL material format", Alias|Wavefront
// Advanced Visualizer manual, Appendix B1: map_Ka, map_Kd, map_Ks, map_Ns, map_d, map_aat? (no
// file), decal, disp, bump, refl; the PBR extension's map_Pr, map_Pm, map_Ps, map_Ke, norm; and the
// common map_bump / map_Bump spelling).
bool is_texture_statement(const std::string& key) {
  std::string k = key;
  std::transform(k.begin(), k.end(), k.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (k == "map_aat") return false;  // "map_aat on": a switch, no file
  return k.rfind("map_", 0) == 0 || k == "bump" || k == "disp" || k == "decal" || k == "refl" ||
         k == "norm";
}

// Options before the file name and how many numbers/words they take (same appendix: -blendu on,
// -blendv on, -bm mult, -boost value, -cc on, -clamp on, -imfchan r|g|b|m|l|z, -mm base gain,
// -o u [v [w]], -s u [v [w]], -t u [v [w]], -texres value, -type sphere|cube_*).
int option_arguments(const std::string& flag, bool& up_to_three) {
  up_to_three = flag == "-o" || flag == "-s" || flag == "-t";
  if (up_to_three) return 1;
  if (flag == "-mm") return 2;
  if (flag == "-blendu" || flag == "-blendv" || flag == "-bm" || flag == "-boost" ||
      flag == "-cc" || flag == "-clamp" || flag == "-imfchan" || flag == "-texres" ||
      flag == "-type")
    return 1;
  return -1;
}

struct TextureRef {
  std::size_t name_begin = 0, name_end = 0;  // the file name's span in the line
  std::string name;
};

// The file name of a texture statement (`line` without its terminator): after the options, the rest
// of the line (names may contain spaces), trailing blanks dropped. Empty when there is none.
TextureRef texture_name(const std::string& line) {
  std::vector<std::pair<std::size_t, std::size_t>> tok;  // spans
  for (std::size_t i = 0; i < line.size();) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t s = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > s) tok.emplace_back(s, i);
  }
  auto word = [&](std::size_t k) {
    return line.substr(tok[k].first, tok[k].second - tok[k].first);
  };
  std::size_t k = 1;  // after the statement's keyword
  while (k < tok.size() && line[tok[k].first] == '-' && !is_number(word(k))) {
    bool up_to_three = false;
    const int n = option_arguments(word(k), up_to_three);
    if (n < 0) break;  // not an option we know: the name starts here
    ++k;
    if (up_to_three) {
      for (int m = 0; m < 3 && k + 1 < tok.size() && is_number(word(k)); ++m) ++k;
    } else {
      k += static_cast<std::size_t>(n);
    }
  }
  TextureRef ref;
  if (k >= tok.size()) return ref;
  ref.name_begin = tok[k].first;
  ref.name_end = tok.back().second;
  ref.name = line.substr(ref.name_begin, ref.name_end - ref.name_begin);
  return ref;
}

}  // namespace

Companions MeshDocument::companion_files() const {
  if (format() == MeshFormat::Gltf || format() == MeshFormat::Glb)
    return detail::gltf_image_companions(*impl_);
  Companions out;
  if (format() != MeshFormat::Obj) return out;
  const fs::path obj_dir = fs::path(path()).parent_path();
  std::set<std::string> taken;                // output paths used so far (normalised)
  std::map<std::string, std::string> copied;  // source (canonical) -> output path
  // a file to write; false (nothing added) when another file already has that output path
  auto add = [&](const fs::path& rel, std::string bytes) {
    const std::string key = rel.lexically_normal().generic_string();
    if (!taken.insert(key).second) return false;
    out.files.push_back({key, std::move(bytes)});
    return true;
  };
  for (const auto& lib : material_libraries()) {
    const fs::path rel(lib);
    if (!stays_inside(rel)) {
      out.warnings.push_back("material library '" + lib +
                             "' lies outside the mesh's directory: not copied (the copied OBJ "
                             "names it as the input did)");
      continue;
    }
    const fs::path src = obj_dir / rel;
    if (!fs::is_regular_file(src)) {
      out.warnings.push_back("material library '" + lib + "' not found: not copied");
      continue;
    }
    const std::string text = core::read_file(src.string());
    const std::string mtl_key = rel.lexically_normal().generic_string();
    if (!taken.insert(mtl_key).second) continue;  // named twice
    const fs::path mtl_dir_rel =
        rel.lexically_normal().parent_path();  // relative to the OBJ's directory
    const fs::path mtl_dir = src.parent_path();
    std::string rewritten;
    rewritten.reserve(text.size());
    std::size_t pos = 0, line_no = 0;
    while (pos < text.size()) {
      ++line_no;
      std::size_t nl = text.find('\n', pos);
      const std::size_t stop = nl == std::string::npos ? text.size() : nl;
      std::size_t content_end = stop;
      if (content_end > pos && text[content_end - 1] == '\r') --content_end;
      const std::string line = text.substr(pos, content_end - pos);
      const std::string terminator =
          text.substr(content_end, (nl == std::string::npos ? text.size() : nl + 1) - content_end);
      pos = nl == std::string::npos ? text.size() : nl + 1;
      std::size_t s = line.find_first_not_of(" \t");
      const std::size_t e = s == std::string::npos ? s : line.find_first_of(" \t", s);
      const std::string key =
          s == std::string::npos
              ? std::string()
              : line.substr(s, e == std::string::npos ? std::string::npos : e - s);
      const std::string where = "'" + lib + "' line " + std::to_string(line_no);
      if (key.empty() || key[0] == '#' || !is_texture_statement(key)) {
        rewritten += line + terminator;
        continue;
      }
      const TextureRef ref = texture_name(line);
      if (ref.name.empty()) {
        out.warnings.push_back("texture statement without a file name in " + where);
        rewritten += line + terminator;
        continue;
      }
      const fs::path name(ref.name);
      const fs::path tex_src = name.is_absolute() ? name : mtl_dir / name;
      if (!fs::is_regular_file(tex_src)) {
        out.warnings.push_back("texture '" + ref.name + "' (" + where + ") not found: not copied");
        rewritten += line + terminator;
        continue;
      }
      std::error_code ec;
      const std::string id = fs::weakly_canonical(tex_src, ec).string();
      if (stays_inside(name)) {  // keeps its place relative to the .mtl
        if (!copied.count(id)) {
          if (add(mtl_dir_rel / name, core::read_file(tex_src.string()))) {
            copied[id] = (mtl_dir_rel / name).lexically_normal().generic_string();
          } else {
            out.warnings.push_back("texture '" + ref.name + "' (" + where +
                                   ") has the output name of another copied file: not copied");
          }
        }
        rewritten += line + terminator;
        continue;
      }
      // absolute, or outside the mesh's directory: copied in beside the .mtl under its base name
      // (made unique), and the statement names the copy
      auto it = copied.find(id);
      std::string local;
      if (it != copied.end()) {
        local = fs::path(it->second)
                    .lexically_relative(mtl_dir_rel.empty() ? fs::path(".") : mtl_dir_rel)
                    .generic_string();
      } else {
        const std::string stem = name.stem().string(), ext = name.extension().string();
        local = name.filename().string();
        for (int k = 2; taken.count((mtl_dir_rel / local).lexically_normal().generic_string()); ++k)
          local = stem + "_" + std::to_string(k) + ext;
        copied[id] = (mtl_dir_rel / local).lexically_normal().generic_string();
        add(mtl_dir_rel / local, core::read_file(tex_src.string()));
      }
      out.warnings.push_back("texture '" + ref.name + "' (" + where +
                             ") lies outside the mesh's directory: copied as '" + local +
                             "' and the .mtl line rewritten");
      rewritten += line.substr(0, ref.name_begin) + local + line.substr(ref.name_end) + terminator;
    }
    out.files.push_back({mtl_key, rewritten});
  }
  return out;
}

}  // namespace emoface::facemesh
