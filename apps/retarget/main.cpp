// retarget: fit the built-in face (or a given rig) to any head mesh and write a complete rig for it.
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "emoface/cli/cli.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/facemesh/mesh_io.hpp"
#include "emoface/fuzzyexpr/engine.hpp"
#include "emoface/retarget/io.hpp"
#include "emoface/retarget/outputs.hpp"

namespace fm = emoface::facemesh;
namespace core = emoface::core;
namespace fx = emoface::fuzzyexpr;
namespace rt = emoface::retarget;

namespace {

// The six emotions (thesis ch. 6 fuzzy rules, ESV 0.9) as named parameters for the sheet.
core::Image emotion_sheet(const fm::Face& face, int tile) {
  const fx::Engine engine;
  std::vector<std::map<std::string, double>> expressions;
  for (std::size_t e = 0; e < fx::kEmotionCount; ++e) {
    fx::Esv esv{};
    esv[e] = 0.9;
    const auto sides = fx::expand_to_sides(engine.convert(esv));
    auto& named = expressions.emplace_back();
    for (std::size_t i = 0; i < sides.size(); ++i) named[std::string(fx::side_parameter_names()[i])] = sides[i];
  }
  return rt::expression_sheet(face, expressions, tile);
}

// --mode transfer: everything is computed first, then written as one set (all or nothing).
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
  const core::Image sheet = no_png ? core::Image{} : emotion_sheet(r.face, tile);
  rt::write_transfer_outputs(doc, r, out_dir, no_png ? nullptr : &sheet);
  if (!quiet) std::fputs(rt::transfer_summary(r, out_dir).c_str(), stderr);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Rig a head mesh with the built-in face's muscles (thesis ch. 3 fit + dense registration).\n"
      "--mode transfer (default): OUT/face.<ext> is the input file itself (copied byte for byte,\n"
      "with its .mtl files and their textures; glTF input gives face.glb), OUT/face.rig rigs it\n"
      "in its own frame and units, OUT/report.json; written all or nothing.\n"
      "--mode deform-source: the thesis' literal export (the built-in face bent to the target).\n"
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
      if (!quiet) std::fputs(rt::default_face_summary(rep, make_default).c_str(), stderr);
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
    if (transfer_flag || mode == "transfer")
      return run_transfer(source, target_path, out_dir, landmarks_path, o, no_png, quiet, tile);
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
    if (!quiet) std::fputs(rt::fit_summary(r).c_str(), stderr);
    const core::Image emotions = no_png ? core::Image{} : emotion_sheet(r.face, tile);
    rt::write_deform_source_outputs(r, out_dir, !no_png, tile, &emotions);
    std::fputs(rt::fit_result_line(r, out_dir).c_str(), stderr);
    return 0;
  });
}
