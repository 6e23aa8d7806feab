#include "emoface/facemesh/render.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "test_util.hpp"

namespace emoface::facemesh {
namespace {

std::size_t non_background(const core::Image& im, const RenderOptions& o) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < im.rgb.size(); i += 3) {
    if (std::abs(im.rgb[i] - o.background.x() * 255) > 2 || std::abs(im.rgb[i + 1] - o.background.y() * 255) > 2) ++n;
  }
  return n;
}

TEST(Render, DrawsTheDefaultFaceInBothViews) {
  const Face f = make_generic_face();
  RenderOptions o;
  o.width = 96;
  o.height = 112;
  for (View v : {View::Front, View::ThreeQuarter}) {
    o.view = v;
    const core::Image im = render(f.mesh, material_colors(f.rig), {}, o);
    ASSERT_EQ(im.rgb.size(), 96u * 112u * 3u);
    const std::size_t covered = non_background(im, o);
    EXPECT_GT(covered, 96u * 112u / 4) << to_string(v);
    EXPECT_LT(covered, 96u * 112u) << to_string(v);
    // the centre of the image is the face, not the background
    const std::size_t c = (56u * 96u + 48u) * 3u;
    EXPECT_GT(std::abs(im.rgb[c] - 237), 3);
  }
}

// A 10 cm square at the origin facing the camera (+z), and 32×32 options centred on it.
Mesh front_square() {
  Mesh m;
  m.vertices.resize(4, 3);
  m.vertices << -0.05, -0.05, 0, 0.05, -0.05, 0, 0.05, 0.05, 0, -0.05, 0.05, 0;
  m.faces.resize(2, 3);
  m.faces << 0, 1, 2, 0, 2, 3;
  return m;
}

RenderOptions square_options() {
  RenderOptions o;
  o.width = o.height = 32;
  o.target = Eigen::Vector3d::Zero();
  return o;
}

TEST(Render, ShadingFollowsTheLight) {
  // A square facing the camera, then the same square turned away from the key light (which comes
  // from the upper left, −x): it must render darker.
  const Mesh m = front_square();
  RenderOptions o = square_options();
  const core::Image flat = render(m, {}, {}, o);
  Mesh tilted = m;
  for (long v = 0; v < 4; ++v) tilted.vertices(v, 2) = -tilted.vertices(v, 0);  // normal turns to +x
  const core::Image dark = render(tilted, {}, {}, o);
  const std::size_t c = (16u * 32u + 16u) * 3u;
  EXPECT_GT(flat.rgb[c], dark.rgb[c] + 10);
}

// RenderOptions::key_light: only its direction counts; a key light at or behind the horizon of a
// surface leaves it the ambient and fill terms alone; the light along the normal is the brightest.
TEST(Render, KeyLightDirectionIsAnOption) {
  const Mesh m = front_square();
  RenderOptions o = square_options();
  o.specular = 0.0;
  const core::Image by_default = render(m, {}, {}, o);
  o.key_light = Eigen::Vector3d(-0.7, 1.1, 1.5);  // the default, twice as long
  EXPECT_EQ(render(m, {}, {}, o).rgb, by_default.rgb);
  o.key_light = Eigen::Vector3d(0, 0, -1);  // behind the square
  const core::Image behind = render(m, {}, {}, o);
  o.key_light = Eigen::Vector3d(1, 0, 0);  // grazing
  EXPECT_EQ(render(m, {}, {}, o).rgb, behind.rgb);
  o.key_light = Eigen::Vector3d(0, 0, 1);  // along the normal
  const core::Image along = render(m, {}, {}, o);
  const std::size_t c = (16u * 32u + 16u) * 3u;
  EXPECT_GT(along.rgb[c], by_default.rgb[c]);
  EXPECT_GT(by_default.rgb[c], behind.rgb[c] + 40);
}

// The key light's direction and the light terms as render() has them (upper left front; fill from
// the right): lit = (0.22 + 0.22·fill)·ambient + 0.68·key·shadow.
const Eigen::Vector3d kKeyLight = Eigen::Vector3d(-0.35, 0.55, 0.75).normalized();
const Eigen::Vector3d kFillLight = Eigen::Vector3d(0.6, 0.1, 0.5).normalized();

