#include "runtime/io/sample_checks.hpp"

#include <array>
#include <cmath>
#include <initializer_list>

#include "common/number_text.hpp"

namespace robodds {
namespace {

using Failure = std::optional<SampleCheckFailure>;

Failure fail(const char* reason, std::string field, std::string detail) {
  return SampleCheckFailure{reason, std::move(field), std::move(detail)};
}

/// |value| <= bound, else absurd_magnitude.
Failure within(const char* field, double value, double bound) {
  if (std::fabs(value) <= bound) {
    return std::nullopt;
  }
  return fail(check_reason::kAbsurdMagnitude, field, "is " + shortest_text(value) + ", beyond the bound " + shortest_text(bound));
}

Failure variance(const char* field, double value) {
  if (value < 0.0) {
    return fail(check_reason::kNegativeVariance, field, "is " + shortest_text(value) + " (a variance is >= 0)");
  }
  return within(field, value, sample_bounds::kVariance);
}

Failure duration(const char* field, double value) {
  if (value < 0.0) {
    return fail(check_reason::kNegativeDuration, field, "is " + shortest_text(value) + " (a duration is >= 0)");
  }
  return within(field, value, sample_bounds::kDurationS);
}

/// Row-major 3x3 covariance: diagonal >= 0, every entry bounded.
Failure covariance(const std::array<double, 9>& cov) {
  static const char* const kNames[9] = {"cov[0]", "cov[1]", "cov[2]", "cov[3]", "cov[4]",
                                        "cov[5]", "cov[6]", "cov[7]", "cov[8]"};
  for (std::size_t i = 0; i < 9; ++i) {
    if (auto f = i % 4 == 0 ? variance(kNames[i], cov[i]) : within(kNames[i], cov[i], sample_bounds::kVariance)) {
      return f;
    }
  }
  return std::nullopt;
}

/// The first failure of a list of checks, in order.
Failure first(std::initializer_list<Failure> checks) {
  for (const Failure& f : checks) {
    if (f) {
      return f;
    }
  }
  return std::nullopt;
}

constexpr double kPos = sample_bounds::kPositionM;
constexpr double kSpeed = sample_bounds::kSpeedMps;
constexpr double kTurn = sample_bounds::kTurnRateRadps;
constexpr double kAngle = sample_bounds::kAngleRad;

}  // namespace

Failure check_header(const idl::SampleHeader& header, TimeMode mode, std::int64_t wall_now_ns) {
  const std::int64_t stamp = header.stamp_ns();
  if (stamp < 0) {
    return fail(check_reason::kNegativeStamp, "header.stamp_ns", "is " + std::to_string(stamp) + " (negative)");
  }
  // stamp >= 0 here and wall_now_ns is a real clock reading: the difference cannot overflow.
  if (mode == TimeMode::kRealtime && wall_now_ns >= 0 && stamp - wall_now_ns > sample_bounds::kFutureStampToleranceNs) {
    return fail(check_reason::kStampInFuture, "header.stamp_ns",
                "is " + shortest_text(static_cast<double>(stamp - wall_now_ns) * 1e-9) + " s ahead of this host's wall clock (tolerance " +
                    shortest_text(static_cast<double>(sample_bounds::kFutureStampToleranceNs) * 1e-9) + " s)");
  }
  if (header.step() > header.next_step()) {
    return fail(check_reason::kBadHeader, "header.next_step",
                "is " + std::to_string(header.next_step()) + ", before header.step " + std::to_string(header.step()));
  }
  return std::nullopt;
}

Failure check_content(const idl::SimTick& s) { return duration("step_s", s.step_s()); }

Failure check_content(const idl::StepDone&) { return std::nullopt; }

Failure check_content(const idl::RobotState& s) {
  return first({within("x", s.x(), kPos), within("y", s.y(), kPos), within("theta", s.theta(), kAngle),
                within("v", s.v(), kSpeed), within("omega", s.omega(), kTurn)});
}

Failure check_content(const idl::VelocityCommand& s) {
  const auto mode = static_cast<std::uint32_t>(s.mode());
  if (mode != idl::VELOCITY && mode != idl::WHEEL_SPEEDS) {
    return fail(check_reason::kBadEnum, "mode", "is " + std::to_string(mode) + ", CommandMode has 0 (VELOCITY) and 1 (WHEEL_SPEEDS)");
  }
  return first({within("v", s.v(), kSpeed), within("omega", s.omega(), kTurn), within("v_left", s.v_left(), kSpeed),
                within("v_right", s.v_right(), kSpeed)});
}

Failure check_content(const idl::PositionMeasurement& s) {
  return first({within("x", s.x(), kPos), within("y", s.y(), kPos), variance("var_x", s.var_x()), variance("var_y", s.var_y())});
}

Failure check_content(const idl::Odometry& s) {
  return first({within("v", s.v(), kSpeed), within("omega", s.omega(), kTurn), duration("dt_s", s.dt_s()),
                variance("var_v", s.var_v()), variance("var_omega", s.var_omega())});
}

Failure check_content(const idl::RangeMeasurement& s) {
  // A range sensor reports distances: the simulated one clamps its noisy value at 0, so a
  // negative range is a broken or hostile writer, not noise.
  if (s.range() < 0.0) {
    return fail(check_reason::kAbsurdMagnitude, "range", "is " + shortest_text(s.range()) + " (a range is >= 0)");
  }
  return first({within("range", s.range(), kPos), variance("var", s.var())});
}

Failure check_content(const idl::UwbRanges& s) {
  const std::uint64_t rows = s.rows();
  const std::uint64_t cols = s.cols();
  constexpr std::uint64_t kMaxRanges = 64;  // sequence<double, 64>
  if (rows > kMaxRanges || cols > kMaxRanges || rows * cols != s.ranges().size()) {
    return fail(check_reason::kBadSize, "ranges",
                "has " + std::to_string(s.ranges().size()) + " entries for rows " + std::to_string(rows) + " x cols " +
                    std::to_string(cols) + " (rows * cols entries expected, at most 64)");
  }
  for (std::size_t i = 0; i < s.ranges().size(); ++i) {
    // The simulated sensor clamps its noisy ranges at 0 (as RangeMeasurement); rows = cols = 0
    // with no ranges is the sensor's empty sample (out of range, lost frame).
    if (s.ranges()[i] < 0.0) {
      return fail(check_reason::kAbsurdMagnitude, "ranges[" + std::to_string(i) + "]",
                  "is " + shortest_text(s.ranges()[i]) + " (a range is >= 0)");
    }
    if (std::fabs(s.ranges()[i]) > kPos) {
      return fail(check_reason::kAbsurdMagnitude, "ranges[" + std::to_string(i) + "]",
                  "is " + shortest_text(s.ranges()[i]) + ", beyond the bound " + shortest_text(kPos));
    }
  }
  return std::nullopt;
}

Failure check_content(const idl::PoseEstimate& s) {
  return first({within("x", s.x(), kPos), within("y", s.y(), kPos), within("theta", s.theta(), kAngle), covariance(s.cov())});
}

Failure check_content(const idl::RelativePoseEstimate& s) {
  return first({within("x", s.x(), kPos), within("y", s.y(), kPos), within("theta", s.theta(), kAngle), covariance(s.cov())});
}

Failure check_content(const idl::RangeRateEstimate& s) {
  return first({within("range", s.range(), kPos), within("range_rate", s.range_rate(), kSpeed)});
}

Failure check_content(const idl::WaypointMission& s) {
  for (std::size_t i = 0; i < s.waypoints().size(); ++i) {
    const idl::Waypoint& w = s.waypoints()[i];
    if (std::fabs(w.x()) > kPos || std::fabs(w.y()) > kPos) {
      return fail(check_reason::kAbsurdMagnitude, "waypoints[" + std::to_string(i) + "]",
                  "is (" + shortest_text(w.x()) + ", " + shortest_text(w.y()) + "), beyond the bound " + shortest_text(kPos));
    }
  }
  return std::nullopt;
}

Failure check_content(const idl::TargetAssignment& s) {
  if (s.team_size() > sample_bounds::kTeamSize || (s.team_size() > 0 && s.slot() >= s.team_size())) {
    return fail(check_reason::kBadSize, "slot",
                "is " + std::to_string(s.slot()) + " of team_size " + std::to_string(s.team_size()) +
                    " (slot < team_size <= " + std::to_string(sample_bounds::kTeamSize) + " expected)");
  }
  if (s.desired_radius() < 0.0) {
    return fail(check_reason::kAbsurdMagnitude, "desired_radius", "is " + shortest_text(s.desired_radius()) + " (a radius is >= 0)");
  }
  return first({within("desired_radius", s.desired_radius(), kPos), within("target_x", s.target_x(), kPos),
                within("target_y", s.target_y(), kPos)});
}

Failure check_content(const idl::ControllerStatus& s) {
  if (static_cast<std::uint32_t>(s.state()) > static_cast<std::uint32_t>(idl::DONE)) {
    return fail(check_reason::kBadEnum, "state",
                "is " + std::to_string(static_cast<std::uint32_t>(s.state())) + ", ControlState has 0..5");
  }
  if (s.waypoints_reached() > s.waypoints_total()) {
    return fail(check_reason::kBadSize, "waypoints_reached",
                "is " + std::to_string(s.waypoints_reached()) + " of waypoints_total " + std::to_string(s.waypoints_total()));
  }
  return first({within("distance_to_waypoint", s.distance_to_waypoint(), kPos), within("distance_to_final", s.distance_to_final(), kPos),
                within("alpha", s.alpha(), kAngle), within("sigma", s.sigma(), kAngle),
                within("switch_distance", s.switch_distance(), kPos), within("epsilon", s.epsilon(), kPos)});
}

Failure check_content(const idl::HostReport& s) {
  if (s.late_steps() > s.ticks()) {  // late steps were run, so they are among the ticks
    return fail(check_reason::kBadSize, "late_steps",
                "is " + std::to_string(s.late_steps()) + ", more than the " + std::to_string(s.ticks()) + " steps run");
  }
  return duration("worst_lateness_s", s.worst_lateness_s());
}

}  // namespace robodds
