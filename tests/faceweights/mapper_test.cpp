#include "emoface/faceweights/mapper.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "emoface/core/errors.hpp"
#include "emoface/faceweights/names.hpp"
#include "emoface/muscles/parameters.hpp"

namespace emoface::faceweights {
namespace {

const std::vector<std::string>& names() { return muscles::parameter_names(); }

std::size_t param(const std::string& n) { return muscles::parameter_index(n); }

std::size_t target(const Mapper& m, const std::string& n) { return m.set().find(n).value(); }

TEST(Mapper, ForwardHandComputedRows) {
  const Mapper m(builtin_weight_set("arkit"), names());
  EXPECT_TRUE(m.unbound_inputs().empty());
  std::vector<double> p(names().size(), 0.0);
  p[param("zygomatic_major_l")] = 0.5;
  p[param("zygomatic_minor_l")] = 0.5;
  p[param("eye_gaze_yaw")] = 0.275;  // half of the 0.55 rad range, to the subject's left
  p[param("eye_blink_r")] = 0.8;
  p[param("corrugator_supercilii_r")] = 1.0;
  p[param("depressor_supercilii_r")] = 1.0;
  const auto w = m.forward(p);
  EXPECT_NEAR(w[target(m, "mouthSmile_L")], 0.5 + 0.3 * 0.5, 1e-12);
  EXPECT_NEAR(w[target(m, "mouthUpperUp_L")], 0.5 * 0.5, 1e-12);
  EXPECT_NEAR(w[target(m, "mouthSmile_R")], 0.0, 1e-12);
  EXPECT_NEAR(w[target(m, "eyeLookOut_L")], 0.5, 1e-12);
  EXPECT_NEAR(w[target(m, "eyeLookIn_R")], 0.5, 1e-12);
  EXPECT_NEAR(w[target(m, "eyeLookIn_L")], 0.0, 1e-12);
  EXPECT_NEAR(w[target(m, "eyeBlink_R")], 0.8, 1e-12);
  EXPECT_NEAR(w[target(m, "browDown_R")], 0.45 + 0.35, 1e-12);
  EXPECT_NEAR(w[target(m, "tongueOut")], 0.0, 1e-12);
  // clamped: gaze beyond the range saturates at 1
  p[param("eye_gaze_yaw")] = -2.0;
  EXPECT_NEAR(m.forward(p)[target(m, "eyeLookOut_R")], 1.0, 1e-12);
}

TEST(Mapper, FacsRows) {
  const Mapper f(builtin_weight_set("facs"), names());
  std::vector<double> p(names().size(), 0.0);
  p[param("head_yaw")] = -0.3927;  // half of π/4 to the subject's right
  p[param("masseter")] = 0.6;
  const auto w = f.forward(p);
  EXPECT_NEAR(w[target(f, "AU52")], 0.5, 1e-4);
  EXPECT_NEAR(w[target(f, "AU51")], 0.0, 1e-12);
  EXPECT_NEAR(w[target(f, "AU26")], 0.6, 1e-12);
}

TEST(Mapper, InverseRecoversIdentifiableParameters) {
  const Mapper m(builtin_weight_set("arkit"), names());
  std::vector<double> p(names().size(), 0.0);
  p[param("zygomatic_major_l")] = 0.7;
  p[param("masseter")] = 0.4;
  p[param("eye_blink_l")] = 0.9;
  p[param("frontalis_lateralis_r")] = 0.3;
  p[param("eye_gaze_yaw")] = -0.3;
  p[param("eye_gaze_pitch")] = 0.1;
  p[param("orbicularis_oculi_palpebralis_r")] = 0.5;
  const auto w = m.forward(p);
  std::vector<double> back;
  const auto report = m.inverse(w, back);
  EXPECT_TRUE(report.converged) << report.message;
  ASSERT_EQ(back.size(), names().size());
  for (std::size_t i = 0; i < names().size(); ++i) EXPECT_NEAR(back[i], p[i], 1e-4) << names()[i];
  EXPECT_TRUE(report.unrepresented.empty());
}

TEST(Mapper, InverseReportsShapesWithoutMuscles) {
  const Mapper m(builtin_weight_set("arkit"), names());
  std::vector<double> w(52, 0.0);
  w[target(m, "tongueOut")] = 1.0;
  w[target(m, "jawOpen")] = 0.5;
  std::vector<double> p;
  const auto r = m.inverse(w, p);
  ASSERT_EQ(r.unrepresented.size(), 1u);
  EXPECT_EQ(r.unrepresented[0], "tongueOut");
  EXPECT_NEAR(p[param("masseter")], 0.5, 1e-5);
}

TEST(Mapper, InverseKeepsParametersTheSetDoesNotUse) {
  const Mapper m(builtin_weight_set("arkit"), names());
  std::vector<double> p(names().size(), 0.0);
  p[param("head_yaw")] = 0.25;  // ARKit has no head shapes: the fit leaves it alone
  m.inverse(std::vector<double>(52, 0.0), p);
  EXPECT_DOUBLE_EQ(p[param("head_yaw")], 0.25);
}

TEST(Mapper, SubsetOfNamesLeavesInputsUnbound) {
  // emo2muscle's 35 side parameters: no gaze, no blinks
  std::vector<std::string> sides(names().begin(), names().begin() + muscles::kSideParameterCount);
  const Mapper m(builtin_weight_set("arkit"), sides);
  EXPECT_EQ(m.unbound_inputs(),
            (std::vector<std::string>{"eye_blink_l", "eye_blink_r", "eye_gaze_pitch", "eye_gaze_yaw"}));
  std::vector<double> p(sides.size(), 0.0);
  p[0] = 1.0;  // zygomatic_major_l
  const auto w = m.forward(p);
  EXPECT_NEAR(w[target(m, "mouthSmile_L")], 1.0, 1e-12);
  EXPECT_NEAR(w[target(m, "eyeBlink_L")], 0.0, 1e-12);
}

TEST(Mapper, BadInputsGiveClearErrors) {
  const Mapper m(builtin_weight_set("arkit"), names());
  std::vector<double> p(names().size(), 0.0);
  p[param("masseter")] = std::nan("");
  try {
    m.forward(p);
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("masseter"), std::string::npos);
  }
  p[param("masseter")] = 1.5;
  EXPECT_THROW(m.forward(p), InvalidInput);
  EXPECT_THROW(m.forward(std::vector<double>(3, 0.0)), InvalidInput);
  std::vector<double> w(52, 0.0), out;
  w[target(m, "jawOpen")] = 1.2;
  try {
    m.inverse(w, out);
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("jawOpen"), std::string::npos);
  }
  w[target(m, "jawOpen")] = std::nan("");
  EXPECT_THROW(m.inverse(w, out), InvalidInput);
  w[target(m, "jawOpen")] = -0.1;
  EXPECT_THROW(m.inverse(w, out), InvalidInput);
  EXPECT_THROW(m.inverse(std::vector<double>(51, 0.0), out), InvalidInput);
  EXPECT_THROW(Mapper(builtin_weight_set("arkit"), {"a", "a"}), InvalidInput);
}

TEST(Mapper, FreeFunctionsAgreeWithMapper) {
  std::vector<double> p(names().size(), 0.0);
  p[param("triangularis_l")] = 0.6;
  const auto w = to_arkit(p, names());
  EXPECT_EQ(w, Mapper(builtin_weight_set("arkit"), names()).forward(p));
  EXPECT_EQ(to_facs(p, names()).size(), builtin_weight_set("facs").targets.size());
  FitReport r;
  const auto back = from_arkit(w, names(), &r);
  EXPECT_TRUE(r.converged);
  EXPECT_NEAR(back[param("triangularis_l")], 0.6, 1e-4);
}

}  // namespace
}  // namespace emoface::faceweights
