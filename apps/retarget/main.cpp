// retarget: fit the built-in face (or a given rig) to any head mesh and write a complete rig for it.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "emoface/cli/cli.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/facemesh/mesh_io.hpp"
#include "emoface/facemesh/render.hpp"
#include "emoface/fuzzyexpr/engine.hpp"
#include "emoface/muscles/solver.hpp"
#include "emoface/retarget/default_head.hpp"
#include "emoface/retarget/io.hpp"
#include "emoface/retarget/output_set.hpp"
#include "emoface/retarget/plot.hpp"
#include "emoface/retarget/retarget.hpp"
#include "emoface/retarget/transfer.hpp"
#include "emoface/core/io.hpp"

namespace fm = emoface::facemesh;
namespace fx = emoface::fuzzyexpr;
namespace rt = emoface::retarget;

namespace {

// The six emotions (thesis ch. 6 fuzzy rules, ESV 0.9; anger, disgust, fear, happiness, sadness,
// surprise) on a face: front views in the first row, three-quarter views in the second.
fm::Image emotion_sheet(const fm::Face& face, int tile) {
  fm::RenderOptions ro;
  ro.width = tile;
  ro.height = tile * 19 / 16;
  const auto colors = fm::material_colors(face.rig, face.mesh);
  const emoface::muscles::FaceSolver solver(face.mesh, face.rig);
  const fx::Engine engine;
  std::vector<emoface::muscles::Deformation> shapes;
  for (std::size_t e = 0; e < fx::kEmotionCount; ++e) {
    fx::Esv esv{};
    esv[e] = 0.9;
    const auto sides = fx::expand_to_sides(engine.convert(esv));
    std::map<std::string, double> named;
    for (std::size_t i = 0; i < sides.size(); ++i) named[std::string(fx::side_parameter_names()[i])] = sides[i];
    shapes.push_back(solver.deform(named));
  }
  std::vector<fm::Image> tiles;
  for (auto view : {fm::View::Front, fm::View::ThreeQuarter}) {
    ro.view = view;
    for (const auto& d : shapes) tiles.push_back(fm::render(fm::Mesh{d.vertices, face.mesh.faces}, colors, d.crease, ro));
  }
  return fm::contact_sheet(tiles, static_cast<int>(fx::kEmotionCount));
}

// --mode transfer: everything is computed first; the files are then written as one set
// (rt::OutputSet: on a failure every file and directory it made is removed again).
int run_transfer(const fm::Face& source, const std::string& target_path, const std::string& out_dir,
                 const std::string& landmarks_path, const rt::RetargetOptions& fit, bool no_png, bool quiet, int tile) {
  const fm::MeshDocument doc = fm::read_mesh_document(target_path);
  rt::UserLandmarks landmarks;
  if (!landmarks_path.empty()) landmarks = rt::read_landmarks(landmarks_path);
  rt::TransferOptions o;
  o.fit = fit;
  const auto progress = [&](const rt::GaProgress& p) {
    if (!quiet && (p.generation % 5 == 0 || p.generation == fit.ga.generations))
      std::fprintf(stderr, "retarget: generation %d  best E %.6g\n", p.generation, p.best_error);
  };
  rt::TransferResult r = rt::transfer_rig(source, doc.triangles(), doc.groups(), o, landmarks, progress);
  const fm::MeshFormat format = doc.format();
  const bool gltf = format == fm::MeshFormat::Gltf || format == fm::MeshFormat::Glb;
  const std::string ext = gltf ? "glb" : fm::to_string(format);
  const std::string mesh_name = "face." + ext;
  r.face.rig.mesh_file = mesh_name;
  // The input bytes (non-glTF), the .mtl files and their textures, read before anything is written;
  // what could not be copied (missing, outside the input's directory) becomes a report warning.
  std::string mesh_bytes;
  if (!gltf) mesh_bytes = emoface::core::read_file(target_path);
  fm::Companions companions = doc.companion_files();
  for (const auto& w : companions.warnings) r.report.warnings.push_back(w);
  const std::string rig_text = fm::format_rig(r.face.rig);
  const std::string report_text = rt::format_transfer_report(r);
  fm::Image sheet;
  if (!no_png) sheet = emotion_sheet(r.face, tile);
  rt::OutputSet outputs(out_dir);
  if (gltf) {
    outputs.add_writer(mesh_name, [&](const std::string& path) { doc.write(path, doc.triangles().vertices, false, false); });
  } else {
    outputs.add(mesh_name, std::move(mesh_bytes));
  }
  for (auto& file : companions.files) outputs.add(file.path, std::move(file.bytes));
  outputs.add("face.rig", rig_text);
  outputs.add("report.json", report_text);
  if (!no_png) outputs.add_writer("emotions.png", [&](const std::string& path) { fm::write_png(path, sheet); });
  outputs.commit();
  if (!quiet) {
    const auto& rep = r.report;
    std::fprintf(stderr, "retarget: transfer onto %ld vertices (%zu components): registration RMS %.4g -> %.4g (input units), "
                 "%zu lip-bound, %zu jaw, %zu mouth bag; parts:", static_cast<long>(r.face.mesh.vertices.rows()), rep.components,
                 rep.registration.initial_rms / rep.scale, rep.registration.final_rms / rep.scale, rep.lip_bound, rep.jaw_vertices,
                 rep.mouth_bag);
    for (const auto& p : rep.parts) std::fprintf(stderr, " %s=%s", p.name.c_str(), fm::to_string(p.kind).c_str());
    for (const auto& w : rep.warnings) std::fprintf(stderr, "\nretarget: warning: %s", w.c_str());
    std::fprintf(stderr, "\nretarget: wrote %s\n", out_dir.c_str());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Rig a head mesh with the built-in face's muscles (thesis ch. 3 fit + dense registration).\n"
               "--mode transfer (default): OUT/face.<ext> is the input file itself (copied byte for byte, .mtl too;\n"
               "glTF input gives face.glb), OUT/face.rig rigs it in its own frame and units, OUT/report.json.\n"
               "--mode deform-source: the thesis' literal export (the built-in face bent into the target's shape).\n"
               "Example: retarget --target head.obj --out rigged --seed 7 --generations 40"};
  std::string target_path, out_dir, source_rig, up, front, align_mode = "auto", projection = "evaluate_only";
  rt::RetargetOptions o;
  bool no_png = false, quiet = false;
  int tile = 320;
  std::string mode = "transfer", landmarks_path;
  bool transfer_flag = false;
  std::string make_default;
  app.add_option("--target", target_path, "Target head mesh (OBJ/PLY/OFF; glTF/GLB in --mode transfer)");
  app.add_option("--out", out_dir, "Output directory (transfer: face.<ext>, face.rig, report.json, emotions.png; "
                 "deform-source: face.rig, face.obj, target_aligned.obj, report.json, PNGs)");
  app.add_option("--make-default-face", make_default,
                 "Regenerate the shipped faces in DIR (data/face): generic_face.obj + generic.rig (--rig generic) "
                 "and default_face.obj + default.rig (DIR/makehuman_head.obj rigged by transfer) and exit");
  app.add_option("--mode", mode, "transfer (rig the target mesh itself, default) or deform-source (thesis export)")
      ->check(CLI::IsMember({"transfer", "deform-source"}));
  app.add_flag("--transfer", transfer_flag, "Short for --mode transfer");
  app.add_option("--landmarks", landmarks_path, "iBUG-68 landmarks of the target (emoface.landmarks JSON: vertex ids or "
                 "points in the input frame; transfer mode)");
  app.add_option("--source", source_rig, "Source rig (default: the built-in face)");
  app.add_option("--seed", o.ga.seed, "GA seed (same seed + inputs = same output)");
  app.add_option("--generations", o.ga.generations, "GA generations")->check(CLI::Range(0, 100000));
  app.add_option("--population", o.ga.population, "GA population")->check(CLI::Range(4, 10000));
  app.add_option("--bits", o.ga.bits, "Bits per coordinate (thesis: 5-10)")->check(CLI::Range(2, 16));
  app.add_option("--cube", o.ga.cube_size, "Search cube edge around each landmark, m (thesis frame)")->check(CLI::PositiveNumber);
  app.add_option("--projection", projection, "off, evaluate_only or replace (thesis §3.6.2)")
      ->check(CLI::IsMember({"off", "evaluate_only", "replace"}));
  app.add_option("--planes", o.error.planes, "Sampling planes m")->check(CLI::Range(2, 360));
  app.add_option("--samples", o.error.samples, "Samples per curve n")->check(CLI::Range(2, 10000));
  app.add_option("--mouth-samples", o.mouth_samples, "Extra samples per curve between the source's chin and nose (0 = thesis)")
      ->check(CLI::Range(0, 1000));
  app.add_option("--bottom-y", o.error.bottom_y, "Lowest sampled height, m in the source frame (default: source chin)");
  app.add_option("--top-y", o.error.top_y, "Highest sampled height, m in the source frame (default: top of head)");
  const auto axes = CLI::IsMember({"+x", "-x", "+y", "-y", "+z", "-z"});
  app.add_option("--align", align_mode, "auto (any rotation, found from the geometry) or axes (input already axis-aligned: "
                 "--up/--front exact, default +y/+z)")->check(CLI::IsMember({"auto", "axes"}));
  app.add_option("--up", up, "Input axis pointing to the top of the head (+x,-x,+y,-y,+z,-z); a hint in --align auto")->check(axes);
  app.add_option("--front", front, "Input axis the face looks along; a hint in --align auto")->check(axes);
  app.add_option("--min-confidence", o.align.min_confidence, "Refuse an automatic alignment below this confidence (0-1)")
      ->check(CLI::Range(0.0, 1.0));
  app.add_flag("--refine", o.refine.enabled, "Refine the GA result locally (Levenberg-Marquardt, Ceres)");
  app.add_option("--prior", o.prior_weight, "Weight of the landmark prior (0 = off)")->check(CLI::NonNegativeNumber);
  bool keep_all = false;
  app.add_flag("--keep-all-components", keep_all, "Keep components outside the head's box (default: dropped)");
  app.add_option("--pitch-search", o.pitch_search_degrees, "Pitch correction range on the initial error, degrees (0 = off)")
      ->check(CLI::Range(0.0, 60.0));
  app.add_flag("--no-png", no_png, "Skip the pictures");
  app.add_option("--tile-width", tile, "Width of one picture tile in pixels")->check(CLI::Range(64, 2048));
  app.add_flag("--quiet", quiet, "No progress on stderr");
  if (auto code = emoface::cli::parse(app, argc, argv)) return *code;
  return emoface::cli::run("retarget", [&]() {
    if (!make_default.empty()) {
      const rt::DefaultHeadReport rep = rt::write_default_face_files(make_default);
      if (!quiet)
        std::fprintf(stderr, "retarget: default face: %zu head vertices, eyeballs %zu + %zu (sockets %zu + %zu), "
                     "teeth %zu + %zu, tongue %zu, lashes %zu, neck caps %zu; wrote %s\n",
                     rep.head_vertices, rep.eyeball_vertices[0], rep.eyeball_vertices[1], rep.socket_vertices[0],
                     rep.socket_vertices[1], rep.upper_teeth, rep.lower_teeth, rep.tongue, rep.lashes, rep.neck_cap,
                     make_default.c_str());
      return 0;
    }
    if (target_path.empty() || out_dir.empty()) throw emoface::cli::UsageError("--target and --out are required");
    o.align.mode = rt::align_mode_from_string(align_mode);
    o.clean.enabled = !keep_all;
    if (!up.empty()) o.align.up = rt::axis_from_string(up);
    if (!front.empty()) o.align.front = rt::axis_from_string(front);
    o.ga.projection = rt::projection_mode_from_string(projection);
    if (rt::to_string(o.align.up.value_or(rt::Axis::PosY)).substr(1) == rt::to_string(o.align.front.value_or(rt::Axis::PosZ)).substr(1))
      throw emoface::cli::UsageError("--up and --front must be perpendicular axes");
    const fm::Face source = source_rig.empty() ? fm::make_generic_face() : fm::load_face(source_rig);
    if (transfer_flag) mode = "transfer";
    if (mode == "transfer") return run_transfer(source, target_path, out_dir, landmarks_path, o, no_png, quiet, tile);
    if (!landmarks_path.empty()) throw emoface::cli::UsageError("--landmarks needs --mode transfer");
    fm::MeshReadReport read_report;
    const fm::Mesh target = fm::read_mesh(target_path, fm::MeshReadOptions{true}, &read_report);
    if (!quiet && read_report.orientation.flipped_faces > 0)
      std::fprintf(stderr, "retarget: made the winding consistent: %zu faces flipped (%zu components)\n",
                   read_report.orientation.flipped_faces, read_report.orientation.components);
    const auto progress = [&](const rt::GaProgress& p) {
      if (!quiet && (p.generation % 5 == 0 || p.generation == o.ga.generations))
        std::fprintf(stderr, "retarget: generation %d  best E %.6g  mutation %.2f  evaluations %ld\n", p.generation,
                     p.best_error, p.mutation_rate, p.evaluations);
    };
    const rt::RetargetResult r = rt::retarget_face(source, target, o, progress);
    if (!quiet && r.cleaning.kept_components < r.cleaning.components)
      std::fprintf(stderr, "retarget: dropped %zu of %zu components outside the head (%zu faces)\n",
                   r.cleaning.components - r.cleaning.kept_components, r.cleaning.components, r.cleaning.dropped_faces);
    if (!quiet) std::fprintf(stderr, "retarget: alignment (%s): rotation %.1f deg about (%.3f, %.3f, %.3f), scale %.6g, confidence %.2f; %s\n",
                             rt::to_string(r.alignment.report.method).c_str(), r.alignment.report.angle_deg, r.alignment.report.axis.x(),
                             r.alignment.report.axis.y(), r.alignment.report.axis.z(), r.alignment.scale, r.alignment.report.confidence,
                             r.alignment.report.message.c_str());
    const std::filesystem::path dir(out_dir);
    std::filesystem::create_directories(dir);
    fm::Face face = r.face;
    face.rig.mesh_file = "face.obj";
    fm::save_face((dir / "face.rig").string(), face);
    fm::write_mesh((dir / "target_aligned.obj").string(), r.aligned_target);
    rt::write_report((dir / "report.json").string(), r);
    if (!no_png) {
      fm::RenderOptions ro;
      ro.width = tile;
      ro.height = tile * 19 / 16;
      const auto colors = fm::material_colors(face.rig);
      std::vector<fm::Image> overlay;
      for (auto view : {fm::View::Front, fm::View::ThreeQuarter}) {
        ro.view = view;
        overlay.push_back(fm::render(r.aligned_target, {}, {}, ro));
        overlay.push_back(fm::render(face.mesh, colors, {}, ro));
      }
      fm::write_png((dir / "overlay.png").string(), fm::contact_sheet(overlay, 2));
      fm::write_png((dir / "error_curve.png").string(), rt::plot_series({r.ga.error_curve}));
      fm::write_png((dir / "emotions.png").string(), emotion_sheet(face, tile));  // thesis ch. 6 rules
    }
    std::fprintf(stderr, "retarget: E %.6g -> %.6g (%d generations, %ld evaluations, %.1f s)", r.ga.initial_error,
                 r.ga.best_error, r.ga.generations, r.ga.evaluations, r.ga.seconds);
    if (r.refine.ran) std::fprintf(stderr, " -> refined %.6g (%d iterations, %.1f s)", r.refine.final_error, r.refine.iterations, r.refine.seconds);
    std::fprintf(stderr, "; wrote %s\n", out_dir.c_str());
    return 0;
  });
}
