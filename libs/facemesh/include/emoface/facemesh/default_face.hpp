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

/// The default face's surface paint: skin, short hair above default_hairline() (soft edge) and
/// brows (the generic face's brow curve placed around each of the head's eye centres, 2.7 → 1.2 mm
/// half height, anti-aliased edges) over the frontal (x, y) plane of the neutral head, 0.25 mm per
/// texel; coordinates for the forward-facing skin vertices, so the brows move and stretch with the
/// skin. Built once per process.
const Paint& default_face_paint();

/// The default head's hairline (short hair, issue 14): the hair covers the scalp above a height
/// that depends on the azimuth about a vertical axis through the ears — the forehead hairline 71 mm
/// above the eye centres, a slight recession at the temples, sideburns in front of the ears down to
/// the eye centres' height, an arc over the ears, the nape 45 mm below the eye centres (heights
/// scaled by the eyes' spacing over 64 mm). Built from a rig's eye centres and its "ear_r"/"ear_l"
/// landmarks on the rest mesh; throws InvalidInput when they are missing.
struct Hairline {
  double axis_z = 0.0;  ///< z of the vertical axis (mean of the ear landmarks), m
  double eye_y = 0.0;   ///< mean height of the eye centres, m
  double scale = 1.0;   ///< eye spacing / 64 mm
};
Hairline default_hairline(const Rig& rig, const Vertices& rest);
/// Height (y, m) of the hairline at the azimuth of point p (x, z), rig frame.
double hairline_height(const Hairline& h, const Eigen::Vector3d& p);
/// Hair coverage at the rest-position point p: 0 below the hairline, 1 above, smooth over ±soft
/// (m).
double hair_cover(const Hairline& h, const Eigen::Vector3d& p, double soft);

/// generic_face_paint() or default_face_paint() if `rig` is that face's (same vertex count and
/// materials), else nullptr: callers pass it to render() for any mesh deformed from those faces.
const Paint* paint_for(const Rig& rig);

}  // namespace emoface::facemesh
