#include "components/position_sensor/position_sensor_params.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <string>

#include "tests/support/validation_error.hpp"

namespace robodds::position_sensor {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

using test_support::validation_error;

bool starts_with(const std::string& text, const std::string& prefix) {
  return text.rfind(prefix, 0) == 0;
}

TEST(PositionSensorParams, DefaultsAreValidAndMatchPaper) {
  const PositionSensorParams params;
  EXPECT_NO_THROW(params.validate());
  EXPECT_EQ(params.rate_hz, 10.0);
  EXPECT_EQ(params.noise_var_x_m2, 2.28);
  EXPECT_EQ(params.noise_var_y_m2, 2.28);
  EXPECT_EQ(params.outlier_probability, 0.0);  // no outliers unless asked for
}

TEST(PositionSensorParams, ZeroVarianceIsValid) {
  PositionSensorParams params;
  params.noise_var_x_m2 = 0.0;
  params.noise_var_y_m2 = 0.0;
  EXPECT_NO_THROW(params.validate());
}

TEST(PositionSensorParams, RejectsBadRateNamingKeyAndValue) {
  for (double bad : {0.0, -1.0, kNan, kInf}) {
    PositionSensorParams params;
    params.rate_hz = bad;
    const std::string message = validation_error(params);
    EXPECT_TRUE(starts_with(message, "rate_hz: must be > 0 and finite")) << message;
  }
  PositionSensorParams params;
  params.rate_hz = -1.0;
  EXPECT_EQ(validation_error(params), "rate_hz: must be > 0 and finite (got -1)");
}

TEST(PositionSensorParams, RejectsBadVarianceX) {
  for (double bad : {-1e-9, -2.28, kNan, kInf, -kInf}) {
    PositionSensorParams params;
    params.noise_var_x_m2 = bad;
    const std::string message = validation_error(params);
    EXPECT_TRUE(starts_with(message, "noise_var_x_m2: must be >= 0 and finite (got ")) << message;
  }
}

TEST(PositionSensorParams, RejectsBadVarianceY) {
  for (double bad : {-1e-9, -2.28, kNan, kInf, -kInf}) {
    PositionSensorParams params;
    params.noise_var_y_m2 = bad;
    const std::string message = validation_error(params);
    EXPECT_TRUE(starts_with(message, "noise_var_y_m2: must be >= 0 and finite (got ")) << message;
  }
}

TEST(PositionSensorParams, NanIsReportedAsNan) {
  PositionSensorParams params;
  params.noise_var_y_m2 = kNan;
  EXPECT_EQ(validation_error(params), "noise_var_y_m2: must be >= 0 and finite (got nan)");
}

TEST(PositionSensorParams, OutlierProbabilityIsInZeroToOneExcludingOne) {
  PositionSensorParams params;
  params.outlier_probability = 0.05;
  params.outlier_offset_m = -100.0;
  EXPECT_NO_THROW(params.validate());
  for (double bad : {-0.01, 1.0, kNan}) {
    params.outlier_probability = bad;
    const std::string message = validation_error(params);
    EXPECT_TRUE(starts_with(message, "outlier_probability: must be in [0, 1)")) << message;
  }
}

TEST(PositionSensorParams, OutlierOffsetMustBeFinite) {
  PositionSensorParams params;
  for (double bad : {kNan, kInf}) {
    params.outlier_offset_m = bad;
    const std::string message = validation_error(params);
    EXPECT_TRUE(starts_with(message, "outlier_offset_m: must be finite")) << message;
  }
}

}  // namespace
}  // namespace robodds::position_sensor
