#include "components/uwb_relative_estimator/relative_estimator.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <utility>

#include <Eigen/Cholesky>

#include "common/angle.hpp"

namespace robodds::uwb_relative_estimator {
namespace {

bool finite(const model::Pose2& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta); }

/// Wall-clock milliseconds since `start`.
double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

StageEstimate filter_estimate(const RelativePoseFilter& filter) {
  StageEstimate out;
  if (!filter.initialized()) {
    return out;
  }
  const pf_estimator::PoseEstimate e = filter.estimate();
  out.pose = model::Pose2{e.mean.x(), e.mean.y(), e.mean.z()};
  out.covariance = e.covariance;
  out.valid = true;
  return out;
}

/// A filter stage's estimate as reported: the filter's mean with the covariance of its update
/// errors (`error`) and the arc's bend, plus what its check against this epoch's eq. (1) fix
/// (`uwb`, when valid) finds beyond that; `pose` keeps the mean (where `error` propagates from).
/// A filter the check finds lost (InnovationMonitor::lost: the fixes' median innovation beyond
/// the fixes' and the filter's covariance) is restarted at its mean plus that innovation, with the
/// fixes' mean covariance, and reported from there; `restarts` counts it.
StageEstimate reported_filter_estimate(RelativePoseFilter& filter, FilterErrorCovariance& error, const StageEstimate& uwb,
                                       const Eigen::Matrix3d& uwb_own_covariance, InnovationMonitor& check,
                                       RandomEngine& random, model::Pose2& pose, std::uint64_t& restarts) {
  StageEstimate out = filter_estimate(filter);
  if (out.valid) {
    Eigen::Matrix3d covariance = with_bearing_curvature(error.covariance(), out.pose);
    if (uwb.valid) {
      check.add(out.pose, uwb.pose, uwb.covariance, uwb_own_covariance);
    }
    Eigen::Vector3d correction;
    Eigen::Matrix3d fix_covariance;
    if (check.lost(covariance, correction, fix_covariance)) {
      const model::Pose2 restart{out.pose.x + correction.x(), out.pose.y + correction.y(),
                                 wrap_angle(out.pose.theta + correction.z())};
      filter.initialize(restart, random);
      error.start(fix_covariance);
      check.reset();
      ++restarts;
      out = filter_estimate(filter);
      covariance = with_bearing_curvature(error.covariance(), out.pose);
    }
    out.covariance = covariance + check.excess();
    pose = out.pose;
  }
  return out;
}

}  // namespace

const char* stage_name(Stage stage) {
  switch (stage) {
    case Stage::kUwb:
      return "uwb";
    case Stage::kWindow:
      return "window";
    case Stage::kPf:
      return "pf";
    case Stage::kPfBaseline:
      return "pf_baseline";
    case Stage::kOdometry:
      return "odometry";
    case Stage::kTc:
      return "tc";
  }
  return "?";
}

RelativeEstimator::RelativeEstimator(model::UwbArray own_array, std::vector<PeerSetup> peers, RelativeEstimatorParams params,
                                     std::uint64_t seed)
    : own_array_(std::move(own_array)), setups_(std::move(peers)), params_(std::move(params)) {
  params_.validate();
  model::check_array("own_array", own_array_);
  if (setups_.empty()) {
    throw std::invalid_argument("peers: a relative estimator needs at least one peer");
  }
  std::set<std::uint32_t> ids;
  for (const PeerSetup& peer : setups_) {
    if (!ids.insert(peer.id).second) {
      throw std::invalid_argument("peers: robot " + std::to_string(peer.id) + " is listed twice");
    }
    model::check_array("peer " + std::to_string(peer.id) + " array", peer.array);
    if (peer.known_start && !finite(*peer.known_start)) {
      throw std::invalid_argument("peer " + std::to_string(peer.id) + " known_start is not finite (got " +
                                  model::to_text(*peer.known_start) + ")");
    }
  }
  peers_.reserve(setups_.size());
  for (const PeerSetup& peer : setups_) {
    const std::string stream = "peer" + std::to_string(peer.id);
    peers_.push_back(PeerState{RelativePoseTracker(own_array_, peer.array, params_.solver, params_.tracker),
                               RelativePoseFilter(params_.pf), RelativePoseFilter(params_.pf),
                               RandomEngine(derive_seed(seed, stream + "/pf")),
                               RandomEngine(derive_seed(seed, stream + "/pf_baseline")), RangeNoiseLevel(params_.uncertainty),
                               FilterErrorCovariance(params_.uncertainty), FilterErrorCovariance(params_.uncertainty),
                               InnovationMonitor(params_.uncertainty), InnovationMonitor(params_.uncertainty),
                               model::Pose2{}, model::Pose2{}, peer.known_start, Eigen::Matrix3d::Zero(), {}, {}, RangeErrorMap{}, false,
                               Eigen::VectorXd(), std::nullopt, std::nullopt, Eigen::Matrix3d::Zero(),
                               FixTrackCheck(params_.uncertainty), InnovationMonitor(params_.uncertainty),
                               Eigen::Matrix3d::Zero(), InnovationMonitor(params_.uncertainty), 0, {}, 0.0,
                               Eigen::Matrix3d::Zero()});
    tc_.emplace_back(own_array_, peer.array, params_.tc);
  }
  for (std::size_t a = 0; a < setups_.size(); ++a) {
    for (std::size_t b = a + 1; b < setups_.size(); ++b) {
      links_.push_back(PeerLink{a, b});
      link_trackers_.emplace_back(setups_[a].array, setups_[b].array, params_.solver, params_.tracker);
    }
  }
  pool_ = std::make_unique<WorkerPool>(params_.threads);
}

