// Links every emoface library from an installed tree and makes one real call into each; exits non-zero
// when a result is wrong.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "emoface/bridge/landmark_fit.hpp"
#include "emoface/channels/curves.hpp"
#include "emoface/core/rng.hpp"
#include "emoface/core/version.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/fuzzyexpr/engine.hpp"
#include "emoface/mindmap/mood.hpp"
#include "emoface/mindmotion/behaviour.hpp"
#include "emoface/motiongraph/similarity.hpp"
#include "emoface/muscles/solver.hpp"
#include "emoface/parlee/domain.hpp"
#include "emoface/retarget/rbf.hpp"
#include "emoface/runtime/character.hpp"

namespace {
int failures = 0;
void check(bool ok, const char* what) {
  std::printf("%s %s\n", ok ? "ok  " : "FAIL", what);
  if (!ok) ++failures;
}
}  // namespace

int main() {
  namespace fx = emoface::fuzzyexpr;
  std::printf("%s\n", emoface::kGenerator);

  emoface::core::Rng rng(7);
  check(rng.uniform() < 1.0, "core: seeded RNG");

  const fx::Engine engine;
  fx::Esv esv{};
  esv[fx::index(fx::Emotion::Happiness)] = 1.0;
  const fx::Fmcv fmcv = engine.convert(esv);
  check(fmcv[fx::index(fx::Muscle::ZygomaticMajor)] == 1.0, "fuzzyexpr: happiness drives zygomatic major");

  check(std::abs(emoface::channels::phi_plus(1.0, 1.0) - 1.0) < 1e-12, "channels: onset curve reaches 1 at Do");

  emoface::parlee::DomainSpec domain;
  emoface::parlee::parse_domain_text("(define (domain tiny))", "<consumer>", domain);
  check(domain.name == "tiny", "parlee: domain parsed");

  const auto face = emoface::facemesh::make_generic_face();
  check(face.mesh.vertex_count() > 1000, "facemesh: default face");

  const emoface::muscles::FaceSolver solver(face.mesh, face.rig);
  const auto smile = solver.deform(std::map<std::string, double>{{"zygomatic_major_l", 1.0}});
  check((smile.vertices - face.mesh.vertices).cwiseAbs().maxCoeff() > 1e-4, "muscles: a smile moves vertices");

  Eigen::MatrixX3d src(4, 3), dst(4, 3);
  src << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  dst = src * 2.0;
  const auto net = emoface::retarget::fit_rbf(src, dst);
  check((net.evaluate(Eigen::Vector3d(1, 0, 0)) - Eigen::Vector3d(2, 0, 0)).norm() < 1e-6, "retarget: RBF interpolates");

  const double p[2] = {0, 0}, q[2] = {3, 4}, v[2] = {0, 0};
  check(emoface::motiongraph::similarity(p, v, q, v, 1, 2, emoface::motiongraph::SimilarityOptions{}) > 0.0,
        "motiongraph: similarity metric");

  check(emoface::mindmap::decay_fraction(emoface::mindmap::DecayCurve::Linear, 0.5) > 0.0, "mindmap: decay curve");

  check(emoface::mindmotion::to_string(emoface::mindmotion::SegmentKind::Idle) == "idle", "mindmotion: segment kinds");

  check(emoface::bridge::FitOptions{}.sample_levels.size() > 0, "bridge: fit options");

  emoface::runtime::Character character{emoface::runtime::CharacterConfig{}};
  character.push_emotions({0, 1, 0, 0, 0, 0});
  character.update(2.0);
  check(character.parameters().size() == 42 && character.parameters()[0] > 0.3, "runtime: a character smiles");

  return failures == 0 ? 0 : 1;
}
