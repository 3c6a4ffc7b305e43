#include "components/pf_estimator/heading_track_check.hpp"

#include <algorithm>
#include <cmath>

#include "common/angle.hpp"
#include "common/model/diff_drive_kinematics.hpp"

namespace robodds::pf_estimator {

HeadingTrackCheck::HeadingTrackCheck(std::size_t window_fixes, double sigmas, double max_std_rad,
                                     double max_difference_rad)
    : capacity_(window_fixes), sigmas_(sigmas), max_std_rad_(max_std_rad), max_difference_rad_(max_difference_rad) {
  samples_.resize(capacity_);
}

void HeadingTrackCheck::reset() {
  count_ = 0;
  dr_x_ = dr_y_ = dr_theta_ = 0.0;
  pending_ds_ = pending_dtheta_ = pending_dvar_ = slip_radpm_ = slip_std_radpm_ = 0.0;
  track_theta_rad_ = track_theta_std_rad_ = difference_rad_ = 0.0;
}

void HeadingTrackCheck::predict(double v_mps, double omega_radps, double dt_s, double omega_var_radps2) {
  if (!enabled()) {
    return;
  }
  const model::Pose2 moved = model::integrate_exact({dr_x_, dr_y_, dr_theta_}, {v_mps, omega_radps}, dt_s);
  dr_x_ = moved.x;
  dr_y_ = moved.y;
  dr_theta_ = moved.theta;
  pending_ds_ += v_mps * dt_s;
  pending_dtheta_ += omega_radps * dt_s;
  pending_dvar_ += std::max(0.0, omega_var_radps2) * dt_s * dt_s;
}

void HeadingTrackCheck::add_fix(double x_m, double y_m) {
  if (!enabled()) {
    return;
  }
  samples_[count_ % capacity_] = {x_m, y_m, dr_x_, dr_y_, pending_ds_, pending_dtheta_, pending_dvar_};
  pending_ds_ = pending_dtheta_ = pending_dvar_ = 0.0;
  ++count_;
}

HeadingTrackCheck::Verdict HeadingTrackCheck::verdict(double track_theta_rad, double track_var, double cloud_theta_rad,
                                                      double cloud_theta_var_rad2) {
  track_theta_rad_ = wrap_angle(track_theta_rad);
  track_theta_std_rad_ = std::sqrt(std::max(0.0, track_var));
  difference_rad_ = wrap_angle(cloud_theta_rad - track_theta_rad_);
  if (!(track_theta_std_rad_ <= max_std_rad_)) {
    return Verdict::kPending;
  }
  double bound = sigmas_ * std::sqrt(track_theta_std_rad_ * track_theta_std_rad_ + std::max(0.0, cloud_theta_var_rad2));
  if (max_difference_rad_ > 0.0) {
    bound = std::min(bound, max_difference_rad_);
  }
  return std::abs(difference_rad_) <= bound ? Verdict::kConsistent : Verdict::kContradicted;
}

HeadingTrackCheck::Verdict HeadingTrackCheck::check(double cloud_theta_rad, double cloud_theta_var_rad2) {
  if (!enabled()) {
    return Verdict::kConsistent;
  }
  const std::size_t n = std::min(count_, capacity_);
  if (n < kMinFixes) {
    return Verdict::kPending;
  }
  double fx = 0.0, fy = 0.0, dx = 0.0, dy = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    fx += samples_[i].fix_x;
    fy += samples_[i].fix_y;
    dx += samples_[i].dr_x;
    dy += samples_[i].dr_y;
  }
  const double count = static_cast<double>(n);
  fx /= count;
  fy /= count;
  dx /= count;
  dy /= count;
  // Rotation phi minimising sum |f_k - R(phi) d_k|^2 of the centred sets: atan2(sum d x f, sum d . f).
  double dot = 0.0, cross = 0.0, spread = 0.0, fix_spread = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double ax = samples_[i].dr_x - dx, ay = samples_[i].dr_y - dy;
    const double bx = samples_[i].fix_x - fx, by = samples_[i].fix_y - fy;
    dot += ax * bx + ay * by;
    cross += ax * by - ay * bx;
    spread += ax * ax + ay * ay;
    fix_spread += bx * bx + by * by;
  }
  if (!(spread > 0.0)) {
    return Verdict::kPending;
  }
  const double phi = std::atan2(cross, dot);
  // Residual sum at the fit: sum |b|^2 + sum |a|^2 - 2 (dot cos phi + cross sin phi) = ... - 2 hypot.
  const double residual = std::max(0.0, fix_spread + spread - 2.0 * std::hypot(dot, cross));
  const double noise_var = residual / std::max(1.0, 2.0 * count - 3.0);  // per axis; 3 fitted: phi, shift
  return verdict(phi + dr_theta_, noise_var / spread, cloud_theta_rad, cloud_theta_var_rad2);
}

namespace {

/// The window's track dead-reckoned with turn slip k from its first fix (origin, heading 0): positions
/// p, their derivative J = dp/dk, heading now (with the motion after the last fix) and its dk derivative.
struct SlipTrack {
  std::vector<double> px, py, jx, jy;
  double theta_now = 0.0;
  double distance_now = 0.0;  // m, signed, from the first fix to now
};

}  // namespace

