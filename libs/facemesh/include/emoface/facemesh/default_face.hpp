#pragma once
// The built-in faces.
//  * make_generic_face(): the thesis' generic model (§2.3), generated procedurally: a closed head denser
//    at the eyes, nose, mouth and forehead, eye sockets with separate eyeballs, a mouth opening closed
//    by B-spline lips (24×6 control grid) stitched to the face, the 11 regions, jaw, eyes, landmarks and
//    the 19 muscle types of Table 2.1 placed after Appendix B. Deterministic: same code = same face,
//    byte for byte. It is the *source* rig of every transfer (`--rig generic` where a CLI takes a rig).
//  * make_default_face(): what every app shows — the CC0 MakeHuman head rigged by transfer from the
//    generic face, with procedural eyeballs, teeth, tongue and lashes (retarget::build_default_head),
//    as committed in data/face (default.rig + default_face.obj, compiled into the library: no file is
//    read at run time). Regenerate with `retarget --make-default-face data/face`. See docs/facemesh.md.
#include "emoface/facemesh/io.hpp"
#include "emoface/facemesh/render.hpp"

namespace emoface::facemesh {

/// Builds the procedural generic face (5,250 vertices). mesh_file is "generic_face.obj".
Face make_generic_face();

/// The default face (the rigged MakeHuman head, rig frame = thesis frame, metres). Parsed once per
/// process from the compiled-in data/face files; returns a copy. mesh_file is "default_face.obj".
Face make_default_face();

/// The face a `--rig` option names: "" the default face, "generic" the generic face, anything else
/// a rig file (load_face, with its errors).
Face load_face_or_builtin(const std::string& rig);

/// The generic face's surface paint (render()): skin, brows and hairline drawn analytically (the same
/// curves as its Brow/Hair materials, edges anti-aliased over ≈ 0.6 mm) into a texture over the
/// frontal (x, y) plane of the neutral face, 0.25 mm per texel; texture coordinates for the skin
/// vertices of the front half and the lips' border row, NaN elsewhere. Built once per process.
const Paint& generic_face_paint();

/// The default face's surface paint: skin and brows (the generic face's brow curve placed around each
/// of the head's eye centres, 2.7 → 1.2 mm half height, anti-aliased edges) over the
/// frontal (x, y) plane of the neutral head, 0.25 mm per texel; coordinates for the forward-facing skin
/// vertices, so the brows move and stretch with the skin. Built once per process.
const Paint& default_face_paint();

/// generic_face_paint() or default_face_paint() if `rig` is that face's (same vertex count and
/// materials), else nullptr: callers pass it to render() for any mesh deformed from those faces.
const Paint* paint_for(const Rig& rig);

}  // namespace emoface::facemesh
