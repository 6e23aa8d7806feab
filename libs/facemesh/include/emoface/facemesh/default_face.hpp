#pragma once
// The built-in default face (thesis §2.3), generated procedurally: a closed head denser at the eyes,
// nose, mouth and forehead, eye sockets with separate eyeballs, a mouth opening closed by B-spline lips
// (24×6 control grid) stitched to the face, the 11 regions, jaw, eyes, landmarks and the 19 muscle
// types of Table 2.1 placed after Appendix B. Deterministic: same code = same face, byte for byte.
// `facerender --write-default DIR` style regeneration: see docs/facemesh.md.
#include "emoface/facemesh/io.hpp"

namespace emoface::facemesh {

/// Builds the default face (≈4,000 vertices). mesh_file is "default_face.obj".
Face make_default_face();

}  // namespace emoface::facemesh
