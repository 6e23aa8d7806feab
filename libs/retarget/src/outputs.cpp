// What the retarget CLI writes (outputs.hpp).
#include "emoface/retarget/outputs.hpp"

#include <cstdarg>
#include <cstdio>

#include "emoface/core/io.hpp"
#include "emoface/facemesh/mesh_io.hpp"
#include "emoface/muscles/solver.hpp"
#include "emoface/retarget/io.hpp"
#include "emoface/retarget/output_set.hpp"
#include "emoface/retarget/plot.hpp"

namespace emoface::retarget {

namespace fm = facemesh;

namespace {
std::string printf_string(const char* format, ...) __attribute__((format(printf, 1, 2)));
std::string printf_string(const char* format, ...) {
  char buf[1024];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buf, sizeof buf, format, args);
  va_end(args);
  return buf;
}
}  // namespace

core::Image expression_sheet(const fm::Face& face,
                             const std::vector<std::map<std::string, double>>& expressions,
                             int tile) {
  fm::RenderOptions ro;
  ro.width = tile;
  ro.height = tile * 19 / 16;
  const auto colors = fm::material_colors(face.rig, face.mesh);
  const muscles::FaceSolver solver(face.mesh, face.rig);
  std::vector<muscles::Deformation> shapes;
  for (const auto& named : expressions) shapes.push_back(solver.deform(named));
  std::vector<core::Image> tiles;
  for (auto view : {fm::View::Front, fm::View::ThreeQuarter}) {
    ro.view = view;
    for (const auto& d : shapes)
      tiles.push_back(fm::render(fm::Mesh{d.vertices, face.mesh.faces}, colors, d.crease, ro));
  }
  return core::tile(tiles, static_cast<int>(expressions.size()));
}

void write_transfer_outputs(const fm::MeshDocument& doc, TransferResult& r, const std::string& dir,
                            const core::Image* sheet) {
  const fm::MeshFormat format = doc.format();
  const bool gltf = format == fm::MeshFormat::Gltf || format == fm::MeshFormat::Glb;
  const std::string mesh_name = "face." + (gltf ? std::string("glb") : fm::to_string(format));
  r.face.rig.mesh_file = mesh_name;
  // the input bytes (non-glTF), the .mtl files and their textures, read before anything is written;
  // what could not be copied (missing, outside the input's directory) becomes a report warning
  std::string mesh_bytes;
  if (!gltf) mesh_bytes = core::read_file(doc.path());
  fm::Companions companions = doc.companion_files();
  for (const auto& w : companions.warnings) r.report.warnings.push_back(w);
  OutputSet outputs(dir);
  if (gltf) {
    outputs.add_writer(mesh_name, [&](const std::string& path) {
      doc.write(path, doc.triangles().vertices, false, false);
    });
  } else {
    outputs.add(mesh_name, std::move(mesh_bytes));
  }
  for (auto& file : companions.files) outputs.add(file.path, std::move(file.bytes));
  outputs.add("face.rig", fm::format_rig(r.face.rig));
  outputs.add("report.json", format_transfer_report(r));
  if (sheet)
    outputs.add_writer("emotions.png",
                       [&](const std::string& path) { core::write_png(path, *sheet); });
  outputs.commit();
}

std::string transfer_summary(const TransferResult& r, const std::string& dir) {
  const auto& rep = r.report;
  std::string s = printf_string(
      "retarget: transfer onto %ld vertices (%zu components): registration RMS %.4g -> %.4g (input "
      "units), "
      "%zu lip-bound, %zu jaw, %zu mouth bag; parts:",
      static_cast<long>(r.face.mesh.vertices.rows()), rep.components,
      rep.registration.initial_rms / rep.scale, rep.registration.final_rms / rep.scale,
      rep.lip_bound, rep.jaw_vertices, rep.mouth_bag);
  for (const auto& p : rep.parts) s += " " + p.name + "=" + fm::to_string(p.kind);
  for (const auto& w : rep.warnings) s += "\nretarget: warning: " + w;
  return s + "\nretarget: wrote " + dir + "\n";
}

