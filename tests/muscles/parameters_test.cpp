#include "emoface/muscles/parameters.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>

#include "emoface/core/errors.hpp"

namespace emoface::muscles {
namespace {

TEST(Parameters, NamesMatchTheProjectContract) {
  const auto& side = side_parameter_names();
  ASSERT_EQ(side.size(), kSideParameterCount);
  EXPECT_EQ(side[0], "zygomatic_major_l");
  EXPECT_EQ(side[1], "zygomatic_major_r");
  EXPECT_EQ(side[12], "orbicularis_oris_funneler");
  EXPECT_EQ(side[13], "orbicularis_oris_pressor");
  EXPECT_EQ(side[34], "masseter");
  ASSERT_EQ(parameter_names().size(), kParameterCount);
  EXPECT_EQ(parameter_names()[35], "eye_gaze_yaw");
  EXPECT_EQ(parameter_names()[39], "head_roll");
  std::set<std::string> unique(parameter_names().begin(), parameter_names().end());
  EXPECT_EQ(unique.size(), kParameterCount);
  for (std::size_t i = 0; i < kParameterCount; ++i) EXPECT_EQ(parameter_index(parameter_names()[i]), i);
}

TEST(Parameters, Validation) {
  EXPECT_THROW(parameter_index("smile"), InvalidInput);
  EXPECT_THROW(to_parameter_vector({{"smile", 1.0}}), InvalidInput);
  EXPECT_THROW(to_parameter_vector({{"masseter", std::nan("")}}), InvalidInput);
  EXPECT_THROW(to_parameter_vector({{"masseter", 1.5}}), InvalidInput);
  EXPECT_THROW(to_parameter_vector({{"masseter", -0.1}}), InvalidInput);
  EXPECT_THROW(to_parameter_vector({{"head_yaw", std::numeric_limits<double>::infinity()}}), InvalidInput);
  EXPECT_THROW(to_parameter_vector({{"head_yaw", 4.0}}), InvalidInput);
  EXPECT_NO_THROW(to_parameter_vector({{"head_yaw", -0.5}, {"masseter", 1.0}}));
  EXPECT_THROW(validate_parameter_vector(std::vector<double>(35, 0.0)), InvalidInput);
  const auto v = to_parameter_vector({{"risorius_r", 0.25}});
  EXPECT_EQ(v[parameter_index("risorius_r")], 0.25);
  EXPECT_EQ(v[parameter_index("risorius_l")], 0.0);
}

}  // namespace
}  // namespace emoface::muscles
