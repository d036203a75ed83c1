#include "common/filter/one_euro_filter.h"

#include <cmath>
#include <numbers>

#include "common/error/check.h"

namespace reenact {

void OneEuroOptions::Check() const {
  REENACT_CHECK(std::isfinite(min_cutoff_hz) && min_cutoff_hz > 0, "min_cutoff_hz must be > 0");
  REENACT_CHECK(std::isfinite(beta) && beta >= 0, "beta must be >= 0");
  REENACT_CHECK(std::isfinite(derivative_cutoff_hz) && derivative_cutoff_hz > 0,
                "derivative_cutoff_hz must be > 0");
}

double OneEuroAlpha(double cutoff_hz, double dt_s) {
  REENACT_CHECK(cutoff_hz > 0 && dt_s > 0, "alpha needs a positive cutoff and interval");
  const double tau = 1.0 / (2.0 * std::numbers::pi * cutoff_hz);
  return 1.0 / (1.0 + tau / dt_s);
}

OneEuroFilter3::OneEuroFilter3(const OneEuroOptions& options)
    : options_(options), cutoff_hz_(options.min_cutoff_hz) {
  options_.Check();
}

Eigen::Vector3d OneEuroFilter3::Filter(const Eigen::Vector3d& x, double t_s) {
  REENACT_CHECK(x.allFinite() && std::isfinite(t_s), "the One Euro filter needs finite samples");
  if (!initialised_) {
    initialised_ = true;
    t_prev_ = t_s;
    x_prev_ = x_hat_ = x;
    dx_hat_.setZero();
    cutoff_hz_ = options_.min_cutoff_hz;
    return x_hat_;
  }
  const double dt = t_s - t_prev_;
  if (!(dt > 0)) return x_hat_;
  const Eigen::Vector3d dx = (x - x_prev_) / dt;
  dx_hat_ += OneEuroAlpha(options_.derivative_cutoff_hz, dt) * (dx - dx_hat_);
  cutoff_hz_ = options_.min_cutoff_hz + options_.beta * dx_hat_.norm();
  x_hat_ += OneEuroAlpha(cutoff_hz_, dt) * (x - x_hat_);
  x_prev_ = x;
  t_prev_ = t_s;
  return x_hat_;
}

}  // namespace reenact