RelativeEstimator::~RelativeEstimator() = default;
RelativeEstimator::RelativeEstimator(RelativeEstimator&&) = default;
RelativeEstimator& RelativeEstimator::operator=(RelativeEstimator&&) = default;

EpochResult RelativeEstimator::step(double time_s, const model::Pose2& own_increment, const std::vector<PeerEpoch>& peers,
                                    const std::vector<std::optional<Eigen::MatrixXd>>& link_ranges) {
  if (peers.size() != setups_.size()) {
    throw std::invalid_argument("step: " + std::to_string(peers.size()) + " peer entries for " +
                                std::to_string(setups_.size()) + " peers");
  }
  if (!link_ranges.empty() && link_ranges.size() != links_.size()) {
    throw std::invalid_argument("step: " + std::to_string(link_ranges.size()) + " link entries for " +
                                std::to_string(links_.size()) + " links between peers");
  }
  if (!std::isfinite(time_s)) {
    throw std::invalid_argument("step: time is not finite");
  }
  if (last_time_s_ && time_s < *last_time_s_) {
    throw std::invalid_argument("step: time " + std::to_string(time_s) + " s is before the previous epoch's (" +
                                std::to_string(*last_time_s_) + " s)");
  }
  if (!finite(own_increment)) {
    throw std::invalid_argument("step: own odometry increment is not finite (got " + model::to_text(own_increment) + ")");
  }
  for (std::size_t k = 0; k < peers.size(); ++k) {
    if (!finite(peers[k].odometry_increment)) {
      throw std::invalid_argument("step: odometry increment of peer " + std::to_string(setups_[k].id) +
                                  " is not finite (got " + model::to_text(peers[k].odometry_increment) + ")");
    }
  }
  ++counts_.epochs;
  const double dt_s = last_time_s_ ? time_s - *last_time_s_ : 0.0;
  last_time_s_ = time_s;
  const auto cycle_start = std::chrono::steady_clock::now();
  EpochResult result;
  result.peers.resize(peers.size());
  const std::size_t n = peers.size();
  // Each task below writes only its own peer's (or link's) state and result, and the counts and
  // times it returns are added up afterwards in a fixed order: the estimates do not depend on how
  // many threads run them (issue 29). A stage's time is the sum of its pieces' wall-clock times.
  std::vector<double> piece_ms(2 * n + links_.size(), 0.0);

  // Eq. (1) of every peer (then its odometry stage) and of every link.
  std::vector<std::optional<PairMeasurement>> link_solved(links_.size());
  pool_->run(n + links_.size(), [&](std::size_t i) {
    const auto start = std::chrono::steady_clock::now();
    if (i >= n) {
      const std::size_t l = i - n;
      if (l < link_ranges.size() && link_ranges[l]) {
        const TrackerOutput solved = link_trackers_[l].update(*link_ranges[l], time_s);
        if (solved.status == TrackStatus::kOk) {
          link_solved[l] = PairMeasurement{links_[l].first + 1, links_[l].second + 1, solved.pose};
        }
      }
      piece_ms[2 * n + l] = ms_since(start);
      return;
    }
    run_uwb(i, time_s, own_increment, peers[i], result.peers[i]);
    const auto odometry_start = std::chrono::steady_clock::now();
    piece_ms[i] = std::chrono::duration<double, std::milli>(odometry_start - start).count();
    run_odometry(i, own_increment, peers[i], result.peers[i]);
    piece_ms[n + i] = ms_since(odometry_start);
  });
  std::vector<PairMeasurement> link_edges;
  for (std::size_t l = 0; l < links_.size(); ++l) {
    result.stage_ms[static_cast<std::size_t>(Stage::kUwb)] += piece_ms[2 * n + l];
    if (link_solved[l]) {
      link_edges.push_back(*link_solved[l]);
    }
  }
  for (std::size_t k = 0; k < n; ++k) {
    result.stage_ms[static_cast<std::size_t>(Stage::kUwb)] += piece_ms[k];
    result.stage_ms[static_cast<std::size_t>(Stage::kOdometry)] += piece_ms[n + k];
    if (!result.peers[k].had_ranges) {
      ++counts_.frames_missing;
    }
  }

  // The window (one task, the longest: first), and every peer's tc and pf_baseline beside it.
  std::vector<std::uint64_t> restarts(n, 0);
  pool_->run(1 + 2 * n, [&](std::size_t i) {
    const auto start = std::chrono::steady_clock::now();
    if (i == 0) {
      run_window(own_increment, peers, link_edges, result);
      result.stage_ms[static_cast<std::size_t>(Stage::kWindow)] = ms_since(start);
    } else if (i <= n) {
      run_tc(i - 1, time_s, own_increment, peers[i - 1], result.peers[i - 1]);
      piece_ms[i - 1] = ms_since(start);
    } else {
      run_baseline(i - 1 - n, time_s, dt_s, own_increment, peers[i - 1 - n], result.peers[i - 1 - n], restarts[i - 1 - n]);
      piece_ms[i - 1] = ms_since(start);
    }
  });
  for (std::size_t k = 0; k < n; ++k) {
    result.stage_ms[static_cast<std::size_t>(Stage::kTc)] += piece_ms[k];
    result.stage_ms[static_cast<std::size_t>(Stage::kPfBaseline)] += piece_ms[n + k];
    counts_.baseline_restarts += restarts[k];
    restarts[k] = 0;
  }

  // The pf of every peer (weighted by the window's estimate).
  pool_->run(n, [&](std::size_t k) {
    const auto start = std::chrono::steady_clock::now();
    run_pf(k, time_s, dt_s, own_increment, peers[k], result.peers[k], restarts[k]);
    piece_ms[k] = ms_since(start);
  });
  for (std::size_t k = 0; k < n; ++k) {
    result.stage_ms[static_cast<std::size_t>(Stage::kPf)] += piece_ms[k];
    counts_.filter_restarts += restarts[k];
  }
  result.cycle_ms = ms_since(cycle_start);
  return result;
}

