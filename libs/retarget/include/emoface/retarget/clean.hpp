#pragma once
// Cleaning a scanned target before the fit (beyond the thesis, issue #6 "scans that are not clean"):
// stray pieces (scanner debris, a floating hair card, a second object) would become the "top of the
// head" or tilt the alignment, while pieces inside the head (eyeballs, teeth, the mouth bag) are
// harmless. facemesh::read_mesh(path, {repair_orientation = true}) repairs the winding beforehand.
#include <cstddef>

#include "emoface/facemesh/mesh.hpp"

namespace emoface::retarget {

struct CleanOptions {
  bool enabled = true;
  /// A component is kept when its bounding box lies inside the largest component's box grown by this
  /// fraction of that box's diagonal on every side; [0, 10].
  double margin = 0.05;
  void validate() const;
};

struct CleanReport {
  std::size_t components = 0;          ///< edge-connected components of the input
  std::size_t kept_components = 0;     ///< the largest (by area) + those inside its box
  std::size_t dropped_faces = 0;
  std::size_t dropped_vertices = 0;    ///< vertices no kept face uses (including ones no face used)
};

/// The target with only the kept components; unused vertices removed (ids renumbered in order). Throws
/// InvalidInput for a mesh without faces, ids out of range or non-finite coordinates.
facemesh::Mesh clean_target(const facemesh::Mesh& mesh, const CleanOptions& options = {}, CleanReport* report = nullptr);

}  // namespace emoface::retarget