// Appends the square [x0, x1] × [y0, y1] at depth z (facing +z), n × n quads, to m.
void add_square(Mesh& m, double x0, double x1, double y0, double y1, double z, int n) {
  const long base = m.vertices.rows(), nf = m.faces.rows();
  m.vertices.conservativeResize(base + (n + 1) * (n + 1), 3);
  m.faces.conservativeResize(nf + 2 * n * n, 3);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      m.vertices.row(base + j * (n + 1) + i) << x0 + (x1 - x0) * i / n, y0 + (y1 - y0) * j / n, z;
  long f = nf;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = static_cast<int>(base) + j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      m.faces.row(f++) << a, b, d;
      m.faces.row(f++) << a, d, c;
    }
}

std::uint8_t red_at(const core::Image& im, const RenderOptions& o, const Eigen::Vector3d& p) {
  const Eigen::Vector3d s = project_point(o, p);
  return im.rgb[(static_cast<std::size_t>(s.y()) * im.width + static_cast<std::size_t>(s.x())) * 3];
}

// A small square 5 cm in front of a large one: with the shadow on, the key light is blocked on the
// large square where the line to the light passes through the small one — there the colour is
// base·(0.22 + 0.22·fill) instead of base·(0.22 + 0.22·fill + 0.68·key) (hand-computed below);
// elsewhere the image is unchanged.
TEST(Render, KeyLightShadowFallsBehindAnOccluder) {
  Mesh m;
  m.vertices.resize(0, 3);
  m.faces.resize(0, 3);
  add_square(m, -0.1, 0.1, -0.1, 0.1, 0.0, 4);
  add_square(m, -0.01, 0.01, -0.01, 0.01, 0.05, 1);
  RenderOptions o;
  o.width = o.height = 200;
  o.target = Eigen::Vector3d::Zero();
  o.specular = 0.0;
  const std::vector<Eigen::Vector3f> grey(static_cast<std::size_t>(m.vertex_count()),
                                          Eigen::Vector3f::Constant(0.8f));
  const core::Image lit = render(m, grey, {}, o);
  o.shadow = 1.0;
  const core::Image shadowed = render(m, grey, {}, o);
  // where the ray from the occluder's centre along −key meets z = 0
  const Eigen::Vector3d centre(0.0, 0.0, 0.05),
      behind = centre - (0.05 / kKeyLight.z()) * kKeyLight;
  const double key = kKeyLight.z(), fill = kFillLight.z();  // the plane's normal is +z
  EXPECT_NEAR(red_at(lit, o, behind), 255.0 * 0.8 * (0.22 + 0.22 * fill + 0.68 * key), 1.0);
  EXPECT_NEAR(red_at(shadowed, o, behind), 255.0 * 0.8 * (0.22 + 0.22 * fill), 1.0);
  // away from the shadow (and the occluder) nothing changes
  for (const Eigen::Vector3d& p :
       {Eigen::Vector3d(-0.06, 0.06, 0.0), Eigen::Vector3d(0.06, 0.06, 0.0),
        Eigen::Vector3d(-0.06, -0.06, 0.0), Eigen::Vector3d(0.0, 0.0, 0.05)})
    EXPECT_EQ(red_at(lit, o, p), red_at(shadowed, o, p)) << p.transpose();
  // a plane alone casts no shadow on itself (no acne from the depth map's texels)
  Mesh plane;
  plane.vertices.resize(0, 3);
  plane.faces.resize(0, 3);
  add_square(plane, -0.1, 0.1, -0.1, 0.1, 0.0, 4);
  const std::vector<Eigen::Vector3f> pg(25, Eigen::Vector3f::Constant(0.8f));
  o.shadow = 0.0;
  const core::Image a = render(plane, pg, {}, o);
  o.shadow = 1.0;
  EXPECT_EQ(render(plane, pg, {}, o).rgb, a.rgb);
}

