#include "components/uwb_relative_estimator/relative_pose_tracker.hpp"

#include <stdexcept>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

#include "common/angle.hpp"
#include "common/number_text.hpp"
#include "common/param_checks.hpp"
#include "components/uwb_relative_estimator/median.hpp"

namespace robodds::uwb_relative_estimator {
namespace {

/// Slack on the cold-start period, so that epochs at 0.1 s steps summed in floating point still
/// cold-start at 10 s and not one epoch later.
constexpr double kPeriodSlackS = 1e-6;

bool usable(const SolverResult& r) {
  return r.converged && std::isfinite(r.final_cost) && std::isfinite(r.pose.x) && std::isfinite(r.pose.y) &&
         std::isfinite(r.pose.theta);
}

std::string deg_text(double rad) { return shortest_text(std::round(rad * 180.0 / kPi * 10.0) / 10.0); }
std::string m_text(double m) { return shortest_text(std::round(m * 1000.0) / 1000.0); }

}  // namespace

const params::ParamTable<TrackerParams>& tracker_param_table() {
  using P = TrackerParams;
  static const params::ParamTable<P> table =
      params::ParamTable<P>("Eq. (1) epoch after epoch for one robot pair: warm start with cold-start recovery.")
          .add("cold_start_period_s", &P::cold_start_period_s, "s", params::positive(),
               "cold start (32 starts) at least this often, to leave a wrong minimum")
          .add("cost_ratio", &P::cost_ratio, "", params::shown_as(params::positive(), "> 1"),
               "a warm-start cost above this x the running median triggers a cold start")
          .add("cost_median_window", &P::cost_median_window, "", params::at_least(1),
               "solves whose final costs form the running median")
          .add("cost_floor_m2", &P::cost_floor_m2, "m^2", params::non_negative(),
               "costs at or below this never count as a spike")
          .add("disagreement_position_m", &P::disagreement_position_m, "m", params::positive(),
               "cold and warm start further apart than this: a wrong minimum, epoch suspect")
          .add("disagreement_heading_rad", &P::disagreement_heading_rad, "rad", params::positive(),
               "the same for the heading");
  return table;
}

void TrackerParams::validate() const {
  tracker_param_table().check_ranges(*this);
  if (!(cost_ratio > 1.0)) {
    param_checks::reject("cost_ratio", "must be > 1 and finite", cost_ratio);
  }
}

std::string to_string(TrackStatus status) {
  switch (status) {
    case TrackStatus::kOk:
      return "ok";
    case TrackStatus::kSuspect:
      return "suspect";
    case TrackStatus::kFailed:
      return "failed";
    case TrackStatus::kRejected:
      return "rejected";
  }
  return "unknown";
}

std::string to_string(ColdStart cold_start) {
  switch (cold_start) {
    case ColdStart::kNone:
      return "none";
    case ColdStart::kFirst:
      return "first";
    case ColdStart::kPeriodic:
      return "periodic";
    case ColdStart::kCostSpike:
      return "cost_spike";
    case ColdStart::kWarmFailed:
      return "warm_failed";
  }
  return "unknown";
}

RelativePoseTracker::RelativePoseTracker(UwbArray own, UwbArray peer, SolverOptions solver, TrackerParams params)
    : own_(std::move(own)), peer_(std::move(peer)), solver_(solver), params_(params) {
  model::check_array("own_array", own_);
  model::check_array("peer_array", peer_);
  solver_.validate();
  params_.validate();
}

std::optional<double> RelativePoseTracker::cost_median() const {
  if (costs_.empty()) {
    return std::nullopt;
  }
  return median(std::vector<double>(costs_.begin(), costs_.end()));
}

double RelativePoseTracker::cost_threshold() const {
  const std::optional<double> m = cost_median();
  if (!m) {
    return std::numeric_limits<double>::infinity();
  }
  return std::max(params_.cost_floor_m2, params_.cost_ratio * *m);
}

std::optional<std::string> RelativePoseTracker::check_input(const Eigen::MatrixXd& ranges_m, double time_s) const {
  if (!std::isfinite(time_s)) {
    return "time " + shortest_text(time_s) + " s is not finite";
  }
  if (last_time_s_ && time_s < *last_time_s_) {
    return "time " + shortest_text(time_s) + " s is before the previous epoch's " + shortest_text(*last_time_s_) + " s";
  }
  try {
    require_valid_ranges("RelativePoseTracker", own_, peer_, ranges_m);  // the one range-matrix check
  } catch (const std::invalid_argument& error) {
    return std::string(error.what());
  }
  return std::nullopt;
}

TrackerOutput RelativePoseTracker::update(const Eigen::MatrixXd& ranges_m, double time_s) {
  if (std::optional<std::string> bad = check_input(ranges_m, time_s)) {
    ++counts_.rejected;
    TrackerOutput out;
    out.pose = previous_.value_or(model::Pose2{});
    out.status = TrackStatus::kRejected;
    out.reason = std::move(*bad);
    return out;
  }
  last_time_s_ = time_s;

  TrackerOutput out;
  SolverResult warm;  // meaningful if have_warm (a std::optional here trips GCC's -Wmaybe-uninitialized)
  bool have_warm = false;
  if (!previous_) {
    out.cold_start = ColdStart::kFirst;
  } else {
    warm = solve_relative_pose(own_, peer_, ranges_m, previous_, solver_);
    have_warm = usable(warm);
    if (!have_warm) {
      out.cold_start = ColdStart::kWarmFailed;
    } else if (time_s - last_cold_start_s_ >= params_.cold_start_period_s - kPeriodSlackS) {
      out.cold_start = ColdStart::kPeriodic;
    } else if (warm.final_cost > cost_threshold()) {
      out.cold_start = ColdStart::kCostSpike;
    }
  }

  if (out.cold_start == ColdStart::kNone) {
    out.pose = warm.pose;
    out.cost = warm.final_cost;
    return finish(std::move(out));
  }

  const SolverResult cold = solve_relative_pose(own_, peer_, ranges_m, std::nullopt, solver_);
  ++counts_.cold_starts;
  last_cold_start_s_ = time_s;
  if (!usable(cold)) {
    out.status = TrackStatus::kFailed;
    out.pose = cold.pose;
    out.cost = cold.final_cost;
    out.reason = "cold start failed (no convergence or a non-finite result; cost " + shortest_text(cold.final_cost) + ")";
    return finish(std::move(out));
  }
  const SolverResult& kept = have_warm && warm.final_cost < cold.final_cost ? warm : cold;
  out.pose = kept.pose;
  out.cost = kept.final_cost;
  if (have_warm) {
    const double moved_m = std::hypot(cold.pose.x - warm.pose.x, cold.pose.y - warm.pose.y);
    const double turned_rad = std::abs(wrap_angle(cold.pose.theta - warm.pose.theta));
    if (moved_m > params_.disagreement_position_m || turned_rad > params_.disagreement_heading_rad) {
      out.status = TrackStatus::kSuspect;
      out.reason = "cold start " + m_text(moved_m) + " m / " + deg_text(turned_rad) +
                   " deg from the warm start (a wrong minimum; costs warm " + shortest_text(warm.final_cost) + ", cold " +
                   shortest_text(cold.final_cost) + ")";
      return finish(std::move(out));
    }
  }
  const double threshold = cost_threshold();
  if (out.cost > threshold) {
    out.status = TrackStatus::kSuspect;
    out.reason = "cost " + shortest_text(out.cost) + " m^2 above " + shortest_text(params_.cost_ratio) +
                 " x the running median even after a cold start (threshold " + shortest_text(threshold) + ")";
  }
  return finish(std::move(out));
}

TrackerOutput RelativePoseTracker::finish(TrackerOutput out) {
  switch (out.status) {
    case TrackStatus::kOk:
      ++counts_.ok;
      break;
    case TrackStatus::kSuspect:
      ++counts_.suspect;
      break;
    case TrackStatus::kFailed:
      ++counts_.failed;
      break;
    case TrackStatus::kRejected:
      ++counts_.rejected;
      break;
  }
  if (out.status == TrackStatus::kFailed) {
    previous_.reset();  // the next epoch cold-starts
    return out;
  }
  previous_ = out.pose;
  costs_.push_back(out.cost);
  while (costs_.size() > static_cast<std::size_t>(params_.cost_median_window)) {
    costs_.pop_front();
  }
  return out;
}

}  // namespace robodds::uwb_relative_estimator
