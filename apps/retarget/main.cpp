// retarget: fit the built-in face (or a given rig) to any head mesh and write a complete rig for it.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "emoface/cli/cli.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/facemesh/mesh_io.hpp"
#include "emoface/facemesh/render.hpp"
#include "emoface/fuzzyexpr/engine.hpp"
#include "emoface/muscles/solver.hpp"
#include "emoface/retarget/io.hpp"
#include "emoface/retarget/plot.hpp"
#include "emoface/retarget/retarget.hpp"

namespace fm = emoface::facemesh;
namespace fx = emoface::fuzzyexpr;
namespace rt = emoface::retarget;

int main(int argc, char** argv) {
  CLI::App app{"Fit a rigged face to a head mesh (thesis ch. 3: RBF networks + GA) and write its rig.\n"
               "Example: retarget --target head.obj --out fitted --seed 7 --generations 40 --refine"};
  std::string target_path, out_dir, source_rig, up, front, align_mode = "auto", projection = "evaluate_only";
  rt::RetargetOptions o;
  bool no_png = false, quiet = false;
  int tile = 320;
  app.add_option("--target", target_path, "Target head mesh (OBJ/PLY/OFF)")->required();
  app.add_option("--out", out_dir, "Output directory (face.rig, face.obj, target_aligned.obj, report.json, PNGs)")->required();
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
    o.align.mode = rt::align_mode_from_string(align_mode);
    o.clean.enabled = !keep_all;
    if (!up.empty()) o.align.up = rt::axis_from_string(up);
    if (!front.empty()) o.align.front = rt::axis_from_string(front);
    o.ga.projection = rt::projection_mode_from_string(projection);
    if (rt::to_string(o.align.up.value_or(rt::Axis::PosY)).substr(1) == rt::to_string(o.align.front.value_or(rt::Axis::PosZ)).substr(1))
      throw emoface::cli::UsageError("--up and --front must be perpendicular axes");
    const fm::Face source = source_rig.empty() ? fm::make_default_face() : fm::load_face(source_rig);
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
      // The six emotions (thesis ch. 6 rules) on the new face.
      const emoface::muscles::FaceSolver solver(face.mesh, face.rig);
      const fx::Engine engine;
      std::vector<fm::Image> tiles;
      ro.view = fm::View::Front;
      for (std::size_t e = 0; e < fx::kEmotionCount; ++e) {
        fx::Esv esv{};
        esv[e] = 0.9;
        const auto sides = fx::expand_to_sides(engine.convert(esv));
        std::map<std::string, double> named;
        for (std::size_t i = 0; i < sides.size(); ++i) named[std::string(fx::side_parameter_names()[i])] = sides[i];
        const auto d = solver.deform(named);
        tiles.push_back(fm::render(fm::Mesh{d.vertices, face.mesh.faces}, colors, d.crease, ro));
      }
      fm::write_png((dir / "emotions.png").string(), fm::contact_sheet(tiles, 3));
    }
    std::fprintf(stderr, "retarget: E %.6g -> %.6g (%d generations, %ld evaluations, %.1f s)", r.ga.initial_error,
                 r.ga.best_error, r.ga.generations, r.ga.evaluations, r.ga.seconds);
    if (r.refine.ran) std::fprintf(stderr, " -> refined %.6g (%d iterations, %.1f s)", r.refine.final_error, r.refine.iterations, r.refine.seconds);
    std::fprintf(stderr, "; wrote %s\n", out_dir.c_str());
    return 0;
  });
}
