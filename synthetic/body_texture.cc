#include "synthetic/body_texture.h"

#include <cmath>
#include <numbers>

namespace reenact::capture {
namespace {

using Eigen::Vector3d;

constexpr uint64_t kSkinSeed = 11, kClothSeed = 23, kHairSeed = 37, kDenimSeed = 41;

double Sq(double x) { return x * x; }

Color Skin(const Vector3d& p) {
  const double n = ValueNoise(p * 45.0, kSkinSeed);
  const double blush = ValueNoise(p * 9.0, kSkinSeed + 1);
  return Mix(Rgb(222, 170, 138), Rgb(205, 140, 118), 0.5 * blush) * (0.92 + 0.12 * n);
}

Color Hair(const Vector3d& p) {
  const double strands = ValueNoise(Vector3d(p.x() * 90, p.y() * 90, p.z() * 8), kHairSeed);
  return Rgb(62, 40, 24) * (0.6 + 0.7 * strands);
}

Color ClothNoise(const Color& base, const Vector3d& p) {
  const double weave = ValueNoise(p * 70.0, kClothSeed);
  const double folds = ValueNoise(p * 12.0, kClothSeed + 1);
  return base * (0.86 + 0.12 * weave + 0.1 * folds);
}

// Height above the waist joint (hz), lateral (y) and front/back (x) of a torso point.
Color Shirt(double x, double y, double hz, const Vector3d& p) {
  const Color teal = Rgb(30, 92, 140);
  Color c = teal;
  if (x > 0) {
    if (Fract(hz / 0.08) < 0.3 && hz > 0.05 && hz < 0.45) c = Rgb(232, 232, 222);
    // Emblem on the left breast: a yellow disc with a red five-pointed star.
    const double ey = y - 0.075, ez = hz - 0.40;
    const double r = std::hypot(ey, ez);
    if (r < 0.045) {
      c = Rgb(240, 200, 40);
      const double a = std::atan2(ez, ey);
      const double star = 0.018 + 0.012 * std::cos(5 * (a - std::numbers::pi / 2));
      if (r < star) c = Rgb(200, 30, 30);
      if (r > 0.040) c = Rgb(20, 30, 60);
    }
  } else {
    const double a = std::floor((y + hz) / 0.07), b = std::floor((y - hz) / 0.07);
    if ((static_cast<int64_t>(a + b) & 1) != 0) c = Rgb(16, 40, 80);
    // A white "7" across the shoulder blades.
    const bool bar = hz > 0.42 && hz < 0.46 && std::abs(y) < 0.06;
    const bool stem = hz > 0.18 && hz < 0.46 && std::abs(y + 0.06 - 0.4 * (0.46 - hz)) < 0.02;
    if (bar || stem) c = Rgb(240, 240, 235);
  }
  if (std::abs(x) < 0.006) c *= 0.6;  // side seams
  return ClothNoise(c, p);
}

Color Denim(const Vector3d& p, double seam_angle_cos) {
  const double twill = 0.5 + 0.5 * std::sin((p.y() + p.z() + p.x()) * 420.0);
  const double n = ValueNoise(p * 60.0, kDenimSeed);
  const double fade = ValueNoise(p * 8.0, kDenimSeed + 1);
  Color c = Mix(Rgb(38, 58, 104), Rgb(70, 96, 146), 0.6 * fade) * (0.85 + 0.1 * twill + 0.12 * n);
  if (std::abs(seam_angle_cos) < 0.07) c = Rgb(150, 110, 60) * (0.9 + 0.2 * n);  // side seam
  return c;
}

Color Head(const Vector3d& p) {
  const double x = p.x(), y = p.y(), z = p.z();
  const bool hair =
      z > 0.062 || (x < -0.015 && z > -0.085) || (x < 0.03 && std::abs(y) > 0.058 && z > 0.005);
  if (hair) return Hair(p);
  Color c = Skin(p);
  if (x <= 0.02) {
    if (std::abs(y) > 0.07 && std::abs(z) < 0.03) c *= 0.85;  // ears
    return c;
  }
  for (double side : {-1.0, 1.0}) {
    const double ey = y - side * 0.033, ez = z - 0.02;
    if (Sq(ey / 0.016) + Sq(ez / 0.008) < 1) {
      c = Rgb(242, 240, 232);
      const double r = std::hypot(ey, ez);
      if (r < 0.0065) c = Rgb(60, 110, 160);
      if (r < 0.003) c = Rgb(10, 10, 12);
    }
    if (std::abs(ey) < 0.019 && ez > 0.014 && ez < 0.022 + 0.004 * (1 - Sq(ey / 0.019)))
      c = Rgb(55, 35, 22);  // eyebrow
    if (std::abs(y - side * 0.008) < 0.004 && std::abs(z + 0.03) < 0.003) c = Rgb(120, 70, 60);
  }
  if (std::abs(y) < 0.011 && z > -0.028 && z < 0.012) c *= 0.93;  // nose ridge
  if (Sq(y / 0.027) + Sq((z + 0.058) / 0.009) < 1) {
    c = Rgb(176, 84, 84);
    if (std::abs(z + 0.058) < 0.0015) c = Rgb(90, 30, 35);
  }
  return c;
}

Color UpperArm(const Vector3d& p, bool left) {
  if (p.z() > -0.12) {
    Color c = Rgb(30, 92, 140);
    if (p.z() < -0.105) c = Rgb(232, 232, 222);                                     // sleeve hem
    if (left && p.z() > -0.07 && p.z() < -0.03 && p.y() > 0) c = Rgb(200, 30, 30);  // patch
    return ClothNoise(c, p);
  }
  return Skin(p);
}

Color Forearm(const Vector3d& p, bool left) {
  if (left && p.z() < -0.215 && p.z() > -0.24) {
    Color c = Rgb(25, 25, 28);
    if (p.x() > 0.018) c = Rgb(200, 200, 205);  // watch face
    return c;
  }
  return Skin(p) * (0.9 + 0.1 * ValueNoise(p * 150.0, kSkinSeed + 3));
}

Color Hand(const Vector3d& p) {
  Color c = Skin(p) * 1.03;
  if (p.z() < -0.09) {
    for (double k : {-0.021, 0.0, 0.021})
      if (std::abs(p.x() - k) < 0.0025) c *= 0.7;  // gaps between fingers
  }
  return c;
}

Color LowerTorso(const Vector3d& p) {
  const double x = p.x(), y = p.y(), z = p.z();
  if (z > 0.03) return Shirt(x, y, z, p);
  if (z > -0.01) {
    if (x > 0.05 && std::abs(y) < 0.025) return Rgb(190, 185, 170);   // buckle
    return Rgb(80, 48, 26) * (0.85 + 0.2 * ValueNoise(p * 80.0, 5));  // belt
  }
  Color c = Denim(p, x / std::hypot(x, y));
  if (x < 0 && std::abs(y) > 0.03 && std::abs(y) < 0.13 && z < -0.04 && z > -0.15) {
    const double edge = std::min({std::abs(std::abs(y) - 0.03), std::abs(std::abs(y) - 0.13),
                                  std::abs(z + 0.04), std::abs(z + 0.15)});
    if (edge < 0.004) c = Rgb(200, 140, 60);  // pocket stitching
  }
  if (x > 0 && std::abs(y) < 0.005 && z < -0.01 && z > -0.12) c *= 0.6;  // fly
  return c;
}

Color Leg(const Vector3d& p, bool shin) {
  Color c = Denim(p, p.x() / std::hypot(p.x(), p.y()));
  const double knee_distance = shin ? -p.z() : p.z() + 0.43;
  if (p.x() > 0.02 && std::abs(knee_distance) < 0.08)
    c = Mix(c, Rgb(140, 160, 190), 0.5 * (1 - std::abs(knee_distance) / 0.08));  // worn knee
  if (shin && p.z() < -0.36) c = Rgb(80, 105, 150) * (0.9 + 0.2 * ValueNoise(p * 60.0, 7));
  return c;
}

Color Shoe(const Vector3d& p) {
  const double x = p.x(), y = p.y(), z = p.z();
  if (z < -0.064) return Rgb(235, 233, 225);  // sole
  Color c = Rgb(40, 40, 46) * (0.85 + 0.25 * ValueNoise(p * 90.0, 9));
  if (z > -0.03 && x > 0.02 && x < 0.12 && std::abs(y) < 0.02 && Fract((x - 0.02) / 0.018) < 0.35)
    c = Rgb(230, 230, 230);  // laces
  if (std::abs(y) > 0.03 && std::abs(z - (-0.045 + 0.25 * (x - 0.02))) < 0.006 && x > -0.02 &&
      x < 0.12)
    c = Rgb(200, 40, 40);                             // side stripe
  if (x < -0.055 && z > -0.04) c = Rgb(200, 40, 40);  // heel tab
  return c;
}

}  // namespace

Color BodyAlbedo(Segment segment, const Vector3d& p) {
  switch (segment) {
    case Segment::kHead:
      return Head(p);
    case Segment::kNeck:
      return Skin(p);
    case Segment::kUpperTorso:
      return Shirt(p.x(), p.y(), p.z() + 0.22, p);
    case Segment::kLowerTorso:
      return LowerTorso(p);
    case Segment::kLeftUpperArm:
      return UpperArm(p, true);
    case Segment::kRightUpperArm:
      return UpperArm(p, false);
    case Segment::kLeftForearm:
      return Forearm(p, true);
    case Segment::kRightForearm:
      return Forearm(p, false);
    case Segment::kLeftHand:
    case Segment::kRightHand:
      return Hand(p);
    case Segment::kLeftThigh:
    case Segment::kRightThigh:
      return Leg(p, false);
    case Segment::kLeftShin:
    case Segment::kRightShin:
      return Leg(p, true);
    case Segment::kLeftFoot:
    case Segment::kRightFoot:
      return Shoe(p);
  }
  return Color(1, 0, 1);
}

}  // namespace reenact::capture
