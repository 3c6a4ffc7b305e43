#include "components/uwb_relative_estimator/relative_estimator_params.hpp"

#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/validation_error.hpp"

namespace robodds::uwb_relative_estimator {
namespace {

using test_support::validation_error;

TEST(RelativeEstimatorParams, DefaultsAreIssue11sValues) {
  const RelativeEstimatorParams p;
  EXPECT_EQ(validation_error(p), "");
  EXPECT_EQ(p.window_epochs, 30);
  EXPECT_EQ(p.solver.loss, RobustLoss::kNone) << "the paper solves eq. (1) by plain least squares";
  EXPECT_DOUBLE_EQ(p.window.odometry_xy_std_m, 0.005);
  EXPECT_DOUBLE_EQ(p.window.odometry_theta_std_rad, 0.005);
  EXPECT_DOUBLE_EQ(p.window.uwb_xy_std_m, 0.3);
  EXPECT_DOUBLE_EQ(p.window.uwb_theta_std_rad, 0.1);
  EXPECT_EQ(p.pf.num_particles, 500);
}

TEST(RelativeEstimatorParams, EachBadValueNamesItsKeyWithThePrefix) {
  RelativeEstimatorParams p;
  p.window_epochs = 1;
  EXPECT_NE(validation_error(p).find("window_epochs"), std::string::npos) << validation_error(p);
  p = RelativeEstimatorParams{};
  p.pf.num_particles = 0;
  EXPECT_NE(validation_error(p).find("pf.num_particles"), std::string::npos) << validation_error(p);
  p = RelativeEstimatorParams{};
  p.window.uwb_xy_std_m = 0.0;
  EXPECT_NE(validation_error(p).find("window.uwb_xy_std_m"), std::string::npos) << validation_error(p);
  p = RelativeEstimatorParams{};
  p.tracker.cost_ratio = -1.0;
  EXPECT_NE(validation_error(p).find("tracker.cost_ratio"), std::string::npos) << validation_error(p);
}

}  // namespace
}  // namespace robodds::uwb_relative_estimator
