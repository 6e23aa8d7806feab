#pragma once
// emoface's default face (issue 14 part 1): the CC0 MakeHuman head (data/face/makehuman_head.obj)
// rigged by transfer from the procedural generic face (facemesh::make_generic_face(), the thesis'
// generic model, which stays the transfer *source*), plus what the head lacks, built procedurally:
// eyeballs (the generic's spheres with sclera/iris/pupil, placed in the sockets; the socket surface
// is pulled behind them), upper and lower teeth (the generic's slabs, carried into the mouth bag),
// a tongue (in the jaw, weight 1), upper and lower lashes (ribbons on the lid margins, in the lid
// lists), lip and skin materials and a neck cut flat 20 mm under the chin and closed by a cap. The
// result is in the rig (thesis) frame, metres, with an identity Rig::frame; brows are painted by
// facemesh (paint_for) from the rig's iBUG brow points.
//
//   const auto doc = facemesh::read_mesh_document("data/face/makehuman_head.obj");
//   facemesh::Face face = build_default_head(facemesh::make_generic_face(), doc);
//   write_default_face_files("data/face");   // the shipped files, byte for byte
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "emoface/facemesh/io.hpp"
#include "emoface/facemesh/mesh_document.hpp"
#include "emoface/retarget/transfer.hpp"

namespace emoface::retarget {

struct DefaultHeadReport {
  TransferReport transfer;
  std::size_t head_vertices = 0;  ///< the MakeHuman head's vertices after the neck cut, with the
                                  ///< rim's new ones (ids 0 .. head_vertices−1)
  std::size_t neck_dropped = 0;   ///< head vertices below the neck cut (removed)
  std::array<std::size_t, 2> eyeball_vertices{};  ///< added sphere vertices per eye (right, left)
  std::array<std::size_t, 2> socket_vertices{};   ///< head vertices pulled behind each eyeball
  std::size_t mouth_cavity_vertices = 0;  ///< bag vertices moved behind the teeth (the cavity)
  std::size_t mouth_backdrop = 0;         ///< vertices of the dark sheet closing the mouth's back
  std::size_t hair_vertices = 0;          ///< head vertices above the hairline (material hair)
  double upper_teeth_lowered =
      0.0;  ///< m the upper teeth were moved down (edge to the lips' contact)
  std::size_t upper_teeth = 0, lower_teeth = 0, tongue = 0, lashes = 0;
  std::size_t neck_cap = 0;  ///< vertices of the cap closing the neck (a copy of the rim + centre)
};

/// The transfer options used for the default face (the GA seed and generations fixed: the shipped
/// files depend on them).
TransferOptions default_head_transfer_options();

/// Rigs `head` (the MakeHuman head document: decimetres, +y up, looking +z) by transfer from
/// `generic` and adds the parts above. Deterministic. Throws what transfer_rig throws, and
/// InvalidInput when the head has no mouth bag, eye sockets or lid margins to hang the parts on.
facemesh::Face build_default_head(const facemesh::Face& generic, const facemesh::MeshDocument& head,
                                  DefaultHeadReport* report = nullptr);

/// Writes the shipped face files into `dir`: generic_face.obj + generic.rig (make_generic_face()) and
/// default_face.obj + default.rig (build_default_head of dir/makehuman_head.obj). Returns the report.
DefaultHeadReport write_default_face_files(const std::string& dir);

}  // namespace emoface::retarget
