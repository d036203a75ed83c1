#pragma once
// The One Euro filter (Casiez, Roussel, Vogel, CHI 2012): a first-order low-pass whose cutoff
// rises with the signal's speed, so slow motion is smoothed hard (little jitter) and fast
// motion is followed closely (little lag).
//
// For samples x_n at times t_n (seconds), dt = t_n - t_{n-1}:
//   alpha(f) = 1 / (1 + tau / dt),  tau = 1 / (2 pi f)           (f in Hz)
//   dx_n     = (x_n - x_{n-1}) / dt                                (raw derivative, units/s)
//   dx^_n    = dx^_{n-1} + alpha(derivative_cutoff_hz) (dx_n - dx^_{n-1})
//   f_n      = min_cutoff_hz + beta * |dx^_n|                      (|.|: Euclidean norm)
//   x^_n     = x^_{n-1} + alpha(f_n) (x_n - x^_{n-1})
// With beta = 0 it is the exponential smoother of time constant tau = 1 / (2 pi min_cutoff):
// a step decays by (1 - alpha)^n, about exp(-t / tau) for dt << tau; a ramp of speed v
// settles to a lag of exactly v tau; white noise of deviation sigma leaves deviation
// sigma sqrt(alpha / (2 - alpha)).
//
// Degenerate inputs: the first sample (and the first after Reset) passes unchanged with
// derivative 0; a sample whose dt is zero or negative is ignored and the previous output
// returned. Values and times must be finite (CHECK).

#include <Eigen/Core>

namespace reenact {

struct OneEuroOptions {
  double min_cutoff_hz = 1.0;         // cutoff at rest, Hz, > 0
  double beta = 0.0;                  // cutoff growth per unit of speed, Hz per (unit/s), >= 0
  double derivative_cutoff_hz = 1.0;  // cutoff of the derivative's low-pass, Hz, > 0

  // Throws CheckError when a field is out of range or not finite.
  void Check() const;
};

// The smoothing factor alpha(f) for a sample interval dt (seconds, > 0) and cutoff f (Hz).
double OneEuroAlpha(double cutoff_hz, double dt_s);

// Filters a signal in R^3 (a joint trajectory, metres; speed in m/s, so beta is in
// Hz per m/s).
class OneEuroFilter3 {
 public:
  explicit OneEuroFilter3(const OneEuroOptions& options = {});

  // The filtered value for sample x at time t_s (seconds).
  Eigen::Vector3d Filter(const Eigen::Vector3d& x, double t_s);

  // Forgets the history: the next sample passes unchanged.
  void Reset() { initialised_ = false; }
  bool initialised() const { return initialised_; }
  // The current cutoff (Hz) after the last sample; min_cutoff_hz before any.
  double cutoff_hz() const { return cutoff_hz_; }

 private:
  OneEuroOptions options_;
  bool initialised_ = false;
  double t_prev_ = 0;
  Eigen::Vector3d x_prev_ = Eigen::Vector3d::Zero();  // raw
  Eigen::Vector3d x_hat_ = Eigen::Vector3d::Zero();   // filtered
  Eigen::Vector3d dx_hat_ = Eigen::Vector3d::Zero();  // filtered derivative
  double cutoff_hz_ = 0;
};

}  // namespace reenact
