#pragma once
// The built-in default face (thesis §2.3), generated procedurally: a closed head denser at the eyes,
// nose, mouth and forehead, eye sockets with separate eyeballs, a mouth opening closed by B-spline lips
// (24×6 control grid) stitched to the face, the 11 regions, jaw, eyes, landmarks and the 19 muscle
// types of Table 2.1 placed after Appendix B. Deterministic: same code = same face, byte for byte.
// `facerender --write-default DIR` style regeneration: see docs/facemesh.md.
#include "emoface/facemesh/io.hpp"
#include "emoface/facemesh/render.hpp"

namespace emoface::facemesh {

/// Builds the default face (≈4,000 vertices). mesh_file is "default_face.obj".
Face make_default_face();

/// The default face's surface paint (render()): skin, brows and hairline drawn analytically (the same
/// curves as its Brow/Hair materials, edges anti-aliased over ≈ 0.6 mm) into a texture over the
/// frontal (x, y) plane of the neutral face, 0.25 mm per texel; texture coordinates for the skin
/// vertices of the front half and the lips' border row, NaN elsewhere. Built once per process.
const Paint& default_face_paint();

/// default_face_paint() if `rig` is the default face's (same vertex count and materials), else
/// nullptr: callers pass it to render() for any mesh deformed from the default face.
const Paint* paint_for(const Rig& rig);

}  // namespace emoface::facemesh
