// The default face (issue 14 part 1): data/face regenerates byte for byte from the MakeHuman head
// with one command; make_default_face() is those files; the parts added to the head (eyeballs, teeth,
// tongue, lashes) are bound through the rig so that the solver moves them; bad input.
#include "emoface/retarget/default_head.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/facemesh/render.hpp"
#include "emoface/muscles/solver.hpp"

namespace fs = std::filesystem;
namespace fm = emoface::facemesh;
namespace core = emoface::core;
namespace rt = emoface::retarget;
namespace mu = emoface::muscles;

namespace {

const std::string kData = std::string(EMOFACE_SOURCE_DIR) + "/data/face/";

fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("emoface_default_head_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

const fm::Part& part(const fm::Rig& rig, const std::string& name) {
  for (const auto& p : rig.parts)
    if (p.name == name) return p;
  throw std::runtime_error("no part " + name);
}

// Pixels of a front render that show the teeth: the teeth are coloured pure green, everything else
// keeps its material colour (none of which is green-dominant).
int teeth_pixels(const core::Image& img) {
  int n = 0;
  for (std::size_t i = 0; i + 2 < img.rgb.size(); i += 3)
    if (img.rgb[i + 1] > 60 && img.rgb[i + 1] > 2 * img.rgb[i] && img.rgb[i + 1] > 2 * img.rgb[i + 2]) ++n;
  return n;
}

}  // namespace

TEST(DefaultFace, DataFaceRegeneratesByteForByte) {
  const fs::path dir = temp_dir("regen");
  fs::copy_file(kData + "makehuman_head.obj", dir / "makehuman_head.obj");
  const rt::DefaultHeadReport rep = rt::write_default_face_files(dir.string());
  for (const char* f : {"generic.rig", "generic_face.obj", "default.rig", "default_face.obj"})
    EXPECT_EQ(emoface::core::read_file((dir / f).string()), emoface::core::read_file(kData + f))
        << f << " differs: regenerate with  retarget --make-default-face data/face";
  EXPECT_EQ(rep.head_vertices, 4358u);  // 4,459 − 193 under the neck cut + 92 on its rim
  EXPECT_GT(rep.neck_dropped, 100u);
  fs::remove_all(dir);
}

TEST(DefaultFace, IsTheCompiledInFiles) {
  const fm::Face disk = fm::load_face(kData + "default.rig");
  const fm::Face face = fm::make_default_face();
  EXPECT_EQ(fm::format_rig(face.rig), fm::format_rig(disk.rig));
  EXPECT_EQ(face.mesh.faces, disk.mesh.faces);
  EXPECT_EQ(face.mesh.vertices, disk.mesh.vertices);
  EXPECT_TRUE(face.rig.frame.is_identity());
  EXPECT_EQ(face.rig.mesh_file, "default_face.obj");
  // the human head, not the generic face
  EXPECT_NE(face.mesh.vertex_count(), fm::make_generic_face().mesh.vertex_count());
  EXPECT_NO_THROW(fm::validate_mesh(face.mesh, "default"));
  // the default face has its own paint (brows); the generic keeps its own
  EXPECT_EQ(fm::paint_for(face.rig), &fm::default_face_paint());
  EXPECT_EQ(fm::paint_for(fm::make_generic_face().rig), &fm::generic_face_paint());
}

TEST(DefaultFace, HasEveryPartBoundThroughTheRig) {
  const fm::Face face = fm::make_default_face();
  const auto& rig = face.rig;
  std::map<int, double> jaw;
  for (std::size_t k = 0; k < rig.jaw.vertices.size(); ++k) jaw[rig.jaw.vertices[k]] = rig.jaw.weights[k];
  for (const char* name : {"lower_teeth", "tongue"}) {
    const auto& p = part(rig, name);
    EXPECT_GT(p.vertices.size(), 50u) << name;
    for (int v : p.vertices) ASSERT_EQ(jaw.count(v) ? jaw[v] : 0.0, 1.0) << name << " vertex " << v;
  }
  for (int v : part(rig, "upper_teeth").vertices) EXPECT_EQ(jaw.count(v), 0u);
  for (int e = 0; e < 2; ++e) {
    const auto& eye = rig.eyes[static_cast<std::size_t>(e)];
    const auto& ball = part(rig, e == 0 ? "eyeball_r" : "eyeball_l");
    EXPECT_EQ(eye.eyeball_vertices, ball.vertices);
    int iris = 0, pupil = 0;
    for (int v : ball.vertices) {
      // on the sphere around the eye centre
      EXPECT_NEAR((face.mesh.vertices.row(v).transpose() - eye.centre).norm(), eye.radius, 1e-6);
      iris += rig.materials[static_cast<std::size_t>(v)] == fm::Material::Iris;
      pupil += rig.materials[static_cast<std::size_t>(v)] == fm::Material::Pupil;
    }
    EXPECT_GT(iris, 10);
    EXPECT_GT(pupil, 0);
    // lashes: every lash vertex is in its lid's list (they follow the lid)
    for (int lid = 0; lid < 2; ++lid) {
      const auto& p = part(rig, std::string(lid == 0 ? "upper" : "lower") + "_lashes_" + (e == 0 ? "r" : "l"));
      const auto& list = lid == 0 ? eye.upper_lid : eye.lower_lid;
      EXPECT_GT(p.vertices.size(), 10u);
      for (int v : p.vertices) {
        EXPECT_NE(std::find(list.begin(), list.end(), v), list.end());
        EXPECT_EQ(rig.materials[static_cast<std::size_t>(v)], fm::Material::Lash);
      }
    }
  }
}

TEST(DefaultFace, SolverMovesTheParts) {
  const fm::Face face = fm::make_default_face();
  const mu::FaceSolver solver(face.mesh, face.rig);
  const auto& rig = face.rig;
  // gaze turns the eyeballs about their centres (radius kept); the head does not move
  const mu::Deformation gaze = solver.deform(std::map<std::string, double>{{"eye_gaze_yaw", 0.3}});
  for (int e = 0; e < 2; ++e) {
    const auto& eye = rig.eyes[static_cast<std::size_t>(e)];
    double moved = 0.0;
    for (int v : eye.eyeball_vertices) {
      EXPECT_NEAR((gaze.vertices.row(v).transpose() - eye.centre).norm(), eye.radius, 1e-9);
      moved = std::max(moved, (gaze.vertices.row(v) - face.mesh.vertices.row(v)).norm());
    }
    EXPECT_GT(moved, 0.5 * 0.3 * eye.radius);
  }
  for (int v : part(rig, "head").vertices)
    ASSERT_LT((gaze.vertices.row(v) - face.mesh.vertices.row(v)).norm(), 1e-8);
  // the jaw turns the lower teeth and the tongue rigidly, the upper teeth stay
  const mu::Deformation open = solver.deform(std::map<std::string, double>{{"masseter", 1.0}});
  const auto& lower = part(rig, "lower_teeth").vertices;
  EXPECT_GT((open.vertices.row(lower[0]) - face.mesh.vertices.row(lower[0])).norm(), 0.003);
  for (std::size_t k = 1; k < lower.size(); k += 7) {
    const double d0 = (face.mesh.vertices.row(lower[0]) - face.mesh.vertices.row(lower[k])).norm();
    const double d1 = (open.vertices.row(lower[0]) - open.vertices.row(lower[k])).norm();
    EXPECT_NEAR(d0, d1, 1e-9);
  }
  for (int v : part(rig, "upper_teeth").vertices)
    ASSERT_LT((open.vertices.row(v) - face.mesh.vertices.row(v)).norm(), 1e-8);
  // the lashes follow a blink
  const mu::Deformation blink = solver.deform(std::map<std::string, double>{{"eye_blink_r", 1.0}});
  double lash = 0.0;
  for (int v : part(rig, "upper_lashes_r").vertices)
    lash = std::max(lash, (blink.vertices.row(v) - face.mesh.vertices.row(v)).norm());
  EXPECT_GT(lash, 0.004);
  // the blink closes the eye: the aperture falls to a small fraction of the open one
  EXPECT_LT(mu::eye_aperture(rig, blink.vertices, 0), 0.25 * mu::eye_aperture(rig, face.mesh.vertices, 0));
}

// Rendered with the teeth pure green: closed lips hide them.
TEST(DefaultFace, TeethHiddenBehindClosedLips) {
  const fm::Face face = fm::make_default_face();
  fm::RenderOptions o;
  auto colors = fm::material_colors(face.rig, face.mesh);
  for (std::size_t v = 0; v < colors.size(); ++v)
    if (face.rig.materials[v] == fm::Material::Teeth) colors[v] = Eigen::Vector3f(0.0f, 1.0f, 0.0f);
  const core::Image closed = fm::render(face.mesh, colors, {}, o, fm::paint_for(face.rig));
  // measured 42 px after the transfer moved the lips onto the head's own mouth slit (the bound of
  // 40 was set before that); teeth seen between parted lips are hundreds of pixels
  EXPECT_LT(teeth_pixels(closed), 60) << "teeth show through the closed lips";
  // the teeth and the tongue lie at least 5 mm behind the front of the lips at the middle
  double lips_front = -1.0, parts_front = -1.0;
  for (const auto& b : face.rig.lips.bound)
    if (std::abs(face.mesh.vertices(b.vertex, 0)) < 0.01)
      lips_front = std::max(lips_front, face.mesh.vertices(b.vertex, 2));
  for (const char* name : {"upper_teeth", "lower_teeth", "tongue"})
    for (int v : part(face.rig, name).vertices) parts_front = std::max(parts_front, face.mesh.vertices(v, 2));
  EXPECT_LT(parts_front, lips_front - 0.005);
}

// Rendered with the teeth pure green: the opened jaw shows them (it used to stretch a curtain of
// lip triangles across the mouth: the transfer bound the inside of MakeHuman's lower lip to the
// upper lip's part of the lip surface; fixed by binding the lips by the head's own slit, s3-mouth).
TEST(DefaultFace, TeethShowWhenTheMouthOpens) {
  const fm::Face face = fm::make_default_face();
  const mu::FaceSolver solver(face.mesh, face.rig);
  fm::RenderOptions o;
  auto colors = fm::material_colors(face.rig, face.mesh);
  for (std::size_t v = 0; v < colors.size(); ++v)
    if (face.rig.materials[v] == fm::Material::Teeth) colors[v] = Eigen::Vector3f(0.0f, 1.0f, 0.0f);
  const mu::Deformation d = solver.deform(std::map<std::string, double>{{"masseter", 1.0}});
  const core::Image open = fm::render(fm::Mesh{d.vertices, face.mesh.faces}, colors, d.crease, o,
                                      fm::paint_for(face.rig));
  const int px = teeth_pixels(open);
  std::printf("teeth pixels at masseter 1: %d\n", px);
  // 503 pixels before the mouth cavity (the lower teeth seen through the torn bag, in front of the
  // lit inside of the head); 259 with the bag's wall behind the teeth: the lower lip's lining now
  // runs back over the teeth's top edge (docs/facemesh.md "Mouth cavity"). The upper teeth stay
  // behind the upper lip when only the jaw opens, before and after. Session 5: 205 — the lower
  // lip's border turns with the jaw by the generic's weights (LipGrid::border_jaw; MakeHuman's
  // nearest jaw vertex had given its middle 0) and covers more of the lower teeth's edge.
  EXPECT_GT(px, 200) << "the open mouth shows no teeth";
}

// First surface a ray from the front (+z, looking −z) at (x, y) meets: its depth and the material
// most of the triangle's corners have (Möller–Trumbore on every triangle; a test, not a hot path).
struct Hit {
  double z = -1e9;
  fm::Material material = fm::Material::Skin;
  bool any = false;
};
Hit first_hit_from_front(const fm::Vertices& X, const fm::Faces& F, const fm::Rig& rig, double x,
                         double y) {
  Hit best;
  const Eigen::Vector3d o(x, y, 10.0), dir(0.0, 0.0, -1.0);
  for (long f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = X.row(F(f, 0)).transpose(), b = X.row(F(f, 1)).transpose(),
                          c = X.row(F(f, 2)).transpose();
    const Eigen::Vector3d e1 = b - a, e2 = c - a, p = dir.cross(e2);
    const double det = e1.dot(p);
    if (std::abs(det) < 1e-14) continue;
    const Eigen::Vector3d s = o - a;
    const double u = s.dot(p) / det;
    if (u < 0.0 || u > 1.0) continue;
    const Eigen::Vector3d q = s.cross(e1);
    const double v = dir.dot(q) / det;
    if (v < 0.0 || u + v > 1.0) continue;
    const double z = o.z() - e2.dot(q) / det;
    if (z <= best.z) continue;
    best.z = z, best.any = true;
    const fm::Material m0 = rig.materials[static_cast<std::size_t>(F(f, 0))],
                       m1 = rig.materials[static_cast<std::size_t>(F(f, 1))],
                       m2 = rig.materials[static_cast<std::size_t>(F(f, 2))];
    best.material = (m1 == m2) ? m1 : m0;
  }
  return best;
}

// The opened mouth is dark inside: MakeHuman's bag is a shallow pocket in front of the teeth that
// tears open with the jaw, and the head is an open shell behind it, so rays through the opened
// mouth used to meet skin deep inside the head (the lit inside of its back, 10 cm behind the lips).
// Now the bag's wall sits behind the teeth and a dark backdrop closes the mouth: no ray through the
// opening (the middle 60 % of the teeth's width, deeper than 12 mm behind the lips) meets skin.
TEST(DefaultFace, TheOpenedMouthIsDarkInside) {
  const fm::Face face = fm::make_default_face();
  const mu::FaceSolver solver(face.mesh, face.rig);
  const mu::Deformation d = solver.deform(std::map<std::string, double>{{"masseter", 1.0}});
  double lips_front = -1e9, x0 = 1e9, x1 = -1e9;
  for (const auto& lb : face.rig.lips.bound)
    lips_front = std::max(lips_front, d.vertices(lb.vertex, 2));
  for (int v : part(face.rig, "upper_teeth").vertices)
    x0 = std::min(x0, face.mesh.vertices(v, 0)), x1 = std::max(x1, face.mesh.vertices(v, 0));
  const double cx = 0.5 * (x0 + x1), hw = 0.5 * (x1 - x0), cy = face.rig.lips.centre.y();
  int rays = 0, deep_skin = 0;
  for (double x = cx - 0.6 * hw; x <= cx + 0.6 * hw; x += 0.002)
    for (double y = cy - 0.04; y <= cy + 0.03; y += 0.001) {
      const Hit h = first_hit_from_front(d.vertices, face.mesh.faces, face.rig, x, y);
      if (!h.any || h.z > lips_front - 0.012) continue;  // the lips and the face around them
      ++rays;
      if (h.material == fm::Material::Skin) ++deep_skin;
    }
  std::printf("rays into the opened mouth: %d, meeting skin: %d\n", rays, deep_skin);
  EXPECT_GT(rays, 20) << "the mouth did not open";
  EXPECT_EQ(deep_skin, 0) << "the opened mouth shows skin inside the head";
}

// Height above the eye centre up to which a ray from the front through the column x meets the
// eyeball (sclera, iris or pupil) rather than skin or the socket's lining, in 0.1 mm steps.
double eyeball_seen_above_centre(const fm::Vertices& X, const fm::Faces& F, const fm::Rig& rig,
                                 int e, double x) {
  const auto& eye = rig.eyes[static_cast<std::size_t>(e)];
  double h = 0.0;
  for (; h < 2.0 * eye.radius; h += 1e-4) {
    const fm::Material m = first_hit_from_front(X, F, rig, x, eye.centre.y() + h).material;
    if (m != fm::Material::EyeWhite && m != fm::Material::Iris && m != fm::Material::Pupil) break;
  }
  return h;
}

// The raised upper lid (AU5, levator palpebrae superioris) uncovers the eyeball above the iris: the
// lining of the closed socket behind the lid fold turns with the lid and stays inside the eyeball.
// It used to stay put, so the triangles from the raised margin down to it covered the top of the
// eyeball as a band (issue 14, rounds 5 and 6): at full levator the margin rose 3.45 mm and the
// eyeball seen above the centre grew 0.80 mm; with the lining turning, 2.60 mm (75 %).
TEST(DefaultFace, TheRaisedLidUncoversTheEyeball) {
  const fm::Face face = fm::make_default_face();
  const mu::FaceSolver solver(face.mesh, face.rig);
  const mu::Deformation d =
      solver.deform(std::map<std::string, double>{{"levator_palpebrae_superioris_r", 1.0}});
  const auto& eye = face.rig.eyes[0];
  double rise = 0.0;  // of the upper lid's margin (weight 1) over the middle of the eye
  for (std::size_t k = 0; k < eye.upper_lid.size(); ++k) {
    const int v = eye.upper_lid[k];
    if (eye.upper_lid_weights[k] < 0.999 ||
        std::abs(face.mesh.vertices(v, 0) - eye.centre.x()) > 0.3 * eye.radius ||
        face.mesh.vertices(v, 2) < eye.centre.z())
      continue;
    rise = std::max(rise, d.vertices(v, 1) - face.mesh.vertices(v, 1));
  }
  const double before =
      eyeball_seen_above_centre(face.mesh.vertices, face.mesh.faces, face.rig, 0, eye.centre.x());
  const double after =
      eyeball_seen_above_centre(d.vertices, face.mesh.faces, face.rig, 0, eye.centre.x());
  std::printf("lid margin rose %.2f mm; eyeball seen above the centre %.2f -> %.2f mm\n",
              1e3 * rise, 1e3 * before, 1e3 * after);
  ASSERT_GT(rise, 0.001) << "the levator did not raise the lid";
  EXPECT_GT(after - before, 0.6 * rise) << "the raised lid does not uncover the eyeball";
}

// Rays from the front on a 0.5 mm grid over eye e's box (±1.3 radii across, ±1 radius up and down)
// that meet the eyeball (sclera, iris or pupil).
int eyeball_rays(const fm::Vertices& X, const fm::Faces& F, const fm::Rig& rig, int e) {
  const auto& eye = rig.eyes[static_cast<std::size_t>(e)];
  int n = 0;
  for (double x = -1.3 * eye.radius; x <= 1.3 * eye.radius; x += 5e-4)
    for (double y = -eye.radius; y <= eye.radius; y += 5e-4) {
      const fm::Material m =
          first_hit_from_front(X, F, rig, eye.centre.x() + x, eye.centre.y() + y).material;
      if (m == fm::Material::EyeWhite || m == fm::Material::Iris || m == fm::Material::Pupil) ++n;
    }
  return n;
}

// A full blink (eye_blink 1, AU45) closes the eye along its whole length: the upper lid's closing
// angle is measured where the eye is widest, and towards the corners each margin vertex turns only
// as far as the lower lid (issue 14, session 6). Before, the angle came from the whole margin's
// mean: a slit stayed open along the middle (rays meeting the eyeball at a full blink: 191 / 195 of
// 539 / 551 with main's rig, 177 / 181 with the lining turning; now 4 / 6).
TEST(DefaultFace, AFullBlinkClosesTheEye) {
  const fm::Face face = fm::make_default_face();
  const mu::FaceSolver solver(face.mesh, face.rig);
  const mu::Deformation d =
      solver.deform(std::map<std::string, double>{{"eye_blink_r", 1.0}, {"eye_blink_l", 1.0}});
  for (int e = 0; e < 2; ++e) {
    const int open = eyeball_rays(face.mesh.vertices, face.mesh.faces, face.rig, e);
    const int shut = eyeball_rays(d.vertices, face.mesh.faces, face.rig, e);
    std::printf("eye %d: %d rays meet the eyeball open, %d at a full blink\n", e, open, shut);
    EXPECT_GT(open, 300);
    EXPECT_LT(shut, 0.02 * open) << "eye " << e << " stays open at a full blink";
  }
}

// The blink's wider closing angle is the blink's alone: the tightener (AU7, palpebralis) and the
// cheek's push (AU6) turn the lids by fractions of the tightening angle measured over the whole
// margin (Eye::tighten_angle, rig format 1.3), as before the blink's fix. With the closing angle
// instead they grew by 41 % and narrowed every angry and smiling face's eyes.
TEST(DefaultFace, TheTightenerDoesNotGrowWithTheBlink) {
  const fm::Face face = fm::make_default_face();
  mu::SolverOptions off;  // the tightener alone: no squeeze coupled in
  off.eyelid_coupling = mu::EyelidCoupling::Off;
  fm::Rig closing = face.rig;  // the same rig tightening by the closing angle
  for (auto& eye : closing.eyes) eye.tighten_angle.reset();
  const std::map<std::string, double> au7{{"orbicularis_oculi_palpebralis_r", 1.0},
                                          {"orbicularis_oculi_orbitalis_r", 1.0}};
  const mu::Deformation d = mu::FaceSolver(face.mesh, face.rig, off).deform(au7);
  const mu::Deformation c = mu::FaceSolver(face.mesh, closing, off).deform(au7);
  const int open = eyeball_rays(face.mesh.vertices, face.mesh.faces, face.rig, 0);
  const int tight = eyeball_rays(d.vertices, face.mesh.faces, face.rig, 0);
  const int by_closing = eyeball_rays(c.vertices, face.mesh.faces, face.rig, 0);
  std::printf("rays meeting the right eyeball: open %d, AU7 + AU6 %d (by the closing angle %d)\n",
              open, tight, by_closing);
  for (const auto& eye : face.rig.eyes) {
    ASSERT_TRUE(eye.tighten_angle.has_value());
    EXPECT_LT(*eye.tighten_angle, 0.8 * eye.close_angle);
  }
  // measured 259 of 539, by the closing angle 155
  EXPECT_GT(tight, 0.4 * open) << "the tightener nearly shuts the eye";
}

namespace {

int landmark(const fm::Rig& rig, const std::string& name) {
  for (const auto& l : rig.retarget_landmarks)
    if (l.name == name) return l.vertex;
  throw std::runtime_error("no landmark " + name);
}

double luminance(const core::Image& im, int x, int y) {
  const std::size_t i = (static_cast<std::size_t>(y) * im.width + x) * 3;
  return 0.299 * im.rgb[i] + 0.587 * im.rgb[i + 1] + 0.114 * im.rgb[i + 2];
}

}  // namespace

// Short dark hair (issue 14): the head's skin above the hairline is hair, nothing below it is (the
// face's landmarks, the brows, the ears); the forehead hairline sits 35–60 mm above the brows
// (adult proportions). Rendered (480×560, paint on), neutral and with the brows raised by full
// frontalis, in the columns through the brow landmarks and the midline: skin from above the brow up
// to the highest skin vertex of the column, hair from the lowest hair vertex up.
TEST(DefaultFace, HairAboveTheHairlineOnly) {
  const fm::Face face = fm::make_default_face();
  const auto& X = face.mesh.vertices;
  const auto& mat = face.rig.materials;
  const fm::Hairline hl = fm::default_hairline(face.rig, X);
  int above = 0, above_hair = 0, below_hair = 0;
  for (int v : part(face.rig, "head").vertices) {
    const fm::Material m = mat[static_cast<std::size_t>(v)];
    if (m != fm::Material::Skin && m != fm::Material::Hair) continue;
    const double d = X(v, 1) - fm::hairline_height(hl, X.row(v).transpose());
    if (d > 0.003) above_hair += (++above, m == fm::Material::Hair);
    if (d < -0.003 && m == fm::Material::Hair) ++below_hair;
  }
  EXPECT_GT(above, 200);  // 233 measured
  EXPECT_EQ(above_hair, above) << "skin above the hairline";
  EXPECT_EQ(below_hair, 0) << "hair below the hairline";
  for (const char* n : {"top_of_head", "back_of_head"})
    EXPECT_EQ(mat[static_cast<std::size_t>(landmark(face.rig, n))], fm::Material::Hair) << n;
  for (const char* n : {"forehead_centre", "brow_centre_r", "brow_centre_l", "ear_r", "ear_l",
                        "nose_root", "cheek_r", "cheek_l", "chin", "jaw_r", "jaw_l"})
    EXPECT_NE(mat[static_cast<std::size_t>(landmark(face.rig, n))], fm::Material::Hair) << n;
  for (int v : face.rig.ibug68) EXPECT_NE(mat[static_cast<std::size_t>(v)], fm::Material::Hair);
  const int br = landmark(face.rig, "brow_centre_r"), bl = landmark(face.rig, "brow_centre_l");
  const double above_brows =
      fm::hairline_height(hl, Eigen::Vector3d(0.0, 0.0, 1.0)) - 0.5 * (X(br, 1) + X(bl, 1));
  EXPECT_GT(above_brows, 0.035);
  EXPECT_LT(above_brows, 0.060);

  const mu::FaceSolver solver(face.mesh, face.rig);
  const fm::RenderOptions o;
  const auto colors = fm::material_colors(face.rig, face.mesh);
  const std::map<std::string, double> raise{{"frontalis_medialis_l", 1.0},
                                            {"frontalis_medialis_r", 1.0},
                                            {"frontalis_lateralis_l", 1.0},
                                            {"frontalis_lateralis_r", 1.0}};
  for (const bool raised : {false, true}) {
    const mu::Deformation d = solver.deform(raised ? raise : std::map<std::string, double>{});
    const core::Image im = fm::render(fm::Mesh{d.vertices, face.mesh.faces}, colors, d.crease, o,
                                      fm::paint_for(face.rig));
    auto px = [&](int v) { return fm::project_point(o, d.vertices.row(v).transpose()); };
    for (const int column : {br, bl, -1}) {
      // the column's brow row (the midline has none: the brow landmarks' mean height)
      const double cx = column >= 0 ? X(column, 0) : 0.0;
      const double brow_row = column >= 0 ? px(column).y() : 0.5 * (px(br).y() + px(bl).y());
      const int x = static_cast<int>(
          std::lround(column >= 0 ? px(column).x() : 0.5 * (px(br).x() + px(bl).x())));
      int top_skin = -1, low_hair = -1;  // the column's highest skin and lowest hair vertex (front)
      for (int v : part(face.rig, "head").vertices) {
        if (std::abs(X(v, 0) - cx) > 0.004 || X(v, 2) < 0.06 || X(v, 1) < X(br, 1)) continue;
        const fm::Material m = mat[static_cast<std::size_t>(v)];
        if (m == fm::Material::Skin && (top_skin < 0 || X(v, 1) > X(top_skin, 1))) top_skin = v;
        if (m == fm::Material::Hair && (low_hair < 0 || X(v, 1) < X(low_hair, 1))) low_hair = v;
      }
      ASSERT_GE(top_skin, 0);
      ASSERT_GE(low_hair, 0);
      const double mm = (px(br).y() - fm::project_point(o, d.vertices.row(br).transpose() +
                                                               Eigen::Vector3d(0.0, 0.001, 0.0))
                                          .y());  // pixels per mm
      const int skin_from = static_cast<int>(brow_row - 6.0 * mm),
                skin_to = static_cast<int>(px(top_skin).y());
      const int hair_from = static_cast<int>(px(low_hair).y()),
                hair_to = hair_from - static_cast<int>(8.0 * mm);
      ASSERT_LT(skin_to, skin_from - 10);
      double darkest_skin = 255.0, lightest_hair = 0.0;
      for (int y = skin_to; y <= skin_from; ++y)
        darkest_skin = std::min(darkest_skin, luminance(im, x, y));
      for (int y = hair_to; y <= hair_from; ++y)
        lightest_hair = std::max(lightest_hair, luminance(im, x, y));
      std::printf(
          "%s column %d: forehead rows %d..%d darkest %.0f, hair rows %d..%d lightest %.0f\n",
          raised ? "frontalis 1" : "neutral", x, skin_to, skin_from, darkest_skin, hair_to,
          hair_from, lightest_hair);
      EXPECT_GT(darkest_skin, 110.0) << "hair or brow colour on the forehead, column " << x;
      EXPECT_LT(lightest_hair, 90.0) << "no hair above the hairline, column " << x;
    }
  }
}

// The neck ends in a plane 20 mm under the chin (iBUG 8), closed by a cap with its own copy of the
// rim: nothing of the face lies below the plane; under the chin the only open edges are the rim's,
// on the plane, each there twice (the neck's side and the cap's) with opposite directions; the cap
// faces down; the neck's rim vertices keep the neck's sideways normals (shared with the cap they
// averaged in its downward ones and shaded the neck's end dark).
TEST(DefaultFace, TheNeckEndsInAPlaneUnderTheChin) {
  const fm::Face face = fm::make_default_face();
  const auto& X = face.mesh.vertices;
  const auto& F = face.mesh.faces;
  const double chin = X(face.rig.ibug68[8], 1), y_cut = chin - 0.020;
  EXPECT_GE(X.col(1).minCoeff(), y_cut);
  std::map<std::pair<int, int>, int> directed;
  for (long t = 0; t < F.rows(); ++t)
    for (int k = 0; k < 3; ++k) ++directed[{F(t, k), F(t, (k + 1) % 3)}];
  // open edges under the chin, keyed by their end positions
  std::map<std::array<double, 6>, int> open_at;
  int open = 0;
  for (const auto& [e, n] : directed) {
    if (std::max(X(e.first, 1), X(e.second, 1)) > chin - 0.010) continue;
    EXPECT_EQ(n, 1);
    if (directed.count({e.second, e.first})) continue;
    ++open;
    EXPECT_EQ(X(e.first, 1), y_cut);
    EXPECT_EQ(X(e.second, 1), y_cut);
    std::array<double, 3> a{X(e.first, 0), X(e.first, 1), X(e.first, 2)},
        b{X(e.second, 0), X(e.second, 1), X(e.second, 2)};
    if (b < a) std::swap(a, b);
    ++open_at[{a[0], a[1], a[2], b[0], b[1], b[2]}];
  }
  EXPECT_GT(open, 60);
  EXPECT_EQ(open, static_cast<int>(2 * open_at.size()));
  for (const auto& [key, n] : open_at) EXPECT_EQ(n, 2);
  const auto& cap = part(face.rig, "neck_cap");
  std::vector<char> in_cap(static_cast<std::size_t>(X.rows()), 0);
  for (int v : cap.vertices) in_cap[static_cast<std::size_t>(v)] = 1;
  int cap_faces = 0;
  for (long t = 0; t < F.rows(); ++t) {
    if (!in_cap[static_cast<std::size_t>(F(t, 0))]) continue;
    const Eigen::Vector3d a = X.row(F(t, 0)), b = X.row(F(t, 1)), c = X.row(F(t, 2));
    EXPECT_LT((b - a).cross(c - a).y(), 0.0) << "cap triangle " << t << " faces up";
    ++cap_faces;
  }
  EXPECT_EQ(cap_faces + 1, static_cast<int>(cap.vertices.size()));
  const fm::Vertices n = fm::vertex_normals(X, F);
  double lowest = 1.0;
  for (int v : part(face.rig, "head").vertices)
    if (X(v, 1) == y_cut) lowest = std::min(lowest, n(v, 1));
  std::printf("neck rim: %d open edges, lowest rim normal y %.2f\n", open, lowest);
  EXPECT_GT(lowest, -0.6);
}

// The lips move as a surface: no lip-bound vertex leaves its neighbours (the largest difference
// between a vertex's displacement and its neighbours' mean) when the upper-lip raiser (AU10) or the
// zygomatic minor contracts fully with the mouth closed. The transfer once filed five lower-lip
// vertices near the corners of MakeHuman's closed slit into its upper row (they lay up to 0.2 mm
// above the chord between the corners); they rose with the upper lip in a lip-coloured
// spike: 6.4 and 12.9 mm. With the slit's rows split by their normals: 1.1 and 2.4 mm.
TEST(DefaultFace, TheLipsRiseWithoutSpikes) {
  const fm::Face face = fm::make_default_face();
  const mu::FaceSolver solver(face.mesh, face.rig);
  const auto& F = face.mesh.faces;
  std::vector<std::vector<int>> nb(static_cast<std::size_t>(face.mesh.vertices.rows()));
  for (long t = 0; t < F.rows(); ++t)
    for (int k = 0; k < 3; ++k) {
      nb[static_cast<std::size_t>(F(t, k))].push_back(F(t, (k + 1) % 3));
      nb[static_cast<std::size_t>(F(t, (k + 1) % 3))].push_back(F(t, k));
    }
  ASSERT_GT(face.rig.lips.bound.size(), 200u);
  for (const std::string m : {"levator_labii_superioris", "zygomatic_minor"}) {
    const mu::Deformation d =
        solver.deform(std::map<std::string, double>{{m + "_l", 1.0}, {m + "_r", 1.0}});
    auto moved = [&](int v) -> Eigen::Vector3d {
      return (d.vertices.row(v) - face.mesh.vertices.row(v)).transpose();
    };
    double worst = 0.0, lifted = 0.0;
    int at = -1;
    for (const auto& b : face.rig.lips.bound) {
      const auto& n = nb[static_cast<std::size_t>(b.vertex)];
      ASSERT_FALSE(n.empty());
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      for (int w : n) mean += moved(w);
      mean /= static_cast<double>(n.size());
      const double dev = (moved(b.vertex) - mean).norm();
      if (dev > worst) worst = dev, at = b.vertex;
      lifted = std::max(lifted, moved(b.vertex).y());
    }
    std::printf(
        "%s at 1: lips rise up to %.1f mm; a lip vertex leaves its neighbours by %.2f mm at most "
        "(vertex %d)\n",
        m.c_str(), 1e3 * lifted, 1e3 * worst, at);
    EXPECT_GT(lifted, 0.004) << m;  // the lips do move
    EXPECT_LT(worst, 0.003) << m << ", vertex " << at;
  }
}

TEST(DefaultFace, BadInputWritesNothing) {
  const fs::path dir = temp_dir("bad");
  // no head file
  EXPECT_THROW(rt::write_default_face_files(dir.string()), emoface::IoError);
  EXPECT_FALSE(fs::exists(dir / "default.rig"));
  EXPECT_FALSE(fs::exists(dir / "generic.rig"));
  // a truncated head: the OBJ error names the file and line
  std::string text = emoface::core::read_file(kData + "makehuman_head.obj");
  text = text.substr(0, text.size() / 2);
  text.resize(text.rfind('\n'));
  text += "\nf 1 2 99999\n";
  emoface::core::write_file_atomic((dir / "makehuman_head.obj").string(), text);
  try {
    rt::write_default_face_files(dir.string());
    ADD_FAILURE() << "no error";
  } catch (const emoface::FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("makehuman_head.obj"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir / "default.rig"));
  // NaN in a coordinate
  emoface::core::write_file_atomic((dir / "makehuman_head.obj").string(),
                                   "v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n");
  EXPECT_THROW(rt::write_default_face_files(dir.string()), emoface::FormatError);
  // a mesh that is no head (a single triangle): the transfer refuses it
  emoface::core::write_file_atomic((dir / "makehuman_head.obj").string(),
                                   "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_ANY_THROW(rt::write_default_face_files(dir.string()));
  EXPECT_FALSE(fs::exists(dir / "default.rig"));
  EXPECT_FALSE(fs::exists(dir / "default_face.obj"));
  fs::remove_all(dir);
}
