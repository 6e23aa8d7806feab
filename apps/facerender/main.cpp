// facerender: meshes -> PNG (one image, one per mesh, or a contact sheet) and MP4 via ffmpeg.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

#include "emoface/cli/cli.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/facemesh/io.hpp"
#include "emoface/facemesh/mesh_io.hpp"
#include "emoface/facemesh/render.hpp"

namespace fm = emoface::facemesh;

int main(int argc, char** argv) {
  CLI::App app{"Render face meshes to PNG with a software rasteriser (Phong shading).\n"
               "Example: facerender out/frame_0000.obj out/frame_0001.obj --sheet 2 --out sheet.png"};
  std::vector<std::string> meshes;
  std::string out, view = "front", rig_path, video;
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
  app.add_option("--video", video, "Also encode the frames to this MP4 with the ffmpeg binary");
  app.add_option("--fps", fps, "Video frame rate")->check(CLI::Range(1, 240));
  if (auto code = emoface::cli::parse(app, argc, argv)) return *code;
  return emoface::cli::run("facerender", [&]() {
    if (out.empty() && video.empty()) throw emoface::InvalidInput("give --out FILE.png and/or --video FILE.mp4");
    std::vector<Eigen::Vector3f> colors;
    std::size_t color_vertices = 0;
    if (!rig_path.empty()) {
      const auto rig = fm::read_rig(rig_path);
      colors = fm::material_colors(rig);
      color_vertices = rig.vertex_count;
    } else {
      const auto face = fm::make_default_face();
      colors = fm::material_colors(face.rig);
      color_vertices = face.rig.vertex_count;
    }
    fm::RenderOptions options;
    options.view = fm::view_from_string(view);
    options.width = width;
    options.height = height;
    options.yaw = yaw;
    std::vector<fm::Image> images;
    for (const auto& path : meshes) {
      const auto mesh = fm::read_mesh(path);
      const bool fits = mesh.vertex_count() == color_vertices;
      if (!rig_path.empty() && !fits) throw emoface::InvalidInput(path + ": mesh does not fit the rig's vertex count");
      images.push_back(fm::render(mesh, fits ? colors : std::vector<Eigen::Vector3f>{}, {}, options));
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
      const auto dir = std::filesystem::temp_directory_path() / ("facerender_" + std::to_string(::getpid()));
      std::filesystem::create_directories(dir);
      for (std::size_t i = 0; i < images.size(); ++i) fm::write_png(numbered((dir / "f.png").string(), i), images[i]);
      const std::string tmp = video + ".part.mp4";
      const std::string cmd = "ffmpeg -loglevel error -y -framerate " + std::to_string(fps) + " -i '" +
                              (dir / "f_%04d.png").string() + "' -pix_fmt yuv420p -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' '" + tmp + "'";
      const int rc = std::system(cmd.c_str());
      std::filesystem::remove_all(dir);
      if (rc != 0) {
        std::filesystem::remove(tmp);
        throw emoface::IoError("ffmpeg failed (is the ffmpeg binary installed?) for " + video);
      }
      std::filesystem::rename(tmp, video);
    }
    return 0;
  });
}
