// Validation of the UWB sensor's parameters: ranges from the table, the error model's cross-field
// rule, and the array (explicit nodes: 3 to 8, none coincident), each naming its key.
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
  const model::UwbArray a = p.array();
  ASSERT_EQ(a.nodes_m.size(), 4u);
  EXPECT_EQ(a.nodes_m[0], Eigen::Vector2d(0.25, 0.25)) << "model::square_array: front-left first, counter-clockwise";
  EXPECT_EQ(a.nodes_m[1], Eigen::Vector2d(-0.25, 0.25));
}

TEST(UwbSensorParams, BadValuesNameTheKey) {
  UwbSensorParams p;
  p.array_params.array_side_m = 0.0;
  EXPECT_EQ(message_of(p), "array_side_m: must be > 0 and finite (got 0)");
  p = UwbSensorParams{};
  p.max_range_m = -1.0;
  EXPECT_EQ(message_of(p), "max_range_m: must be > 0 and finite (got -1)");
  p = UwbSensorParams{};
  p.errors.common_sigma_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(message_of(p), "common_sigma_m: must be >= 0 and finite (got nan)");
  p = UwbSensorParams{};
  p.errors.nlos_max_m = 0.1;
  EXPECT_EQ(message_of(p), "nlos_min_m: must be <= nlos_max_m (0.1) (got 0.2)");
}

TEST(UwbSensorParams, ExplicitNodesNeedThreeToEightDistinctNodes) {
  UwbSensorParams p;
  p.array_params.nodes_m = {{0.3, 0.0}, {-0.3, 0.0}};
  EXPECT_EQ(message_of(p), "nodes_m: needs at least 3 nodes (a relative heading needs them) (got 2 nodes)");
  p.array_params.nodes_m = {{0.3, 0.0}, {-0.3, 0.0}, {0.3, 0.0005}};
  EXPECT_EQ(message_of(p), "nodes_m: nodes 0 and 2 coincide (closer than 0.001 m) (got 5e-04 m apart)");
  p.array_params.nodes_m = {{0.3, 0.0}, {-0.3, 0.0}, {0.0, 0.3}};
  EXPECT_EQ(message_of(p), "ok");
  EXPECT_EQ(p.array().nodes_m[2], Eigen::Vector2d(0.0, 0.3)) << "explicit nodes replace the square";
  p.array_params.nodes_m.clear();
  for (int k = 0; k < 9; ++k) {
    p.array_params.nodes_m.push_back({std::cos(k * 0.6), std::sin(k * 0.6)});
  }
  EXPECT_EQ(message_of(p), "nodes_m: must have at most 8 nodes (K x L ranges per sample, at most 64) (got 9 nodes)");
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
