#include "components/range_rate_observer/observer_params.hpp"

#include <string>

namespace robodds::range_rate_observer {
namespace {

constexpr const char* kNoiseFloorDescription = "the range sensor's configured noise sigma: floor of the online noise estimate";

/// The restart keys every observer has (RangeRateObserver's restart rule and window), after its
/// own: restart_sigmas, noise_floor_m, restart_window_s.
template <class P>
params::ParamTable<P>& add_restart_keys(params::ParamTable<P>& table, const std::string& noise_floor_description) {
  return table
      .add("restart_sigmas", &P::restart_sigmas, "", params::non_negative("0 = never restart"),
           "a range step the rate misses by more than this many times its estimated spread restarts the observer")
      .add("noise_floor_m", &P::noise_floor_m, "m", params::positive(), noise_floor_description)
      .add("restart_window_s", &P::restart_window_s, "s", params::positive(),
           "after a restart: least-squares window that sets range and rate; not valid until full");
}

}  // namespace

const params::ParamTable<SuperTwistingParams>& super_twisting_param_table() {
  using P = SuperTwistingParams;
  static const params::ParamTable<P> table = add_restart_keys(
      params::ParamTable<P>("Sliding-mode range-rate observer of paper 2, eq. (1) as read in README.md.")
          .add("a", &P::a, "m^(1/2)/s", params::in_open_interval(0.0, 2.5),
               "gain on |e|^(1/2) sgn(e); range of the paper's Lyapunov analysis (section 1.2)")
          .add("b", &P::b, "m/s^2", params::positive(),
               "gain on sgn(e); above the largest |range acceleration| to follow")
          .add("c", &P::c, "1/s^2", params::positive(), "gain on e in the rate equation")
          .add("d", &P::d, "1/s", params::non_negative("0 = plain super-twisting"), "linear gain on e, J of eq. (3)"),
      kNoiseFloorDescription);
  return table;
}

const params::ParamTable<LinearObserverParams>& linear_observer_param_table() {
  using P = LinearObserverParams;
  static const params::ParamTable<P> table = add_restart_keys(
      params::ParamTable<P>("Linear baseline range-rate observer, eq. (9) as read in README.md.")
          .add("k1", &P::k1, "1/s", params::positive(), "gain on the range error in the range equation")
          .add("k2", &P::k2, "1/s^2", params::positive(), "gain on the range error in the rate equation"),
      kNoiseFloorDescription);
  return table;
}

const params::ParamTable<KalmanObserverParams>& kalman_observer_param_table() {
  using P = KalmanObserverParams;
  static const params::ParamTable<P> table = add_restart_keys(
      params::ParamTable<P>("Kalman filter on range, range rate and range acceleration (issue 28, beyond the paper).")
          .add("jerk_psd_m2ps5", &P::jerk_psd_m2ps5, "m^2/s^5", params::positive(),
               "q: spectral density of the white jerk driving the range acceleration (smaller: lower noise floor, "
               "slower to follow a change of acceleration)")
          .add("initial_accel_std_mps2", &P::initial_accel_std_mps2, "m/s^2", params::non_negative(),
               "std of the range acceleration at a (re)start")
          .add("min_range_sigma_m", &P::min_range_sigma_m, "m", params::positive(),
               "the smallest range noise sigma a range is weighed by (the filter uses the online estimate)"),
      std::string(kNoiseFloorDescription) + " (restarts; the filter's weights until the estimate is trained)");
  return table;
}

void KalmanObserverParams::validate() const { kalman_observer_param_table().check_ranges(*this); }

void SuperTwistingParams::validate() const { super_twisting_param_table().check_ranges(*this); }

void LinearObserverParams::validate() const { linear_observer_param_table().check_ranges(*this); }

}  // namespace robodds::range_rate_observer