// Ambient occlusion at the centre of the floor of an open box (floor 10 cm square, walls 5 cm high,
// open towards the camera): the cosine-weighted share of the sky it sees is the view factor from a
// point to the parallel square opening centred above it, 4 · (1/2π)·[A/√(1+A²)·atan(B/√(1+A²)) +
// B/√(1+B²)·atan(A/√(1+B²))] with A = B = half side / height = 1: 0.5541 (hand-computed; the
// point-to-rectangle view factor of radiative transfer tables). Recovered from the pixel with the
// light terms above; 512 directions.
TEST(Render, AmbientOcclusionIsTheViewFactorOfTheSky) {
  Mesh m;
  m.vertices.resize(0, 3);
  m.faces.resize(0, 3);
  add_square(m, -0.05, 0.05, -0.05, 0.05, 0.0, 8);  // the floor; its centre is vertex 40
  const auto wall = [&](const Eigen::Vector3d& a,
                        const Eigen::Vector3d& b) {  // a vertical quad from a to b, 5 cm deep
    const long v = m.vertices.rows(), f = m.faces.rows();
    m.vertices.conservativeResize(v + 4, 3);
    m.vertices.row(v) = a.transpose();
    m.vertices.row(v + 1) = b.transpose();
    m.vertices.row(v + 2) = (b + Eigen::Vector3d(0, 0, 0.05)).transpose();
    m.vertices.row(v + 3) = (a + Eigen::Vector3d(0, 0, 0.05)).transpose();
    m.faces.conservativeResize(f + 2, 3);
    m.faces.row(f) << static_cast<int>(v), static_cast<int>(v + 1), static_cast<int>(v + 2);
    m.faces.row(f + 1) << static_cast<int>(v), static_cast<int>(v + 2), static_cast<int>(v + 3);
  };
  wall({-0.05, -0.05, 0}, {0.05, -0.05, 0});
  wall({0.05, -0.05, 0}, {0.05, 0.05, 0});
  wall({0.05, 0.05, 0}, {-0.05, 0.05, 0});
  wall({-0.05, 0.05, 0}, {-0.05, -0.05, 0});
  RenderOptions o;
  o.width = o.height = 400;
  o.target = Eigen::Vector3d::Zero();
  o.specular = 0.0;
  o.occlusion = 1.0;
  o.occlusion_directions = 512;
  const std::vector<Eigen::Vector3f> grey(static_cast<std::size_t>(m.vertex_count()),
                                          Eigen::Vector3f::Constant(0.8f));
  const double red = red_at(render(m, grey, {}, o), o, Eigen::Vector3d::Zero()) / 255.0;
  const double key = kKeyLight.z(), fill = kFillLight.z();
  const double sky = (red / 0.8 - 0.68 * key) / (0.22 + 0.22 * fill);
  const double a = 1.0 / std::sqrt(2.0),
               expected = 4.0 / (2.0 * 3.14159265358979) * 2.0 * a * std::atan(a);
  EXPECT_NEAR(expected, 0.5541, 1e-4);
  EXPECT_NEAR(sky, expected, 0.04);
  // the floor alone sees the whole sky: occlusion changes nothing
  Mesh floor;
  floor.vertices.resize(0, 3);
  floor.faces.resize(0, 3);
  add_square(floor, -0.05, 0.05, -0.05, 0.05, 0.0, 8);
  const std::vector<Eigen::Vector3f> fg(81, Eigen::Vector3f::Constant(0.8f));
  const core::Image with = render(floor, fg, {}, o);
  o.occlusion = 0.0;
  EXPECT_EQ(render(floor, fg, {}, o).rgb, with.rgb);
}

