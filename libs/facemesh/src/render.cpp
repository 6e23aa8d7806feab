// Software rasteriser: perspective camera, z-buffer, per-pixel Phong shading (Bui Tuong Phong 1975,
// the shading the thesis uses in §2.3), 4-sample rotated-grid anti-aliasing, deferred shading,
// optional surface paint (texture), optional key-light shadow (depth map) and per-vertex ambient
// occlusion, into a core::Image.
#include "emoface/facemesh/render.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>

#include "emoface/core/errors.hpp"

namespace emoface::facemesh {
namespace {
constexpr double kPi = 3.14159265358979323846;

/// Orthographic depth map of a mesh seen from the unit direction `toward` (surface → light): per
/// texel the largest p·toward of the triangles over the texel centre, i.e. the surface nearest the
/// light (both sides of every triangle occlude). The map spans the mesh's projection with a
/// one-texel margin.
class DepthMap {
 public:
  DepthMap(const Vertices& vertices, const Faces& faces, const Eigen::Vector3d& toward,
           int resolution)
      : d_(toward.normalized()), n_(resolution) {
    u_ = (std::abs(d_.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY())
             .cross(d_)
             .normalized();
    v_ = d_.cross(u_);
    const long nv = vertices.rows();
    std::vector<Eigen::Vector3d> q(static_cast<std::size_t>(nv));
    double xmin = std::numeric_limits<double>::infinity(), ymin = xmin, xmax = -xmin, ymax = -xmin;
    for (long i = 0; i < nv; ++i) {
      const Eigen::Vector3d p = vertices.row(i);
      q[static_cast<std::size_t>(i)] = {p.dot(u_), p.dot(v_), p.dot(d_)};
      xmin = std::min(xmin, p.dot(u_)), xmax = std::max(xmax, p.dot(u_));
      ymin = std::min(ymin, p.dot(v_)), ymax = std::max(ymax, p.dot(v_));
    }
    texel_ = std::max({xmax - xmin, ymax - ymin, 1e-12}) / (n_ - 2);
    x0_ = xmin - texel_;
    y0_ = ymin - texel_;
    top_.assign(static_cast<std::size_t>(n_) * n_, -std::numeric_limits<float>::infinity());
    for (auto& p : q)
      p = {(p.x() - x0_) / texel_ - 0.5, (p.y() - y0_) / texel_ - 0.5,
           p.z()};  // texel-centre coordinates
    for (long f = 0; f < faces.rows(); ++f) {
      const Eigen::Vector3d& a = q[static_cast<std::size_t>(faces(f, 0))];
      const Eigen::Vector3d& b = q[static_cast<std::size_t>(faces(f, 1))];
      const Eigen::Vector3d& c = q[static_cast<std::size_t>(faces(f, 2))];
      const double area = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
      if (area == 0.0) continue;
      const int i0 = std::max(0, static_cast<int>(std::ceil(std::min({a.x(), b.x(), c.x()}))));
      const int i1 =
          std::min(n_ - 1, static_cast<int>(std::floor(std::max({a.x(), b.x(), c.x()}))));
      const int j0 = std::max(0, static_cast<int>(std::ceil(std::min({a.y(), b.y(), c.y()}))));
      const int j1 =
          std::min(n_ - 1, static_cast<int>(std::floor(std::max({a.y(), b.y(), c.y()}))));
      for (int j = j0; j <= j1; ++j) {
        for (int i = i0; i <= i1; ++i) {
          const double w0 = ((b.x() - i) * (c.y() - j) - (b.y() - j) * (c.x() - i)) / area;
          const double w1 = ((c.x() - i) * (a.y() - j) - (c.y() - j) * (a.x() - i)) / area;
          const double w2 = 1.0 - w0 - w1;
          if (w0 < 0.0 || w1 < 0.0 || w2 < 0.0) continue;
          float& t = top_[static_cast<std::size_t>(j) * n_ + i];
          t = std::max(t, static_cast<float>(w0 * a.z() + w1 * b.z() + w2 * c.z()));
        }
      }
    }
    // Triangles thinner than a texel cover no texel centre: their vertices still occlude.
    for (const auto& p : q) {
      const int i = std::clamp(static_cast<int>(std::lround(p.x())), 0, n_ - 1);
      const int j = std::clamp(static_cast<int>(std::lround(p.y())), 0, n_ - 1);
      float& t = top_[static_cast<std::size_t>(j) * n_ + i];
      t = std::max(t, static_cast<float>(p.z()));
    }
  }
  double texel() const { return texel_; }
  /// Share of the (2r+1)² texels around p where p, raised by `bias` towards the light, is not below
  /// the stored surface: 1 = fully lit.
  double lit(const Eigen::Vector3d& p, double bias, int r) const {
    const int i = static_cast<int>(std::lround((p.dot(u_) - x0_) / texel_ - 0.5));
    const int j = static_cast<int>(std::lround((p.dot(v_) - y0_) / texel_ - 0.5));
    const float z = static_cast<float>(p.dot(d_) + bias);
    int lit = 0, all = 0;
    for (int dj = -r; dj <= r; ++dj) {
      for (int di = -r; di <= r; ++di) {
        ++all;
        const int x = i + di, y = j + dj;
        if (x < 0 || y < 0 || x >= n_ || y >= n_ || z >= top_[static_cast<std::size_t>(y) * n_ + x])
          ++lit;
      }
    }
    return static_cast<double>(lit) / all;
  }

 private:
  Eigen::Vector3d d_, u_, v_;
  int n_;
  double x0_ = 0.0, y0_ = 0.0, texel_ = 1.0;
  std::vector<float> top_;
};

/// Depth bias for a surface whose normal makes cos_angle with the light: one texel plus the depth a
/// slope of that angle gains over two texels (slope-scaled bias), capped for grazing light.
double shadow_bias(double texel, double cos_angle) {
  const double c = std::clamp(cos_angle, 0.2, 1.0);
  return texel * (1.0 + 2.0 * std::sqrt(1.0 - c * c) / c);
}

/// Per-vertex ambient occlusion: the cosine-weighted share of `directions` (a Fibonacci sphere)
/// over each vertex's normal hemisphere in which no part of the mesh stands between the vertex and
/// the sky.
std::vector<float> ambient_occlusion(const Vertices& vertices, const Faces& faces,
                                     const Vertices& normals, int directions) {
  constexpr int kResolution = 256;
  const long nv = vertices.rows();
  std::vector<double> seen(static_cast<std::size_t>(nv), 0.0),
      total(static_cast<std::size_t>(nv), 0.0);
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  for (int k = 0; k < directions; ++k) {
    const double y = 1.0 - (k + 0.5) * 2.0 / directions,
                 rad = std::sqrt(std::max(0.0, 1.0 - y * y));
    const Eigen::Vector3d dir(rad * std::cos(golden * k), y, rad * std::sin(golden * k));
    const DepthMap map(vertices, faces, dir, kResolution);
    for (long v = 0; v < nv; ++v) {
      const Eigen::Vector3d n = normals.row(v);
      const double c = n.dot(dir);
      if (c <= 0.0) continue;
      const Eigen::Vector3d p = Eigen::Vector3d(vertices.row(v)) + map.texel() * n;
      seen[static_cast<std::size_t>(v)] += c * map.lit(p, shadow_bias(map.texel(), c), 0);
      total[static_cast<std::size_t>(v)] += c;
    }
  }
  std::vector<float> out(static_cast<std::size_t>(nv), 1.0f);
  for (std::size_t v = 0; v < out.size(); ++v) {
    if (total[v] > 0.0) out[v] = static_cast<float>(seen[v] / total[v]);
  }
  return out;
}
}  // namespace

std::string to_string(View view) { return view == View::Front ? "front" : "threequarter"; }
View view_from_string(std::string_view name) {
  if (name == "front") return View::Front;
  if (name == "threequarter") return View::ThreeQuarter;
  throw InvalidInput("unknown view '" + std::string(name) + "' (front or threequarter)");
}

void RenderOptions::validate() const {
  auto check = [](bool ok, const char* what) {
    if (!ok) throw InvalidInput(std::string("RenderOptions: ") + what);
  };
  check(width >= 16 && width <= 8192 && height >= 16 && height <= 8192, "width/height must be in [16, 8192]");
  check(std::isfinite(yaw) && std::abs(yaw) <= kPi, "yaw must be in [-pi, pi]");
  check(field_of_view > 0.05 && field_of_view < 2.5, "field_of_view must be in (0.05, 2.5)");
  check(std::isfinite(distance) && distance > 0.0, "distance must be > 0");
  check(target.allFinite(), "target must be finite");
  check(background.allFinite() && background.minCoeff() >= 0.0 && background.maxCoeff() <= 1.0, "background in [0,1]");
  check(shininess >= 1.0 && shininess <= 512.0, "shininess must be in [1, 512]");
  check(specular >= 0.0 && specular <= 1.0, "specular must be in [0, 1]");
  check(normal_smoothing >= 0 && normal_smoothing <= 10, "normal_smoothing must be in [0, 10]");
  check(shadow >= 0.0 && shadow <= 1.0, "shadow must be in [0, 1]");
  check(occlusion >= 0.0 && occlusion <= 1.0, "occlusion must be in [0, 1]");
  check(key_light.allFinite() && key_light.norm() > 1e-9,
        "key_light must be a finite, non-zero direction");
  check(occlusion_directions >= 4 && occlusion_directions <= 512,
        "occlusion_directions must be in [4, 512]");
}

void Paint::validate(std::size_t vertex_count) const {
  if (width < 1 || width > 8192 || height < 1 || height > 8192)
    throw InvalidInput("Paint: width/height must be in [1, 8192]");
  if (texels.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height))
    throw InvalidInput("Paint: texels must hold width*height values");
  if (uv.size() != vertex_count) throw InvalidInput("Paint: one uv per vertex");
  for (std::size_t v = 0; v < uv.size(); ++v) {
    const Eigen::Vector2f& t = uv[v];
    if (std::isnan(t.x()) || std::isnan(t.y())) continue;
    if (!(t.x() >= 0.0f && t.x() <= 1.0f && t.y() >= 0.0f && t.y() <= 1.0f))
      throw InvalidInput("Paint: uv of vertex " + std::to_string(v) + " outside [0, 1]");
  }
  for (const auto& c : texels) {
    if (!c.allFinite() || !(c.minCoeff() >= 0.0f && c.maxCoeff() <= 1.0f))
      throw InvalidInput("Paint: texel values must be in [0, 1]");
  }
}

Eigen::Vector4f Paint::sample(float u, float v) const {
  const float fx = std::clamp(u, 0.0f, 1.0f) * static_cast<float>(width) - 0.5f;
  const float fy = std::clamp(v, 0.0f, 1.0f) * static_cast<float>(height) - 0.5f;
  const int x0 = std::clamp(static_cast<int>(std::floor(fx)), 0, width - 1),
            y0 = std::clamp(static_cast<int>(std::floor(fy)), 0, height - 1);
  const int x1 = std::min(x0 + 1, width - 1), y1 = std::min(y0 + 1, height - 1);
  const float a = std::clamp(fx - static_cast<float>(x0), 0.0f, 1.0f),
              b = std::clamp(fy - static_cast<float>(y0), 0.0f, 1.0f);
  auto t = [&](int x, int y) -> const Eigen::Vector4f& {
    return texels[static_cast<std::size_t>(y) * width + x];
  };
  return (1 - b) * ((1 - a) * t(x0, y0) + a * t(x1, y0)) +
         b * ((1 - a) * t(x0, y1) + a * t(x1, y1));
}

std::vector<Eigen::Vector3f> material_colors(const Rig& rig) {
  std::vector<Eigen::Vector3f> out(rig.materials.size());
  for (std::size_t v = 0; v < out.size(); ++v) {
    switch (rig.materials[v]) {
      case Material::Skin: out[v] = {0.87f, 0.69f, 0.58f}; break;
      case Material::Lip: out[v] = {0.72f, 0.45f, 0.42f}; break;
      case Material::EyeWhite: out[v] = {0.94f, 0.93f, 0.90f}; break;
      case Material::Iris:
        // mid brown: a blue-grey iris is as light as the skin in grey and the eye reads half shut
        // (docs/muscles.md, "Session 11")
        out[v] = {0.30f, 0.19f, 0.11f};
        break;
      case Material::Pupil: out[v] = {0.05f, 0.05f, 0.06f}; break;
      case Material::Brow:
        out[v] = {0.16f, 0.11f, 0.08f};
        break;
      case Material::Hair: out[v] = {0.28f, 0.19f, 0.13f}; break;
      case Material::MouthInterior:
        out[v] = {0.12f, 0.04f, 0.04f};
        break;
      case Material::Teeth: out[v] = {0.92f, 0.90f, 0.84f}; break;
      case Material::Tongue: out[v] = {0.70f, 0.36f, 0.36f}; break;
      case Material::Lash: out[v] = {0.10f, 0.08f, 0.07f}; break;
    }
  }
  return out;
}

std::vector<Eigen::Vector3f> material_colors(const Rig& rig, const Mesh& mesh, int iterations) {
  if (iterations < 0 || iterations > 20) throw InvalidInput("material_colors: iterations must be in [0, 20]");
  if (mesh.vertex_count() != rig.materials.size()) throw InvalidInput("material_colors: mesh and rig differ in vertex count");
  std::vector<Eigen::Vector3f> colors = material_colors(rig);
  auto soft = [&](int v) {
    const Material m = rig.materials[static_cast<std::size_t>(v)];
    return m == Material::Skin || m == Material::Brow || m == Material::Hair;
  };
  for (int it = 0; it < iterations; ++it) {
    std::vector<Eigen::Vector3f> sum(colors.size(), Eigen::Vector3f::Zero());
    std::vector<float> count(colors.size(), 0.0f);
    for (long f = 0; f < mesh.faces.rows(); ++f) {
      for (int k = 0; k < 3; ++k) {
        const int a = mesh.faces(f, k), b = mesh.faces(f, (k + 1) % 3);
        if (a < 0 || b < 0 || static_cast<std::size_t>(a) >= colors.size() || static_cast<std::size_t>(b) >= colors.size()) {
          throw InvalidInput("material_colors: face id out of range");
        }
        if (!soft(a) || !soft(b)) continue;
        sum[static_cast<std::size_t>(a)] += colors[static_cast<std::size_t>(b)];
        count[static_cast<std::size_t>(a)] += 1.0f;
        sum[static_cast<std::size_t>(b)] += colors[static_cast<std::size_t>(a)];
        count[static_cast<std::size_t>(b)] += 1.0f;
      }
    }
    for (std::size_t v = 0; v < colors.size(); ++v) {
      if (count[v] > 0.0f) colors[v] = 0.5f * colors[v] + 0.5f * sum[v] / count[v];
    }
  }
  return colors;
}

core::Image render(const Mesh& mesh, const std::vector<Eigen::Vector3f>& colors,
                   const std::vector<std::uint8_t>& crease, const RenderOptions& options,
                   const Paint* paint) {
  options.validate();
  const std::size_t nv = mesh.vertex_count();
  if (!colors.empty() && colors.size() != nv) throw InvalidInput("render: colors must be empty or one per vertex");
  if (!crease.empty() && crease.size() != nv) throw InvalidInput("render: crease must be empty or one per vertex");
  if (paint != nullptr && paint->uv.size() != nv)
    throw InvalidInput("render: paint must have one uv per vertex");
  for (long f = 0; f < mesh.faces.rows(); ++f) {
    for (int c = 0; c < 3; ++c) {
      if (mesh.faces(f, c) < 0 || static_cast<std::size_t>(mesh.faces(f, c)) >= nv) throw InvalidInput("render: face id out of range");
    }
  }
  // Anti-aliasing: 4 samples per pixel on a rotated grid (RGSS; offsets in 1/8 pixel, every row and
  // column of the 4×4 sub-grid used once), box-filtered. Near-horizontal and near-vertical edges
  // get 4 coverage levels instead of the 2 of a 2×2 ordered grid, at the same cost.
  constexpr int kSamples = 4;
  static constexpr double kOffX[kSamples] = {0.375, 0.875, 0.125, 0.625};
  static constexpr double kOffY[kSamples] = {0.125, 0.375, 0.625, 0.875};
  const int w = options.width, h = options.height;
  // Camera: orbit about the target; three-quarter = 35 degrees towards the subject's right.
  const double yaw = options.yaw + (options.view == View::ThreeQuarter ? -35.0 * kPi / 180.0 : 0.0);
  const Eigen::Vector3d forward(-std::sin(yaw), 0.0, -std::cos(yaw));  // camera looks along this
  const Eigen::Vector3d eye = options.target - options.distance * forward;
  const Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitY()).normalized();
  const Eigen::Vector3d up = right.cross(forward);
  const double focal = 0.5 * h / std::tan(0.5 * options.field_of_view);

