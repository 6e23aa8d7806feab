// libFuzzer target for retarget's handling of arbitrary target geometry: the fuzz input is read as an
// OBJ (with orientation repair), cleaned (clean_target) and aligned (align_to_frame, automatic) to a
// small source head. Anything either aligns to a finite similarity transform or throws FormatError /
// InvalidInput with a message — never crashes, hangs or returns NaN.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/facemesh/mesh_io.hpp"
#include "emoface/retarget/align.hpp"
#include "emoface/retarget/clean.hpp"

namespace {
// A small ellipsoid head (vertex 0 = top) with a nose pushed out of its front.
emoface::facemesh::Mesh source_head(int& nose) {
  const double pi = 3.14159265358979323846;
  const int rings = 10, segments = 16;
  emoface::facemesh::Mesh m;
  m.vertices.resize(2 + (rings - 1) * segments, 3);
  m.vertices.row(0) << 0, 0.11, 0;
  for (int i = 1; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const double th = pi * i / rings, ph = 2 * pi * j / segments;
      m.vertices.row(1 + (i - 1) * segments + j) << 0.08 * std::sin(th) * std::sin(ph), 0.11 * std::cos(th), 0.09 * std::sin(th) * std::cos(ph);
    }
  const int bottom = 1 + (rings - 1) * segments;
  m.vertices.row(bottom) << 0, -0.11, 0;
  nose = 1 + (rings / 2) * segments;  // ring below the equator, azimuth 0 (front)
  m.vertices(nose, 2) += 0.03;
  m.faces.resize(2 * segments * (rings - 1), 3);
  int f = 0;
  auto id = [&](int i, int j) { return 1 + (i - 1) * segments + (j % segments); };
  for (int j = 0; j < segments; ++j) m.faces.row(f++) << 0, id(1, j + 1), id(1, j);
  for (int i = 1; i + 1 < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      m.faces.row(f++) << id(i, j), id(i, j + 1), id(i + 1, j + 1);
      m.faces.row(f++) << id(i, j), id(i + 1, j + 1), id(i + 1, j);
    }
  for (int j = 0; j < segments; ++j) m.faces.row(f++) << bottom, id(rings - 1, j), id(rings - 1, j + 1);
  return m;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static int nose = 0;
  static const emoface::facemesh::Mesh source = source_head(nose);
  static const std::string path = [] {
    const auto d = std::filesystem::temp_directory_path() / ("emoface_fuzz_align_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return (d / "input.obj").string();
  }();
  emoface::core::write_file_atomic(path, std::string(reinterpret_cast<const char*>(data), size));
  try {
    const auto mesh = emoface::facemesh::read_mesh(path, emoface::facemesh::MeshReadOptions{true});
    if (mesh.face_count() > 5000) return 0;  // keep each run short
    const auto cleaned = emoface::retarget::clean_target(mesh);
    emoface::retarget::AlignOptions o;
    o.samples = 200;
    const auto a = emoface::retarget::align_to_frame(cleaned, source, source.vertices.row(0), source.vertices.row(nose), o);
    if (!std::isfinite(a.scale) || !a.rotation.allFinite() || !a.translation.allFinite() || !(a.report.confidence >= 0.0) ||
        !(a.report.confidence <= 1.0))
      std::abort();
  } catch (const emoface::FormatError&) {
  } catch (const emoface::IoError&) {
  } catch (const emoface::InvalidInput&) {
  }
  return 0;
}
