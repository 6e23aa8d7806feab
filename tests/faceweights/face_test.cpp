// Face checks of the weight sets with the muscle model on the default face:
//  * every FACS / ARKit row with muscle terms moves the face region of its action unit most, on the
//    row's side (iBUG-68 landmark groups of the default face);
//  * the round trip params → ARKit → params on the six emotions (fuzzyexpr, intensity 0.9).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "emoface/facemesh/default_face.hpp"
#include "emoface/faceweights/mapper.hpp"
#include "emoface/fuzzyexpr/engine.hpp"
#include "emoface/fuzzyexpr/names.hpp"
#include "emoface/muscles/parameters.hpp"
#include "emoface/muscles/solver.hpp"

namespace emoface::faceweights {
namespace {

const facemesh::Face& face() {
  static const facemesh::Face f = facemesh::make_generic_face();
  return f;
}
const muscles::FaceSolver& solver() {
  static const muscles::FaceSolver s(face().mesh, face().rig);
  return s;
}

// iBUG-68 groups (0-based): jaw/chin 5–11, brows 17–26, nose 27–35, eyes 36–47, mouth 48–67.
struct Group {
  const char* name;
  int first, last;
};
constexpr Group kGroups[] = {{"chin", 5, 11}, {"brow", 17, 26}, {"nose", 27, 35},
                             {"eye", 36, 47}, {"mouth", 48, 67}};

// The region(s) each action unit moves (FACS manual AU descriptions; thesis Table A.1).
std::set<std::string> expected_groups(int au) {
  if (au == 1 || au == 2 || au == 4) return {"brow"};
  if (au == 5 || au == 7 || au == 43 || au == 45) return {"eye"};
  if (au == 6) return {"eye"};  // orbicularis oculi orbitalis: around the eye (cheek and lids)
  if (au == 9) return {"nose"};
  if (au == 10 || au == 11) return {"mouth", "nose"};
  if (au == 17 || au == 26) return {"chin", "mouth"};
  return {"mouth"};
}

int first_au(const std::string& facs) {
  if (facs.rfind("AU", 0) != 0) return -1;
  return std::atoi(facs.c_str() + 2);
}

struct Motion {
  std::map<std::string, double> group;  // largest vertex displacement per region, metres
  double left = 0, right = 0;           // summed displacement of all vertices with x > 0 / x < 0
};

// The region of each vertex: the group of its nearest iBUG landmark (neutral face), so the chin
// boss (nearest to the chin tip 8 or the lower lip) and the cheeks are covered, not only the
// landmark vertices.
const std::vector<int>& vertex_groups() {
  static const std::vector<int> groups = [] {
    const auto& v = face().mesh.vertices;
    std::vector<int> out(static_cast<std::size_t>(v.rows()), -1);
    for (long i = 0; i < v.rows(); ++i) {
      double best = 1e300;
      for (int g = 0; g < 5; ++g) {
        for (int k = kGroups[g].first; k <= kGroups[g].last; ++k) {
          const double d = (v.row(i) - v.row(face().rig.ibug68[static_cast<std::size_t>(k)])).norm();
          if (d < best) best = d, out[static_cast<std::size_t>(i)] = g;
        }
      }
    }
    return out;
  }();
  return groups;
}

Motion motion_of(const std::vector<double>& params) {
  const auto d0 = solver().deform(std::vector<double>(muscles::kParameterCount, 0.0));
  const auto d = solver().deform(params);
  Motion m;
  for (const auto& g : kGroups) m.group[g.name] = 0.0;
  for (long v = 0; v < d.vertices.rows(); ++v) {
    const double len = (d.vertices.row(v) - d0.vertices.row(v)).norm();
    double& best = m.group[kGroups[vertex_groups()[static_cast<std::size_t>(v)]].name];
    best = std::max(best, len);
    (face().mesh.vertices(v, 0) > 0 ? m.left : m.right) += len;
  }
  return m;
}

void check_rows(const WeightSet& set) {
  const auto& names = muscles::parameter_names();
  int checked = 0;
  for (const auto& t : set.targets) {
    if (t.terms.empty()) continue;
    bool level_only = true;
    std::vector<double> p(names.size(), 0.0);
    for (const auto& term : t.terms) {
      const char last = term.input.back();
      if (last == '+' || last == '-') level_only = false;
      else p[muscles::parameter_index(term.input)] = 1.0;
    }
    if (!level_only) continue;  // gaze and head rows rotate eyes / head (checked by muscles' tests)
    const int au = first_au(t.facs);
    ASSERT_GT(au, 0) << t.name;
    const Motion m = motion_of(p);
    const auto best = std::max_element(m.group.begin(), m.group.end(),
                                       [](auto& a, auto& b) { return a.second < b.second; });
    const auto expected = expected_groups(au);
    EXPECT_TRUE(expected.count(best->first))
        << set.set << " " << t.name << " (AU" << au << ") moves " << best->first << " most ("
        << best->second * 1000 << " mm)";
    EXPECT_GT(best->second, 0.5e-3) << t.name << " hardly moves the face";
    const std::string& n = t.name;
    // the side check applies to rows whose muscles are all on one side (not the one pressor)
    bool all_l = true, all_r = true;
    for (const auto& term : t.terms) {
      all_l = all_l && term.input.size() > 2 && term.input.substr(term.input.size() - 2) == "_l";
      all_r = all_r && term.input.size() > 2 && term.input.substr(term.input.size() - 2) == "_r";
    }
    const bool left = all_l && n.size() > 2 && n.substr(n.size() - 2) == "_L";
    const bool right = all_r && n.size() > 2 && n.substr(n.size() - 2) == "_R";
    EXPECT_EQ(all_l, n.substr(n.size() - 2) == "_L" && all_l) << n;
    if (left) {
      EXPECT_GT(m.left, 3.0 * m.right) << t.name << " should move the subject's left (+x)";
    }
    if (right) {
      EXPECT_GT(m.right, 3.0 * m.left) << t.name << " should move the subject's right (-x)";
    }
    ++checked;
  }
  EXPECT_GT(checked, 25);
}

TEST(FaceRegions, EveryFacsRowMovesItsRegion) { check_rows(builtin_weight_set("facs")); }
TEST(FaceRegions, EveryArkitRowMovesItsRegion) { check_rows(builtin_weight_set("arkit")); }

std::vector<double> emotion_params(fuzzyexpr::Emotion e) {
  static const fuzzyexpr::Engine engine;
  const auto sides = fuzzyexpr::expand_to_sides(engine.single(e, 0.9));
  std::vector<double> p(muscles::kParameterCount, 0.0);
  for (std::size_t i = 0; i < sides.size(); ++i)
    p[muscles::parameter_index(std::string(fuzzyexpr::side_parameter_names()[i]))] = sides[i];
  return p;
}

// Round trip params → ARKit → params on the six emotions at 0.9. Not every parameter can come back
// (ARKit has one browDown per side for three brow-lowering muscles), so the tolerances are stated
// where it matters: the ARKit weights of the fitted parameters match the original ones within 0.001
// (measured ≤ 1e-5: the fit is exact in ARKit space), the identifiable parameters (the muscles with
// an ARKit shape of their own) within 0.02 (measured 0.012, happiness: the zygomatic minor's column
// is 0.3·mouthSmile + 0.5·mouthUpperUp, the same as zygomatic major + levator labii superioris),
// and the deformed faces within 7 mm at every vertex (measured 0.0–5.9 mm on the issue-14 face, whose
// stronger zygomatic minor makes the happiness gap larger than the 3.4 mm of the earlier face; the
// largest for happiness for the same reason; docs/engines.md).
TEST(RoundTrip, SixEmotionsThroughArkit) {
  const auto& names = muscles::parameter_names();
  const Mapper m(builtin_weight_set("arkit"), names);
  const std::set<std::string> identifiable = {
      "zygomatic_major_l", "zygomatic_major_r", "triangularis_l", "triangularis_r", "risorius_l",
      "risorius_r", "depressor_labii_l", "depressor_labii_r", "frontalis_lateralis_l",
      "frontalis_lateralis_r", "levator_palpebrae_superioris_l", "levator_palpebrae_superioris_r",
      "orbicularis_oculi_palpebralis_l", "orbicularis_oculi_palpebralis_r",
      "orbicularis_oculi_orbitalis_l", "orbicularis_oculi_orbitalis_r", "masseter",
      "orbicularis_oris_funneler", "orbicularis_oris_pressor", "eye_blink_l", "eye_blink_r"};
  for (std::size_t e = 0; e < fuzzyexpr::kEmotionCount; ++e) {
    const auto emotion = fuzzyexpr::emotion_at(e);
    const auto p = emotion_params(emotion);
    const auto w = m.forward(p);
    std::vector<double> back;
    const auto report = m.inverse(w, back);
    EXPECT_TRUE(report.converged) << report.message;
    const auto w2 = m.forward(back);
    double werr = 0, perr = 0, verr = 0;
    for (std::size_t k = 0; k < w.size(); ++k) werr = std::max(werr, std::fabs(w2[k] - w[k]));
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (identifiable.count(names[i])) perr = std::max(perr, std::fabs(back[i] - p[i]));
    }
    const auto a = solver().deform(p);
    const auto b = solver().deform(back);
    for (long v = 0; v < a.vertices.rows(); ++v)
      verr = std::max(verr, (a.vertices.row(v) - b.vertices.row(v)).norm());
    std::printf("round trip %-9s: ARKit max %.5f  identifiable params max %.5f  face max %.3f mm  "
                "(%d iterations)\n",
                std::string(fuzzyexpr::to_string(emotion)).c_str(), werr, perr, verr * 1000,
                report.sweeps);
    EXPECT_LT(werr, 1e-3) << fuzzyexpr::to_string(emotion);
    EXPECT_LT(perr, 0.02) << fuzzyexpr::to_string(emotion);
    // happiness 7.57 mm since session 7's 1.3× stronger zygomatics (the error scales with the
    // smile)
    EXPECT_LT(verr, 8e-3) << fuzzyexpr::to_string(emotion);
  }
}

}  // namespace
}  // namespace emoface::faceweights
