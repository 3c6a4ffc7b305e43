#include "components/circumnavigation_controller/node/circumnavigation_controller_params.hpp"

#include <stdexcept>

namespace robodds::circumnavigation_controller {

ObserverTopic observer_topic_from_string(std::string_view text) {
  if (text == "observer/range_rate") {
    return ObserverTopic::kSuperTwisting;
  }
  if (text == "observer/range_rate_linear") {
    return ObserverTopic::kLinear;
  }
  if (text == "observer/range_rate_kf") {
    return ObserverTopic::kKalman;
  }
  throw std::invalid_argument(
      "observer_topic: must be \"observer/range_rate\", \"observer/range_rate_linear\" or \"observer/range_rate_kf\" (got \"" +
      std::string(text) + "\")");
}

std::string to_string(ObserverTopic topic) {
  switch (topic) {
    case ObserverTopic::kLinear:
      return "observer/range_rate_linear";
    case ObserverTopic::kKalman:
      return "observer/range_rate_kf";
    case ObserverTopic::kSuperTwisting:
      break;
  }
  return "observer/range_rate";
}

const params::ParamTable<CircumnavigationControllerParams>& circumnavigation_controller_param_table() {
  using P = CircumnavigationControllerParams;
  static const params::ParamTable<P> table =
      params::ParamTable<P>(
          "Circumnavigation guidance of paper 2 (issue 10): observed range and range rate + the team's poses ->\n"
          "plant/cmd. The orbit radius and the team come from mission/target. At start-up V_max omega_max <= b\n"
          "is checked against the b of the scenario's range_rate_observer (README.md).")
          .add("rate_hz", &P::rate_hz, "Hz", params::positive(), "control rate; must divide the simulation rate")
          .include(&P::guidance, guidance_param_table())
          .add_enum("observer_topic", &P::observer_topic, observer_topic_from_string, to_string,
                    {"observer/range_rate", "observer/range_rate_linear", "observer/range_rate_kf"},
                    "range-rate estimate used: super-twisting (the paper's), the linear baseline or the Kalman filter (issue 28)")
          .add("estimate_timeout_s", &P::estimate_timeout_s, "s", params::positive(),
               "real time only: an observer estimate received longer ago than this stops the robot; > the control period")
          .add("peer_timeout_s", &P::peer_timeout_s, "s", params::positive(),
               "real time only: a team mate whose pose was received longer ago than this drops out of the spacing")
          .include_as("gap_hold", &P::gap_hold, model::hold_param_table(),
                      "a steering robot whose estimate is briefly unusable (restart window, target switch) keeps its "
                      "last curvature at a reduced speed for at most hold_s, then stops (issue 27)");
  return table;
}

}  // namespace robodds::circumnavigation_controller
