#pragma once
// The estimator must model the array the sensor measures with: a different side or labelling
// biases every estimate without raising the cost. When the scenario simulates the sensor
// (components of type uwb_sensor), their arrays are compared with the estimator's at start-up.
#include <optional>
#include <string>

#include "common/model/uwb_array.hpp"
#include "runtime/scenario.hpp"

namespace robodds::uwb {

/// Why `estimator_array` differs from the array of a uwb_sensor component of `scenario` (naming
/// that component and both arrays), or nullopt when none differs (or the scenario has none).
std::optional<std::string> scenario_array_mismatch(const Scenario& scenario, const model::UwbArray& estimator_array);

}  // namespace robodds::uwb
