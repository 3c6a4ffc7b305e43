#include "components/uwb_sensor/uwb_error_model.hpp"

#include <algorithm>
#include <cmath>

#include "common/number_text.hpp"
#include "common/param_checks.hpp"

namespace robodds::uwb_sensor {

const params::ParamTable<UwbErrorParams>& uwb_error_param_table() {
  using P = UwbErrorParams;
  static const params::ParamTable<P> table =
      params::ParamTable<P>()
          .add("white_sigma_m", &P::white_sigma_m, "m", params::non_negative(),
               "white range noise w, independent per range and frame (issue 11: 0.04)")
          .add("link_bias_sigma_m", &P::link_bias_sigma_m, "m", params::non_negative(),
               "stationary sigma of the Gauss-Markov bias b_kl of each node-to-node link (issue 11: 0.07)")
          .add("link_bias_tau_s", &P::link_bias_tau_s, "s", params::positive(),
               "correlation time of the link bias (issue 11: 2)")
          .add("common_sigma_m", &P::common_sigma_m, "m", params::non_negative(),
               "stationary sigma of the Gauss-Markov error c_ij common to all links of a robot pair (issue 11: 0.30)")
          .add("common_tau_s", &P::common_tau_s, "s", params::positive(),
               "correlation time of the common-mode error (issue 11: 10)")
          .add("nlos_probability", &P::nlos_probability, "", params::in_half_open_interval(0.0, 1.0),
               "probability that a range gets a non-line-of-sight excess (0 = never)")
          .add("nlos_min_m", &P::nlos_min_m, "m", params::shown_as(params::non_negative(), "[0, nlos_max_m]"),
               "smallest NLOS excess (uniform in [nlos_min_m, nlos_max_m])")
          .add("nlos_max_m", &P::nlos_max_m, "m", params::non_negative(), "largest NLOS excess")
          .add("sigma_scale", &P::sigma_scale, "", params::non_negative(),
               "multiplies every sigma (white, link bias, common mode): uniformly worse ranging in one knob")
          .add("frame_loss_probability", &P::frame_loss_probability, "", params::in_half_open_interval(0.0, 1.0),
               "probability that a whole frame (K x L ranges of one direction) is lost (0 = never)");
  return table;
}

void UwbErrorParams::validate() const {
  uwb_error_param_table().check_ranges(*this);
  if (!(nlos_min_m <= nlos_max_m)) {
    param_checks::reject("nlos_min_m", "must be <= nlos_max_m (" + shortest_text(nlos_max_m) + ")", nlos_min_m);
  }
}

PairErrors::PairErrors(Eigen::Index nodes_a, Eigen::Index nodes_b, double time_s, const UwbErrorParams& params,
                       RandomEngine bias_engine, RandomEngine common_engine)
    : params_(params),
      bias_engine_(bias_engine),
      common_engine_(common_engine),
      time_s_(time_s),
      bias_m_(nodes_a, nodes_b) {
  const double bias_sigma = params_.sigma_scale * params_.link_bias_sigma_m;
  for (Eigen::Index k = 0; k < nodes_a; ++k) {
    for (Eigen::Index l = 0; l < nodes_b; ++l) {
      bias_m_(k, l) = bias_sigma * standard_normal(bias_engine_);
    }
  }
  common_m_ = params_.sigma_scale * params_.common_sigma_m * standard_normal(common_engine_);
}

void PairErrors::advance_to(double time_s) {
  if (!(time_s > time_s_)) {
    return;
  }
  const double dt_s = time_s - time_s_;
  const double bias_sigma = params_.sigma_scale * params_.link_bias_sigma_m;
  for (Eigen::Index k = 0; k < bias_m_.rows(); ++k) {
    for (Eigen::Index l = 0; l < bias_m_.cols(); ++l) {
      const double n = standard_normal(bias_engine_);
      bias_m_(k, l) = gauss_markov_step(bias_m_(k, l), dt_s, params_.link_bias_tau_s, bias_sigma, n);
    }
  }
  const double n = standard_normal(common_engine_);
  common_m_ = gauss_markov_step(common_m_, dt_s, params_.common_tau_s, params_.sigma_scale * params_.common_sigma_m, n);
  time_s_ = time_s;
}

Eigen::MatrixXd PairErrors::link_bias_m(bool from_a) const {
  if (from_a) {
    return bias_m_;
  }
  return bias_m_.transpose();
}

Eigen::MatrixXd measure_ranges(const Eigen::MatrixXd& true_m, const Eigen::MatrixXd& link_bias_m, double common_m,
                               const UwbErrorParams& params, RandomEngine& white_engine, RandomEngine& nlos_engine,
                               const BlockedLinks& blocked) {
  const double white_sigma = params.sigma_scale * params.white_sigma_m;
  const bool any_wall = blocked.size() != 0;
  Eigen::MatrixXd ranges(true_m.rows(), true_m.cols());
  for (Eigen::Index k = 0; k < true_m.rows(); ++k) {
    for (Eigen::Index l = 0; l < true_m.cols(); ++l) {
      // Named draws in a fixed order (argument evaluation order is unspecified).
      const double white = standard_normal(white_engine);
      const double nlos_draw = uniform01(nlos_engine);
      const double nlos_size = uniform01(nlos_engine);
      const bool nlos = nlos_draw < params.nlos_probability || (any_wall && blocked(k, l));
      const double excess = nlos ? params.nlos_min_m + (params.nlos_max_m - params.nlos_min_m) * nlos_size : 0.0;
      const double r = true_m(k, l) + white_sigma * white + link_bias_m(k, l) + common_m + excess;
      ranges(k, l) = std::max(0.0, r);
    }
  }
  return ranges;
}

bool frame_lost(const UwbErrorParams& params, RandomEngine& loss_engine) {
  return uniform01(loss_engine) < params.frame_loss_probability;
}

}  // namespace robodds::uwb_sensor