HeadingTrackCheck::Verdict HeadingTrackCheck::check_drifting(double cloud_theta_rad, double cloud_theta_var_rad2) {
  if (!enabled()) {
    return Verdict::kConsistent;
  }
  const std::size_t n = std::min(count_, capacity_);
  if (n < kMinFixes) {
    return Verdict::kPending;
  }
  const std::size_t first = count_ - n;  // oldest sample in the ring
  const auto at = [&](std::size_t i) -> const Sample& { return samples_[(first + i) % capacity_]; };
  const double count = static_cast<double>(n);
  double fx = 0.0, fy = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    fx += at(i).fix_x;
    fy += at(i).fix_y;
  }
  fx /= count;
  fy /= count;
  SlipTrack track;
  track.px.resize(n);
  track.py.resize(n);
  track.jx.resize(n);
  track.jy.resize(n);
  const auto integrate = [&](double k) {
    // Each interval between fixes as one arc (midpoint heading): 0.1 s at 10 Hz.
    double x = 0.0, y = 0.0, theta = 0.0, s = 0.0, jx = 0.0, jy = 0.0;
    track.px[0] = track.py[0] = track.jx[0] = track.jy[0] = 0.0;
    for (std::size_t i = 1; i < n; ++i) {
      const Sample& step = at(i);
      const double theta_mid = theta + 0.5 * (step.dtheta - k * step.ds);
      const double dtheta_mid_dk = -(s + 0.5 * step.ds);
      x += step.ds * std::cos(theta_mid);
      y += step.ds * std::sin(theta_mid);
      jx += -step.ds * std::sin(theta_mid) * dtheta_mid_dk;
      jy += step.ds * std::cos(theta_mid) * dtheta_mid_dk;
      theta += step.dtheta - k * step.ds;
      s += step.ds;
      track.px[i] = x;
      track.py[i] = y;
      track.jx[i] = jx;
      track.jy[i] = jy;
    }
    track.theta_now = theta + pending_dtheta_ - k * pending_ds_;
    track.distance_now = s + pending_ds_;
  };
  double k = 0.0, phi = 0.0;
  double gg = 0.0, gh = 0.0, hh = 0.0, gr = 0.0, hr = 0.0, rr = 0.0;
  bool solved = false;
  for (int iteration = 0; iteration < 5; ++iteration) {
    integrate(k);
    double dx = 0.0, dy = 0.0, jxm = 0.0, jym = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      dx += track.px[i];
      dy += track.py[i];
      jxm += track.jx[i];
      jym += track.jy[i];
    }
    dx /= count;
    dy /= count;
    jxm /= count;
    jym /= count;
    double dot = 0.0, cross = 0.0, spread = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double ax = track.px[i] - dx, ay = track.py[i] - dy;
      const double bx = at(i).fix_x - fx, by = at(i).fix_y - fy;
      dot += ax * bx + ay * by;
      cross += ax * by - ay * bx;
      spread += ax * ax + ay * ay;
    }
    if (!(spread > 0.0)) {
      return Verdict::kPending;
    }
    phi = std::atan2(cross, dot);  // the best rotation for this k
    const double c = std::cos(phi), sn = std::sin(phi);
    gg = gh = hh = gr = hr = rr = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double ax = track.px[i] - dx, ay = track.py[i] - dy;
      const double jx = track.jx[i] - jxm, jy = track.jy[i] - jym;
      const double gx = -c * ay - sn * ax, gy = -sn * ay + c * ax;  // d/dphi: R(phi) (-ay, ax)
      const double hx = c * jx - sn * jy, hy = sn * jx + c * jy;    // d/dk: R(phi) (J - J_mean)
      const double rx = at(i).fix_x - fx - (c * ax - sn * ay);
      const double ry = at(i).fix_y - fy - (sn * ax + c * ay);
      gg += gx * gx + gy * gy;
      gh += gx * hx + gy * hy;
      hh += hx * hx + hy * hy;
      gr += gx * rx + gy * ry;
      hr += hx * rx + hy * ry;
      rr += rx * rx + ry * ry;
    }
    const double det = gg * hh - gh * gh;
    if (!(det > 0.0)) {
      return Verdict::kPending;
    }
    const double dk = (gg * hr - gh * gr) / det;
    solved = true;
    if (std::abs(dk) < 1e-6) {
      break;
    }
    k += dk;
  }
  if (!solved) {
    return Verdict::kPending;
  }
  // Covariance of (phi, k) from the last linearisation; the heading now is phi + theta_now(k):
  // gradient (1, -distance_now).
  const double det = gg * hh - gh * gh;
  const double noise_var = std::max(0.0, rr) / std::max(1.0, 2.0 * count - 4.0);  // 4 fitted: phi, k, shift
  const double var_phi = noise_var * hh / det, var_k = noise_var * gg / det, cov = -noise_var * gh / det;
  const double lever = track.distance_now;
  double track_var = var_phi - 2.0 * lever * cov + lever * lever * var_k;
  // The odometry's turn-rate noise since the window's fixes, on average over them.
  double since = pending_dvar_, mean_since = 0.0;
  for (std::size_t i = n; i-- > 0;) {
    mean_since += since;
    since += at(i).dvar;
  }
  track_var += mean_since / count;
  slip_radpm_ = k;
  slip_std_radpm_ = std::sqrt(std::max(0.0, var_k));
  return verdict(phi + track.theta_now, track_var, cloud_theta_rad, cloud_theta_var_rad2);
}

double HeadingTrackCheck::slip_std_with_prior_radpm(double prior_std_radpm) const {
  if (!(prior_std_radpm > 0.0)) {
    return slip_std_radpm_;
  }
  if (!(slip_std_radpm_ > 0.0)) {
    return 0.0;
  }
  const double precision = 1.0 / (slip_std_radpm_ * slip_std_radpm_) + 1.0 / (prior_std_radpm * prior_std_radpm);
  return 1.0 / std::sqrt(precision);
}

}  // namespace robodds::pf_estimator
