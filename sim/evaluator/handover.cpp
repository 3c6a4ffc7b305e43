#include "sim/evaluator/handover.hpp"

namespace robodds::evaluator {

void GapTracker::observe(double t_s) {
  if (t_s < after_s_ || (samples_ > 0 && t_s < last_s_)) {
    return;
  }
  if (samples_ > 0 && t_s - last_s_ > longest_.length_s) {
    longest_ = Gap{t_s - last_s_, last_s_, t_s};
  }
  last_s_ = t_s;
  ++samples_;
}

}  // namespace robodds::evaluator
