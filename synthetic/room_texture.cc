#include "synthetic/room_texture.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace reenact::capture {
namespace {

double Sq(double x) { return x * x; }

// Wood grain along u.
Color Wood(double u, double v, const Color& tone, uint64_t seed) {
  const double grain = Fbm(u * 3.0, v * 60.0, 3, seed);
  const double rings = 0.5 + 0.5 * std::sin(v * 180.0 + 12.0 * grain);
  return tone * (0.78 + 0.18 * rings + 0.14 * grain);
}

Color Palette(uint64_t h) {
  static const Color kColors[] = {
      Rgb(180, 40, 40),  Rgb(40, 90, 160), Rgb(230, 190, 60),  Rgb(40, 130, 70),  Rgb(120, 60, 140),
      Rgb(230, 120, 40), Rgb(30, 30, 35),  Rgb(235, 235, 225), Rgb(90, 160, 190), Rgb(150, 30, 80)};
  return kColors[h % 10];
}

// A "painting": coloured rectangles and discs on a background, (s, t) in [0, 1].
Color Painting(double s, double t, uint64_t seed) {
  Color c = Mix(Palette(Mix64(seed)), Rgb(240, 235, 220), 0.4);
  Random rng(seed);
  for (int i = 0; i < 9; ++i) {
    const double cx = rng.Uniform(), cy = rng.Uniform(), r = rng.Uniform(0.06, 0.25);
    const Color col = Palette(rng.Next());
    const bool disc = rng.Uniform() < 0.5;
    if (disc ? Sq(s - cx) + Sq(t - cy) < r * r : std::abs(s - cx) < r && std::abs(t - cy) < r * 0.6)
      c = col;
  }
  return c * (0.9 + 0.1 * Fbm(s * 20, t * 20, 2, seed));
}

// A frame with a painting inside; returns false outside the frame.
bool Framed(double u, double v, double x0, double y0, double w, double h, uint64_t seed,
            Color* out) {
  const double s = (u - x0) / w, t = (v - y0) / h;
  if (s < 0 || s > 1 || t < 0 || t > 1) return false;
  const double border = 0.04;
  const double du = std::min(u - x0, x0 + w - u), dv = std::min(v - y0, y0 + h - v);
  if (du < border || dv < border)
    *out = Rgb(60, 40, 25) * (0.8 + 0.4 * Fract(std::min(du, dv) / border));
  else
    *out = Painting(s, t, seed);
  return true;
}

Color Door(double u, double v, double x0, const Color& tone, bool* inside) {
  *inside = u > x0 && u < x0 + 0.9 && v < 2.05;
  if (!*inside) return {};
  const double s = u - x0;
  Color c = Wood(s, v, tone, 77);
  for (double py : {0.15, 1.1})
    if (s > 0.12 && s < 0.78 && v > py && v < py + 0.8) {
      const double edge = std::min({s - 0.12, 0.78 - s, v - py, py + 0.8 - v});
      if (edge < 0.025) c *= 0.7;
    }
  if (Sq(s - 0.8) + Sq(v - 1.0) < Sq(0.03)) c = Rgb(200, 195, 170);
  if (s < 0.02 || s > 0.88 || v > 2.03) c = Rgb(240, 240, 235);
  return c;
}

Color Baseboard(double v, const Color& wall) {
  if (v < 0.1) return Rgb(235, 232, 225) * (v < 0.01 ? 0.7 : 1.0);
  return wall * (1 - 0.18 * std::exp(-(v - 0.1) / 0.25));  // soft corner shading
}

Color Floor(double u, double v) {
  // Rug at u in [0.4, 1.9], v in [1.8, 3.2] (world x in [-2.6, -1.1], y in [-2.2, -0.8]).
  const double ru = u - 0.4, rv = v - 1.8;
  if (ru > 0 && ru < 1.5 && rv > 0 && rv < 1.4) {
    const double e = std::min({ru, 1.5 - ru, rv, 1.4 - rv});
    if (e < 0.04) return Rgb(230, 220, 190);
    if (e < 0.15) return Fract((ru + rv) / 0.1) < 0.5 ? Rgb(140, 30, 40) : Rgb(30, 50, 100);
    const double d = std::abs(ru - 0.75) / 0.6 + std::abs(rv - 0.7) / 0.55;
    Color c =
        d < 1 ? (Fract(d * 4) < 0.5 ? Rgb(200, 150, 60) : Rgb(140, 30, 40)) : Rgb(120, 25, 35);
    return c * (0.85 + 0.2 * ValueNoise(u * 120, v * 120, 3));
  }
  // Planks 0.14 m wide along y, 1.2 m long, staggered per row.
  const double row = std::floor(u / 0.14);
  const double shifted = v + 0.37 * row;
  const double col = std::floor(shifted / 1.2);
  const uint64_t id = Mix64(static_cast<uint64_t>(row * 1000 + col + 500000));
  const Color tone = Mix(Rgb(150, 100, 60), Rgb(200, 150, 100), (id % 1000) / 1000.0);
  Color c = Wood(shifted, u, tone, id % 97);
  const double gu = Fract(u / 0.14) * 0.14, gv = Fract(shifted / 1.2) * 1.2;
  if (gu < 0.004 || gv < 0.004) c *= 0.45;
  return c;
}

Color Plaster(double u, double v, double width) {
  Color c = Rgb(226, 214, 190) * (0.92 + 0.1 * Fbm(u * 8, v * 8, 3, 91));
  Color framed;
  if (Framed(u, v, 0.6, 1.2, 0.9, 0.7, 1001, &framed)) return framed;
  if (Framed(u, v, width / 2 - 0.35, 1.45, 0.7, 0.9, 1002, &framed)) return framed;
  if (Framed(u, v, width - 1.3, 1.3, 0.5, 0.5, 1003, &framed)) return framed;
  // A clock.
  const double cu = u - (width - 1.05), cv = v - 2.3, r = std::hypot(cu, cv);
  if (r < 0.17) {
    c = r > 0.155 ? Rgb(30, 30, 30) : Rgb(245, 245, 240);
    const double a = std::atan2(cv, cu);
    if (r > 0.12 && r < 0.15 && std::abs(Fract(a / (2 * std::numbers::pi) * 12 + 0.5) - 0.5) < 0.06)
      c = Rgb(20, 20, 20);
    if (std::abs(cu) < 0.006 && cv > 0 && cv < 0.12) c = Rgb(20, 20, 20);
    if (std::abs(cv) < 0.006 && cu > 0 && cu < 0.09) c = Rgb(20, 20, 20);
  }
  return Baseboard(v, c);
}

Color Brick(double u, double v, double width) {
  const double course = std::floor(v / 0.075);
  const double shifted = u + (static_cast<int64_t>(course) % 2 ? 0.11 : 0);
  const double col = std::floor(shifted / 0.225);
  const uint64_t id = Mix64(static_cast<uint64_t>(course * 1000 + col + 100000));
  Color c = Mix(Rgb(150, 60, 40), Rgb(190, 100, 70), (id % 1000) / 1000.0) *
            (0.85 + 0.25 * ValueNoise(u * 60, v * 60, 13));
  if (Fract(v / 0.075) * 0.075 < 0.01 || Fract(shifted / 0.225) * 0.225 < 0.01)
    c = Rgb(200, 195, 185) * (0.85 + 0.2 * ValueNoise(u * 90, v * 90, 17));
  // A poster.
  const double pu = u - (width / 2 - 0.4), pv = v - 1.1;
  if (pu > 0 && pu < 0.8 && pv > 0 && pv < 1.1) {
    c = Rgb(245, 240, 225);
    if (pv > 0.75 && pv < 0.95 && pu > 0.08 && pu < 0.72) c = Rgb(20, 20, 20);
    if (pv > 0.8 && pv < 0.9 && Fract(pu / 0.09) < 0.5 && pu > 0.1 && pu < 0.7)
      c = Rgb(230, 190, 60);
    if (Sq(pu - 0.4) + Sq(pv - 0.4) < Sq(0.25))
      c = Fract(std::hypot(pu - 0.4, pv - 0.4) / 0.08) < 0.5 ? Rgb(40, 90, 160) : Rgb(200, 50, 40);
  }
  return Baseboard(v, c);
}

Color Wallpaper(double u, double v, double width) {
  const double su = Fract(u / 0.25) - 0.5, sv = Fract(v / 0.3) - 0.5;
  Color c = Rgb(200, 215, 190);
  const double d = std::abs(su) + std::abs(sv);
  if (d < 0.3 && d > 0.22) c = Rgb(120, 150, 110);
  if (Sq(su) + Sq(sv) < 0.01) c = Rgb(150, 90, 90);
  c *= 0.93 + 0.1 * ValueNoise(u * 30, v * 30, 19);
  // Whiteboard with scribbles.
  const double wu = u - 1.0, wv = v - 0.95;
  if (wu > 0 && wu < 1.6 && wv > 0 && wv < 1.0) {
    c = (wu < 0.03 || wu > 1.57 || wv < 0.03 || wv > 0.97) ? Rgb(170, 170, 175)
                                                           : Rgb(248, 248, 248);
    Random rng(555);
    for (int i = 0; i < 14; ++i) {
      const double x0 = rng.Uniform(0.1, 1.4), y0 = rng.Uniform(0.1, 0.9);
      const double x1 = x0 + rng.Uniform(-0.3, 0.3), y1 = y0 + rng.Uniform(-0.2, 0.2);
      const Color ink =
          i % 3 == 0 ? Rgb(200, 30, 30) : (i % 3 == 1 ? Rgb(30, 60, 180) : Rgb(20, 20, 20));
      const double dx = x1 - x0, dy = y1 - y0, len2 = dx * dx + dy * dy;
      const double t = std::clamp(((wu - x0) * dx + (wv - y0) * dy) / len2, 0.0, 1.0);
      if (Sq(wu - x0 - t * dx) + Sq(wv - y0 - t * dy) < Sq(0.006)) c = ink;
    }
  }
  bool in_door = false;
  const Color door = Door(u, v, width - 1.6, Rgb(160, 110, 70), &in_door);
  if (in_door) return door;
  return Baseboard(v, c);
}

Color Painted(double u, double v, double width) {
  Color c = Rgb(150, 170, 185) * (0.93 + 0.1 * Fbm(u * 6, v * 6, 3, 29));
  // Map-like poster: blobs of "land" on blue with grid lines.
  const double mu = u - 0.8, mv = v - 1.0;
  if (mu > 0 && mu < 1.8 && mv > 0 && mv < 1.1) {
    const double land = Fbm(mu * 3, mv * 3, 4, 31);
    c = land > 0.55 ? Mix(Rgb(120, 170, 90), Rgb(200, 180, 120), (land - 0.55) * 3)
                    : Rgb(90, 140, 200);
    if (Fract(mu / 0.2) < 0.02 || Fract(mv / 0.2) < 0.02) c *= 0.7;
    if (mu < 0.02 || mu > 1.78 || mv < 0.02 || mv > 1.08) c = Rgb(30, 30, 30);
  }
  bool in_door = false;
  const Color door = Door(u, v, width - 1.4, Rgb(120, 80, 50), &in_door);
  if (in_door) return door;
  return Baseboard(v, c);
}

Color Ceiling(double u, double v, double width, double height) {
  const double cu = u - width / 2, cv = v - height / 2;
  if (std::abs(cu) < 0.6 && std::abs(cv) < 0.3)
    return (std::abs(cu) > 0.57 || std::abs(cv) > 0.27) ? Rgb(180, 180, 180) : Rgb(255, 255, 250);
  return Rgb(238, 238, 232) * (0.95 + 0.05 * ValueNoise(u * 20, v * 20, 37));
}

Color Bookshelf(double u, double v, double width, double height) {
  const Color wood = Wood(u, v, Rgb(120, 80, 50), 43);
  if (u < 0.03 || u > width - 0.03 || v > height - 0.03) return wood;
  const double shelf = 0.38;
  const double level = std::floor(v / shelf), within = v - level * shelf;
  if (within < 0.025 || level >= 4) return wood;
  // Books: walk along the shelf with random widths.
  Random rng(900 + static_cast<uint64_t>(level));
  double x = 0.03;
  while (x < width - 0.03) {
    const double w = rng.Uniform(0.02, 0.055), h = rng.Uniform(0.2, 0.33);
    const uint64_t look = rng.Next();
    const bool gap = look % 11 == 0;
    if (u >= x && u < x + w) {
      if (gap || within > h + 0.025) return Rgb(50, 35, 25);
      Color c = Palette(look) * (0.8 + 0.2 * ValueNoise(u * 200, v * 40, 47));
      const double band = within - 0.025;
      if ((look >> 8) % 3 == 0 && std::abs(band - h * 0.75) < 0.012) c = Rgb(230, 200, 90);
      if ((look >> 8) % 3 == 1 && std::abs(band - h * 0.3) < 0.008) c = Rgb(240, 240, 240);
      if (u - x < 0.002) c *= 0.5;
      return c;
    }
    x += w;
  }
  return Rgb(50, 35, 25);
}

Color Cabinet(double u, double v, double width, double height) {
  Color c = Wood(u, v, Rgb(170, 120, 75), 53);
  const int drawers = 3;
  const double dh = (height - 0.1) / drawers;
  const double row = std::floor((v - 0.05) / dh);
  if (row >= 0 && row < drawers) {
    const double dv = v - 0.05 - row * dh;
    if (dv < 0.012 || u < 0.03 || u > width - 0.03) c *= 0.55;
    if (std::abs(u - width / 2) < 0.08 && std::abs(dv - dh / 2) < 0.012) c = Rgb(190, 190, 195);
  }
  return c;
}

Color Cardboard(double u, double v, double width, double height) {
  Color c = Rgb(185, 145, 95) * (0.9 + 0.15 * Fbm(u * 30, v * 30, 2, 61));
  if (std::abs(v - height * 0.5) < 0.03) c = Rgb(200, 170, 120) * 1.05;  // tape
  const double lu = u - width * 0.15, lv = v - height * 0.58;
  if (lu > 0 && lu < 0.22 && lv > 0 && lv < 0.14) {
    c = Rgb(245, 245, 245);
    if (lv < 0.06 && lu > 0.02 && lu < 0.2 && Mix64(static_cast<uint64_t>(lu / 0.005)) % 3 != 0)
      c = Rgb(20, 20, 20);  // barcode
    if (lv > 0.08 && lv < 0.1 && lu > 0.02 && lu < 0.16) c = Rgb(20, 20, 20);
  }
  const double au = u - width * 0.75, av = v - height * 0.2;
  if (std::abs(au) < 0.015 && av > 0 && av < 0.1) c = Rgb(40, 40, 40);  // arrow up
  if (av >= 0.1 && av < 0.14 && std::abs(au) < 0.04 - (av - 0.1)) c = Rgb(40, 40, 40);
  return c;
}

Color Tablecloth(double u, double v) {
  const bool a = Fract(u / 0.05) < 0.5, b = Fract(v / 0.05) < 0.5;
  const Color c = (a && b) ? Rgb(180, 30, 40) : (a || b) ? Rgb(220, 130, 130) : Rgb(245, 240, 235);
  return c * (0.92 + 0.1 * ValueNoise(u * 80, v * 80, 71));
}

}  // namespace

Color RoomAlbedo(RoomMaterial m, double u, double v, double width, double height) {
  switch (m) {
    case RoomMaterial::kFloorPlanks:
      return Floor(u, v);
    case RoomMaterial::kPlasterWall:
      return Plaster(u, v, width);
    case RoomMaterial::kBrickWall:
      return Brick(u, v, width);
    case RoomMaterial::kWallpaper:
      return Wallpaper(u, v, width);
    case RoomMaterial::kPaintedWall:
      return Painted(u, v, width);
    case RoomMaterial::kCeiling:
      return Ceiling(u, v, width, height);
    case RoomMaterial::kBookshelf:
      return Bookshelf(u, v, width, height);
    case RoomMaterial::kWood:
      return Wood(u, v, Rgb(140, 95, 60), 83);
    case RoomMaterial::kCabinet:
      return Cabinet(u, v, width, height);
    case RoomMaterial::kCardboard:
      return Cardboard(u, v, width, height);
    case RoomMaterial::kTablecloth:
      return Tablecloth(u, v);
  }
  return Color(1, 0, 1);
}

}  // namespace reenact::capture
