#pragma once
// A small software rasteriser (z-buffer, per-pixel Phong shading of interpolated normals) for
// looking at faces headlessly. It renders into core::Image (emoface/core/image.hpp), which also
// makes contact sheets (core::tile), PNG files (core::write_png) and video frames.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "emoface/core/image.hpp"
#include "emoface/facemesh/mesh.hpp"
#include "emoface/facemesh/rig.hpp"

namespace emoface::facemesh {

enum class View { Front, ThreeQuarter };
std::string to_string(View view);
View view_from_string(std::string_view name);

struct RenderOptions {
  View view = View::Front;
  int width = 480;               ///< pixels, [16, 8192]
  int height = 560;              ///< pixels, [16, 8192]
  double yaw = 0.0;              ///< extra camera yaw about the head centre, radians, [-π, π]
  double field_of_view = 0.35;   ///< vertical field of view, radians, (0.05, 2.5)
  double distance = 0.75;        ///< camera distance from the framing centre, m, > 0
  Eigen::Vector3d target = Eigen::Vector3d(0.0, -0.01, 0.0);  ///< framing centre, m
  Eigen::Vector3d background = Eigen::Vector3d(0.93, 0.94, 0.96);  ///< RGB in [0,1]
  double shininess = 24.0;       ///< Phong exponent, [1, 512]
  double specular = 0.18;        ///< specular strength, [0, 1]
  /// Rounds of averaging the shading normals over the triangles around each vertex (area-weighted),
  /// [0, 10]: smooth shading across seams of thin triangles (the lips' stitching, folding lids);
  /// 0 = the plain area-weighted vertex normals.
  int normal_smoothing = 1;
  /// Direction towards the key light in the head frame (x to the front view's right, y up, z
  /// towards the front camera), normalised when rendering; finite and not zero. The default lights
  /// the face from the upper left at ≈ 34° elevation; the fill light and ambient term are fixed.
  Eigen::Vector3d key_light = Eigen::Vector3d(-0.35, 0.55, 0.75);
  /// Strength of the key light's cast shadow, [0, 1] (0 = none): the key light is blocked where
  /// other parts of the mesh stand between it and the surface (under the upper lip and nose, inside
  /// an open mouth, under the brows). An orthographic depth map from the light (1024², 3×3
  /// percentage-closer filtered). Off by default: on the default face it did not help the
  /// expression oracle (docs/muscles.md).
  double shadow = 0.0;
  /// Strength of ambient occlusion, [0, 1] (0 = none): the ambient and fill terms are scaled by the
  /// share of the sky each vertex sees over its normal's hemisphere (cosine-weighted, from
  /// orthographic depth maps in `occlusion_directions` directions), so cavities — the inside of an
  /// open mouth, the corners of the eyes, the nostrils — stay dark instead of lit by a uniform
  /// ambient term. Off by default, like `shadow`.
  double occlusion = 0.0;
  int occlusion_directions = 48;  ///< [4, 512]
  void validate() const;
};

/// Per-vertex linear RGB colours in [0,1] for a rig's materials (skin, lips, eyes, brows, hair).
std::vector<Eigen::Vector3f> material_colors(const Rig& rig);
/// The same, with the skin/brow/hair boundaries softened over the mesh (`iterations` rounds of averaging
/// with edge neighbours of those materials; lips and eyes keep crisp edges), so that colour edges on a
/// coarse grid read as gradients instead of staircases. `iterations` in [0, 20].
std::vector<Eigen::Vector3f> material_colors(const Rig& rig, const Mesh& mesh, int iterations = 2);

/// Surface paint (a texture): per-vertex coordinates into an RGBA image, sampled per pixel (bilinear)
/// at the perspective-correct interpolated coordinates. Painted detail (brows, hairline) is as sharp
/// as the image, whatever the mesh density, and moves and stretches with the surface. A triangle with
/// a vertex without coordinates (NaN) keeps the vertex colours.
struct Paint {
  std::vector<Eigen::Vector2f> uv;      ///< per vertex, in [0, 1]² (u right, v up), or NaN = unpainted
  int width = 0;                        ///< texels, [1, 8192]
  int height = 0;                       ///< texels, [1, 8192]
  std::vector<Eigen::Vector4f> texels;  ///< width*height, row 0 at v = 0; RGB in [0, 1], A = coverage
  /// Throws InvalidInput: sizes (uv per vertex, texels = width·height), uv outside [0, 1]² or ±inf,
  /// texels outside [0, 1] or NaN.
  void validate(std::size_t vertex_count) const;
  /// Bilinear lookup, (u, v) clamped to [0, 1]².
  Eigen::Vector4f sample(float u, float v) const;
};

/// Renders `mesh`. `colors` (per vertex) may be empty (uniform skin). `crease` (per vertex, optional)
/// marks vertices shaded with their face normal instead of the averaged normal — the thesis' fix for the
/// "unrepresentative vertex normal" at wrinkle feet (§2.4.1). Back faces are shaded dark (mouth inside).
/// `paint` (optional, not owned) is blended over the vertex colours by its alpha.
core::Image render(const Mesh& mesh, const std::vector<Eigen::Vector3f>& colors,
                   const std::vector<std::uint8_t>& crease, const RenderOptions& options,
                   const Paint* paint = nullptr);

/// Fits the camera to `vertices` (#V by 3, any frame and units, +y up): target = bounding-box centre,
/// distance such that the projected vertices span about `fill` ∈ (0, 1] of the image (from the
/// bounding sphere, then two rounds of rescaling; never inside the sphere). View, yaw and field of
/// view as in `options`. Throws InvalidInput for no vertices, non-finite coordinates or a zero extent.
RenderOptions fit_camera(const Vertices& vertices, RenderOptions options, double fill = 0.9);
/// Where render() draws the point p: (x, y) in pixels (origin top left, y down) and its depth along
/// the view direction (z, > 0 in front of the camera). Throws InvalidInput for invalid options.
Eigen::Vector3d project_point(const RenderOptions& options, const Eigen::Vector3d& p);
/// Fraction of `vertices` that project inside the image, in front of the camera (0: nothing visible).
double visible_fraction(const Vertices& vertices, const RenderOptions& options);
/// `options` unchanged when the bounding box of `vertices` is in front of its camera, its centre in the
/// middle half of the image and its projected height in [min_fill, 2] image heights (a face in the
/// thesis frame keeps the usual framing); otherwise fit_camera. Throws like fit_camera.
RenderOptions frame_camera(const Vertices& vertices, const RenderOptions& options, double min_fill = 0.3);

}  // namespace emoface::facemesh
