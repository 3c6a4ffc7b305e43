#include "components/uwb_relative_pose/uwb_array.hpp"

#include "common/param_checks.hpp"

namespace robodds::uwb {

UwbArray square_array(double side_m) {
  param_checks::require_positive("side_m", side_m);
  const double h = 0.5 * side_m;
  return UwbArray{{{h, h}, {-h, h}, {-h, -h}, {h, -h}}};
}

}  // namespace robodds::uwb
