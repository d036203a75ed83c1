#include "synthetic/procedural.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace reenact::capture {

uint64_t Mix64(uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

double HashUnit(int64_t x, int64_t y, int64_t z, uint64_t seed) {
  uint64_t h = Mix64(seed);
  h = Mix64(h ^ static_cast<uint64_t>(x));
  h = Mix64(h ^ static_cast<uint64_t>(y));
  h = Mix64(h ^ static_cast<uint64_t>(z));
  return static_cast<double>(h >> 11) * (1.0 / 9007199254740992.0);
}

namespace {
double Fade(double t) { return t * t * (3 - 2 * t); }
}  // namespace

double ValueNoise(const Eigen::Vector3d& p, uint64_t seed) {
  const double fx = std::floor(p.x()), fy = std::floor(p.y()), fz = std::floor(p.z());
  const int64_t x = static_cast<int64_t>(fx), y = static_cast<int64_t>(fy),
                z = static_cast<int64_t>(fz);
  const double tx = Fade(p.x() - fx), ty = Fade(p.y() - fy), tz = Fade(p.z() - fz);
  double c[2][2][2];
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      for (int k = 0; k < 2; ++k) c[i][j][k] = HashUnit(x + i, y + j, z + k, seed);
  auto lerp = [](double a, double b, double t) { return a + t * (b - a); };
  const double c00 = lerp(c[0][0][0], c[1][0][0], tx), c10 = lerp(c[0][1][0], c[1][1][0], tx);
  const double c01 = lerp(c[0][0][1], c[1][0][1], tx), c11 = lerp(c[0][1][1], c[1][1][1], tx);
  return lerp(lerp(c00, c10, ty), lerp(c01, c11, ty), tz);
}

double ValueNoise(double px, double py, uint64_t seed) {
  const double fx = std::floor(px), fy = std::floor(py);
  const int64_t x = static_cast<int64_t>(fx), y = static_cast<int64_t>(fy);
  const double tx = Fade(px - fx), ty = Fade(py - fy);
  const double a = HashUnit(x, y, 0, seed), b = HashUnit(x + 1, y, 0, seed);
  const double c = HashUnit(x, y + 1, 0, seed), d = HashUnit(x + 1, y + 1, 0, seed);
  const double top = a + tx * (b - a), bottom = c + tx * (d - c);
  return top + ty * (bottom - top);
}

double Fbm(double x, double y, int octaves, uint64_t seed) {
  double sum = 0, amplitude = 1, total = 0;
  for (int i = 0; i < octaves; ++i) {
    sum += amplitude * ValueNoise(x, y, seed + i);
    total += amplitude;
    x *= 2.03;
    y *= 2.03;
    amplitude *= 0.5;
  }
  return sum / total;
}

uint64_t Random::Next() {
  state_ += 0x9e3779b97f4a7c15ULL;
  return Mix64(state_);
}

double Random::Uniform() { return static_cast<double>(Next() >> 11) * (1.0 / 9007199254740992.0); }

double Random::Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }

int Random::UniformInt(int lo, int hi) {
  return lo + static_cast<int>(Next() % static_cast<uint64_t>(hi - lo + 1));
}

double Random::Normal() {
  const double u1 = 1.0 - Uniform();  // (0, 1]
  const double u2 = Uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

double SmoothStep(double edge0, double edge1, double x) {
  const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

double Fract(double x) { return x - std::floor(x); }

}  // namespace reenact::capture
