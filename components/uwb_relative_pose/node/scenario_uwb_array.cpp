#include "components/uwb_relative_pose/node/scenario_uwb_array.hpp"

#include <sstream>
#include <stdexcept>

#include "common/model/uwb_array_params.hpp"
#include "runtime/params.hpp"

namespace robodds::uwb {
namespace {

std::string to_text(const model::UwbArray& array) {
  std::ostringstream out;
  out << "[";
  for (std::size_t k = 0; k < array.nodes_m.size(); ++k) {
    out << (k == 0 ? "" : ", ") << "[" << array.nodes_m[k].x() << ", " << array.nodes_m[k].y() << "]";
  }
  out << "]";
  return out.str();
}

bool same(const model::UwbArray& a, const model::UwbArray& b) {
  if (a.nodes_m.size() != b.nodes_m.size()) {
    return false;
  }
  for (std::size_t k = 0; k < a.nodes_m.size(); ++k) {
    if ((a.nodes_m[k] - b.nodes_m[k]).norm() > 1e-9) {
      return false;
    }
  }
  return true;
}

}  // namespace

std::optional<std::string> scenario_array_mismatch(const Scenario& scenario, const model::UwbArray& estimator_array) {
  for (const ComponentSpec& spec : scenario.components) {
    if (spec.type != "uwb_sensor") {
      continue;
    }
    // The sensor's own keys over the defaults both share (model::UwbArrayParams).
    ParamReader overrides(spec.name, spec.overrides);
    model::UwbArrayParams sensor;
    if (overrides.has("array_side_m")) {
      sensor.array_side_m = overrides.get_double("array_side_m");
    }
    if (overrides.has("nodes_m")) {
      sensor.nodes_m = overrides.get_point_list("nodes_m");
    }
    model::UwbArray sensor_array;
    try {
      sensor_array = sensor.array();
    } catch (const std::exception&) {
      continue;  // a bad sensor array: the sensor's own start-up check names it
    }
    if (!same(sensor_array, estimator_array)) {
      return "the estimator's array " + to_text(estimator_array) + " is not the array of the scenario's UWB sensor '" +
             spec.name + "' " + to_text(sensor_array) + " (set the same array_side_m / nodes_m on both)";
    }
  }
  return std::nullopt;
}

}  // namespace robodds::uwb