void RelativeEstimator::run_uwb(std::size_t k, double time_s, const model::Pose2& own_increment, const PeerEpoch& input,
                                PeerResult& out) {
  PeerState& peer = peers_[k];
  peer.fix_variances.resize(0);
  peer.fix_check.predict(own_increment, input.odometry_increment, params_.window.odometry_xy_std_m,
                         params_.window.odometry_theta_std_rad);
  out.had_ranges = input.ranges_m.has_value();
  if (!out.had_ranges) {
    out.uwb_reason = "no frame";
    return;
  }
  const TrackerOutput solved = peer.tracker.update(*input.ranges_m, time_s);
  out.uwb_status = solved.status;
  out.uwb_reason = solved.reason;
  StageEstimate& uwb = out.stages[static_cast<std::size_t>(Stage::kUwb)];
  uwb.pose = solved.pose;
  uwb.valid = solved.status == TrackStatus::kOk;
  if (!uwb.valid) {
    return;
  }
  const Eigen::MatrixXd& ranges = *input.ranges_m;
  peer.range_noise.add(robust_residual_std_m(own_array_, setups_[k].array, ranges, uwb.pose));
  // The running median of robust stds is the noise level (a lucky epoch does not shrink it);
  // this epoch's plain residual std, when larger, widens it while the link biases line up
  // badly (they last ~2 s) or a range the fit followed is far off (non-line-of-sight).
  const double epoch_std_m = residual_rms_std_m(own_array_, setups_[k].array, ranges, uwb.pose);
  const double noise_std_m = peer.range_noise.std_m();
  // A range whose leave-one-out residual is far beyond the noise level (non-line-of-sight, a
  // blocked link) gets its own variance: the fit moved by what it pulled.
  RangeErrorMap error;
  if (range_error_map(own_array_, setups_[k].array, uwb.pose, std::max(noise_std_m, epoch_std_m),
                      params_.uncertainty.range_common_std_m, error, params_.uncertainty.node_bias_std_m)) {
    error.independent_variance_m2 =
        range_error_variances(own_array_, setups_[k].array, ranges, uwb.pose, std::max(noise_std_m, epoch_std_m),
                              noise_std_m, params_.uncertainty.outlier_sigma);
    peer.fix_model_covariance = with_bearing_curvature(error.covariance(), uwb.pose);
    // What the sequence of fixes shows beyond the model (an error that one epoch's residuals
    // cannot see but that changes as the robots move) widens what this stage reports.
    peer.fix_check.add(time_s, uwb.pose, error, peer.fix_model_covariance);
    uwb.covariance = peer.fix_check.inflate(peer.fix_model_covariance);
    peer.fix_variances = error.independent_variance_m2;
    peer.fix_own_covariance = error.independent_map * error.independent_variance_m2.asDiagonal() * error.independent_map.transpose();
  } else {
    uwb.covariance = Eigen::Matrix3d::Constant(std::numeric_limits<double>::quiet_NaN());  // degenerate geometry
    peer.fix_model_covariance = uwb.covariance;
  }
}

