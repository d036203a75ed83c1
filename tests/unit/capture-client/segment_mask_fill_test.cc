// Hole filling of the person mask on constructed depth images: projector shadows beside the
// body and on it, depth holes inside it, enclosed gaps between limbs.
#include <gtest/gtest.h>

#include "capture-client/segment/mask_fill.h"

namespace reenact::capture {
namespace {

constexpr int kW = 80, kH = 40;

struct Frame {
  ImageDepthMm depth{kW, kH, 1, 4000};  // a wall 4 m away
  ImageGray8 mask{kW, kH, 1, 0};
  PixelRect box{kW, kH, 0, 0};

  // A person rectangle at depth z_mm, in the mask.
  void Person(int x0, int y0, int x1, int y1, uint16_t z_mm) {
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        depth.at(x, y) = z_mm;
        mask.at(x, y) = 255;
      }
    box = {std::min(box.x0, x0), std::min(box.y0, y0), std::max(box.x1, x1), std::max(box.y1, y1)};
  }
  void Depth(int x0, int y0, int x1, int y1, uint16_t z_mm) {
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) depth.at(x, y) = z_mm;
  }
  void Unmask(int x0, int y0, int x1, int y1) {
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) mask.at(x, y) = 0;
  }
  int FillRuns(int max_run = 48) {
    return FillDepthHoles([&](int x, int y) { return depth.at(x, y) * 1e-3; }, max_run, box, &mask);
  }
  int FillEnclosed(uint16_t floor_mm = 0) {
    return FillEnclosedHoles(
        [&](int x, int y) { return depth.at(x, y) * 1e-3; },
        [&](int x, int y, double) { return floor_mm != 0 && depth.at(x, y) == floor_mm; },
        DepthTolerance{0.02, 0.008}, 0.5, box, &mask);
  }
  int Count(int x0, int y0, int x1, int y1) const {
    int n = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) n += mask.at(x, y) != 0;
    return n;
  }
};

TEST(FillDepthHoles, ShadowBesideTheBodyOnTheWallStaysOut) {
  Frame f;
  f.Person(30, 5, 50, 35, 2000);
  f.Depth(22, 5, 30, 35, 0);  // the projector's shadow, left of the body, on the wall
  EXPECT_EQ(f.FillRuns(), 0);
  EXPECT_EQ(f.Count(0, 0, 30, kH), 0);
}

TEST(FillDepthHoles, ShadowOfAnArmOnTheTorsoJoins) {
  Frame f;
  f.Person(20, 5, 40, 35, 2200);  // torso
  f.Person(46, 5, 52, 35, 2000);  // arm, nearer
  f.Depth(40, 5, 46, 35, 2200);
  f.Depth(34, 10, 46, 20, 0);  // shadow of the arm on the torso (and the gap beyond)
  f.Unmask(34, 10, 46, 20);
  EXPECT_EQ(f.FillRuns(), 12 * 10);
  EXPECT_EQ(f.Count(34, 10, 46, 20), 12 * 10);
}

TEST(FillDepthHoles, HoleInsideTheBodyJoinsAndLongOrOpenRunsDoNot) {
  Frame f;
  f.Person(10, 5, 70, 35, 2000);
  f.Depth(20, 8, 26, 12, 0);  // dark hair: 6 px wide
  f.Unmask(20, 8, 26, 12);
  f.Depth(11, 20, 69, 22, 0);  // 58 px wide: longer than the 48 px limit
  f.Unmask(11, 20, 69, 22);
  EXPECT_EQ(f.FillRuns(), 6 * 4);
  EXPECT_EQ(f.Count(20, 8, 26, 12), 6 * 4);
  EXPECT_EQ(f.Count(11, 20, 69, 22), 0);
  EXPECT_EQ(f.FillRuns(64), 58 * 2);  // a longer limit takes it

  Frame open;  // a run reaching the image border has no far end to judge by
  open.Person(0, 5, 20, 35, 2000);
  open.Depth(0, 10, 5, 12, 0);
  open.Unmask(0, 10, 5, 12);
  EXPECT_EQ(open.FillRuns(), 0);
}

TEST(FillDepthHoles, ShadowOfAnObjectInFrontOfThePersonJoins) {
  Frame f;
  f.Person(10, 5, 40, 35, 3000);
  f.Depth(40, 5, 50, 35, 2000);  // a chair leg in front, not in the mask
  f.Depth(34, 12, 40, 30, 0);    // its shadow on the person
  f.Unmask(34, 12, 40, 30);
  EXPECT_EQ(f.FillRuns(), 6 * 18);
  EXPECT_EQ(f.Count(40, 0, 50, kH), 0);
}

TEST(FillEnclosedHoles, SpecksAtThePersonsDepthJoin) {
  Frame f;
  f.Person(10, 5, 50, 35, 2000);
  f.Depth(20, 10, 23, 13, 2010);  // rejected by noise, 1 cm off
  f.Unmask(20, 10, 23, 13);
  EXPECT_EQ(f.FillEnclosed(), 9);
  EXPECT_EQ(f.Count(10, 5, 50, 35), 40 * 30);
}

TEST(FillEnclosedHoles, AViewThroughAGapStaysOut) {
  Frame wall;  // a gap between arm and torso showing the wall 2 m behind
  wall.Person(10, 5, 50, 35, 2000);
  wall.Depth(20, 10, 30, 20, 4000);
  wall.Unmask(20, 10, 30, 20);
  EXPECT_EQ(wall.FillEnclosed(), 0);

  Frame shadowed = wall;  // the same gap without readings (in the projector's shadow)
  shadowed.Depth(20, 10, 30, 20, 0);
  EXPECT_EQ(shadowed.FillEnclosed(), 0);

  Frame floor = wall;                 // the floor seen between the legs
  floor.Depth(20, 10, 30, 20, 2030);  // within depth_step (5.2 cm at 2 m) of the body
  EXPECT_EQ(floor.FillEnclosed(2030), 0);
  EXPECT_EQ(floor.FillEnclosed(), 100);  // the same readings, not floor: person depth

  Frame mixed = wall;  // 60 of 100 pixels at the person's depth: over half
  mixed.Depth(20, 10, 30, 16, 2005);
  EXPECT_EQ(mixed.FillEnclosed(), 100);
}

TEST(FillEnclosedHoles, RegionsOpenToTheOutsideStayOut) {
  Frame f;  // a C shape: the notch opens to the right
  f.Person(10, 5, 50, 35, 2000);
  f.Depth(30, 15, 50, 25, 2005);
  f.Unmask(30, 15, 50, 25);
  EXPECT_EQ(f.FillEnclosed(), 0);
  Frame border;  // a notch open to the image border
  border.Person(0, 5, 40, 35, 2000);
  border.Depth(0, 15, 10, 25, 2005);
  border.Unmask(0, 15, 10, 25);
  EXPECT_EQ(border.FillEnclosed(), 0);
  Frame empty;
  EXPECT_EQ(empty.FillEnclosed(), 0);
  EXPECT_EQ(empty.FillRuns(), 0);
}

}  // namespace
}  // namespace reenact::capture
