#include "sim/evaluator/metrics/circumnavigation/circumnavigation_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/angle.hpp"
#include "common/number_text.hpp"

namespace robodds::evaluator {

using namespace circumnavigation;

namespace {

constexpr double kTwoPi = 2.0 * kPi;
constexpr double kDegPerRad = 180.0 / kPi;

bool same_assignment(const TargetAssignmentInfo& a, const TargetAssignmentInfo& b) {
  if (a.active != b.active) {
    return false;
  }
  return !a.active || (a.target_id == b.target_id && a.target_x == b.target_x && a.target_y == b.target_y &&
                       a.desired_radius == b.desired_radius);
}

}  // namespace

const char* observer_kind_name(ObserverKind kind) {
  switch (kind) {
    case ObserverKind::kSta:
      return "sta";
    case ObserverKind::kLinear:
      return "linear";
    case ObserverKind::kKalman:
      break;
  }
  return "kalman";
}

RangeDerivatives range_derivatives(double x, double y, double theta, double v, double omega, double v_dot,
                                   double target_x, double target_y) {
  RangeDerivatives d;
  const double dx = x - target_x;
  const double dy = y - target_y;
  d.r = std::hypot(dx, dy);
  if (d.r <= 0.0) {
    return d;  // on the target: the range has no direction
  }
  const double ux = dx / d.r;
  const double uy = dy / d.r;
  const double c = std::cos(theta);
  const double s = std::sin(theta);
  d.rdot = v * (ux * c + uy * s);
  const double ax = v_dot * c - v * omega * s;
  const double ay = v_dot * s + v * omega * c;
  d.rddot = (v * v - d.rdot * d.rdot) / d.r + ux * ax + uy * ay;
  return d;
}

std::optional<double> SquareSum::rms() const {
  if (count == 0) {
    return std::nullopt;
  }
  return std::sqrt(sum_squares / static_cast<double>(count));
}

void TailSum::add(std::uint64_t step, double error) {
  if (step + window_steps_ <= newest_) {
    return;  // older than the window of a newer step
  }
  if (steps_.empty() || step > steps_.back().first) {
    steps_.emplace_back(step, SquareSum{});
    steps_.back().second.add(error);
  } else if (step == steps_.back().first) {
    steps_.back().second.add(error);
  } else {  // a step already there or between (estimates of several robots, out of order)
    auto it = std::lower_bound(steps_.begin(), steps_.end(), step,
                               [](const auto& entry, std::uint64_t s) { return entry.first < s; });
    if (it == steps_.end() || it->first != step) {
      it = steps_.emplace(it, step, SquareSum{});
    }
    it->second.add(error);
  }
  if (step > newest_) {
    newest_ = step;
    while (!steps_.empty() && steps_.front().first + window_steps_ <= newest_) {
      steps_.pop_front();
    }
  }
}

SquareSum TailSum::over_window_ending(std::uint64_t end_step) const {
  SquareSum sum;
  for (const auto& [step, s] : steps_) {
    if (step + window_steps_ > end_step && step <= end_step) {
      sum.add(s);
    }
  }
  return sum;
}

CircumnavigationMetrics::CircumnavigationMetrics(double step_s, double b) : step_s_(step_s), b_(b) {}

std::uint64_t CircumnavigationMetrics::steps(double seconds) const {
  return static_cast<std::uint64_t>(std::llround(seconds / step_s_));
}

void CircumnavigationMetrics::add_truth(std::uint32_t robot, const PlantSample& sample) {
  Robot& r = robots_[robot];
  if ((any_closed_ && sample.step <= closed_through_) || (!r.truth.empty() && sample.step <= r.truth.back().s.step)) {
    return;  // too late (its step is evaluated) or out of order
  }
  r.truth.push_back(TruthEntry{sample});
}

void CircumnavigationMetrics::add_assignment(std::uint32_t robot, std::uint64_t step,
                                             const TargetAssignmentInfo& assignment) {
  if (assignment.active) {
    targets_[assignment.target_id] = {assignment.target_x, assignment.target_y};
  }
  Robot& r = robots_[robot];
  const bool had = !r.assignments.empty();
  if (had && same_assignment(r.assignments.back().second, assignment)) {
    return;  // republished, nothing changed
  }
  auto at = std::upper_bound(r.assignments.begin(), r.assignments.end(), step,
                             [](std::uint64_t s, const auto& entry) { return s < entry.first; });
  r.assignments.insert(at, {step, assignment});
  if (boundaries_.empty() || had) {
    auto b = std::lower_bound(boundaries_.begin(), boundaries_.end(), step);
    if (b == boundaries_.end() || *b != step) {
      boundaries_.insert(b, step);
    }
  }
}

void CircumnavigationMetrics::add_estimate(ObserverKind kind, std::uint32_t robot, const RateEstimateSample& estimate) {
  robots_[robot].streams[static_cast<std::size_t>(kind)].pending.push_back(estimate);
}

const TargetAssignmentInfo* CircumnavigationMetrics::assignment_at(const Robot& robot, std::uint64_t step) const {
  auto it = std::upper_bound(robot.assignments.begin(), robot.assignments.end(), step,
                             [](std::uint64_t s, const auto& entry) { return s < entry.first; });
  return it == robot.assignments.begin() ? nullptr : &std::prev(it)->second;
}

std::size_t CircumnavigationMetrics::phase_of(std::uint64_t step) const {
  return static_cast<std::size_t>(std::upper_bound(boundaries_.begin(), boundaries_.end(), step) - boundaries_.begin());
}

CircumnavigationMetrics::Phase& CircumnavigationMetrics::phase(std::size_t index) {
  const std::uint64_t window = steps(kTailWindowS);
  while (phases_.size() < index) {
    Phase p{boundaries_[phases_.size()], 0, false, false, 0, TailSum(window), TailSum(window),
            std::vector<TailSum>(kObserverKinds, TailSum(window))};
    phases_.push_back(std::move(p));
  }
  return phases_[index - 1];
}

bool CircumnavigationMetrics::close_next(bool all) {
  std::uint64_t step = std::numeric_limits<std::uint64_t>::max();
  std::uint64_t newest = 0;
  bool any = false;
  for (const auto& [id, r] : robots_) {
    if (r.truth.empty()) {
      continue;
    }
    newest = std::max(newest, r.truth.back().s.step);
    if (r.closed < r.truth.size()) {
      step = std::min(step, r.truth[r.closed].s.step);
      any = true;
    }
  }
  if (!any) {
    return false;
  }
  if (!all) {
    for (const auto& [id, r] : robots_) {
      // A robot whose truth stopped more than the capacity ago no longer holds the others back.
      if (!r.truth.empty() && r.truth.back().s.step <= step && r.truth.back().s.step + kTruthCapacity > newest) {
        return false;  // its sample of `step` may still come
      }
    }
  }
  close_step(step);
  return true;
}

void CircumnavigationMetrics::close_step(std::uint64_t step) {
  const std::size_t p = phase_of(step);
  std::map<std::uint32_t, std::vector<double>> teams;  // target id -> angles of its members
  std::map<std::uint32_t, bool> incomplete;            // a member has no truth at this step
  std::vector<double> radius_errors;
  for (auto& [id, r] : robots_) {
    const TargetAssignmentInfo* a = assignment_at(r, step);
    const bool active = a != nullptr && a->active;
    TruthEntry* entry = r.closed < r.truth.size() && r.truth[r.closed].s.step == step ? &r.truth[r.closed] : nullptr;
    if (entry == nullptr) {
      if (active) {
        incomplete[a->target_id] = true;
      }
      continue;
    }
    entry->closed = true;
    ++r.closed;
    entry->active = active;
    entry->phase = p;
    const PlantSample& s = entry->s;
    const bool had_previous = r.has_previous;
    const double v_dot = had_previous ? (s.v - r.previous_v) / (static_cast<double>(step - r.previous_step) * step_s_) : 0.0;
    r.has_previous = true;
    r.previous_step = step;
    r.previous_v = s.v;
    if (!active) {
      continue;
    }
    const RangeDerivatives d = range_derivatives(s.x, s.y, s.theta, s.v, s.omega, v_dot, a->target_x, a->target_y);
    if (had_previous) {
      ++accel_samples_;
      entry->over_b = std::abs(d.rddot) > b_;
      accel_over_b_ += entry->over_b ? 1 : 0;
    }
    radius_errors.push_back(d.r - a->desired_radius);
    teams[a->target_id].push_back(std::atan2(s.y - a->target_y, s.x - a->target_x));
  }
  any_closed_ = true;
  closed_through_ = step;
  if (p == 0 || (radius_errors.empty() && incomplete.empty())) {
    return;  // before the first assignment, or nobody active
  }
  Phase& ph = phase(p);
  ph.any = true;
  ph.last_step = step;
  bool ok = true;
  for (double e : radius_errors) {
    ph.radius.add(step, e);
    ok = ok && std::abs(e) <= kSettleRadiusTolM;
  }
  for (auto& [target, angles] : teams) {
    if (incomplete.count(target) != 0 || angles.size() < 2) {
      continue;
    }
    std::sort(angles.begin(), angles.end());
    const double even_deg = 360.0 / static_cast<double>(angles.size());
    for (std::size_t i = 0; i < angles.size(); ++i) {
      const double gap = i + 1 < angles.size() ? angles[i + 1] - angles[i] : angles[0] + kTwoPi - angles[i];
      const double e = gap * kDegPerRad - even_deg;
      ph.spacing.add(step, e);
      ok = ok && std::abs(e) <= kSettleGapTolDeg;
    }
  }
  if (!incomplete.empty()) {
    return;  // not every member is known at this step: it neither settles nor unsettles
  }
  if (!ok) {
    ph.settled = false;
  } else if (!ph.settled) {
    ph.settled = true;
    ph.settled_from = step;
  }
}

void CircumnavigationMetrics::handle(ObserverKind kind, Stream& stream, const RateEstimateSample& e,
                                     const TruthEntry* truth) {
  const auto k = static_cast<std::size_t>(kind);
  ObserverTotals& totals = totals_[k];
  if (!stream.any) {
    stream.any = true;
    stream.first_step = e.step;
    stream.start_step = e.step;
    stream.last_target = e.target_id;
  } else {
    if (e.restarted) {
      ++totals.restarts;
      stream.start_step = e.step;
      stream.restart_waiting = true;
      stream.restart_window = false;
    }
    if (e.target_id != stream.last_target) {
      stream.start_step = e.step;
      stream.last_target = e.target_id;
    }
  }
  if (truth == nullptr || !truth->active) {
    return;
  }
  auto target = targets_.find(e.target_id);
  if (target == targets_.end()) {
    return;
  }
  const PlantSample& s = truth->s;
  const double rdot =
      range_derivatives(s.x, s.y, s.theta, s.v, s.omega, 0.0, target->second.first, target->second.second).rdot;
  const double err = e.range_rate - rdot;
  if (!stream.consistency) {
    stream.consistency.emplace(step_s_);
  }
  stream.consistency->add_scalar(e.step, e.valid, err, e.range_rate_std * e.range_rate_std);
  if (!e.valid) {
    return;
  }
  ++totals.matched;
  const std::uint64_t since_start = e.step - stream.start_step;
  if (since_start >= steps(kTransientFromS) && since_start <= steps(kTransientToS)) {
    totals.transient.add(err);
  }
  if (truth->phase > 0) {
    phase(truth->phase).observer[k].add(e.step, err);
  }
  if (stream.restart_waiting) {
    stream.restart_waiting = false;
    stream.restart_window = true;
    stream.restart_from = e.step;
  }
  if (stream.restart_window) {
    if (e.step - stream.restart_from <= steps(kRestartWindowS)) {
      totals.max_after_restart = std::max(totals.max_after_restart.value_or(0.0), std::abs(err));
    } else {
      stream.restart_window = false;
    }
  }
  if (!stream.converged) {
    if (truth->over_b) {
      stream.any_over_b = true;
      stream.excused_until = e.step + steps(kBoundRecoveryS);
    }
    if (std::abs(err) <= kConvergenceTolMps) {
      if (!stream.run_open) {
        stream.run_open = true;
        stream.run_from = e.step;
      }
    } else if (stream.run_open && stream.any_over_b && e.step <= stream.excused_until &&
               e.step - stream.run_from >= steps(kConvergenceConfirmS)) {
      // Paper 2's convergence holds while |r''| <= b: an excursion where the truth broke the
      // bound (or shortly after) is excused once the error had held within the tolerance, so the
      // observer had converged; its transient from the start is never excused.
      ++stream.excused;
    } else {
      stream.run_open = false;
    }
    if (stream.run_open && e.step - stream.run_from >= steps(kConvergenceHoldS)) {
      stream.converged = true;
      stream.convergence_s = static_cast<double>(stream.run_from - stream.first_step) * step_s_;
    }
  }
}

void CircumnavigationMetrics::match(ObserverKind kind, Robot& robot) {
  Stream& stream = robot.streams[static_cast<std::size_t>(kind)];
  while (!stream.pending.empty()) {
    const RateEstimateSample e = stream.pending.front();
    if (!stream.any || e.step >= stream.floor) {
      if (!any_closed_ || closed_through_ < e.step) {
        return;  // its truth is not evaluated yet
      }
      auto it = std::lower_bound(robot.truth.begin(), robot.truth.end(), e.step,
                                 [](const TruthEntry& t, std::uint64_t s) { return t.s.step < s; });
      const TruthEntry* truth = it != robot.truth.end() && it->s.step == e.step && it->closed ? &*it : nullptr;
      handle(kind, stream, e, truth);
      stream.floor = e.step;
    }
    stream.pending.pop_front();
  }
}

void CircumnavigationMetrics::trim(Robot& robot) {
  std::uint64_t needed = std::numeric_limits<std::uint64_t>::max();
  for (std::size_t k = 0; k < kObserverKinds; ++k) {
    if (!expected_[k]) {
      continue;
    }
    const Stream& s = robot.streams[k];
    needed = std::min(needed, !s.pending.empty() ? std::min(s.pending.front().step, s.floor) : s.floor);
  }
  while (robot.closed > 0 && (robot.truth.front().s.step < needed || robot.truth.size() > kTruthCapacity)) {
    robot.truth.pop_front();
    --robot.closed;
  }
}

void CircumnavigationMetrics::update() {
  while (close_next(false)) {
  }
  for (auto& [id, r] : robots_) {
    for (std::size_t k = 0; k < kObserverKinds; ++k) {
      match(static_cast<ObserverKind>(k), r);
    }
    trim(r);
  }
}

void CircumnavigationMetrics::finish() {
  while (close_next(true)) {
  }
  update();
}

std::size_t CircumnavigationMetrics::kept_truth() const {
  std::size_t n = 0;
  for (const auto& [id, r] : robots_) {
    n += r.truth.size();
  }
  return n;
}

CircumnavigationSummary CircumnavigationMetrics::summary() const {
  CircumnavigationSummary out;
  SquareSum steady[kObserverKinds];
  for (const Phase& ph : phases_) {
    PhaseMetrics m;
    m.start_s = static_cast<double>(ph.start_step) * step_s_;
    if (ph.any) {
      m.evaluated = true;
      if (ph.settled) {
        m.settle_time_s = static_cast<double>(ph.settled_from - ph.start_step) * step_s_;
      }
      // The tail window's first step: (last - window, last], within the phase.
      const std::uint64_t window = steps(kTailWindowS);
      const std::uint64_t tail_from = std::max(ph.start_step, ph.last_step + 1 > window ? ph.last_step + 1 - window : 0);
      if (!ph.settled) {
        m.not_settled = "never settled (radius within " + shortest_text(kSettleRadiusTolM) + " m and every gap within " +
                        shortest_text(kSettleGapTolDeg) + " deg did not hold to the phase's end)";
      } else if (ph.settled_from > tail_from) {
        const double held_s = std::round(static_cast<double>(ph.last_step + 1 - ph.settled_from) * step_s_ * 10.0) / 10.0;
        m.not_settled = "settled only " + shortest_text(held_s) +
                        " s before the phase's end: its last " + shortest_text(kTailWindowS) + " s include the approach";
      } else {
        m.radius_rmse_m = ph.radius.over_window_ending(ph.last_step).rms();
        m.spacing_rmse_deg = ph.spacing.over_window_ending(ph.last_step).rms();
      }
      for (std::size_t k = 0; k < kObserverKinds; ++k) {
        steady[k].add(ph.observer[k].over_window_ending(ph.last_step));
      }
    }
    out.phases.push_back(m);
  }
  for (std::size_t k = 0; k < kObserverKinds; ++k) {
    ObserverMetrics& o = out.observers[k];
    const ObserverTotals& t = totals_[k];
    o.transient_rmse_mps = t.transient.rms();
    o.steady_rmse_mps = steady[k].rms();
    o.max_error_after_restart_mps = t.max_after_restart;
    o.restarts = t.restarts;
    o.matched = t.matched;
    bool any = false;
    bool all_converged = true;
    double worst = 0.0;
    for (const auto& [id, r] : robots_) {
      const Stream& s = r.streams[k];
      if (s.consistency) {
        o.consistency = pooled(o.consistency, s.consistency->stats());
      }
      if (!s.any) {
        continue;
      }
      any = true;
      all_converged = all_converged && s.converged;
      worst = std::max(worst, s.convergence_s);
      o.convergence_excused += s.excused;
    }
    o.convergence_s = any && all_converged ? worst : -1.0;
  }
  out.range_accel_samples = accel_samples_;
  if (accel_samples_ > 0) {
    out.range_accel_over_b_fraction = static_cast<double>(accel_over_b_) / static_cast<double>(accel_samples_);
  }
  return out;
}

}  // namespace robodds::evaluator
