// The default head's mouth (issue 14 with 13): the transfer's lips must not tear. Measured on the
// head as build_default_head makes it from data/face/makehuman_head.obj (the shipped files are the
// same bytes: DefaultFace.DataFaceRegeneratesByteForByte), against the generic face it is rigged
// from: flipped triangles around the mouth for the six emotions at 0.9 and an open jaw, lip corners
// under happiness, the opening under surprise, lip colour only on the lips, lip bindings near the
// lip surface they follow. Every check prints the measured figure.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "emoface/facemesh/default_face.hpp"
#include "emoface/facemesh/io.hpp"
#include "emoface/facemesh/mesh_document.hpp"
#include "emoface/fuzzyexpr/engine.hpp"
#include "emoface/fuzzyexpr/names.hpp"
#include "emoface/muscles/solver.hpp"
#include "emoface/retarget/default_head.hpp"
#include "emoface/retarget/transfer.hpp"

namespace fm = emoface::facemesh;
namespace rt = emoface::retarget;
namespace mu = emoface::muscles;
namespace fx = emoface::fuzzyexpr;

namespace {

using Params = std::map<std::string, double>;

const std::string kData = std::string(EMOFACE_SOURCE_DIR) + "/data/face/";

struct Built {
  fm::Face generic, head;
  rt::DefaultHeadReport report;
};

const Built& built() {
  static const Built b = [] {
    Built out;
    out.generic = fm::make_generic_face();
    // EMOFACE_MOUTH_RIG=path: measure a saved rig instead (e.g. an older data/face/default.rig,
    // for the before/after figures in docs/retarget.md)
    if (const char* rig = std::getenv("EMOFACE_MOUTH_RIG")) {
      out.head = fm::load_face(rig);
    } else {
      const fm::MeshDocument doc = fm::read_mesh_document(kData + "makehuman_head.obj");
      out.head = rt::build_default_head(out.generic, doc, &out.report);
    }
    return out;
  }();
  return b;
}

// Neutral + the six emotions at 0.9 (fuzzyexpr order: sadness, happiness, anger, fear, disgust,
// surprise) and the jaw fully open.
std::vector<std::pair<std::string, Params>> poses() {
  const fx::Engine engine;
  std::vector<std::pair<std::string, Params>> out;
  const char* names[] = {"sadness", "happiness", "anger", "fear", "disgust", "surprise"};
  for (std::size_t e = 0; e < fx::kEmotionCount; ++e) {
    fx::Esv esv{};
    esv[e] = 0.9;
    const auto sides = fx::expand_to_sides(engine.convert(esv));
    Params p;
    for (std::size_t i = 0; i < sides.size(); ++i)
      p[std::string(fx::side_parameter_names()[i])] = sides[i];
    out.push_back({names[e], p});
  }
  out.push_back({"jaw open", Params{{"masseter", 1.0}}});
  return out;
}

Params emotion(const std::string& name) {
  for (auto& [n, p] : poses())
    if (n == name) return p;
  throw std::runtime_error("no pose " + name);
}

const fm::Part* part(const fm::Rig& rig, const std::string& name) {
  for (const auto& p : rig.parts)
    if (p.name == name) return &p;
  return nullptr;
}

// Mouth width: distance between the outer mouth corners (iBUG 48, 54).
double mouth_width(const fm::Face& f) {
  return (f.mesh.vertices.row(f.rig.ibug68[48]) - f.mesh.vertices.row(f.rig.ibug68[54])).norm();
}

double inner_width(const fm::Face& f) {
  return (f.mesh.vertices.row(f.rig.ibug68[60]) - f.mesh.vertices.row(f.rig.ibug68[64])).norm();
}

// The mouth region: head (skin/lip) triangles facing forward at neutral (n_z > 0.2) with a corner
// within 1.35 inner mouth widths (x/y) and 0.75 (depth) of the middle of the mouth (mean of the
// inner corners iBUG 60 and 64), so the lips, the skin round them and the chin's top, not the
// inside of the bag.
std::vector<int> mouth_triangles(const fm::Face& f) {
  const auto& V = f.mesh.vertices;
  const Eigen::Vector3d c = 0.5 * (V.row(f.rig.ibug68[60]) + V.row(f.rig.ibug68[64])).transpose();
  const double w = 1.5 * inner_width(f);
  std::vector<char> head(static_cast<std::size_t>(V.rows()), 1);
  for (const auto& p : f.rig.parts)
    if (p.kind != fm::PartKind::Head)
      for (int v : p.vertices) head[static_cast<std::size_t>(v)] = 0;
  std::vector<int> out;
  for (Eigen::Index t = 0; t < f.mesh.faces.rows(); ++t) {
    const Eigen::Vector3d a = V.row(f.mesh.faces(t, 0)), b = V.row(f.mesh.faces(t, 1)),
                          d = V.row(f.mesh.faces(t, 2));
    bool in = false, all_head = true;
    for (int k = 0; k < 3; ++k) {
      const int v = f.mesh.faces(t, k);
      all_head = all_head && head[static_cast<std::size_t>(v)];
      const Eigen::Vector3d p = V.row(v).transpose() - c;
      in = in ||
           (p.head<2>().norm() < 0.9 * w && std::abs(p.z()) < 0.5 * w);  // w = 1.5 inner widths
    }
    const Eigen::Vector3d n = (b - a).cross(d - a);
    if (in && all_head && n.norm() > 0 && n.normalized().z() > 0.2)
      out.push_back(static_cast<int>(t));
  }
  return out;
}

int flipped(const fm::Face& f, const std::vector<int>& tris, const fm::Vertices& X) {
  int n = 0;
  for (int t : tris) {
    auto normal = [&](const fm::Vertices& P) {
      const Eigen::Vector3d a = P.row(f.mesh.faces(t, 0)), b = P.row(f.mesh.faces(t, 1)),
                            c = P.row(f.mesh.faces(t, 2));
      return Eigen::Vector3d((b - a).cross(c - a));
    };
    if (normal(f.mesh.vertices).dot(normal(X)) <= 0.0) ++n;
  }
  return n;
}

}  // namespace

