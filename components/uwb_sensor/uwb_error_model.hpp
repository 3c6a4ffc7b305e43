#pragma once
// Error model of the UWB array sensor (issue 11; paper 3 gives only the figures it reproduces,
// README "Calibration"). A range between node k of robot i and node l of robot j at time t is
//   r = d + w + b_kl(t) + c_ij(t) + o, clamped at 0,
// d the true range; w white Gaussian noise; b_kl a first-order Gauss-Markov bias of the link
// (k, l); c_ij a Gauss-Markov error common to all links of the robot pair; o a non-line-of-sight
// excess, uniform in [nlos_min_m, nlos_max_m] with probability nlos_probability, else 0.
//
// Both directions of a pair are one physical link: the measurements i -> j and j -> i share
// b_kl (link (k of i, l of j) is link (l of j, k of i)) and c_ij (PairErrors, one per unordered
// pair); w, o and frame losses are drawn per direction and frame (two-way ranging exchanges of
// their own).
//
// Gauss-Markov processes use the exact discretisation x' = a x + sqrt(1 - a^2) sigma n,
// a = exp(-dt / tau), n ~ N(0, 1), and start from their stationary distribution N(0, sigma^2),
// so their statistics do not depend on the sampling rate or on when a run starts.
//
// Random streams: one RandomEngine per stream, drawn in a fixed order and the same number of
// times whatever the parameters (nlos_probability, frame_loss_probability, sigma 0), so changing
// one parameter does not shift the others' draws.

#include <Eigen/Core>

#include "common/param_table.hpp"
#include "common/random.hpp"
#include "components/uwb_sensor/uwb_walls.hpp"

namespace robodds::uwb_sensor {

// Units, ranges and one-line descriptions of these fields: uwb_error_param_table(), the one
// source. Defaults: the initialisers (issue 11's values).
struct UwbErrorParams {
  double white_sigma_m = 0.04;
  double link_bias_sigma_m = 0.07;
  double link_bias_tau_s = 2.0;
  double common_sigma_m = 0.30;
  double common_tau_s = 10.0;
  double nlos_probability = 0.0;
  /// nlos_min_m <= nlos_max_m (validate()). Not scaled by sigma_scale: an excess path, not a sigma.
  double nlos_min_m = 0.2;
  double nlos_max_m = 1.5;
  /// Multiplies every sigma (white, link bias, common mode): uniformly worse ranging in one knob.
  /// (Experiment 2 sets the sigmas one by one instead: components/uwb_sensor/README.md.)
  double sigma_scale = 1.0;
  /// A whole frame (all K x L ranges of one direction at one sample time) is lost.
  double frame_loss_probability = 0.0;

  /// Throws std::invalid_argument "key: reason (got value)" for the first bad field.
  void validate() const;
};

const params::ParamTable<UwbErrorParams>& uwb_error_param_table();

/// The errors that both directions of one robot pair (a, b) share: the link biases b_kl
/// (nodes_a x nodes_b, row k: node k of a) and the common-mode error c_ab.
class PairErrors {
 public:
  /// Starts at `time_s` from the stationary distribution: draws nodes_a * nodes_b normals from
  /// `bias_engine` (row major) and one from `common_engine`. `params` must have passed validate().
  PairErrors(Eigen::Index nodes_a, Eigen::Index nodes_b, double time_s, const UwbErrorParams& params,
             RandomEngine bias_engine, RandomEngine common_engine);

  /// Moves both processes to `time_s`: nodes_a * nodes_b normals (row major) and one normal
  /// when time_s > time_s(), nothing otherwise (the second direction of a pair at the same time).
  void advance_to(double time_s);

  double time_s() const { return time_s_; }
  /// nodes_a x nodes_b, m.
  const Eigen::MatrixXd& link_bias_m() const { return bias_m_; }
  /// The biases oriented for a measurement from robot a (`from_a`, nodes_a x nodes_b) or from
  /// robot b (the transpose).
  Eigen::MatrixXd link_bias_m(bool from_a) const;
  double common_m() const { return common_m_; }

 private:
  UwbErrorParams params_;
  RandomEngine bias_engine_;
  RandomEngine common_engine_;
  double time_s_;
  Eigen::MatrixXd bias_m_;
  double common_m_ = 0.0;
};

/// The random streams of one direction (robot i measuring robot j).
struct DirectionStreams {
  RandomEngine white;
  RandomEngine nlos;
  RandomEngine loss;
};

/// One frame of one direction: `true_m` (K x L) plus white noise, the shared `link_bias_m`
/// (oriented like `true_m`) and `common_m`, plus NLOS excesses, clamped at 0. A link gets an
/// excess with probability nlos_probability, and always where `blocked` (K x L, a wall in the
/// way: uwb_walls.hpp; empty = nothing blocked). Draws K * L normals from `white_engine` and
/// 2 * K * L uniforms from `nlos_engine` (whether, how much), row major, whatever the parameters
/// and walls. `params` must have passed validate().
Eigen::MatrixXd measure_ranges(const Eigen::MatrixXd& true_m, const Eigen::MatrixXd& link_bias_m, double common_m,
                               const UwbErrorParams& params, RandomEngine& white_engine, RandomEngine& nlos_engine,
                               const BlockedLinks& blocked = BlockedLinks());

/// Whether a frame is lost (probability frame_loss_probability). Always one uniform.
bool frame_lost(const UwbErrorParams& params, RandomEngine& loss_engine);

}  // namespace robodds::uwb_sensor