void RelativeEstimator::run_odometry(std::size_t k, const model::Pose2& own_increment, const PeerEpoch& input,
                                     PeerResult& out) {
  PeerState& peer = peers_[k];
  const StageEstimate& uwb = out.stages[static_cast<std::size_t>(Stage::kUwb)];
  if (peer.odometry_pose) {
    peer.odometry_covariance =
        propagate_relative_covariance(peer.odometry_covariance, *peer.odometry_pose, own_increment,
                                      input.odometry_increment, params_.window.odometry_xy_std_m,
                                      params_.window.odometry_theta_std_rad);
    peer.odometry_pose = model::compose(model::between(own_increment, *peer.odometry_pose), input.odometry_increment);
  } else if (uwb.valid) {
    peer.odometry_pose = uwb.pose;  // no known start: dead reckoning from the first valid fix
    peer.odometry_covariance = uwb.covariance;
  }
  StageEstimate& odometry = out.stages[static_cast<std::size_t>(Stage::kOdometry)];
  odometry.valid = peer.odometry_pose.has_value();
  if (odometry.valid) {
    odometry.pose = *peer.odometry_pose;
    // Its own check: the fixes (independent of the odometry) against the dead reckoning; what
    // neither covariance explains (a slip's drift, carried to now along its trend) is added.
    if (uwb.valid) {
      peer.odometry_check.add(odometry.pose, uwb.pose, peer.fix_model_covariance);
    }
    odometry.covariance = peer.odometry_covariance + peer.odometry_check.drifting_excess(peer.odometry_covariance);
  }
}

