#include "sim/open_loop_commander/open_loop_commander.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <string>

#include "tests/support/validation_error.hpp"

namespace robodds::open_loop_commander {
namespace {

TEST(OpenLoop, SineAroundBiasWithPerRobotPhase) {
  OpenLoopParams p;
  p.omega_bias_radps = 0.1;
  p.omega_amplitude_radps = 0.5;
  p.omega_period_s = 4.0;
  p.phase_per_robot_rad = 0.0;
  EXPECT_DOUBLE_EQ(open_loop_command(p, 0, 0.0).omega, 0.1);
  EXPECT_NEAR(open_loop_command(p, 0, 1.0).omega, 0.6, 1e-12);
  EXPECT_DOUBLE_EQ(open_loop_command(p, 3, 0.0).v, 1.0);
  p.phase_per_robot_rad = 1.0;
  EXPECT_NE(open_loop_command(p, 0, 0.3).omega, open_loop_command(p, 1, 0.3).omega);
}

using test_support::validation_error;

TEST(OpenLoop, RejectsNonPositivePeriod) {
  OpenLoopParams p;
  EXPECT_EQ(validation_error(p), "");
  p.omega_period_s = 0.0;
  EXPECT_EQ(validation_error(p), "omega_period_s: must be > 0 and finite (got 0)");
}

TEST(OpenLoop, RejectsNonFiniteCommandParameters) {
  OpenLoopParams p;
  p.v_mps = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(validation_error(p), "v_mps: must be finite (got nan)");
  p = OpenLoopParams{};
  p.omega_amplitude_radps = std::numeric_limits<double>::infinity();
  EXPECT_EQ(validation_error(p), "omega_amplitude_radps: must be finite (got inf)");
}

}  // namespace
}  // namespace robodds::open_loop_commander
