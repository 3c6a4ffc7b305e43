#include "components/uwb_relative_estimator/relative_pf_params.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <string>

#include "tests/support/validation_error.hpp"

namespace robodds::uwb_relative_estimator {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

std::string validation_error(const std::function<void(RelativePfParams&)>& mutate) {
  RelativePfParams params;
  mutate(params);
  return test_support::validation_error(params);
}

TEST(RelativePfParams, DefaultsAreValidAndThoseOfIssue11) {
  const RelativePfParams params;
  EXPECT_NO_THROW(params.validate());
  EXPECT_EQ(params.num_particles, 500);
  EXPECT_EQ(params.odometry_xy_std_m, 0.005);
  EXPECT_EQ(params.odometry_theta_std_rad, 0.003);
  EXPECT_EQ(params.lambda_d_m, 0.3);
  EXPECT_EQ(params.lambda_theta_rad, 0.1);
  EXPECT_EQ(params.range_std_m, 0.3);
  EXPECT_EQ(params.resample_ess_fraction, 1.0);  // the paper resamples after every update
}

TEST(RelativePfParams, EachBadValueGivesOneMessageNamingItsKey) {
  EXPECT_EQ(validation_error([](RelativePfParams& p) { p.num_particles = 0; }), "num_particles: must be >= 1 (got 0)");
  EXPECT_EQ(validation_error([](RelativePfParams& p) { p.lambda_d_m = 0.0; }).rfind("lambda_d_m: ", 0), 0u);
  EXPECT_EQ(validation_error([](RelativePfParams& p) { p.lambda_theta_rad = kNan; }).rfind("lambda_theta_rad: ", 0), 0u);
  EXPECT_EQ(validation_error([](RelativePfParams& p) { p.range_std_m = -0.1; }).rfind("range_std_m: ", 0), 0u);
  EXPECT_EQ(validation_error([](RelativePfParams& p) { p.odometry_xy_std_m = -1e-3; }).rfind("odometry_xy_std_m: ", 0), 0u);
  EXPECT_EQ(validation_error([](RelativePfParams& p) { p.odometry_theta_std_rad = kNan; }).rfind("odometry_theta_std_rad: ", 0),
            0u);
  EXPECT_EQ(validation_error([](RelativePfParams& p) { p.resample_ess_fraction = 0.0; }).rfind("resample_ess_fraction: ", 0),
            0u);
  EXPECT_EQ(validation_error([](RelativePfParams& p) { p.resample_ess_fraction = 1.5; }),
            "resample_ess_fraction: must be in (0, 1] (got 1.5)");
}

TEST(RelativePfParams, ZeroOdometryNoiseAndOneParticleAreAllowed) {
  EXPECT_EQ(validation_error([](RelativePfParams& p) {
              p.odometry_xy_std_m = 0.0;
              p.odometry_theta_std_rad = 0.0;
              p.num_particles = 1;
            }),
            "");
}

TEST(RelativePfParams, TableDocumentsEveryField) {
  const params::ParamDoc doc = relative_pf_param_table().doc();
  ASSERT_EQ(doc.params.size(), 7u);
  EXPECT_EQ(doc.params[0].key, "num_particles");
  EXPECT_EQ(doc.params[0].default_yaml, "500");
  EXPECT_EQ(doc.params[6].key, "resample_ess_fraction");
  EXPECT_EQ(doc.params[6].range, "(0, 1]");
}

}  // namespace
}  // namespace robodds::uwb_relative_estimator
