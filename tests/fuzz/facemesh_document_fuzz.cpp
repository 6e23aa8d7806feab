// libFuzzer target for facemesh::read_mesh_document (our OBJ and PLY parsers; glTF/GLB through
// tinygltf, sparse accessors included). The first byte picks the format; the rest is the file. Any
// input either reads (ids in range, finite positions, and an OBJ or PLY written back with the same
// positions is byte for byte the input) or throws FormatError / IoError — never crashes, hangs or
// throws anything else.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/facemesh/mesh_document.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  static const char* exts[] = {".obj", ".gltf", ".glb", ".ply"};
  const std::string ext = exts[data[0] % 4];
  static const std::string dir = [] {
    const auto d = std::filesystem::temp_directory_path() / ("emoface_fuzz_document_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d.string();
  }();
  const std::string path = dir + "/input" + ext;
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  emoface::core::write_file_atomic(path, text);
  try {
    const auto doc = emoface::facemesh::read_mesh_document(path);
    const auto& m = doc.triangles();
    if (m.face_count() == 0 || !m.vertices.allFinite()) std::abort();
    if (m.faces.minCoeff() < 0 || static_cast<std::size_t>(m.faces.maxCoeff()) >= m.vertex_count()) std::abort();
    if (doc.polygon_of_triangle().size() != m.face_count()) std::abort();
    if (ext == ".obj" || ext == ".ply") {
      doc.write(dir + "/again" + ext, m.vertices, true, false);
      if (emoface::core::read_file(dir + "/again" + ext) != text)
        std::abort();  // unmoved: byte for byte
    }
  } catch (const emoface::FormatError&) {
  } catch (const emoface::IoError&) {
  }
  return 0;
}
