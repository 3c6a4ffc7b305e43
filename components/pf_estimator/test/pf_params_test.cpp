#include "components/pf_estimator/pf_params.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

#include "tests/support/validation_error.hpp"

namespace robodds::pf_estimator {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// The validate() message of the defaults changed by `mutate`, or "" if accepted.
std::string validation_error(const std::function<void(PfParams&)>& mutate) {
  PfParams params;
  mutate(params);
  return test_support::validation_error(params);
}

// The message must start with the YAML key so the node can point at the offending line.
void expect_rejected_with_key(const std::string& key, const std::function<void(PfParams&)>& mutate) {
  const std::string message = validation_error(mutate);
  ASSERT_FALSE(message.empty()) << key << " was accepted";
  EXPECT_EQ(message.rfind(key + ":", 0), 0u) << "message: " << message;
}

TEST(PfParams, DefaultsAreValidAndThoseOfTheScenarios) {
  const PfParams params;
  EXPECT_NO_THROW(params.validate());
  EXPECT_EQ(params.num_particles, 1000);
  EXPECT_DOUBLE_EQ(params.resample_threshold, 500.0);
  EXPECT_EQ(params.measurement_std_m, 1.51);  // ~ sqrt(2.28), the paper's measurement variance
  EXPECT_EQ(params.resampling, ResamplingScheme::kSystematic);
  EXPECT_EQ(params.init_mode, InitMode::kFirstFix);  // the paper's uniform_area is an option
}

TEST(PfParams, MessageHasKeyRequirementAndValue) {
  EXPECT_EQ(validation_error([](PfParams& p) { p.num_particles = 0; }),
            "num_particles: must be >= 1 (got 0)");
}

TEST(PfParams, RejectsTooFewParticles) {
  expect_rejected_with_key("num_particles", [](PfParams& p) { p.num_particles = 0; });
  expect_rejected_with_key("num_particles", [](PfParams& p) { p.num_particles = -5; });
}

TEST(PfParams, ResampleThresholdMustBeInZeroToM) {
  expect_rejected_with_key("resample_threshold", [](PfParams& p) { p.resample_threshold = 0.0; });
  expect_rejected_with_key("resample_threshold", [](PfParams& p) { p.resample_threshold = -1.0; });
  expect_rejected_with_key("resample_threshold",
                           [](PfParams& p) { p.resample_threshold = 1000.5; });
  expect_rejected_with_key("resample_threshold", [](PfParams& p) {
    p.num_particles = 100;
    p.resample_threshold = 500.0;  // the default no longer fits a smaller M
  });
  expect_rejected_with_key("resample_threshold", [](PfParams& p) { p.resample_threshold = kNan; });
  // Both ends of (0, M]: M itself is allowed, a tiny positive value too.
  EXPECT_EQ(validation_error([](PfParams& p) { p.resample_threshold = 1000.0; }), "");
  EXPECT_EQ(validation_error([](PfParams& p) { p.resample_threshold = 1e-9; }), "");
}

TEST(PfParams, StandardDeviationsMustBePositiveOrNonNegative) {
  expect_rejected_with_key("measurement_std_m", [](PfParams& p) { p.measurement_std_m = 0.0; });
  expect_rejected_with_key("measurement_std_m", [](PfParams& p) { p.measurement_std_m = -1.0; });
  expect_rejected_with_key("init_fix_std_m", [](PfParams& p) { p.init_fix_std_m = 0.0; });
  expect_rejected_with_key("odom_v_std_mps", [](PfParams& p) { p.odom_v_std_mps = -0.1; });
  expect_rejected_with_key("odom_omega_std_radps",
                           [](PfParams& p) { p.odom_omega_std_radps = -0.1; });
  expect_rejected_with_key("process_pos_std_m", [](PfParams& p) { p.process_pos_std_m = -0.1; });
  expect_rejected_with_key("process_theta_std_rad",
                           [](PfParams& p) { p.process_theta_std_rad = -0.1; });
  expect_rejected_with_key("regularization_scale",
                           [](PfParams& p) { p.regularization_scale = -0.5; });
  // Zero process and odometry noise is a legal (if fragile) choice.
  EXPECT_EQ(validation_error([](PfParams& p) {
              p.odom_v_std_mps = 0.0;
              p.odom_omega_std_radps = 0.0;
              p.process_pos_std_m = 0.0;
              p.process_theta_std_rad = 0.0;
              p.regularization_scale = 0.0;
            }),
            "");
}

TEST(PfParams, RejectsNonFiniteValuesByKey) {
  expect_rejected_with_key("measurement_std_m", [](PfParams& p) { p.measurement_std_m = kNan; });
  expect_rejected_with_key("measurement_std_m", [](PfParams& p) { p.measurement_std_m = kInf; });
  expect_rejected_with_key("odom_v_std_mps", [](PfParams& p) { p.odom_v_std_mps = kNan; });
  expect_rejected_with_key("odom_omega_std_radps",
                           [](PfParams& p) { p.odom_omega_std_radps = kInf; });
  expect_rejected_with_key("process_pos_std_m", [](PfParams& p) { p.process_pos_std_m = kNan; });
  expect_rejected_with_key("process_theta_std_rad",
                           [](PfParams& p) { p.process_theta_std_rad = kNan; });
  expect_rejected_with_key("regularization_scale",
                           [](PfParams& p) { p.regularization_scale = kInf; });
  expect_rejected_with_key("init_area_min_x", [](PfParams& p) { p.init_area_min_x = kNan; });
  expect_rejected_with_key("init_area_max_y", [](PfParams& p) { p.init_area_max_y = kInf; });
  expect_rejected_with_key("init_theta_rad", [](PfParams& p) { p.init_theta_rad = kNan; });
  expect_rejected_with_key("init_fix_std_m", [](PfParams& p) { p.init_fix_std_m = kNan; });
}

TEST(PfParams, RobustnessKeysAreCheckedByName) {
  expect_rejected_with_key("odom_omega_std_per_mps", [](PfParams& p) { p.odom_omega_std_per_mps = -0.1; });
  expect_rejected_with_key("odom_omega_std_fraction", [](PfParams& p) { p.odom_omega_std_fraction = kNan; });
  expect_rejected_with_key("turn_slip_std_radpm", [](PfParams& p) { p.turn_slip_std_radpm = -1.0; });
  expect_rejected_with_key("turn_slip_walk_std_radpm", [](PfParams& p) { p.turn_slip_walk_std_radpm = kInf; });
  expect_rejected_with_key("gate_probability", [](PfParams& p) { p.gate_probability = 1.0; });
  expect_rejected_with_key("gate_probability", [](PfParams& p) { p.gate_probability = -0.1; });
  expect_rejected_with_key("recovery_rejected_share", [](PfParams& p) { p.recovery_rejected_share = 1.0; });
  expect_rejected_with_key("recovery_window_fixes", [](PfParams& p) { p.recovery_window_fixes = 0.5; });
  expect_rejected_with_key("recovery_uniform_heading_fraction",
                           [](PfParams& p) { p.recovery_uniform_heading_fraction = 1.5; });
  // The mean d^2 of a consistent filter is 2, and accepted fixes never average above the gate.
  expect_rejected_with_key("recovery_nis", [](PfParams& p) { p.recovery_nis = 2.0; });
  expect_rejected_with_key("recovery_nis", [](PfParams& p) { p.recovery_nis = 9.5; });
  EXPECT_EQ(validation_error([](PfParams& p) { p.recovery_nis = 0.0; }), "");  // off
  EXPECT_EQ(validation_error([](PfParams& p) {
              p.gate_probability = 0.0;  // no gate: any threshold above 2
              p.recovery_nis = 50.0;
            }),
            "");
}

TEST(PfParams, InitAreaMaxMustExceedMin) {
  expect_rejected_with_key("init_area_max_x", [](PfParams& p) {
    p.init_area_min_x = 5.0;
    p.init_area_max_x = 5.0;
  });
  expect_rejected_with_key("init_area_max_y", [](PfParams& p) {
    p.init_area_min_y = 2.0;
    p.init_area_max_y = -2.0;
  });
}

TEST(PfParams, RejectsOutOfRangeEnumValues) {
  expect_rejected_with_key("resampling",
                           [](PfParams& p) { p.resampling = static_cast<ResamplingScheme>(7); });
  expect_rejected_with_key("init_mode", [](PfParams& p) { p.init_mode = static_cast<InitMode>(7); });
}

TEST(PfParams, EnumStringsRoundTrip) {
  for (const auto scheme : {ResamplingScheme::kSystematic, ResamplingScheme::kResidual}) {
    EXPECT_EQ(resampling_scheme_from_string(to_string(scheme)), scheme);
  }
  for (const auto mode : {InitMode::kUniformArea, InitMode::kFirstFix}) {
    EXPECT_EQ(init_mode_from_string(to_string(mode)), mode);
  }
  EXPECT_EQ(to_string(ResamplingScheme::kResidual), "residual");
  EXPECT_EQ(to_string(InitMode::kFirstFix), "first_fix");
}

TEST(PfParams, UnknownEnumStringsNameTheKey) {
  try {
    resampling_scheme_from_string("multinomial");
    FAIL() << "accepted an unknown resampling scheme";
  } catch (const std::invalid_argument& error) {
    EXPECT_EQ(std::string(error.what()).rfind("resampling:", 0), 0u) << error.what();
  }
  try {
    init_mode_from_string("Uniform_Area");
    FAIL() << "accepted an unknown init mode";
  } catch (const std::invalid_argument& error) {
    EXPECT_EQ(std::string(error.what()).rfind("init_mode:", 0), 0u) << error.what();
  }
}

}  // namespace
}  // namespace robodds::pf_estimator
