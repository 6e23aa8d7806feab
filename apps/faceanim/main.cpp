// faceanim: parameter frames -> deformed meshes (OBJ/PLY/OFF per frame) and an animated glTF.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "emoface/cli/cli.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/facemesh/gltf_morph.hpp"
#include "emoface/facemesh/render.hpp"
#include "emoface/facemesh/io.hpp"
#include "emoface/facemesh/mesh_io.hpp"
#include "emoface/faceweights/mapper.hpp"
#include "emoface/faceweights/tracks.hpp"
#include "emoface/muscles/io.hpp"
#include "emoface/muscles/morph_targets.hpp"
#include "emoface/muscles/solver.hpp"

namespace fm = emoface::facemesh;
namespace mu = emoface::muscles;

int main(int argc, char** argv) {
  CLI::App app{"Deform a face by muscle parameters, one mesh per frame (thesis ch. 2 muscle model).\n"
               "Example: faceanim --params expressions.csv --out frames --gltf anim.gltf\n"
               "         faceanim --write-generic-face DIR   (the procedural generic face, --rig generic)"};
  std::string rig_path, params, out_dir, format, gltf, default_dir, shard_text, weights;
  double fps = 25.0, delta_c = 0.2;
  bool no_wrinkles = false, ignore_unknown = false, blendshapes = false;
  app.add_option("--rig", rig_path, "Rig file (emoface.rig JSON), or 'generic' for the procedural generic face; "
                 "default: the built-in default face (the rigged MakeHuman head)");
  app.add_option("--params", params, "Parameter frames: .csv, .ndjson/.jsonl or .json");
  app.add_option("--weights", weights,
                 "arkit|facs: --params is a CSV of ARKit blend-shape (or FACS) weights, fitted to the "
                 "face parameters by bounded least squares (Live Link Face CSV too)")
      ->check(CLI::IsMember({"arkit", "facs"}));
  app.add_flag("--blendshapes", blendshapes,
               "With --weights: pose the face as a blendshape character (neutral + sum of weight x "
               "the set's\n"
               "baked targets, as an engine drives the glTF's ARKit targets) instead of fitting "
               "parameters;\n"
               "frames only (--out), Live Link angle columns ignored");
  app.add_option("--out", out_dir, "Directory for frame_0000.<format> ...");
  app.add_option("--format", format,
                 "Mesh format of the frames (default: the rig's mesh kind, obj, ply or glb). "
                 "Frames are in the\n"
                 "mesh file's own frame; obj/glb/gltf of an OBJ/glTF mesh keep its UVs, groups and "
                 "materials,\n"
                 "ply of a PLY mesh every property (vertex colours)")
      ->check(CLI::IsMember({"obj", "ply", "off", "glb", "gltf"}));
  app.add_option("--gltf", gltf,
                 "Also write a glTF 2.0 (.gltf or .glb) for engines: named morph targets per face "
                 "parameter and per ARKit shape, the frames as weights over time, eyes and jaw as "
                 "nodes; on a rig transferred to a user's glTF, their file with our targets added");
  app.add_option("--fps", fps, "Frame rate for inputs without times")->check(CLI::Range(0.001, 1000.0));
  app.add_option("--delta-c", delta_c, "Contraction step (thesis: 0.2)")->check(CLI::Range(0.001, 1.0));
  app.add_flag("--no-wrinkles", no_wrinkles, "Disable bulges and wrinkles");
  app.add_flag("--ignore-unknown-columns", ignore_unknown, "Skip columns/keys that are not face parameters");
  app.add_option("--shard", shard_text,
                 "i/N: only the i-th of N contiguous blocks of frames (files keep their global "
                 "numbers); auto: from a Slurm job array");
  app.add_option("--write-generic-face", default_dir, "Write generic_face.obj + generic.rig (the procedural generic "
                 "face) into DIR and exit (all of data/face: retarget --make-default-face data/face)");
  if (auto code = emoface::cli::parse(app, argc, argv)) return *code;
  return emoface::cli::run("faceanim", [&]() {
    if (!default_dir.empty()) {
      std::filesystem::create_directories(default_dir);
      fm::save_face((std::filesystem::path(default_dir) / "generic.rig").string(), fm::make_generic_face());
      return 0;
    }
    if (params.empty() || (out_dir.empty() && gltf.empty())) throw emoface::InvalidInput("give --params FILE and --out DIR and/or --gltf FILE");
    const auto shard = shard_text.empty() ? emoface::cli::Shard{} : emoface::cli::parse_shard(shard_text);
    fm::Face face = fm::load_face_or_builtin(rig_path);
    if (format.empty()) format = fm::frame_format(face);
    mu::SolverOptions options;
    options.delta_c = delta_c;
    options.wrinkles = !no_wrinkles;
    const mu::FaceSolver solver(face.mesh, face.rig, options);
    mu::FrameReadOptions read;
    read.fps = fps;
    read.ignore_unknown_columns = ignore_unknown;
    namespace fw = emoface::faceweights;
    auto read_weights = [&](const fw::Mapper& mapper) {  // --weights: an ARKit/FACS weight CSV
      fw::WeightTrackReadOptions wopt;
      wopt.fps = fps;
      wopt.ignore_unknown_columns = ignore_unknown;
      return fw::read_weight_track(params, mapper.set(), wopt);
    };
    if (blendshapes) {
      if (weights.empty() || out_dir.empty() || !gltf.empty())
        throw emoface::cli::UsageError("--blendshapes needs --weights and --out (and no --gltf)");
      const fw::Mapper mapper(fw::builtin_weight_set(weights), mu::parameter_names());
      const fw::WeightTrack track = read_weights(mapper);
      const mu::BakedRig rig = mu::bake_rig(solver, face.mesh.faces, {&mapper});
      std::filesystem::create_directories(out_dir);
      for (std::size_t i = 0; i < track.weights.size(); ++i) {
        if (!shard.owns(i, track.weights.size())) continue;  // contiguous block, global indices
        char name[64];
        std::snprintf(name, sizeof name, "frame_%04zu.%s", i, format.c_str());
        fm::write_face_mesh((std::filesystem::path(out_dir) / name).string(), face,
                            mu::blend_targets(rig, mu::set_target_weights(rig, track.weights[i])));
      }
      return 0;
    }
    std::vector<mu::ParameterFrame> frames;
    if (weights.empty()) {
      frames = mu::read_parameter_frames(params, read);
    } else {
      const fw::Mapper mapper(fw::builtin_weight_set(weights), mu::parameter_names());
      const fw::WeightTrack track = read_weights(mapper);
      const auto fitted = fw::fit_weight_track(track, mapper);
      for (std::size_t i = 0; i < fitted.size(); ++i) frames.push_back({track.times[i], fitted[i]});
    }
    if (frames.empty()) throw emoface::InvalidInput(params + ": no frames");
    if (!out_dir.empty()) std::filesystem::create_directories(out_dir);
    std::vector<std::vector<double>> gltf_frames;
    std::vector<double> times;
    mu::Deformation d;
    for (std::size_t i = 0; i < frames.size(); ++i) {
      if (!shard.owns(i, frames.size())) continue;  // contiguous block: files keep global indices
      solver.deform(frames[i].values, d);
      if (!out_dir.empty()) {
        char name[64];
        std::snprintf(name, sizeof name, "frame_%04zu.%s", i, format.c_str());
        // in the mesh file's frame; through the user's document when the format is its kind
        fm::write_face_mesh((std::filesystem::path(out_dir) / name).string(), face, d.vertices);
      }
      if (!gltf.empty()) {
        gltf_frames.push_back(frames[i].values);
        times.push_back(frames[i].time);
      }
    }
    if (!gltf.empty()) {
      // times must increase for the animation; fall back to index/fps if the file's times do not
      for (std::size_t i = 1; i < times.size(); ++i) {
        if (!(times[i] > times[i - 1])) {
          for (std::size_t k = 0; k < times.size(); ++k) times[k] = static_cast<double>(k) / fps;
          break;
        }
      }
      // a user's glTF keeps everything of theirs; otherwise eyes and jaw are nodes
      // (morph_targets.hpp)
      mu::write_rig_gltf(gltf, face, solver, times, gltf_frames);
    }
    return 0;
  });
}