// Every vertex bound to the lip surface with full weight lies near it (the offset is constant in
// the rig frame: a far vertex does not turn with the lip and tears off its neighbours).
TEST(DefaultHeadMouth, LipBindingsLieNearTheLipSurface) {
  const auto& f = built().head;
  int far = 0, full = 0;
  double worst = 0.0;
  for (const auto& b : f.rig.lips.bound) {
    // the visible lips (the bag behind them follows them with falling weight, at its own offset)
    if (f.rig.materials[static_cast<std::size_t>(b.vertex)] == fm::Material::MouthInterior)
      continue;
    const double o = b.offset.norm();
    if (b.weight >= 0.999) ++full;
    if (o > 0.004 && b.weight > 0.5) ++far;
    if (b.weight > 0.5) worst = std::max(worst, o);
  }
  std::printf(
      "lip bindings: %zu (%d full weight), weight > 0.5 with offset > 4 mm: %d, worst %.1f mm\n",
      f.rig.lips.bound.size(), full, far, 1e3 * worst);
  EXPECT_EQ(far, 0);
}

TEST(DefaultHeadMouth, NoTrianglesTurnOverAroundTheMouth) {
  const auto& f = built().head;
  const mu::FaceSolver solver(f.mesh, f.rig);
  const auto tris = mouth_triangles(f);
  int total = 0, worst = 0;
  for (const auto& [name, p] : poses()) {
    const int n = flipped(f, tris, solver.deform(p).vertices);
    std::printf("%-9s flipped %d of %zu mouth triangles\n", name.c_str(), n, tris.size());
    total += n, worst = std::max(worst, n);
  }
  std::printf("total %d\n", total);
  // before this session's lip transfer: worst 38 (happiness), total 159; after: 20 (jaw open), 74.
  // Session 5: 31 (jaw open), 84: the lip border now turns with the jaw by the generic's weights
  // (LipGrid::border_jaw) — before, the border took MakeHuman's nearest jaw vertex, which turned
  // the upper lip's middle with the jaw (0.83-0.87, a V torn down into the opened mouth) and left
  // the lower lip's middle behind (0); the lower lip now opens fully and its rows fold over the
  // bag. With round 5's surprise (the jaw at Big, docs/fuzzyexpr.md) on the integrated tree:
  // surprise 19, total 92. Session 7 (zygomatics 1.3× stronger, the AU4 group 2×): total 101.
  EXPECT_LE(worst, 32);
  EXPECT_LE(total, 105);
}

// Happiness (zygomatic major) lifts the mouth corners (the inner corners iBUG 60/64: on the head
// the transfer puts them on its own slit's corners; the outer 48/54 come from the registration
// and sat 13 mm outside them) on the head by at least half of what it does on the generic face,
// scaled by the mouth widths.
TEST(DefaultHeadMouth, HappinessRaisesTheCorners) {
  const auto& b = built();
  auto rise = [&](const fm::Face& f) {
    const mu::FaceSolver solver(f.mesh, f.rig);
    const auto X = solver.deform(emotion("happiness")).vertices;
    double r = 0.0;
    for (int k : {60, 64}) r += 0.5 * (X(f.rig.ibug68[k], 1) - f.mesh.vertices(f.rig.ibug68[k], 1));
    return r / inner_width(f);
  };
  const double g = rise(b.generic), h = rise(b.head);
  std::printf("corner rise / mouth width: generic %.3f, head %.3f\n", g, h);
  EXPECT_GT(g, 0.0);
  EXPECT_GT(h, 0.5 * g);
}