void RelativeEstimator::run_pf(std::size_t k, double time_s, double dt_s, const model::Pose2& own_increment,
                               const PeerEpoch& input, PeerResult& result, std::uint64_t& restarts) {
  PeerState& peer = peers_[k];
  const WindowWeights& odometry = params_.window;  // the odometry stds the odometry stage reports with
  peer.pf.predict(own_increment, input.odometry_increment, peer.pf_random);
  peer.pf_error.predict(peer.pf_pose, own_increment, input.odometry_increment, dt_s, odometry.odometry_xy_std_m,
                        odometry.odometry_theta_std_rad);
  const StageEstimate& window = result.stages[static_cast<std::size_t>(Stage::kWindow)];
  const bool fix = result.stages[static_cast<std::size_t>(Stage::kUwb)].valid;
  if (window.valid) {
    // The window's pose errs as a fix at that pose would (the window smooths its errors: no
    // larger, FilterErrorCovariance); R is what the filter's weights assume.
    const RangeErrorMap& error = peer.window_error;
    const bool mapped = peer.window_mapped;
    const double ld = params_.pf.lambda_d_m;
    const double lt = params_.pf.lambda_theta_rad;
    const bool restart = fix && peer.pf.initialized() && peer.last_fix_s && time_s - *peer.last_fix_s > params_.restart_after_gap_s;
    if (restart || !peer.pf.initialized()) {
      if (restart) {
        peer.pf.initialize(window.pose, peer.pf_random);  // the cloud (and the window) drifted on odometry alone
      } else {
        peer.pf.update_with_pose(window.pose, peer.pf_random);  // initialises around it
      }
      peer.pf_check.reset();
      if (mapped) {
        peer.pf_error.start(error);
      } else {
        peer.pf_error.start(Eigen::Vector3d(ld * ld, ld * ld, lt * lt).asDiagonal().toDenseMatrix());
      }
    } else {
      const Eigen::Matrix3d prior = peer.pf.estimate().covariance;
      peer.pf.update_with_pose(window.pose, peer.pf_random);
      if (mapped) {
        peer.pf_error.update(update_gain(prior, Eigen::Vector3d(ld * ld, ld * ld, lt * lt).asDiagonal().toDenseMatrix()), error);
      }
    }
  }
  if (fix) {
    peer.last_fix_s = time_s;
  }
  result.stages[static_cast<std::size_t>(Stage::kPf)] =
      reported_filter_estimate(peer.pf, peer.pf_error, model_fix(peer, result), peer.fix_own_covariance,
                               peer.pf_check, peer.pf_random, peer.pf_pose, restarts);
}

void RelativeEstimator::run_baseline(std::size_t k, double time_s, double dt_s, const model::Pose2& own_increment,
                                     const PeerEpoch& input, PeerResult& result, std::uint64_t& restarts) {
  PeerState& peer = peers_[k];
  const WindowWeights& odometry = params_.window;
  peer.baseline.predict(own_increment, input.odometry_increment, peer.baseline_random);
  peer.baseline_error.predict(peer.baseline_pose, own_increment, input.odometry_increment, dt_s,
                              odometry.odometry_xy_std_m, odometry.odometry_theta_std_rad);
  if (result.had_ranges && result.uwb_status != TrackStatus::kRejected) {
    const bool after_gap = peer.last_frame_s && time_s - *peer.last_frame_s > params_.restart_after_gap_s;
    const StageEstimate& fix = result.stages[static_cast<std::size_t>(Stage::kUwb)];
    const Eigen::MatrixXd& ranges = *input.ranges_m;
    // The independent range std of this epoch's ranges, as the uwb stage sees it: the running
    // median, or this epoch's residual std at the solve when larger (a non-line-of-sight range).
    const double noise_std_m = peer.range_noise.std_m();
    const bool solved = result.uwb_status == TrackStatus::kOk || result.uwb_status == TrackStatus::kSuspect;
    const double range_std_m =
        solved ? std::max(noise_std_m, residual_rms_std_m(own_array_, setups_[k].array, ranges, fix.pose)) : noise_std_m;
    const double common_std_m = params_.uncertainty.range_common_std_m;
    const double node_bias_std_m = params_.uncertainty.node_bias_std_m;
    // Each range's variance, an outlier's its own (as the uwb stage's), from the solve's residuals.
    const auto set_variances = [&](RangeErrorMap& error) {
      if (solved) {
        error.independent_variance_m2 = range_error_variances(own_array_, setups_[k].array, ranges, fix.pose, range_std_m,
                                                              noise_std_m, params_.uncertainty.outlier_sigma);
      }
    };
    if (peer.baseline.initialized() && !after_gap) {
      const pf_estimator::PoseEstimate prior = peer.baseline.estimate();
      const model::Pose2 at{prior.mean.x(), prior.mean.y(), prior.mean.z()};
      peer.baseline.update_with_ranges(own_array_, setups_[k].array, ranges, peer.baseline_random);
      peer.last_frame_s = time_s;
      RangeErrorMap error;
      if (range_error_map(own_array_, setups_[k].array, at, range_std_m, common_std_m, error, node_bias_std_m)) {
        set_variances(error);
        // The weights' N(r - d(x); range_std_m) on K L ranges: a pose measurement of covariance
        // range_std_m^2 (J^T J)^-1 to first order.
        const double assumed = params_.pf.range_std_m;
        const Eigen::Matrix3d measurement = assumed * assumed * (error.independent_map * error.independent_map.transpose());
        peer.baseline_error.update(update_gain(prior.covariance, measurement), error);
      }
    } else if (fix.valid) {
      peer.baseline.initialize(fix.pose, peer.baseline_random);  // first fix, or the cloud drifted
      peer.last_frame_s = time_s;
      peer.baseline_check.reset();
      RangeErrorMap error;
      if (range_error_map(own_array_, setups_[k].array, fix.pose, range_std_m, common_std_m, error, node_bias_std_m)) {
        set_variances(error);
        peer.baseline_error.start(error);
      } else {
        peer.baseline_error.start(fix.covariance);
      }
    }
  }
  result.stages[static_cast<std::size_t>(Stage::kPfBaseline)] = reported_filter_estimate(
      peer.baseline, peer.baseline_error, model_fix(peer, result), peer.fix_own_covariance,
      peer.baseline_check, peer.baseline_random, peer.baseline_pose, restarts);
}