TEST(Render, Validation) {
  RenderOptions o;
  o.width = 0;
  EXPECT_THROW(o.validate(), InvalidInput);
  o = RenderOptions{};
  o.field_of_view = 3.0;
  EXPECT_THROW(o.validate(), InvalidInput);
  for (double bad : {-0.1, 1.5, std::numeric_limits<double>::quiet_NaN()}) {
    o = RenderOptions{};
    o.shadow = bad;
    EXPECT_THROW(o.validate(), InvalidInput) << bad;
    o = RenderOptions{};
    o.occlusion = bad;
    EXPECT_THROW(o.validate(), InvalidInput) << bad;
  }
  o = RenderOptions{};
  o.occlusion_directions = 3;
  EXPECT_THROW(o.validate(), InvalidInput);
  for (const Eigen::Vector3d& bad : std::vector<Eigen::Vector3d>{
           Eigen::Vector3d::Zero(), Eigen::Vector3d(0, std::nan(""), 1),
           Eigen::Vector3d(0, 1, std::numeric_limits<double>::infinity())}) {
    o = RenderOptions{};
    o.key_light = bad;
    EXPECT_THROW(o.validate(), InvalidInput) << bad.transpose();
  }
  EXPECT_THROW(view_from_string("side"), InvalidInput);
  EXPECT_EQ(view_from_string(to_string(View::ThreeQuarter)), View::ThreeQuarter);
  const Mesh t = testing::tetrahedron();
  EXPECT_THROW(render(t, std::vector<Eigen::Vector3f>(3), {}, RenderOptions{}), InvalidInput);
}

// A black square in the plane z = 0 whose right edge projects to screen column `edge_x` (pixels)
// with the default front camera on a white background.
core::Image square_with_edge_at(double edge_x, int w, int h) {
  RenderOptions o;
  o.width = w;
  o.height = h;
  o.target = Eigen::Vector3d::Zero();
  o.background = Eigen::Vector3d::Ones();
  o.specular = 0.0;
  o.normal_smoothing = 0;
  const double focal = 0.5 * h / std::tan(0.5 * o.field_of_view);  // as in render()
  const double x_edge = (edge_x - 0.5 * w) * o.distance / focal;
  Mesh m;
  m.vertices.resize(4, 3);
  m.vertices << -0.2, -0.2, 0, x_edge, -0.2, 0, x_edge, 0.2, 0, -0.2, 0.2, 0;
  m.faces.resize(2, 3);
  m.faces << 0, 1, 2, 0, 2, 3;
  return render(m, std::vector<Eigen::Vector3f>(4, Eigen::Vector3f::Zero()), {}, o);
}

TEST(Render, RotatedGridAntiAliasing) {
  // 4 samples per pixel at x offsets 1/8, 3/8, 5/8, 7/8 (one per row): a vertical edge 0.3 px into
  // a pixel covers 1 sample (value 255·3/4 ≈ 191 on white), 0.55 px 2 (128), 0.8 px 3 (64). A 2×2
  // ordered grid would give 255, 128, 128: it cannot tell 0.3 from 0.55 from 0.8.
  const int w = 64, h = 48;
  const struct {
    double frac;
    int value;
  } cases[] = {{0.3, 191}, {0.55, 128}, {0.8, 64}};
  for (const auto& c : cases) {
    const core::Image im = square_with_edge_at(40.0 + c.frac, w, h);
    const std::size_t row = static_cast<std::size_t>(h / 2) * w;
    EXPECT_NEAR(im.rgb[(row + 40) * 3], c.value, 1) << c.frac;
    EXPECT_EQ(im.rgb[(row + 39) * 3], 0);    // inside: black
    EXPECT_EQ(im.rgb[(row + 41) * 3], 255);  // outside: white
  }
}

