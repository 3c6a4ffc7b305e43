#pragma once
// Plausibility checks of input samples, declared once per topic type (not per node): every
// Input runs them on every sample after the non-finite check (io.hpp), so every consumer of
// every topic is covered. A sample that fails is dropped and counted under the check's reason
// (InputCounts::rejected) and logged once per writer and reason. The table of checks and bounds
// is in docs/architecture.md, "Input checks"; the bounds are the constants below (one place).

#include <cstdint>
#include <optional>
#include <string>

#include "robodds/idl/robodds.h"
#include "runtime/bus/bus.hpp"

namespace robodds {

/// The first check a sample failed: reason (the InputCounts key, e.g. "bad_enum"), the field it
/// concerns ("mode", "header.stamp_ns") and what was wrong ("is 7, CommandMode has 0..1").
struct SampleCheckFailure {
  std::string reason;
  std::string field;
  std::string detail;
};

/// Rejection reasons (InputCounts::rejected keys) besides detail::kRejectNonFinite.
namespace check_reason {
inline constexpr const char* kNegativeStamp = "negative_stamp";    // header.stamp_ns < 0
inline constexpr const char* kStampInFuture = "stamp_in_future";   // real time: ahead of our wall clock
inline constexpr const char* kBadHeader = "bad_header";            // header.step > header.next_step
inline constexpr const char* kBadEnum = "bad_enum";                // enum value outside its declaration
inline constexpr const char* kBadSize = "bad_size";                // sizes or indices inconsistent
inline constexpr const char* kNegativeVariance = "negative_variance";  // a variance or covariance diagonal < 0
inline constexpr const char* kNegativeDuration = "negative_duration";  // dt_s, step_s < 0
inline constexpr const char* kAbsurdMagnitude = "absurd_magnitude";    // beyond a generous physical bound
}  // namespace check_reason

/// Generous physical bounds per field kind: far beyond anything a robot of this platform does,
/// tight enough that nothing above them is integrated (v = 1e300 is refused, not saturated).
namespace sample_bounds {
inline constexpr double kPositionM = 1e6;          // |x|, |y|, way-points, ranges, distances
inline constexpr double kSpeedMps = 1e3;           // |v|, |v_left|, |v_right|, |range_rate|
inline constexpr double kTurnRateRadps = 1e3;      // |omega|
inline constexpr double kAngleRad = 1e3;           // |theta|, |alpha|, |sigma| (wrapped or not)
inline constexpr double kVariance = 1e12;          // variances and covariance entries (m^2, rad^2, ...)
inline constexpr double kDurationS = 1e6;          // dt_s, step_s
inline constexpr std::uint32_t kTeamSize = 1u << 16;  // TargetAssignment::team_size
/// Real time: how far a sample's header.stamp_ns (the sender's wall clock) may be ahead of this
/// process's wall clock before the sample is refused. Hosts of one system are assumed
/// synchronised (NTP/PTP) far better than this.
inline constexpr std::int64_t kFutureStampToleranceNs = 1'000'000'000;
}  // namespace sample_bounds

/// Header checks of every type: stamp (negative always; in real time also ahead of `wall_now_ns`
/// by more than the tolerance; in lockstep stamps are sim time and only negative is absurd) and
/// step <= next_step. Overflow-free for any stamp (INT64_MIN, INT64_MAX).
std::optional<SampleCheckFailure> check_header(const idl::SampleHeader& header, TimeMode mode, std::int64_t wall_now_ns);

/// Content checks, one per topic type (header excluded). Non-finite numbers are caught before.
std::optional<SampleCheckFailure> check_content(const idl::SimTick& s);
std::optional<SampleCheckFailure> check_content(const idl::StepDone& s);
std::optional<SampleCheckFailure> check_content(const idl::RobotState& s);
std::optional<SampleCheckFailure> check_content(const idl::VelocityCommand& s);
std::optional<SampleCheckFailure> check_content(const idl::PositionMeasurement& s);
std::optional<SampleCheckFailure> check_content(const idl::Odometry& s);
std::optional<SampleCheckFailure> check_content(const idl::RangeMeasurement& s);
std::optional<SampleCheckFailure> check_content(const idl::UwbRanges& s);
std::optional<SampleCheckFailure> check_content(const idl::PoseEstimate& s);
std::optional<SampleCheckFailure> check_content(const idl::RelativePoseEstimate& s);
std::optional<SampleCheckFailure> check_content(const idl::RangeRateEstimate& s);
std::optional<SampleCheckFailure> check_content(const idl::WaypointMission& s);
std::optional<SampleCheckFailure> check_content(const idl::TargetAssignment& s);
std::optional<SampleCheckFailure> check_content(const idl::ControllerStatus& s);
std::optional<SampleCheckFailure> check_content(const idl::HostReport& s);

/// Every check of `sample` (header, then content); the first failure or nullopt. `wall_now_ns`
/// is read only in real time.
template <class Msg>
std::optional<SampleCheckFailure> check_sample(const Msg& sample, TimeMode mode, std::int64_t wall_now_ns) {
  if (auto failed = check_header(sample.header(), mode, wall_now_ns)) {
    return failed;
  }
  return check_content(sample);
}

}  // namespace robodds
