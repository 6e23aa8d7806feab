#pragma once
// Pictures of landmark motion for docs and the mgraph CLI: poses drawn as dots (coloured by region),
// contact sheets of frames, trajectory plots, encoded as PNG (zlib). No text rendering.
#include <cstdint>
#include <string>
#include <vector>

#include "emoface/motiongraph/database.hpp"

namespace emoface::motiongraph {

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  ///< row-major, 3 bytes per pixel
  Image() = default;
  Image(int w, int h, std::uint8_t grey = 255);
  void set(int x, int y, std::uint32_t colour);  ///< 0xRRGGBB; outside pixels are ignored
};

struct RenderOptions {
  int width = 640;           ///< image size of one pose (pixels), [16, 8192]
  int height = 490;
  double scale = 1.0;        ///< landmark units → pixels
  double dot_radius = 2.5;   ///< pixels, > 0
  void validate() const;
};

/// Draws one pose; `groups[i]` picks the colour of landmark i (empty = one colour).
void draw_pose(Image& image, const Pose& pose, const std::vector<int>& groups, const RenderOptions& options,
               int offset_x = 0, int offset_y = 0, double extra_scale = 1.0);

/// Frames tiled left-to-right, top-to-bottom, each cell options.width·cell_scale wide.
Image contact_sheet(const std::vector<Pose>& frames, const std::vector<int>& groups, int columns,
                    double cell_scale, const RenderOptions& options = {});

/// Line plot of several series (one colour each) over frames, axes box and per-frame ticks.
Image plot_series(const std::vector<std::vector<double>>& series, int width = 640, int height = 320);

/// PNG file bytes (8-bit RGB, zlib).
std::string encode_png(const Image& image);

}  // namespace emoface::motiongraph
