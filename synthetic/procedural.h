#pragma once
// Deterministic procedural helpers for the synthetic scene: integer hashing, a portable
// random generator, value noise and colour arithmetic. Everything here gives bit-identical
// results on every platform for the same inputs (no std::*_distribution).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>

namespace reenact::capture {

// Colours are sRGB in [0, 1], (r, g, b).
using Color = Eigen::Vector3d;

// SplitMix64 finaliser: a well-mixed 64-bit hash of x.
uint64_t Mix64(uint64_t x);

// A hash of integer lattice coordinates and a seed, mapped to [0, 1).
double HashUnit(int64_t x, int64_t y, int64_t z, uint64_t seed);

// Smooth value noise in [0, 1] with unit lattice spacing (C1 continuous).
double ValueNoise(const Eigen::Vector3d& p, uint64_t seed);
double ValueNoise(double x, double y, uint64_t seed);

// Sum of `octaves` value-noise layers, each at twice the frequency and half the amplitude,
// normalised back to [0, 1].
double Fbm(double x, double y, int octaves, uint64_t seed);

// Portable pseudo-random generator (SplitMix64 stream).
class Random {
 public:
  explicit Random(uint64_t seed) : state_(seed) {}
  uint64_t Next();
  double Uniform();                      // [0, 1)
  double Uniform(double lo, double hi);  // [lo, hi)
  int UniformInt(int lo, int hi);        // [lo, hi]
  double Normal();                       // standard normal (Box-Muller)

 private:
  uint64_t state_;
};

double SmoothStep(double edge0, double edge1, double x);
// Fractional part in [0, 1).
double Fract(double x);
inline Color Mix(const Color& a, const Color& b, double t) { return a + t * (b - a); }
// Colour from 8-bit sRGB components.
inline Color Rgb(int r, int g, int b) { return Color(r, g, b) / 255.0; }

}  // namespace reenact::capture
