// Validation of the UWB sensor's parameters: ranges from the table, the error model's cross-field
// rule and the walls, each naming its key. (The array is the scenario's fact `facts: uwb_array:`:
// its checks are tested in common/model/test and system/test.)
#include "components/uwb_sensor/uwb_sensor_params.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace robodds::uwb_sensor {
namespace {

std::string message_of(const UwbSensorParams& p) {
  try {
    p.validate();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "ok";
}

TEST(UwbSensorParams, DefaultsAreIssue11s) {
  const UwbSensorParams p;
  EXPECT_EQ(message_of(p), "ok");
  EXPECT_EQ(p.rate_hz, 50.0);
  EXPECT_EQ(p.max_range_m, 100.0);
  EXPECT_EQ(p.errors.white_sigma_m, 0.04);
  EXPECT_EQ(p.errors.link_bias_sigma_m, 0.07);
  EXPECT_EQ(p.errors.link_bias_tau_s, 2.0);
  EXPECT_EQ(p.errors.common_sigma_m, 0.30);
  EXPECT_EQ(p.errors.common_tau_s, 10.0);
  EXPECT_EQ(p.errors.nlos_probability, 0.0);
  EXPECT_EQ(p.errors.sigma_scale, 1.0);
  EXPECT_EQ(p.errors.frame_loss_probability, 0.0);
}

TEST(UwbSensorParams, BadValuesNameTheKey) {
  UwbSensorParams p;
  p.max_range_m = -1.0;
  EXPECT_EQ(message_of(p), "max_range_m: must be > 0 and finite (got -1)");
  p = UwbSensorParams{};
  p.errors.common_sigma_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(message_of(p), "common_sigma_m: must be >= 0 and finite (got nan)");
  p = UwbSensorParams{};
  p.errors.nlos_max_m = 0.1;
  EXPECT_EQ(message_of(p), "nlos_min_m: must be <= nlos_max_m (0.1) (got 0.2)");
}

TEST(UwbSensorParams, WallsArePairsOfFinitePointsAndNotPoints) {
  UwbSensorParams p;
  p.nlos_walls_m = {{1.0, -1.0}, {1.0, 1.0}, {3.0, 0.0}, {4.0, 0.0}};
  EXPECT_EQ(message_of(p), "ok");
  ASSERT_EQ(p.walls().size(), 2u);
  EXPECT_EQ(p.walls()[1].to, Eigen::Vector2d(4.0, 0.0));
  p.nlos_walls_m = {{1.0, -1.0}, {1.0, 1.0}, {3.0, 0.0}};
  EXPECT_EQ(message_of(p),
            "nlos_walls_m: must list walls as pairs of end points (an even number of points) (got 3 points)");
  p.nlos_walls_m = {{1.0, std::nan("")}, {1.0, 1.0}};
  EXPECT_EQ(message_of(p).rfind("nlos_walls_m: point 0 must be finite", 0), 0u) << message_of(p);
  p.nlos_walls_m = {{1.0, 1.0}, {1.0, 1.0}};
  EXPECT_EQ(message_of(p).rfind("nlos_walls_m: a wall must be at least 1 mm long", 0), 0u) << message_of(p);
}

}  // namespace
}  // namespace robodds::uwb_sensor
