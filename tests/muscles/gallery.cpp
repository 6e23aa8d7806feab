// Writes the pictures of docs/facemesh.md and docs/muscles.md (deterministic):
//   build/tests/muscles/muscles_gallery docs/img
#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "emoface/facemesh/default_face.hpp"
#include "emoface/facemesh/render.hpp"
#include "emoface/fuzzyexpr/engine.hpp"
#include "emoface/muscles/solver.hpp"

namespace fm = emoface::facemesh;
namespace core = emoface::core;
namespace mu = emoface::muscles;
namespace fx = emoface::fuzzyexpr;
using Named = std::map<std::string, double>;

namespace {

const fm::Face& face() {
  static const fm::Face f = fm::make_generic_face();
  return f;
}

core::Image shot(const mu::Deformation& d, fm::View view, int w, int h,
                 const std::vector<Eigen::Vector3f>& colors) {
  fm::RenderOptions o;
  o.view = view;
  o.width = w;
  o.height = h;
  return fm::render(fm::Mesh{d.vertices, face().mesh.faces}, colors, d.crease, o,
                    fm::paint_for(face().rig));
}

Named from_esv(const fx::Engine& engine, const fx::Esv& esv) {
  const auto sides = fx::expand_to_sides(engine.convert(esv));
  Named named;
  for (std::size_t i = 0; i < sides.size(); ++i) named[std::string(fx::side_parameter_names()[i])] = sides[i];
  return named;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: muscles_gallery OUT_DIR (e.g. docs/img)\n";
    return 1;
  }
  const std::filesystem::path out(argv[1]);
  std::filesystem::create_directories(out / "facemesh");
  std::filesystem::create_directories(out / "muscles");
  const auto colors = fm::material_colors(face().rig, face().mesh);
  const mu::FaceSolver solver(face().mesh, face().rig);
  const auto neutral = solver.deform(Named{});

  // facemesh: neutral face, front and three-quarter; regions
  core::write_png((out / "facemesh/neutral.png").string(),
                  core::tile({shot(neutral, fm::View::Front, 320, 376, colors),
                              shot(neutral, fm::View::ThreeQuarter, 320, 376, colors)},
                             2));
  {
    const Eigen::Vector3f palette[fm::kRegionCount] = {
        {0.85f, 0.35f, 0.30f}, {0.95f, 0.65f, 0.30f}, {0.55f, 0.80f, 0.40f}, {0.35f, 0.70f, 0.75f}, {0.45f, 0.50f, 0.90f},
        {0.70f, 0.25f, 0.25f}, {0.80f, 0.55f, 0.20f}, {0.40f, 0.65f, 0.30f}, {0.25f, 0.55f, 0.60f}, {0.35f, 0.38f, 0.75f},
        {0.80f, 0.80f, 0.80f}};
    std::vector<Eigen::Vector3f> rc(face().rig.regions.size());
    for (std::size_t v = 0; v < rc.size(); ++v) rc[v] = palette[static_cast<int>(face().rig.regions[v])];
    core::write_png((out / "facemesh/regions.png").string(),
                    core::tile({shot(neutral, fm::View::Front, 320, 376, rc),
                                shot(neutral, fm::View::ThreeQuarter, 320, 376, rc)},
                               2));
  }

  // each muscle type at full contraction (both sides), Table 2.1 order, neutral first
  {
    std::vector<core::Image> tiles{shot(neutral, fm::View::Front, 190, 222, colors)};
    for (const auto& type : mu::muscle_type_names()) {
      Named n;
      for (const auto& p : mu::side_parameter_names()) {
        if (p == type || p == type + "_l" || p == type + "_r") n[p] = 1.0;
      }
      tiles.push_back(shot(solver.deform(n), fm::View::Front, 190, 222, colors));
    }
    core::write_png((out / "muscles/muscle_types.png").string(), core::tile(tiles, 5));
  }

  // the six basic emotions and two blends through fuzzyexpr (thesis ch. 6 rules)
  const fx::Engine engine;
  const std::vector<fx::Esv> esvs = {
      {0.9, 0, 0, 0, 0, 0}, {0, 0.9, 0, 0, 0, 0}, {0, 0, 0.9, 0, 0, 0}, {0, 0, 0, 0.9, 0, 0},
      {0, 0, 0, 0, 0.9, 0}, {0, 0, 0, 0, 0, 0.9}, {0, 0.7, 0, 0, 0, 0.6}, {0.7, 0, 0, 0.5, 0, 0}};
  for (auto view : {fm::View::Front, fm::View::ThreeQuarter}) {
    std::vector<core::Image> tiles;
    for (const auto& esv : esvs) tiles.push_back(shot(solver.deform(from_esv(engine, esv)), view, 230, 270, colors));
    core::write_png((out / ("muscles/emotions_" + fm::to_string(view) + ".png")).string(),
                    core::tile(tiles, 4));
  }

