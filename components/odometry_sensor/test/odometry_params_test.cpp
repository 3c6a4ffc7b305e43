#include "components/odometry_sensor/odometry_params.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <string>

#include "tests/support/validation_error.hpp"

namespace robodds::odometry_sensor {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

using test_support::validation_error;

bool starts_with(const std::string& text, const std::string& prefix) {
  return text.rfind(prefix, 0) == 0;
}

TEST(OdometryParams, DefaultsAreValid) {
  const OdometryParams params;
  EXPECT_NO_THROW(params.validate());
  EXPECT_EQ(params.rate_hz, 50.0);
  EXPECT_EQ(params.wheel_speed_noise_std_mps, 0.02);
  EXPECT_EQ(params.left_slip, 0.0);
  EXPECT_EQ(params.right_slip, 0.0);
  EXPECT_EQ(params.turn_rate_bias_radps, 0.0);
  EXPECT_EQ(params.slip_wander_sigma, 0.0) << "off by default: no scenario draws for it unless it asks";
}

TEST(OdometryParams, AcceptsZeroNoiseAndSlipsInsideTheRange) {
  OdometryParams params;
  params.wheel_speed_noise_std_mps = 0.0;
  params.left_slip = 0.4999;
  params.right_slip = -0.4999;
  EXPECT_NO_THROW(params.validate());
}

TEST(OdometryParams, RejectsBadRate) {
  for (double bad : {0.0, -1.0, kNan, kInf}) {
    OdometryParams params;
    params.rate_hz = bad;
    const std::string message = validation_error(params);
    EXPECT_TRUE(starts_with(message, "rate_hz: must be > 0 and finite (got ")) << message;
  }
  OdometryParams params;
  params.rate_hz = -1.0;
  EXPECT_EQ(validation_error(params), "rate_hz: must be > 0 and finite (got -1)");
}

TEST(OdometryParams, RejectsBadNoiseStd) {
  for (double bad : {-0.01, kNan, kInf}) {
    OdometryParams params;
    params.wheel_speed_noise_std_mps = bad;
    const std::string message = validation_error(params);
    EXPECT_TRUE(starts_with(message, "wheel_speed_noise_std_mps: must be >= 0 and finite (got "))
        << message;
  }
}

TEST(OdometryParams, RejectsLeftSlipOutsideOpenRange) {
  for (double bad : {0.5, -0.5, 0.7, -3.0, kNan, kInf, -kInf}) {
    OdometryParams params;
    params.left_slip = bad;
    const std::string message = validation_error(params);
    EXPECT_TRUE(starts_with(message, "left_slip: must be in (-0.5, 0.5) (got ")) << message;
  }
}

TEST(OdometryParams, RejectsRightSlipOutsideOpenRange) {
  for (double bad : {0.5, -0.5, 0.7, -3.0, kNan, kInf, -kInf}) {
    OdometryParams params;
    params.right_slip = bad;
    const std::string message = validation_error(params);
    EXPECT_TRUE(starts_with(message, "right_slip: must be in (-0.5, 0.5) (got ")) << message;
  }
  OdometryParams params;
  params.right_slip = kNan;
  EXPECT_EQ(validation_error(params), "right_slip: must be in (-0.5, 0.5) (got nan)");
}

TEST(OdometryParams, TurnRateBiasMayHaveEitherSignButMustBeFinite) {
  OdometryParams params;
  params.turn_rate_bias_radps = -0.02;
  EXPECT_NO_THROW(params.validate());
  for (double bad : {kNan, kInf, -kInf}) {
    params.turn_rate_bias_radps = bad;
    const std::string message = validation_error(params);
    EXPECT_TRUE(starts_with(message, "turn_rate_bias_radps: must be finite (got ")) << message;
  }
}

TEST(OdometryParams, RejectsABadSlipWander) {
  for (double bad : {-0.001, 0.5, kNan, kInf}) {
    OdometryParams params;
    params.slip_wander_sigma = bad;
    const std::string message = validation_error(params);
    EXPECT_TRUE(starts_with(message, "slip_wander_sigma: must be in [0, 0.5) (got ")) << message;
  }
  for (double bad : {0.0, -1.0, kNan, kInf}) {
    OdometryParams params;
    params.slip_wander_tau_s = bad;
    const std::string message = validation_error(params);
    EXPECT_TRUE(starts_with(message, "slip_wander_tau_s: must be > 0 and finite (got ")) << message;
  }
}

}  // namespace
}  // namespace robodds::odometry_sensor
