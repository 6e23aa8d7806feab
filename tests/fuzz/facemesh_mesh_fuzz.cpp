// libFuzzer target for the mesh reader retarget uses (facemesh::read_mesh through OpenMesh, OBJ/PLY/OFF,
// plain and with orientation repair). The first byte picks the format; the rest is the file. Any input
// either reads into a mesh that passes validate_mesh or throws FormatError / IoError — never crashes,
// hangs or throws anything else.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/facemesh/mesh.hpp"
#include "emoface/facemesh/mesh_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  static const char* exts[] = {".obj", ".ply", ".off"};
  const std::string ext = exts[data[0] % 3];
  static const std::string dir = [] {
    const auto d = std::filesystem::temp_directory_path() / ("emoface_fuzz_mesh_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d.string();
  }();
  const std::string path = dir + "/input" + ext;
  emoface::core::write_file_atomic(path, std::string(reinterpret_cast<const char*>(data) + 1, size - 1));
  for (bool repair : {false, true}) {
    try {
      emoface::facemesh::MeshReadReport report;
      const auto mesh = emoface::facemesh::read_mesh(path, emoface::facemesh::MeshReadOptions{repair}, &report);
      emoface::facemesh::validate_mesh(mesh, path);  // what the reader returns is always valid
      if (report.orientation.flipped_faces > mesh.face_count()) std::abort();
    } catch (const emoface::FormatError&) {
    } catch (const emoface::IoError&) {
    }
  }
  return 0;
}
