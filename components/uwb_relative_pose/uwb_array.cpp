#include "components/uwb_relative_pose/uwb_array.hpp"

#include <string>

#include "common/number_text.hpp"
#include "common/param_checks.hpp"

namespace robodds::uwb {

UwbArray square_array(double side_m) {
  param_checks::require_positive("side_m", side_m);
  const double h = 0.5 * side_m;
  return UwbArray{{{h, h}, {-h, h}, {-h, -h}, {h, -h}}};
}

void validate_array(const UwbArray& array, std::string_view key) {
  const auto& nodes = array.nodes_m;
  if (nodes.size() < 3) {
    param_checks::reject(key, "needs at least 3 nodes", std::to_string(nodes.size()) + " nodes");
  }
  const auto text = [](const Eigen::Vector2d& p) { return "[" + shortest_text(p.x()) + ", " + shortest_text(p.y()) + "]"; };
  for (std::size_t a = 0; a < nodes.size(); ++a) {
    if (!nodes[a].allFinite()) {
      param_checks::reject(key, "node " + std::to_string(a) + " must be finite", text(nodes[a]));
    }
    for (std::size_t b = 0; b < a; ++b) {
      if ((nodes[a] - nodes[b]).norm() < kMinNodeSeparationM) {
        param_checks::reject(key, "nodes " + std::to_string(b) + " and " + std::to_string(a) + " coincide (closer than 1 mm)",
                             text(nodes[b]) + " and " + text(nodes[a]));
      }
    }
  }
}

}  // namespace robodds::uwb
