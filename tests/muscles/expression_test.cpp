// Issue 14: expressions through the whole chain (fuzzyexpr rules → muscles on the default face): the
// eyes narrow but never shut outside blinks, surprise opens them.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "emoface/facemesh/default_face.hpp"
#include "emoface/fuzzyexpr/engine.hpp"
#include "emoface/muscles/solver.hpp"

namespace emoface::muscles {
namespace {

namespace fm = facemesh;
namespace fx = fuzzyexpr;

const fm::Face& face() {
  static const fm::Face f = fm::make_default_face();
  return f;
}
const FaceSolver& solver() {
  static const FaceSolver s(face().mesh, face().rig);
  return s;
}

std::vector<double> parameters(const fx::Esv& esv) {
  static const fx::Engine engine;
  const fx::SideParameters sides = fx::expand_to_sides(engine.convert(esv));
  std::vector<double> v(kParameterCount, 0.0);
  for (std::size_t i = 0; i < sides.size(); ++i) v[i] = sides[i];
  return v;
}

// Smallest of the two eyes' apertures as a fraction of neutral.
double aperture_fraction(const std::vector<double>& values) {
  const double a0 = eye_aperture(face().rig, face().mesh.vertices, 0);
  const auto d = solver().deform(values);
  return std::min(eye_aperture(face().rig, d.vertices, 0), eye_aperture(face().rig, d.vertices, 1)) / a0;
}

TEST(Expressions, EyesNarrowButNeverShut) {
  for (std::size_t e = 0; e < fx::kEmotionCount; ++e) {
    for (double x : {0.3, 0.5, 0.7, 0.9, 1.0}) {
      fx::Esv esv{};
      esv[e] = x;
      const double f = aperture_fraction(parameters(esv));
      EXPECT_GE(f, 0.30) << std::string(fx::to_string(fx::emotion_at(e))) << " " << x;
      if (x == 0.9) std::printf("%-10s 0.9: aperture %.2f of neutral\n", std::string(fx::to_string(fx::emotion_at(e))).c_str(), f);
    }
  }
  // the blends of the docs sheets too
  for (const fx::Esv& esv : {fx::Esv{0.7, 0, 0, 0.5, 0, 0}, fx::Esv{0, 0.7, 0, 0, 0, 0.6},
                             fx::Esv{0, 0, 0.7, 0, 0.5, 0}, fx::Esv{0, 0, 0, 0.6, 0, 0.8}}) {
    EXPECT_GE(aperture_fraction(parameters(esv)), 0.30);
  }
  fx::Esv anger{}, fear{}, surprise{};
  anger[fx::index(fx::Emotion::Anger)] = 0.9;
  fear[fx::index(fx::Emotion::Fear)] = 0.9;
  surprise[fx::index(fx::Emotion::Surprise)] = 0.9;
  EXPECT_LT(aperture_fraction(parameters(anger)), 0.85);  // AU7: narrowed
  EXPECT_LT(aperture_fraction(parameters(fear)), 0.85);
  EXPECT_GT(aperture_fraction(parameters(surprise)), 1.15);  // AU5: opened
}

}  // namespace
}  // namespace emoface::muscles