void RelativeEstimator::run_window(const model::Pose2& own_increment, const std::vector<PeerEpoch>& peers,
                                   const std::vector<PairMeasurement>& link_edges, EpochResult& result) {
  std::vector<PairMeasurement> edges;
  std::vector<bool> has_edge(peers.size(), false);
  for (std::size_t k = 0; k < peers.size(); ++k) {
    const StageEstimate& uwb = result.peers[k].stages[static_cast<std::size_t>(Stage::kUwb)];
    if (uwb.valid) {
      edges.push_back(PairMeasurement{0, k + 1, uwb.pose});
      has_edge[k] = true;
    }
  }
  if (!window_) {
    if (edges.empty()) {
      return;  // no peer measured yet: no window (every peer's window estimate invalid)
    }
    window_.emplace(peers.size() + 1, static_cast<std::size_t>(params_.window_epochs), params_.window);
  }
  // A link to a peer whose poses are still a guess would pull the other towards the guess.
  for (const PairMeasurement& link : link_edges) {
    if (placed(link.own - 1) && placed(link.other - 1)) {
      edges.push_back(link);
    }
  }
  std::vector<model::Pose2> increments;
  increments.reserve(peers.size() + 1);
  increments.push_back(own_increment);
  for (const PeerEpoch& peer : peers) {
    increments.push_back(peer.odometry_increment);
  }
  window_->add_epoch(increments, edges);
  for (std::size_t k = 0; k < peers.size(); ++k) {
    if (has_edge[k] && !placed(k)) {
      // Its poses are a guess (its first edge, or none in the window for window_epochs epochs).
      window_->place_robot(k + 1, 0, result.peers[k].stages[static_cast<std::size_t>(Stage::kUwb)].pose);
    }
    std::deque<bool>& recent = peers_[k].window_edges;
    recent.push_back(has_edge[k]);
    std::deque<Eigen::VectorXd>& variances = peers_[k].window_variances;
    variances.push_back(has_edge[k] ? peers_[k].fix_variances : Eigen::VectorXd());
    if (recent.size() > static_cast<std::size_t>(params_.window_epochs)) {
      recent.pop_front();
      variances.pop_front();
    }
  }
  const bool converged = window_->optimize();
  if (!converged) {
    ++counts_.window_not_converged;
  }
  for (std::size_t k = 0; k < peers.size(); ++k) {
    StageEstimate& window = result.peers[k].stages[static_cast<std::size_t>(Stage::kWindow)];
    window.pose = window_->latest_relative(0, k + 1);
    // Valid while the window holds at least one measurement of this peer and the solve converged
    // to a finite pose.
    window.valid = converged && placed(k) && std::isfinite(window.pose.x) && std::isfinite(window.pose.y) &&
                   std::isfinite(window.pose.theta);
    PeerState& peer = peers_[k];
    peer.window_mapped = false;
    if (window.valid) {
      // The fixes' dominant errors (the pair's common mode, tau ~10 s; the link biases, ~2 s) last
      // about as long as the window or longer: averaging them over the window is given no credit.
      // Each range's variance is its mean over the window's fixes (an outlier's share of it).
      const double noise_std_m = peer.range_noise.std_m();
      if (range_error_map(own_array_, setups_[k].array, window.pose, noise_std_m, params_.uncertainty.range_common_std_m,
                          peer.window_error, params_.uncertainty.node_bias_std_m)) {
        Eigen::VectorXd sum = Eigen::VectorXd::Zero(peer.window_error.independent_variance_m2.size());
        int count = 0;
        for (const Eigen::VectorXd& v : peer.window_variances) {
          if (v.size() == sum.size()) {
            sum += v;
            ++count;
          }
        }
        if (count > 0) {
          peer.window_error.independent_variance_m2 =
              (sum / count).cwiseMax(noise_std_m * noise_std_m);
        }
        peer.window_mapped = true;
        window.covariance = with_bearing_curvature(peer.window_error.covariance(), window.pose);
      } else {
        window.covariance = Eigen::Matrix3d::Constant(std::numeric_limits<double>::quiet_NaN());
      }
    }
  }
}