TEST(Render, PaintIsSampledAtTheInterpolatedCoordinates) {
  Paint p;
  p.width = 2;
  p.height = 1;
  p.texels = {{0.0f, 0.0f, 0.0f, 1.0f}, {1.0f, 1.0f, 1.0f, 1.0f}};
  p.uv.assign(4, Eigen::Vector2f(0.5f, 0.5f));
  EXPECT_NO_THROW(p.validate(4));
  // bilinear between texel centres u = 0.25 and 0.75; clamped outside
  EXPECT_FLOAT_EQ(p.sample(0.5f, 0.5f).x(), 0.5f);
  EXPECT_FLOAT_EQ(p.sample(0.375f, 0.0f).x(), 0.25f);
  EXPECT_FLOAT_EQ(p.sample(0.0f, 1.0f).x(), 0.0f);
  EXPECT_FLOAT_EQ(p.sample(1.0f, 0.3f).x(), 1.0f);
  // a square painted black on its left half, white on its right: the left of the image is dark
  Mesh m;
  m.vertices.resize(4, 3);
  m.vertices << -0.05, -0.05, 0, 0.05, -0.05, 0, 0.05, 0.05, 0, -0.05, 0.05, 0;
  m.faces.resize(2, 3);
  m.faces << 0, 1, 2, 0, 2, 3;
  p.uv = {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}};
  p.width = 64;
  p.texels.assign(64, Eigen::Vector4f(1, 1, 1, 1));
  for (int i = 0; i < 32; ++i) p.texels[static_cast<std::size_t>(i)] = {0, 0, 0, 1};
  RenderOptions o;
  o.width = o.height = 64;
  o.target = Eigen::Vector3d::Zero();
  o.specular = 0.0;
  const core::Image plain = render(m, {}, {}, o);
  const core::Image painted = render(m, {}, {}, o, &p);
  const std::size_t left = (32u * 64u + 26u) * 3u, right = (32u * 64u + 38u) * 3u;
  EXPECT_LT(painted.rgb[left], 5);
  EXPECT_GT(painted.rgb[right], plain.rgb[right]);  // white paint is brighter than skin
  // a vertex without coordinates leaves its triangles unpainted
  p.uv[1] = Eigen::Vector2f(std::nanf(""), std::nanf(""));
  const core::Image half = render(m, {}, {}, o, &p);
  EXPECT_EQ(half.rgb[right], plain.rgb[right]);
  // bad paints
  Paint bad = p;
  bad.uv.pop_back();
  EXPECT_THROW(bad.validate(4), InvalidInput);
  EXPECT_THROW(render(m, {}, {}, o, &bad), InvalidInput);
  bad = p;
  bad.uv[0] = {1.5f, 0.0f};
  EXPECT_THROW(bad.validate(4), InvalidInput);
  bad = p;
  bad.uv[0] = {std::numeric_limits<float>::infinity(), 0.0f};
  EXPECT_THROW(bad.validate(4), InvalidInput);
  bad = p;
  bad.texels[3] = {0.5f, std::nanf(""), 0.0f, 1.0f};
  EXPECT_THROW(bad.validate(4), InvalidInput);
  bad = p;
  bad.width = 63;
  EXPECT_THROW(bad.validate(4), InvalidInput);
  bad = p;
  bad.width = 0;
  EXPECT_THROW(bad.validate(4), InvalidInput);
  o.normal_smoothing = 11;
  EXPECT_THROW(o.validate(), InvalidInput);
}

TEST(Render, DefaultFacePaint) {
  const Face f = make_generic_face();
  const Paint* p = paint_for(f.rig);
  ASSERT_NE(p, nullptr);
  EXPECT_NO_THROW(p->validate(f.mesh.vertex_count()));
  Rig other = f.rig;
  other.materials[0] = Material::Lip;
  EXPECT_EQ(paint_for(other), nullptr);  // not the default face
  // brows dark, forehead skin light, in the paint's frontal frame (brow at x = ±3 cm, y ≈ 2.4 cm)
  auto at = [&](double x, double y) {
    return p->sample(static_cast<float>((x + 0.086) / 0.172),
                     static_cast<float>((y + 0.140) / 0.268));
  };
  EXPECT_LT(at(-0.03, 0.0235).x(), 0.4f);
  EXPECT_LT(at(0.03, 0.0235).x(), 0.4f);
  EXPECT_GT(at(0.0, 0.045).x(), 0.8f);
  EXPECT_LT(at(0.0, 0.110).x(), 0.3f);  // hair
}

