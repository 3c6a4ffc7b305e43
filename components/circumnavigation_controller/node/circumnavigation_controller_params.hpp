#pragma once
// Every parameter of the circumnavigation_controller component: the law's (GuidanceParams) plus
// the node's own. config/circumnavigation_controller.params.yaml is generated from the table.

#include <string>
#include <string_view>

#include "common/param_table.hpp"
#include "common/model/estimate_gap_hold.hpp"
#include "components/circumnavigation_controller/guidance_params.hpp"

namespace robodds::circumnavigation_controller {

/// Which range-rate estimate the law uses: the super-twisting observer's (the paper's), the
/// linear baseline's or the Kalman filter's (issue 28).
enum class ObserverTopic { kSuperTwisting, kLinear, kKalman };

/// "observer/range_rate" / "observer/range_rate_linear" / "observer/range_rate_kf"; throws std::invalid_argument
/// ("observer_topic: ...") otherwise.
ObserverTopic observer_topic_from_string(std::string_view text);
std::string to_string(ObserverTopic topic);

// Units, ranges and one-line descriptions of these fields: circumnavigation_controller_param_table()
// (the one source; `robodds components --params circumnavigation_controller` prints it).
// Defaults: the member initialisers.
struct CircumnavigationControllerParams {
  double rate_hz = 50.0;
  GuidanceParams guidance;
  ObserverTopic observer_topic = ObserverTopic::kSuperTwisting;
  double estimate_timeout_s = 0.5;
  double peer_timeout_s = 1.0;
  model::HoldParams gap_hold;
};

const params::ParamTable<CircumnavigationControllerParams>& circumnavigation_controller_param_table();

}  // namespace robodds::circumnavigation_controller