  Vertices vn = vertex_normals(mesh.vertices, mesh.faces);
  if (options.normal_smoothing > 0) {
    // Shading normals averaged over the triangles around each vertex, each triangle weighted by its
    // area and carrying the mean of its three vertex normals: the fans of thin triangles where a
    // coarse rim meets a finer row (the lips' stitching) otherwise shade as wedges, and slivers
    // carry almost no weight. Geometry, depth and crease vertices (face normals) are unchanged.
    Vertices next(vn.rows(), 3);
    std::vector<double> area(static_cast<std::size_t>(mesh.faces.rows()));
    for (long f = 0; f < mesh.faces.rows(); ++f) {
      const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0)),
                            b = mesh.vertices.row(mesh.faces(f, 1)),
                            c = mesh.vertices.row(mesh.faces(f, 2));
      area[static_cast<std::size_t>(f)] = 0.5 * (b - a).cross(c - a).norm();
    }
    for (int it = 0; it < options.normal_smoothing; ++it) {
      next.setZero();
      for (long f = 0; f < mesh.faces.rows(); ++f) {
        const Eigen::RowVector3d m =
            area[static_cast<std::size_t>(f)] *
            (vn.row(mesh.faces(f, 0)) + vn.row(mesh.faces(f, 1)) + vn.row(mesh.faces(f, 2)));
        for (int k = 0; k < 3; ++k) next.row(mesh.faces(f, k)) += m;
      }
      for (long v = 0; v < next.rows(); ++v) {
        const double len = next.row(v).norm();
        if (len > 0.0)
          next.row(v) /= len;
        else
          next.row(v) = vn.row(v);
      }
      std::swap(vn, next);
    }
  }
  const Vertices fn = face_normals(mesh.vertices, mesh.faces);
  std::vector<Eigen::Vector3d> screen(nv);  // x, y pixels; z = depth along forward
  for (std::size_t v = 0; v < nv; ++v) {
    const Eigen::Vector3d d = Eigen::Vector3d(mesh.vertices.row(static_cast<long>(v))) - eye;
    const double z = d.dot(forward);
    screen[v] = {0.5 * w + focal * d.dot(right) / std::max(z, 1e-6), 0.5 * h - focal * d.dot(up) / std::max(z, 1e-6), z};
  }
  // Pass 1 (visibility): z-buffer with the winning face and its perspective-correct barycentric weights
  // per sample. Pass 2 shades each visible sample once (deferred shading), so hidden surfaces cost no
  // lighting. The winner is the same as shading in submission order with a strict depth test.
  const std::size_t samples = static_cast<std::size_t>(w) * h * kSamples;
  std::vector<double> inv_depth(samples, 0.0);  // 1/z: interpolates linearly in screen space, larger = closer
  std::vector<std::int32_t> face_of(samples, -1);
  std::vector<float> bary(2 * samples);
  for (long f = 0; f < mesh.faces.rows(); ++f) {
    const Eigen::Vector3d& a = screen[mesh.faces(f, 0)];
    const Eigen::Vector3d& b = screen[mesh.faces(f, 1)];
    const Eigen::Vector3d& c = screen[mesh.faces(f, 2)];
    if (a.z() <= 1e-4 || b.z() <= 1e-4 || c.z() <= 1e-4) continue;
    const double area = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
    if (area == 0.0) continue;
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({a.x(), b.x(), c.x()}))));
    const int x1 = std::min(w - 1, static_cast<int>(std::floor(std::max({a.x(), b.x(), c.x()}))));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({a.y(), b.y(), c.y()}))));
    const int y1 = std::min(h - 1, static_cast<int>(std::floor(std::max({a.y(), b.y(), c.y()}))));
    if (x0 > x1 || y0 > y1) continue;
    // Edge functions are affine in the sample position (px, py): w0 = k0 + px·d0x + py·d0y, ...
    const double inv_area = 1.0 / area;
    const double d0x = (b.y() - c.y()) * inv_area, d0y = (c.x() - b.x()) * inv_area;
    const double d1x = (c.y() - a.y()) * inv_area, d1y = (a.x() - c.x()) * inv_area;
    const double k0 = (b.x() * c.y() - b.y() * c.x()) * inv_area,
                 k1 = (c.x() * a.y() - c.y() * a.x()) * inv_area;
    const double iza = 1.0 / a.z(), izb = 1.0 / b.z(), izc = 1.0 / c.z();
    for (int y = y0; y <= y1; ++y) {
      for (int s = 0; s < kSamples; ++s) {
        const double py = y + kOffY[s], px0 = x0 + kOffX[s];
        double w0 = k0 + px0 * d0x + py * d0y;
        double w1 = k1 + px0 * d1x + py * d1y;
        std::size_t idx = (static_cast<std::size_t>(y) * w + x0) * kSamples + s;
        for (int x = x0; x <= x1; ++x, idx += kSamples, w0 += d0x, w1 += d1x) {
          const double w2 = 1.0 - w0 - w1;
          if (w0 < 0.0 || w1 < 0.0 || w2 < 0.0) continue;
          const double q0 = w0 * iza, q1 = w1 * izb, qs = q0 + q1 + w2 * izc;
          if (qs <= inv_depth[idx]) continue;  // not closer (z = 1/qs ≥ the stored depth)
          inv_depth[idx] = qs;
          face_of[idx] = static_cast<std::int32_t>(f);
          const double z = 1.0 / qs;
          bary[2 * idx] = static_cast<float>(q0 * z);
          bary[2 * idx + 1] = static_cast<float>(q1 * z);
        }
      }
    }
  }

  const Eigen::Vector3f background = options.background.cast<float>();
  const Eigen::Vector3d key_light = options.key_light.normalized();
  const Eigen::Vector3d fill_light = Eigen::Vector3d(0.6, 0.1, 0.5).normalized();
  const Eigen::Vector3d half = (key_light - forward).normalized();  // Blinn half vector, view = -forward
  const Eigen::Vector3f skin(0.87f, 0.69f, 0.58f);
  const Eigen::Vector3f cavity(0.18f, 0.07f, 0.07f);  // inside of the head: dark mouth cavity
  // specular * (n·h)^shininess from a table over n·h in [0, 1], interpolated linearly: with 4096 steps
  // the error is below s(s-1)/(8·4096²) ≈ 2e-5 for s = 64, far under one 8-bit level.
  constexpr int kSpecSteps = 4096;
  std::vector<double> spec_table(kSpecSteps + 2);
  for (int i = 0; i <= kSpecSteps; ++i)
    spec_table[static_cast<std::size_t>(i)] = options.specular * std::pow(static_cast<double>(i) / kSpecSteps, options.shininess);
  spec_table[kSpecSteps + 1] = spec_table[kSpecSteps];
  // Ambient occlusion per vertex and the key light's depth map (only when asked for).
  std::vector<float> ao;
  if (options.occlusion > 0.0 && nv > 0)
    ao = ambient_occlusion(mesh.vertices, mesh.faces, vn, options.occlusion_directions);
  std::optional<DepthMap> key_map;
  if (options.shadow > 0.0 && nv > 0) key_map.emplace(mesh.vertices, mesh.faces, key_light, 1024);
  const auto shade = [&](std::size_t idx) -> Eigen::Vector3f {
    const std::int32_t f = face_of[idx];
    if (f < 0) return background;
    const int ids[3] = {mesh.faces(f, 0), mesh.faces(f, 1), mesh.faces(f, 2)};
    const Eigen::Vector3d& a = screen[ids[0]];
    const Eigen::Vector3d& b = screen[ids[1]];
    const Eigen::Vector3d& c = screen[ids[2]];
    const bool back = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x()) > 0.0;
    const double w0 = bary[2 * idx], w1 = bary[2 * idx + 1];
    const double wk[3] = {w0, w1, 1.0 - w0 - w1};
    if (back) {
      // A back face is the inside of the head (dark mouth cavity) unless the surface around it
      // faces the camera: then it is a thin fold of skin (a closing lid, the lips' stitching pulled
      // over the rim), shaded with the interpolated vertex normals instead of as a dark streak.
      Eigen::Vector3d n = Eigen::Vector3d::Zero();
      for (int k = 0; k < 3; ++k) n += wk[k] * Eigen::Vector3d(vn.row(ids[k]));
      if (n.dot(forward) >= -0.05 * n.norm()) return cavity;
    }
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    Eigen::Vector3f base = Eigen::Vector3f::Zero();
    for (int k = 0; k < 3; ++k) {
      const bool use_face = !back && !crease.empty() && crease[static_cast<std::size_t>(ids[k])];
      normal += wk[k] * (use_face ? Eigen::Vector3d(fn.row(f)) : Eigen::Vector3d(vn.row(ids[k])));
      base += static_cast<float>(wk[k]) * (colors.empty() ? skin : colors[static_cast<std::size_t>(ids[k])]);
    }
    if (paint != nullptr) {
      const Eigen::Vector2f& t0 = paint->uv[static_cast<std::size_t>(ids[0])];
      const Eigen::Vector2f& t1 = paint->uv[static_cast<std::size_t>(ids[1])];
      const Eigen::Vector2f& t2 = paint->uv[static_cast<std::size_t>(ids[2])];
      if (!std::isnan(t0.x()) && !std::isnan(t1.x()) && !std::isnan(t2.x())) {
        const Eigen::Vector2f t = static_cast<float>(wk[0]) * t0 + static_cast<float>(wk[1]) * t1 +
                                  static_cast<float>(wk[2]) * t2;
        const Eigen::Vector4f pc = paint->sample(t.x(), t.y());
        base += pc.w() * (pc.head<3>() - base);
      }
    }
    if (normal.squaredNorm() > 0.0) normal.normalize();
    const double kd = std::max(0.0, normal.dot(key_light));
    const double fd = std::max(0.0, normal.dot(fill_light));
    double spec = 0.0;
    if (const double nh = normal.dot(half); nh > 0.0) {
      const double t = std::min(nh, 1.0) * kSpecSteps;
      const int i = static_cast<int>(t);
      spec = spec_table[static_cast<std::size_t>(i)] + (t - i) * (spec_table[static_cast<std::size_t>(i) + 1] - spec_table[static_cast<std::size_t>(i)]);
    }
    double ambient = 1.0, direct = 1.0;
    if (!ao.empty()) {
      double sky = 0.0;
      for (int k = 0; k < 3; ++k) sky += wk[k] * ao[static_cast<std::size_t>(ids[k])];
      ambient = 1.0 - options.occlusion * (1.0 - sky);
    }
    if (key_map && kd > 0.0) {
      Eigen::Vector3d p = Eigen::Vector3d::Zero();
      for (int k = 0; k < 3; ++k) p += wk[k] * Eigen::Vector3d(mesh.vertices.row(ids[k]));
      p += key_map->texel() * normal;  // normal offset: no self-shadowing acne
      direct = 1.0 - options.shadow * (1.0 - key_map->lit(p, shadow_bias(key_map->texel(), kd), 1));
    }
    spec *= direct;
    const double light = (0.22 + 0.22 * fd) * ambient + 0.68 * kd * direct;
    const Eigen::Vector3f out = base * static_cast<float>(light) + Eigen::Vector3f::Constant(static_cast<float>(spec));
    return out.cwiseMin(1.0f).cwiseMax(0.0f);
  };

  // Pass 2 fused with the box filter: each visible sample is shaded exactly once.
  core::Image image;
  image.width = options.width;
  image.height = options.height;
  image.rgb.resize(static_cast<std::size_t>(options.width) * options.height * 3);
  for (int y = 0; y < options.height; ++y) {
    for (int x = 0; x < options.width; ++x) {
      const std::size_t base_idx = (static_cast<std::size_t>(y) * w + x) * kSamples;
      Eigen::Vector3f sum = Eigen::Vector3f::Zero();
      for (int s = 0; s < kSamples; ++s) sum += shade(base_idx + s);
      sum /= static_cast<float>(kSamples);
      for (int k = 0; k < 3; ++k) {
        image.rgb[(static_cast<std::size_t>(y) * options.width + x) * 3 + k] =
            static_cast<std::uint8_t>(std::lround(std::min(1.0f, std::max(0.0f, sum[k])) * 255.0f));
      }
    }
  }
  return image;
}

}  // namespace emoface::facemesh