// project_point: the target lands in the image centre at depth = distance; a point 1 cm above it
// (same depth) lands focal·0.01/distance pixels higher, focal = (h/2)/tan(fov/2); the three-quarter
// view turns the camera 35° about the target.
TEST(Render, ProjectPoint) {
  RenderOptions o;
  o.width = 200;
  o.height = 100;
  const Eigen::Vector3d c = project_point(o, o.target);
  EXPECT_NEAR(c.x(), 100.0, 1e-9);
  EXPECT_NEAR(c.y(), 50.0, 1e-9);
  EXPECT_NEAR(c.z(), o.distance, 1e-12);
  const double focal = 50.0 / std::tan(0.5 * o.field_of_view);
  const Eigen::Vector3d up = project_point(o, o.target + Eigen::Vector3d(0.0, 0.01, 0.0));
  EXPECT_NEAR(up.y(), 50.0 - focal * 0.01 / o.distance, 1e-9);
  const Eigen::Vector3d left = project_point(o, o.target + Eigen::Vector3d(0.01, 0.0, 0.0));
  EXPECT_NEAR(left.x(), 100.0 + focal * 0.01 / o.distance,
              1e-9);  // +x = the subject's left = image right
  o.view = View::ThreeQuarter;
  const double a = 35.0 * M_PI / 180.0;
  // a point on the camera's axis (from the target towards the eye) projects to the centre
  const Eigen::Vector3d on_axis =
      project_point(o, o.target + 0.1 * Eigen::Vector3d(-std::sin(a), 0.0, std::cos(a)));
  EXPECT_NEAR(on_axis.x(), 100.0, 1e-9);
  EXPECT_NEAR(on_axis.z(), o.distance - 0.1, 1e-12);
  o.width = 0;
  EXPECT_THROW(project_point(o, Eigen::Vector3d::Zero()), InvalidInput);
}

}  // namespace
}  // namespace emoface::facemesh

namespace emoface::facemesh {
namespace {

TEST(Render, SoftenedMaterialColours) {
  const Face f = make_generic_face();
  const auto crisp = material_colors(f.rig);
  const auto soft = material_colors(f.rig, f.mesh, 2);
  ASSERT_EQ(soft.size(), crisp.size());
  std::size_t changed = 0;
  for (std::size_t v = 0; v < soft.size(); ++v) {
    const Material m = f.rig.materials[v];
    if (m == Material::Lip || m == Material::Iris || m == Material::EyeWhite || m == Material::Pupil) {
      ASSERT_EQ(soft[v], crisp[v]) << v;  // lips and eyes keep crisp edges
    }
    changed += (soft[v] - crisp[v]).norm() > 1e-4f ? 1 : 0;
    for (int k = 0; k < 3; ++k) ASSERT_TRUE(soft[v][k] >= 0.0f && soft[v][k] <= 1.0f);
  }
  EXPECT_GT(changed, 100u);                    // the brow and hair boundaries are softened
  EXPECT_LT(changed, soft.size() / 2);         // ... and only they
  EXPECT_EQ(material_colors(f.rig, f.mesh, 0), crisp);
  EXPECT_THROW(material_colors(f.rig, f.mesh, 21), InvalidInput);
  EXPECT_THROW(material_colors(f.rig, testing::tetrahedron(), 1), InvalidInput);
}

// The iris must read dark in grey, as the expression networks see faces (docs/muscles.md "Session
// 11": a blue-grey iris, about as light as the skin, made open eyes read half shut). Luma weights
// of ITU-R BT.601, the ones @vladmandic/human's emotion model uses on its crop.
TEST(Render, TheIrisIsDarkInGrey) {
  const Face f = make_default_face();
  const auto colours = material_colors(f.rig);
  auto luma_of = [&](Material m) {
    for (std::size_t v = 0; v < colours.size(); ++v)
      if (f.rig.materials[v] == m)
        return 0.299f * colours[v].x() + 0.587f * colours[v].y() + 0.114f * colours[v].z();
    ADD_FAILURE() << "no vertex of material " << to_string(m);
    return 0.0f;
  };
  const float iris = luma_of(Material::Iris), skin = luma_of(Material::Skin),
              white = luma_of(Material::EyeWhite);
  EXPECT_LT(iris, 0.4f * skin);  // the blue-grey iris (0.30, 0.42, 0.55) was 0.55 of the skin
  EXPECT_LT(iris, 0.3f * white);
  EXPECT_GT(iris, luma_of(Material::Pupil));  // the pupil still shows inside it
}

}  // namespace
}  // namespace emoface::facemesh
