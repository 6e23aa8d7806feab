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
#include "emoface/facemesh/mesh_io.hpp"
#include "emoface/facemesh/render.hpp"

namespace fm = emoface::facemesh;

int main(int argc, char** argv) {
  CLI::App app{"Render face meshes to PNG with a software rasteriser (Phong shading).\n"
               "Example: facerender out/frame_0000.obj out/frame_0001.obj --sheet 2 --out sheet.png"};
  std::vector<std::string> meshes;
  std::string out, view = "front", rig_path, video, audio;
  int sheet = 0, width = 480, height = 560, fps = 25;
  double yaw = 0.0;
  app.add_option("meshes", meshes, "Mesh files (OBJ/PLY/OFF)")->required();
  app.add_option("--out", out, "Output PNG; with several meshes and no --sheet, NAME_0000.png ... are written");
  app.add_option("--view", view, "front or threequarter")->check(CLI::IsMember({"front", "threequarter"}));
  app.add_option("--sheet", sheet, "Tile all meshes into one contact sheet with this many columns")->check(CLI::Range(1, 64));
  app.add_option("--rig", rig_path, "Rig for material colours (default: built-in face when the vertex count matches)");
  app.add_option("--width", width, "Image width in pixels")->check(CLI::Range(16, 8192));
  app.add_option("--height", height, "Image height in pixels")->check(CLI::Range(16, 8192));
  app.add_option("--yaw", yaw, "Extra camera yaw in radians")->check(CLI::Range(-3.14159, 3.14159));
  app.add_option("--video", video, "Also encode the frames to a video (.mp4/.mov/.mkv/.gif) with the ffmpeg binary");
  app.add_option("--audio", audio, "Audio file (e.g. WAV) muxed into --video");
  app.add_option("--fps", fps, "Video frame rate")->check(CLI::Range(1, 240));
  if (auto code = emoface::cli::parse(app, argc, argv)) return *code;
  return emoface::cli::run("facerender", [&]() {
    if (out.empty() && video.empty()) throw emoface::InvalidInput("give --out FILE.png and/or --video FILE.mp4");
    if (!audio.empty() && video.empty()) throw emoface::InvalidInput("--audio needs --video");
    const fm::Rig rig = rig_path.empty() ? fm::make_default_face().rig : fm::read_rig(rig_path);
    std::vector<Eigen::Vector3f> colors;  // from the first mesh that fits the rig (same topology)
    fm::RenderOptions options;
    options.view = fm::view_from_string(view);
    options.width = width;
    options.height = height;
    options.yaw = yaw;
    const fm::Paint* paint = fm::paint_for(rig);  // brows and hairline of the built-in face
    std::vector<fm::Image> images;
    for (const auto& path : meshes) {
      const auto mesh = fm::read_mesh(path);
      const bool fits = mesh.vertex_count() == rig.vertex_count;
      if (!rig_path.empty() && !fits) throw emoface::InvalidInput(path + ": mesh does not fit the rig's vertex count");
      if (fits && colors.empty()) colors = fm::material_colors(rig, mesh);
      images.push_back(fm::render(mesh, fits ? colors : std::vector<Eigen::Vector3f>{}, {}, options,
                                  fits ? paint : nullptr));
    }
    auto numbered = [](const std::string& base, std::size_t i) {
      const std::filesystem::path p(base);
      char suffix[32];
      std::snprintf(suffix, sizeof suffix, "_%04zu", i);
      return (p.parent_path() / (p.stem().string() + suffix + p.extension().string())).string();
    };
    if (!out.empty()) {
      if (sheet > 0) {
        fm::write_png(out, fm::contact_sheet(images, sheet));
      } else if (images.size() == 1) {
        fm::write_png(out, images[0]);
      } else {
        for (std::size_t i = 0; i < images.size(); ++i) fm::write_png(numbered(out, i), images[i]);
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