// Surprise opens the mouth: upper and lower lip apart at the middle (iBUG 62, 66) by at least 10 %
// of the inner mouth width (60–64); printed with the inner corners' distances to their neighbours
// 61 and 65 (equal on both sides when the opening is symmetric).
TEST(DefaultHeadMouth, SurpriseOpensTheMouth) {
  const auto& f = built().head;
  const mu::FaceSolver solver(f.mesh, f.rig);
  const auto X = solver.deform(emotion("surprise")).vertices;
  auto dist = [&](int a, int c) {
    return (X.row(f.rig.ibug68[a]) - X.row(f.rig.ibug68[c])).norm();
  };
  const double w = inner_width(f), mid = X(f.rig.ibug68[62], 1) - X(f.rig.ibug68[66], 1);
  std::printf(
      "surprise: opening at the middle %.1f %% of the mouth width, corners %.1f / %.1f %%\n",
      100 * mid / w, 100 * dist(60, 61) / w, 100 * dist(64, 65) / w);
  EXPECT_GT(mid, 0.1 * w);
}

// Lip colour only on the lips, no halo: vertex colours are interpolated over the triangles, so a
// lip-coloured vertex tints every triangle around it. No head triangle with a lip-coloured corner
// has its centroid beyond the mouth's corners (the inner corners iBUG 60/64, which the transfer
// puts on the target's own slit) by more than 3 mm, or farther above or below the line through
// them than 40 % of the mouth's width (the lips of a closed mouth are less high than that), in
// front of the corners (the bag's inside is not seen).
TEST(DefaultHeadMouth, LipColourOnlyOnTheLips) {
  const auto& f = built().head;
  const auto& V = f.mesh.vertices;
  const Eigen::Vector3d c0 = V.row(f.rig.ibug68[60]).transpose(),
                        c1 = V.row(f.rig.ibug68[64]).transpose();
  const double w = c1.x() - c0.x();
  ASSERT_GT(w, 0.0);
  const fm::Part* head = part(f.rig, "head");
  ASSERT_NE(head, nullptr);
  std::vector<char> in_head(static_cast<std::size_t>(V.rows()), 0);
  for (int v : head->vertices) in_head[static_cast<std::size_t>(v)] = 1;
  int beyond = 0;
  double worst = 0.0;
  for (Eigen::Index t = 0; t < f.mesh.faces.rows(); ++t) {
    bool lip = false, all_head = true;
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      const int v = f.mesh.faces(t, k);
      all_head = all_head && in_head[static_cast<std::size_t>(v)];
      lip = lip || f.rig.materials[static_cast<std::size_t>(v)] == fm::Material::Lip;
      p += V.row(v).transpose() / 3.0;
    }
    if (!lip || !all_head || p.z() < std::min(c0.z(), c1.z())) continue;
    const double s = std::clamp((p.x() - c0.x()) / w, 0.0, 1.0);
    const double dy = std::abs(p.y() - ((1 - s) * c0.y() + s * c1.y()));
    const double d = std::max({c0.x() - p.x(), p.x() - c1.x(), dy - 0.4 * w, 0.0});
    worst = std::max(worst, d);
    beyond += d > 0.003;
  }
  std::printf(
      "lip-tinted triangles beyond 3 mm of the mouth (corners %.1f / %.1f mm): %d (worst "
      "%.1f mm)\n",
      1e3 * c0.x(), 1e3 * c1.x(), beyond, 1e3 * worst);
  EXPECT_EQ(beyond, 0);
}

// The mouth's iBUG landmarks lie on the head's own lips: the upper lip's outer centre (51) above
// the corners (60, 64) and the lower lip's (57) below them, each by at least 10 % of the inner
// mouth width (MakeHuman's lower lip centre used to sit 3 mm below the corners, at the slit), and
// the inner upper and lower points (61/67, 62/66, 63/65) on different vertices (a closed slit's two
// rows are 1.4 mm apart; 61 and 67 used to share one).
TEST(DefaultHeadMouth, MouthLandmarksOnTheirOwnLips) {
  const auto& f = built().head;
  const auto& V = f.mesh.vertices;
  const auto& ib = f.rig.ibug68;
  const double line = 0.5 * (V(ib[60], 1) + V(ib[64], 1)), w = inner_width(f);
  std::printf("iBUG 51 %.1f %%, 57 %.1f %% of the inner width above the corners\n",
              100 * (V(ib[51], 1) - line) / w, 100 * (V(ib[57], 1) - line) / w);
  EXPECT_GT(V(ib[51], 1) - line, 0.1 * w);
  EXPECT_LT(V(ib[57], 1) - line, -0.1 * w);
  for (const auto& [up, low] : {std::pair{61, 67}, std::pair{62, 66}, std::pair{63, 65}})
    EXPECT_NE(ib[static_cast<std::size_t>(up)], ib[static_cast<std::size_t>(low)])
        << up << "/" << low;
}