StageEstimate RelativeEstimator::model_fix(const PeerState& peer, const PeerResult& result) {
  StageEstimate fix = result.stages[static_cast<std::size_t>(Stage::kUwb)];
  if (fix.valid) {
    fix.covariance = peer.fix_model_covariance;
  }
  return fix;
}

void RelativeEstimator::run_tc(std::size_t k, double time_s, const model::Pose2& own_increment, const PeerEpoch& input,
                               PeerResult& out) {
  // Beyond the paper (issue 28): the raw ranges of an accepted frame, started from an ok fix.
  const StageEstimate& uwb = out.stages[static_cast<std::size_t>(Stage::kUwb)];
  const bool accepted = out.had_ranges && out.uwb_status != TrackStatus::kRejected;
  StageEstimate& estimate = out.stages[static_cast<std::size_t>(Stage::kTc)];
  // A range the uwb stage's outlier test finds far beyond the noise level (non-line-of-sight, a
  // blocked link) gets the excess of its own variance over tc's model of an independent range
  // error (white and link bias): range_error_variances at this epoch's fix, as the uwb stage.
  Eigen::VectorXd outliers;
  if (accepted && uwb.valid) {
    const TightWindowParams& tc = params_.tc;
    const double base_std_m = std::hypot(tc.white_std_m, tc.link_bias_std_m);
    outliers = (range_error_variances(own_array_, setups_[k].array, *input.ranges_m, uwb.pose, base_std_m,
                                      peers_[k].range_noise.std_m(), params_.uncertainty.outlier_sigma)
                    .array() -
                base_std_m * base_std_m)
                   .cwiseMax(0.0)
                   .matrix();
  }
  estimate.valid = tc_[k].step(time_s, own_increment, input.odometry_increment,
                               accepted ? input.ranges_m : std::optional<Eigen::MatrixXd>(),
                               uwb.valid ? std::optional<model::Pose2>(uwb.pose) : std::nullopt, outliers);
  if (estimate.valid) {
    estimate.pose = tc_[k].pose();
    // What the uwb stage's check over time finds in the fixes beyond the range error model (an
    // error of another kind: a board's excess on the links through it) reaches tc through the
    // same ranges: its covariance is scaled alike (1 while the fixes hold their model).
    Eigen::Matrix3d covariance = tc_[k].covariance();
    // A bias per UWB node (uncertainty.node_bias_std_m, a consider parameter of the uwb stage's
    // error model: an antenna's delay, a node shadowed) moves the fit as a moved node would, into
    // heading and bearing; tc's range model (white, link and common biases) has no such state and
    // its window cannot average a bias that lasts: the covariance it would cause is added, as the
    // uwb stage's model counts it (s_n^2 N N^T at tc's pose).
    RangeErrorMap node;
    if (params_.tc.node_bias_term &&
        range_error_map(own_array_, setups_[k].array, estimate.pose, params_.tc.white_std_m, 0.0, node,
                        params_.uncertainty.node_bias_std_m) &&
        node.node_map.cols() > 0) {
      covariance += node.node_bias_std_m * node.node_bias_std_m * (node.node_map * node.node_map.transpose());
    }
    // Ranges fix the distance and leave the bearing less certain: the peer lies on an arc, not on
    // the tangent tc's linearised information draws (with_bearing_curvature, as the uwb stage and
    // the filters report; tenths of a metre at a few metres with a weak bearing).
    if (params_.tc.bearing_curvature_term) {
      covariance = with_bearing_curvature(covariance, estimate.pose);
    }
    estimate.covariance = peers_[k].fix_check.inflate(covariance);
    // Its own check against the fixes (issue 27), as the filters': tc is kept by its odometry and
    // its window near a minimum its ranges allow; where that minimum is wrong (a jump to a
    // non-line-of-sight fix's pose, a start from a wrong fix, a geometry that hides the bearing)
    // its information at the minimum does not say so, the fixes over the last
    // innovation_window_epochs do: what their median innovation shows beyond the fixes' own
    // covariance is added (zero while tc follows the fixes).
    if (params_.tc.innovation_check) {
      PeerState& peer = peers_[k];
      if (tc_[k].restarts() != peer.tc_restarts) {
        peer.tc_check.reset();
        peer.tc_restarts = tc_[k].restarts();
      }
      if (uwb.valid) {
        peer.tc_check.add(estimate.pose, uwb.pose, peer.fix_model_covariance, peer.fix_own_covariance);
      }
      estimate.covariance += peer.tc_check.excess();
    }
    if (params_.tc.jump_check_epochs > 0) {
      estimate.covariance += tc_jump_term(peers_[k], time_s, own_increment, input.odometry_increment, estimate);
    }
  } else {
    peers_[k].tc_kept.clear();
    peers_[k].tc_jump.setZero();
  }
}

