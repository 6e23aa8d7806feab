#pragma once
// What the retarget CLI writes, as library calls (issue 18 item 4: the CLI stays thin). Both modes
// write their files as one all-or-nothing set (output_set.hpp).
//
//   TransferResult r = transfer_rig(source, doc.triangles(), doc.groups(), options, landmarks);
//   const auto sheet = expression_sheet(r.face, expressions, 320);   // expressions: the app's
//   write_transfer_outputs(doc, r, "rigged", &sheet);
#include <map>
#include <string>
#include <vector>

#include "emoface/facemesh/mesh_document.hpp"
#include "emoface/facemesh/render.hpp"
#include "emoface/retarget/default_head.hpp"
#include "emoface/retarget/retarget.hpp"
#include "emoface/retarget/transfer.hpp"

namespace emoface::retarget {

/// One expression per column (named solver parameters, e.g. the six emotions from fuzzyexpr, which
/// sits above this library), front views in the first row and three-quarter views in the second;
/// tiles `tile` pixels wide and tile·19/16 high, the rig's material colours.
core::Image expression_sheet(const facemesh::Face& face,
                             const std::vector<std::map<std::string, double>>& expressions,
                             int tile);

/// --mode transfer: `dir`/face.<ext> (the input file itself: its bytes for OBJ/PLY/OFF, the
/// document written as .glb for glTF), every companion file (.mtl files and their textures),
/// face.rig (result.face.rig with mesh_file set), report.json (the companion warnings added to
/// result.report.warnings first) and emotions.png when `sheet` is given. Everything is read before
/// the first file is written; on any failure nothing of the set is left.
void write_transfer_outputs(const facemesh::MeshDocument& document, TransferResult& result,
                            const std::string& dir, const core::Image* sheet);
/// The stderr summary of a transfer (several lines, each "retarget: ...", ends with a newline).
std::string transfer_summary(const TransferResult& result, const std::string& dir);

/// --mode deform-source: face.rig + face.obj (the fitted source), target_aligned.obj, report.json
/// and, with `pictures`, overlay.png, error_curve.png and emotions.png (`emotions`, when given).
void write_deform_source_outputs(const RetargetResult& result, const std::string& dir,
                                 bool pictures, int tile, const core::Image* emotions);
/// The stderr lines of a fit: components dropped (if any) and the alignment.
std::string fit_summary(const RetargetResult& result);
/// "retarget: E a -> b (... generations ...)[ -> refined ...]; wrote DIR\n".
std::string fit_result_line(const RetargetResult& result, const std::string& dir);
/// The stderr line of --make-default-face.
std::string default_face_summary(const DefaultHeadReport& report, const std::string& dir);

}  // namespace emoface::retarget
