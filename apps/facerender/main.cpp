// facerender: meshes -> PNG (one image, one per mesh, or a contact sheet) and MP4 via ffmpeg.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "emoface/cli/cli.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/core/video.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/facemesh/io.hpp"
#include "emoface/facemesh/mesh_document.hpp"
#include "emoface/facemesh/mesh_io.hpp"
#include "emoface/facemesh/render.hpp"

namespace fm = emoface::facemesh;
namespace core = emoface::core;

int main(int argc, char** argv) {
  CLI::App app{"Render face meshes to PNG with a software rasteriser (Phong shading).\n"
               "Example: facerender out/frame_0000.obj out/frame_0001.obj --sheet 2 --out sheet.png"};
  std::vector<std::string> meshes;
  std::string out, view = "front", rig_path, video, audio;
  int sheet = 0, fps = 25;
  fm::RenderOptions ro;  // size, yaw and light terms straight from the flags
  std::string camera = "auto";
  bool no_paint = false;
  app.add_option("meshes", meshes, "Mesh files (OBJ/PLY/OFF/glTF/GLB)")->required();
  app.add_option("--camera", camera,
                 "auto: keep the face framing when the meshes fill it, else fit the camera to their bounding\n"
                 "box (any frame and units); fixed: the face framing, refused when a mesh would not be visible")
      ->check(CLI::IsMember({"auto", "fixed"}));
  app.add_option("--out", out, "Output PNG; with several meshes and no --sheet, NAME_0000.png ... are written");
  app.add_option("--view", view, "front or threequarter")->check(CLI::IsMember({"front", "threequarter"}));
  app.add_option("--sheet", sheet, "Tile all meshes into one contact sheet with this many columns")->check(CLI::Range(1, 64));
  app.add_option("--rig", rig_path,
                 "Rig for material colours and its mesh frame, or 'generic' (default: the built-in default face, or\n"
                 "the generic face, when the vertex count matches; otherwise the mesh's own vertex colours, else\n"
                 "uniform skin)");
  app.add_option("--width", ro.width, "Image width in pixels")->check(CLI::Range(16, 8192));
  app.add_option("--height", ro.height, "Image height in pixels")->check(CLI::Range(16, 8192));
  app.add_option("--yaw", ro.yaw, "Extra camera yaw in radians")
      ->check(CLI::Range(-3.14159, 3.14159));
  app.add_option(
         "--distance", ro.distance,
         "Camera distance from the head in metres (the face framing: 0.75; larger shows the head\n"
         "smaller, with room around it, as in a portrait photograph)")
      ->check(CLI::Range(0.05, 100.0));
  app.add_option("--shadow", ro.shadow, "Strength of the key light's cast shadow, 0 = none")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--occlusion", ro.occlusion,
                 "Strength of ambient occlusion (dark cavities), 0 = none")
      ->check(CLI::Range(0.0, 1.0));
  std::vector<double> key;
  app.add_option("--key-light", key,
                 "Direction towards the key light, X Y Z in the head frame (x to the front view's\n"
                 "right, y up, z towards the camera; default -0.35 0.55 0.75)")
      ->expected(3);
  app.add_option("--video", video, "Also encode the frames to a video (.mp4/.mov/.mkv/.gif) with the ffmpeg binary");
  app.add_option("--audio", audio, "Audio file (e.g. WAV) muxed into --video");
  app.add_option("--fps", fps, "Video frame rate")->check(CLI::Range(1, 240));
  app.add_flag(
      "--no-paint", no_paint,
      "Vertex colours only, without the built-in face's surface paint (brows, hairline): the\n"
      "colours a glTF written by faceanim --gltf carries (COLOR_0)");
  if (auto code = emoface::cli::parse(app, argc, argv)) return *code;
  return emoface::cli::run("facerender", [&]() {
    if (out.empty() && video.empty()) throw emoface::InvalidInput("give --out FILE.png and/or --video FILE.mp4");
    if (!audio.empty() && video.empty()) throw emoface::InvalidInput("--audio needs --video");
    fm::Rig rig = rig_path.empty()          ? fm::make_default_face().rig
                  : rig_path == "generic" ? fm::make_generic_face().rig
                                          : fm::read_rig(rig_path);
    std::vector<Eigen::Vector3f> colors;  // from the first mesh that fits the rig (same topology)
    fm::RenderOptions options = ro;
    options.view = fm::view_from_string(view);
    if (!key.empty()) options.key_light = Eigen::Vector3d(key[0], key[1], key[2]);
    options.validate();  // --key-light 0 0 0 or inf: the option's error, before any mesh is read
    struct Input {
      fm::Mesh mesh;
      std::vector<Eigen::Vector3f> colors;
      const fm::Paint* paint = nullptr;  // brows and hairline of the built-in face
    };
    if (rig_path.empty() && !meshes.empty()) {
      // meshes of the generic face (e.g. faceanim --rig generic) get the generic face's colours
      const fm::Rig generic = fm::make_generic_face().rig;
      const fm::MeshDocument first = fm::read_mesh_document(meshes.front());
      if (first.triangles().vertex_count() != rig.vertex_count &&
          first.triangles().vertex_count() == generic.vertex_count)
        rig = generic;
    }
    const fm::Paint* paint = no_paint ? nullptr : fm::paint_for(rig);
    std::vector<Input> inputs;
    fm::Vertices box(2, 3);  // bounding box of all meshes (rows: min, max)
    for (const auto& path : meshes) {
      const fm::MeshDocument doc = fm::read_mesh_document(path);
      Input in{doc.triangles(), {}};
      const bool fits = in.mesh.vertex_count() == rig.vertex_count;
      if (!rig_path.empty() && !fits) throw emoface::InvalidInput(path + ": mesh does not fit the rig's vertex count");
      if (fits) {
        // a rig's mesh files are in the mesh frame: render in the rig frame, where the rig's colours live
        for (long v = 0; v < in.mesh.vertices.rows(); ++v) {
          if (!rig.frame.is_identity()) in.mesh.vertices.row(v) = rig.frame.to_rig(in.mesh.vertices.row(v).transpose()).transpose();
        }
        if (!doc.vertex_colors().empty() && !fm::paint_for(rig)) {
          in.colors =
              doc.vertex_colors();  // a user's rigged mesh: their own colours (OBJ, PLY, COLOR_0)
        } else {
          if (colors.empty()) colors = fm::material_colors(rig, in.mesh);
          in.colors = colors;
          in.paint = paint;
        }
      } else {
        in.colors = doc.vertex_colors();  // the file's own colours, else uniform skin
      }
      const Eigen::RowVector3d lo = in.mesh.vertices.colwise().minCoeff(), hi = in.mesh.vertices.colwise().maxCoeff();
      box.row(0) = inputs.empty() ? lo : box.row(0).cwiseMin(lo);
      box.row(1) = inputs.empty() ? hi : box.row(1).cwiseMax(hi);
      inputs.push_back(std::move(in));
    }
    if (camera == "auto") {
      fm::Vertices corners(8, 3);  // of the common bounding box: one camera for all, frames stay comparable
      for (int c = 0; c < 8; ++c) corners.row(c) << box((c & 1), 0), box((c >> 1) & 1, 1), box((c >> 2) & 1, 2);
      options = fm::frame_camera(corners, options);
    } else {
      for (std::size_t i = 0; i < inputs.size(); ++i) {
        if (fm::visible_fraction(inputs[i].mesh.vertices, options) == 0.0) {
          throw emoface::InvalidInput(meshes[i] + ": nothing of the mesh would be visible with the fixed camera (try --camera auto)");
        }
      }
    }
    std::vector<core::Image> images;
    for (const auto& in : inputs) images.push_back(fm::render(in.mesh, in.colors, {}, options, in.paint));
    auto numbered = [](const std::string& base, std::size_t i) {
      const std::filesystem::path p(base);
      char suffix[32];
      std::snprintf(suffix, sizeof suffix, "_%04zu", i);
      return (p.parent_path() / (p.stem().string() + suffix + p.extension().string())).string();
    };
    if (!out.empty()) {
      if (sheet > 0) {
        core::write_png(out, core::tile(images, sheet));
      } else if (images.size() == 1) {
        core::write_png(out, images[0]);
      } else {
        for (std::size_t i = 0; i < images.size(); ++i)
          core::write_png(numbered(out, i), images[i]);
      }
    }
    if (!video.empty()) {
      emoface::core::VideoOptions vo;
      vo.width = images.front().width;
      vo.height = images.front().height;
      vo.fps = fps;
      vo.audio_path = audio;
      emoface::core::VideoWriter writer(video, vo);
      for (const auto& image : images) writer.add_frame(image.rgb);
      writer.finish();
    }
    return 0;
  });
}