void write_deform_source_outputs(const RetargetResult& r, const std::string& dir, bool pictures,
                                 int tile, const core::Image* emotions) {
  fm::Face face = r.face;
  face.rig.mesh_file = "face.obj";
  OutputSet outputs(dir);
  outputs.add_writer("face.obj", [&](const std::string& path) {
    fm::write_face_mesh(path, face, face.mesh.vertices);
  });
  outputs.add_writer("face.rig", [&](const std::string& path) { fm::write_rig(path, face.rig); });
  outputs.add_writer("target_aligned.obj",
                     [&](const std::string& path) { fm::write_mesh(path, r.aligned_target); });
  outputs.add("report.json", format_report(r));
  if (pictures) {
    fm::RenderOptions ro;
    ro.width = tile;
    ro.height = tile * 19 / 16;
    const auto colors = fm::material_colors(face.rig);
    std::vector<core::Image> overlay;
    for (auto view : {fm::View::Front, fm::View::ThreeQuarter}) {
      ro.view = view;
      overlay.push_back(fm::render(r.aligned_target, {}, {}, ro));
      overlay.push_back(fm::render(face.mesh, colors, {}, ro));
    }
    const core::Image sheet = core::tile(overlay, 2);
    outputs.add_writer("overlay.png",
                       [sheet](const std::string& path) { core::write_png(path, sheet); });
    const core::Image curve = plot_series({r.ga.error_curve});
    outputs.add_writer("error_curve.png",
                       [curve](const std::string& path) { core::write_png(path, curve); });
    if (emotions)
      outputs.add_writer("emotions.png",
                         [emotions](const std::string& path) { core::write_png(path, *emotions); });
  }
  outputs.commit();
}

std::string fit_summary(const RetargetResult& r) {
  std::string s;
  if (r.cleaning.kept_components < r.cleaning.components)
    s += printf_string("retarget: dropped %zu of %zu components outside the head (%zu faces)\n",
                       r.cleaning.components - r.cleaning.kept_components, r.cleaning.components,
                       r.cleaning.dropped_faces);
  const auto& a = r.alignment.report;
  s += printf_string(
      "retarget: alignment (%s): rotation %.1f deg about (%.3f, %.3f, %.3f), scale %.6g, "
      "confidence %.2f; %s\n",
      to_string(a.method).c_str(), a.angle_deg, a.axis.x(), a.axis.y(), a.axis.z(),
      r.alignment.scale, a.confidence, a.message.c_str());
  return s;
}

std::string fit_result_line(const RetargetResult& r, const std::string& dir) {
  std::string s = printf_string(
      "retarget: E %.6g -> %.6g (%d generations, %ld evaluations, %.1f s)", r.ga.initial_error,
      r.ga.best_error, r.ga.generations, r.ga.evaluations, r.ga.seconds);
  if (r.refine.ran)
    s += printf_string(" -> refined %.6g (%d iterations, %.1f s)", r.refine.final_error,
                       r.refine.iterations, r.refine.seconds);
  return s + "; wrote " + dir + "\n";
}

std::string default_face_summary(const DefaultHeadReport& rep, const std::string& dir) {
  return printf_string(
      "retarget: default face: %zu head vertices, eyeballs %zu + %zu (sockets %zu + %zu), "
      "mouth cavity %zu (backdrop %zu), teeth %zu + %zu, tongue %zu, lashes %zu, hair %zu, "
      "neck cut %zu vertices, cap %zu; "
      "wrote %s\n",
      rep.head_vertices, rep.eyeball_vertices[0], rep.eyeball_vertices[1], rep.socket_vertices[0],
      rep.socket_vertices[1], rep.mouth_cavity_vertices, rep.mouth_backdrop, rep.upper_teeth,
      rep.lower_teeth, rep.tongue, rep.lashes, rep.hair_vertices, rep.neck_dropped, rep.neck_cap,
      dir.c_str());
}

}  // namespace emoface::retarget