  // wrinkles and parallel contraction on/off (like thesis Fig. 2.24): sadness and surprise
  {
    mu::SolverOptions plain;
    plain.wrinkles = false;
    plain.parallel = false;
    const mu::FaceSolver old_style(face().mesh, face().rig, plain);
    std::vector<core::Image> tiles;
    for (const auto& esv : {esvs[0], esvs[5]}) {
      const Named n = from_esv(engine, esv);
      fm::RenderOptions o;
      o.width = 300;
      o.height = 250;
      o.target = Eigen::Vector3d(0, 0.03, 0);
      o.distance = 0.45;
      const auto a = solver.deform(n);
      const auto b = old_style.deform(n);
      tiles.push_back(fm::render(fm::Mesh{a.vertices, face().mesh.faces}, colors, a.crease, o,
                                 fm::paint_for(face().rig)));
      tiles.push_back(fm::render(fm::Mesh{b.vertices, face().mesh.faces}, colors, b.crease, o,
                                 fm::paint_for(face().rig)));
    }
    core::write_png((out / "muscles/wrinkles_on_off.png").string(), core::tile(tiles, 2));
  }

  // forehead close-up: frontalis (medialis + lateralis, both sides) at 0, 0.5, 0.75 and 1 (issue
  // 14), on the generic face and on the default face (the MakeHuman head users see)
  {
    const fm::Face head = fm::make_default_face();
    const mu::FaceSolver head_solver(head.mesh, head.rig);
    const auto head_colors = fm::material_colors(head.rig, head.mesh);
    const auto closeup = [](const fm::Face& f, const mu::FaceSolver& s,
                            const std::vector<Eigen::Vector3f>& c, const char* file,
                            const std::filesystem::path& dir) {
      std::vector<core::Image> tiles;
      for (double level : {0.0, 0.5, 0.75, 1.0}) {
        Named n;
        for (const char* p : {"frontalis_medialis_l", "frontalis_medialis_r",
                              "frontalis_lateralis_l", "frontalis_lateralis_r"})
          n[p] = level;
        fm::RenderOptions o;
        o.width = 360;
        o.height = 260;
        o.target = Eigen::Vector3d(0, 0.035, 0);
        o.distance = 0.40;
        const auto a = s.deform(n);
        tiles.push_back(
            fm::render(fm::Mesh{a.vertices, f.mesh.faces}, c, a.crease, o, fm::paint_for(f.rig)));
      }
      core::write_png((dir / file).string(), core::tile(tiles, 2));
    };
    closeup(face(), solver, colors, "muscles/forehead_closeup.png", out);
    closeup(head, head_solver, head_colors, "muscles/forehead_closeup_default.png", out);
  }

  // eyes, lids, jaw, lips
  {
    const std::vector<Named> poses = {
        {{"eye_gaze_yaw", 0.4}},
        {{"eye_gaze_yaw", -0.4}},
        {{"eye_gaze_pitch", 0.3}},
        {{"eye_gaze_yaw", 1.5}, {"eye_gaze_pitch", 1.0}},
        {{"orbicularis_oculi_palpebralis_l", 1.0}, {"orbicularis_oculi_palpebralis_r", 1.0}},
        {{"eye_blink_l", 1.0}, {"eye_blink_r", 1.0}},
        {{"eye_blink_l", 1.0}},
        {{"levator_palpebrae_superioris_l", 1.0}, {"levator_palpebrae_superioris_r", 1.0}},
        {{"masseter", 1.0}},
        {{"orbicularis_oris_funneler", 1.0}},
        {{"orbicularis_oris_pressor", 1.0}},
        {{"masseter", 0.6}, {"orbicularis_oris_funneler", 0.8}},
        {{"head_yaw", 0.4}, {"head_pitch", 0.15}, {"eye_gaze_yaw", -0.3}}};
    std::vector<core::Image> tiles;
    for (const auto& p : poses) tiles.push_back(shot(solver.deform(p), fm::View::Front, 190, 222, colors));
    core::write_png((out / "muscles/eyes_jaw_lips.png").string(), core::tile(tiles, 4));
  }
  return 0;
}
