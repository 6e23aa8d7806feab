#pragma once
// Pictures of landmark motion for docs and the mgraph CLI: poses drawn as dots (coloured by
// region), contact sheets of frames, trajectory plots, as core::Image (core::encode_png makes the
// PNG). No text rendering.
#include <cstdint>
#include <string>
#include <vector>

#include "emoface/core/image.hpp"
#include "emoface/motiongraph/database.hpp"

namespace emoface::motiongraph {

/// Maps landmark coordinates to pixels: pixel = offset + scale · coordinate.
struct View {
  double scale = 1.0;
  double offset_x = 0.0, offset_y = 0.0;
};

/// The view that fits the bounding box of all frames (x, y columns) into width × height pixels with
/// a relative margin on each side, preserving the aspect ratio.
View fit_view(const std::vector<Pose>& frames, int width, int height, double margin = 0.08);

/// Draws one pose as dots; `groups[i]` picks the colour of landmark i (empty = one colour).
void draw_pose(core::Image& image, const Pose& pose, const std::vector<int>& groups,
               const View& view, double dot_radius = 2.5);

/// The iBUG-68 face outline as polylines of landmark ids: jaw 0–16, brows 17–21 and 22–26, nose bridge
/// 27–30, nose base 31–35, eyes 36–41 and 42–47 and lips 48–59 and 60–67 (closed: the first id is
/// repeated at the end).
const std::vector<std::vector<int>>& ibug68_contours();

/// The iBUG-68 contours through the landmarks a pose has: `landmark_ids[r]` is the iBUG id of pose row r
/// (e.g. MotionGraph::landmark_ids() of synthesized poses; 0…67 for full poses). Each contour keeps its
/// present landmarks in order, as pose rows; contours with fewer than 2 present landmarks are dropped.
std::vector<std::vector<int>> contours_for(const std::vector<int>& landmark_ids);

/// Draws polylines through pose rows (`contours` as from contours_for) in `colour` (0xRRGGBB).
void draw_contours(core::Image& image, const Pose& pose,
                   const std::vector<std::vector<int>>& contours, const View& view,
                   std::uint32_t colour = 0xb0b0b0);

/// Frames tiled left-to-right, top-to-bottom in cells of cell_width × cell_height pixels, all with
/// the same view (so motion is visible across cells); `contours` (pose rows, contours_for) are drawn
/// as light lines under the dots (issue 19: sheets with contour lines).
core::Image contact_sheet(const std::vector<Pose>& frames, const std::vector<int>& groups,
                          int columns, int cell_width = 160, int cell_height = 140,
                          const std::vector<std::vector<int>>& contours = {});

/// Line plot of several series over frames (core::draw_chart, the one chart routine): each series
/// in its own horizontal band, scaled to its own range (at least `min_range`, filling 85 % of the
/// band), with a frame tick per sample. No text; non-finite values are gaps. Throws InvalidInput
/// for sizes outside [32, 8192] pixels, bands under 8 pixels or min_range ≤ 0.
core::Image plot_series(const std::vector<std::vector<double>>& series, int width = 640,
                        int height = 320, double min_range = 2.0);

/// Trajectories of a landmark sequence: for each group, the landmark with the largest range of
/// `coordinate` (0 = x, 1 = y) is plotted over the frames, one colour per group.
core::Image plot_trajectories(const std::vector<Pose>& frames, const std::vector<int>& groups,
                              int coordinate = 1, int width = 640, int height = 320);

}  // namespace emoface::motiongraph