Eigen::Matrix3d RelativeEstimator::tc_jump_term(PeerState& peer, double time_s, const model::Pose2& own_increment,
                                                const model::Pose2& peer_increment, const StageEstimate& estimate) const {
  // tc's own check over its last tc.jump_check_epochs epochs: each estimate it reported then,
  // dead-reckoned by both odometries to now with the covariance it reported propagated (P'),
  // against this epoch's. A least-squares window that jumps to another minimum (a
  // non-line-of-sight fix's pose, a flipped bearing), at once or over a few epochs, moves by more
  // than P' allows (d^2 of the position beyond chi-square's 99.9 % quantile with 2 degrees of
  // freedom, 13.82, or z^2 of the heading beyond 10.83 with 1): one of the two minima is wrong and
  // nothing within the window says which, so the jump nu nu^T (the largest d^2's) is what tc
  // reports beyond its own covariance (the part of it the term does not hold yet is added), and
  // decays as the pair's longest range error does (uncertainty.range_common_time_s). P' bounds a
  // consistent estimator's move from above (its updates only shrink it).
  constexpr double kPositionGate = 13.82;
  constexpr double kHeadingGate = 10.83;
  if (!peer.tc_kept.empty()) {
    peer.tc_jump *= std::exp(-(time_s - peer.tc_time_s) / params_.uncertainty.range_common_time_s);
    double worst = 0.0;
    Eigen::Vector3d jump = Eigen::Vector3d::Zero();
    for (auto& [pose, covariance] : peer.tc_kept) {
      covariance = propagate_relative_covariance(covariance, pose, own_increment, peer_increment,
                                                 params_.tc.odometry_xy_std_m, params_.tc.odometry_theta_std_rad);
      pose = model::compose(model::between(own_increment, pose), peer_increment);
      const Eigen::Vector3d nu(estimate.pose.x - pose.x, estimate.pose.y - pose.y, wrap_angle(estimate.pose.theta - pose.theta));
      const Eigen::LLT<Eigen::Matrix2d> position(covariance.topLeftCorner<2, 2>());
      if (!nu.allFinite() || position.info() != Eigen::Success || !(covariance(2, 2) > 0.0)) {
        continue;
      }
      const double d2 = nu.head<2>().dot(position.solve(nu.head<2>()));
      const double z2 = nu.z() * nu.z() / covariance(2, 2);
      const double excess = std::max(d2 / kPositionGate, z2 / kHeadingGate);
      if (excess > 1.0 && excess > worst) {
        worst = excess;
        jump = nu;
      }
    }
    if (worst > 1.0) {
      // The smallest addition that makes the term hold nu nu^T: its positive eigen-part beyond it.
      peer.tc_jump += positive_part(jump * jump.transpose() - peer.tc_jump);
    }
  }
  peer.tc_kept.emplace_back(estimate.pose, estimate.covariance + peer.tc_jump);
  while (peer.tc_kept.size() > static_cast<std::size_t>(params_.tc.jump_check_epochs)) {
    peer.tc_kept.pop_front();
  }
  peer.tc_time_s = time_s;
  return peer.tc_jump;
}

bool RelativeEstimator::placed(std::size_t k) const {
  const std::deque<bool>& recent = peers_[k].window_edges;
  return std::find(recent.begin(), recent.end(), true) != recent.end();
}

}  // namespace robodds::uwb_relative_estimator
