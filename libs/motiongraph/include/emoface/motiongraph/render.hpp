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

/// Maps landmark coordinates to pixels: pixel = offset + scale · coordinate.
struct View {
  double scale = 1.0;
  double offset_x = 0.0, offset_y = 0.0;
};

/// The view that fits the bounding box of all frames (x, y columns) into width × height pixels with
/// a relative margin on each side, preserving the aspect ratio.
View fit_view(const std::vector<Pose>& frames, int width, int height, double margin = 0.08);

/// Draws one pose as dots; `groups[i]` picks the colour of landmark i (empty = one colour).
void draw_pose(Image& image, const Pose& pose, const std::vector<int>& groups, const View& view,
               double dot_radius = 2.5);

/// Frames tiled left-to-right, top-to-bottom in cells of cell_width × cell_height pixels, all with
/// the same view (so motion is visible across cells).
Image contact_sheet(const std::vector<Pose>& frames, const std::vector<int>& groups, int columns,
                    int cell_width = 160, int cell_height = 140);

/// Line plot of several series over frames: each series in its own horizontal band, scaled to its
/// own range (at least `min_range`), with a frame tick per sample. No text.
Image plot_series(const std::vector<std::vector<double>>& series, int width = 640, int height = 320,
                  double min_range = 2.0);

/// Trajectories of a landmark sequence: for each group, the landmark with the largest range of
/// `coordinate` (0 = x, 1 = y) is plotted over the frames, one colour per group.
Image plot_trajectories(const std::vector<Pose>& frames, const std::vector<int>& groups, int coordinate = 1,
                        int width = 640, int height = 320);

/// PNG file bytes (8-bit RGB, zlib).
std::string encode_png(const Image& image);

}  // namespace emoface::motiongraph
