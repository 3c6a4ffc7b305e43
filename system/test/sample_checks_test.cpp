// The robot system's content checks (system/sample_checks.hpp), as the runtime runs them:
// installed before main() because this test links robodds_system (system/install_at_start.cpp).
#include "system/sample_checks.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

#include "runtime/testing/sample_check_cases.hpp"

namespace robodds::system {
namespace {

using robodds::testing::check_reason_of;
using robodds::testing::plausible_sample;
constexpr std::int64_t kNow = robodds::testing::kCheckNowNs;

TEST(SampleChecks, CommandModeAndMagnitudes) {
  auto c = plausible_sample<idl::VelocityCommand>();
  c.mode(idl::WHEEL_SPEEDS);
  c.v_left(999.0);
  EXPECT_EQ(check_reason_of(c), "ok");
  c.mode(static_cast<idl::CommandMode>(2));
  const auto failed = check_sample(c, TimeMode::kLockstep, kNow);
  ASSERT_TRUE(failed);
  EXPECT_EQ(failed->reason, "bad_enum");
  EXPECT_NE(failed->detail.find("is 2"), std::string::npos) << failed->detail;
  c.mode(idl::VELOCITY);
  c.v(1e300);
  EXPECT_EQ(check_reason_of(c), "absurd_magnitude:v");
  c.v(-1e300);
  EXPECT_EQ(check_reason_of(c), "absurd_magnitude:v");
  c.v(1.0);
  c.omega(2e3);
  EXPECT_EQ(check_reason_of(c), "absurd_magnitude:omega");
  c.omega(0.0);
  c.v_right(-1e4);
  EXPECT_EQ(check_reason_of(c), "absurd_magnitude:v_right");
}

TEST(SampleChecks, SensorVariancesDurationsAndPositions) {
  auto p = plausible_sample<idl::PositionMeasurement>();
  p.var_x(0.01);
  p.var_y(0.01);
  EXPECT_EQ(check_reason_of(p), "ok");
  p.var_y(-0.01);
  EXPECT_EQ(check_reason_of(p), "negative_variance:var_y");
  p.var_y(0.01);
  p.x(2e6);
  EXPECT_EQ(check_reason_of(p), "absurd_magnitude:x");

  auto o = plausible_sample<idl::Odometry>();
  o.dt_s(0.01);
  EXPECT_EQ(check_reason_of(o), "ok");
  o.dt_s(-0.01);
  EXPECT_EQ(check_reason_of(o), "negative_duration:dt_s");
  o.dt_s(0.01);
  o.var_omega(-1.0);
  EXPECT_EQ(check_reason_of(o), "negative_variance:var_omega");

  auto r = plausible_sample<idl::RangeMeasurement>();
  r.range(0.0);  // the simulated sensor clamps noise at 0
  EXPECT_EQ(check_reason_of(r), "ok");
  r.var(-1.0);
  EXPECT_EQ(check_reason_of(r), "negative_variance:var");
}

TEST(SampleChecks, UwbRangesSizesMustAgree) {
  auto u = plausible_sample<idl::UwbRanges>();
  u.rows(2);
  u.cols(3);
  u.ranges(std::vector<double>(6, 1.0));
  EXPECT_EQ(check_reason_of(u), "ok");
  u.ranges(std::vector<double>(5, 1.0));
  EXPECT_EQ(check_reason_of(u), "bad_size:ranges");
  u.rows(0xffffffffu);  // rows * cols must not wrap to a matching size
  u.cols(0xffffffffu);
  u.ranges({});
  EXPECT_EQ(check_reason_of(u), "bad_size:ranges");
  u.rows(1);
  u.cols(1);
  u.ranges({1e7});
  EXPECT_EQ(check_reason_of(u), "absurd_magnitude:ranges[0]");
  u.ranges({0.0});  // the sensor clamps at 0
  EXPECT_EQ(check_reason_of(u), "ok");
  u.ranges({-0.01});
  EXPECT_EQ(check_reason_of(u), "absurd_magnitude:ranges[0]");
  u.rows(0);  // the sensor's empty sample: out of range or a lost frame
  u.cols(0);
  u.ranges({});
  EXPECT_EQ(check_reason_of(u), "ok");
}

TEST(SampleChecks, EstimatesCovarianceDiagonal) {
  auto e = plausible_sample<idl::PoseEstimate>();
  e.cov()[4] = 0.5;
  e.cov()[1] = -0.2;  // off-diagonal may be negative
  EXPECT_EQ(check_reason_of(e), "ok");
  e.cov()[8] = -1e-3;
  EXPECT_EQ(check_reason_of(e), "negative_variance:cov[8]");
  auto rel = plausible_sample<idl::RelativePoseEstimate>();
  rel.theta(1e4);
  EXPECT_EQ(check_reason_of(rel), "absurd_magnitude:theta");
  auto range = plausible_sample<idl::RangeMeasurement>();
  range.range(-0.01);
  EXPECT_EQ(check_reason_of(range), "absurd_magnitude:range");
  auto rr = plausible_sample<idl::RangeRateEstimate>();
  rr.range_rate(5e3);
  EXPECT_EQ(check_reason_of(rr), "absurd_magnitude:range_rate");
}

TEST(SampleChecks, MissionsAssignmentsAndStatus) {
  auto m = plausible_sample<idl::WaypointMission>();
  m.waypoints().resize(2);
  EXPECT_EQ(check_reason_of(m), "ok");
  m.waypoints()[1].y(-5e6);
  EXPECT_EQ(check_reason_of(m), "absurd_magnitude:waypoints[1]");

  auto a = plausible_sample<idl::TargetAssignment>();
  a.team_size(3);
  a.slot(2);
  a.desired_radius(5.0);
  EXPECT_EQ(check_reason_of(a), "ok");
  a.slot(3);
  EXPECT_EQ(check_reason_of(a), "bad_size:slot");
  a.slot(0);
  a.desired_radius(-1.0);
  EXPECT_EQ(check_reason_of(a), "absurd_magnitude:desired_radius");
  a.desired_radius(5.0);
  a.target_x(2e6);
  EXPECT_EQ(check_reason_of(a), "absurd_magnitude:target_x");

  auto s = plausible_sample<idl::ControllerStatus>();
  s.waypoints_total(4);
  s.waypoints_reached(4);
  EXPECT_EQ(check_reason_of(s), "ok");
  s.waypoints_reached(5);
  EXPECT_EQ(check_reason_of(s), "bad_size:waypoints_reached");
  s.waypoints_reached(0);
  s.state(static_cast<idl::ControlState>(6));
  EXPECT_EQ(check_reason_of(s), "bad_enum:state");
}

}  // namespace
}  // namespace robodds::system
