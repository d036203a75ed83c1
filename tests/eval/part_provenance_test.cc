#include "tests/eval/part_provenance.h"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "common/error/check.h"

namespace reenact::eval {
namespace {

constexpr int kTorso = PartLabel(BodyPart::kUpperTorso);
constexpr int kArm = PartLabel(BodyPart::kLeftForearm);

// A 4x3 crop at (10, 20) of a 40x30 sensor image: labels arm in sensor columns < 12 (crop
// columns 0, 1), torso from column 12 on; crop row 2 is off the subject's mask.
struct Fixture {
  ImageGray8 mask{4, 3, 1, 255};
  ImageLabel8 labels{40, 30, 1, 0};
  Fixture() {
    for (int x = 0; x < 4; ++x) mask.at(x, 2) = 0;
    for (int y = 0; y < 30; ++y)
      for (int x = 0; x < 40; ++x) labels.at(x, y) = x < 12 ? kArm : kTorso;
  }
  SourceLabels source() const { return {&mask, 10, 20, &labels}; }
};

TEST(PartProvenance, TexelCentresCountWhollyRightOrWrong) {
  const Fixture f;
  EXPECT_DOUBLE_EQ(WrongShareOfSample(f.source(), 0, 0, kArm), 0.0);
  EXPECT_DOUBLE_EQ(WrongShareOfSample(f.source(), 1, 1, kArm), 0.0);
  EXPECT_DOUBLE_EQ(WrongShareOfSample(f.source(), 2, 0, kArm), 1.0);
  EXPECT_DOUBLE_EQ(WrongShareOfSample(f.source(), 2, 0, kTorso), 0.0);
}

TEST(PartProvenance, SamplesAcrossABorderSplitByBilinearWeight) {
  const Fixture f;
  // Between crop columns 1 (arm) and 2 (torso): the torso texels weigh t.
  EXPECT_NEAR(WrongShareOfSample(f.source(), 1.5, 0.5, kArm), 0.5, 1e-12);
  EXPECT_NEAR(WrongShareOfSample(f.source(), 1.25, 0, kArm), 0.25, 1e-12);
  EXPECT_NEAR(WrongShareOfSample(f.source(), 1.75, 0.3, kTorso), 0.25, 1e-12);
}

TEST(PartProvenance, TexelsOffTheMaskGiveNoColourAndAreLeftOut) {
  const Fixture f;
  // Rows 1 (subject) and 2 (off the mask) at column 1.5: only row 1's two texels count,
  // renormalised, whatever the vertical weight.
  EXPECT_NEAR(WrongShareOfSample(f.source(), 1.5, 1.9, kArm), 0.5, 1e-12);
  // Wholly off the mask: the renderer discards such a fragment; nothing is wrong.
  EXPECT_DOUBLE_EQ(WrongShareOfSample(f.source(), 1, 2, kArm), 0.0);
}

TEST(PartProvenance, BackgroundLabelsAndLabelsOutsideTheImageAreWrong) {
  Fixture f;
  f.labels.at(10, 20) = kBackgroundLabel;  // crop texel (0, 0)
  EXPECT_DOUBLE_EQ(WrongShareOfSample(f.source(), 0, 0, kArm), 1.0);
  // A crop lying partly outside a (smaller) label image: texels there read background.
  const ImageLabel8 small(11, 30, 1, kArm);  // sensor columns 0..10 only
  const SourceLabels s{&f.mask, 10, 20, &small};
  EXPECT_DOUBLE_EQ(WrongShareOfSample(s, 0, 1, kArm), 0.0);
  EXPECT_DOUBLE_EQ(WrongShareOfSample(s, 1, 1, kArm), 1.0);
}

TEST(PartProvenance, SamplesBeyondTheCropEdgeClampToIt) {
  const Fixture f;
  EXPECT_DOUBLE_EQ(WrongShareOfSample(f.source(), -0.5, 0, kArm), 0.0);
  EXPECT_DOUBLE_EQ(WrongShareOfSample(f.source(), 3.5, 0, kTorso), 0.0);
}

// A cap seen head-on through an identity stored_from_viewer samples the crop at the very
// pixel it covers; the labels' border runs through the cap at x = 84. A second, flat-coloured
// part stands apart.
struct CapOverALabelBorder {
  PinholeCamera camera{160, 120, 200, 200, 80.3, 60.7, {}};
  ReferenceCrop crop;
  ImageLabel8 labels{160, 120, 1, 0};
  ReferenceRender render;
  std::vector<BodyPart> cylinder_parts = {BodyPart::kLeftForearm, BodyPart::kHead};
  int cap = 0, right_of_border = 0, flat = 0;

  CapOverALabelBorder() {
    crop.color = ImageRgb8(100, 80, 3, 128);
    crop.mask = ImageGray8(100, 80, 1, 255);
    crop.camera = camera.Cropped(40, 20, 100, 80);
    for (int y = 0; y < 120; ++y)
      for (int x = 0; x < 160; ++x) labels.at(x, y) = x < 84 ? kArm : kTorso;
    std::vector<ReferencePart> parts(2);
    parts[0].cylinder = Cylinder{{0.02, -0.01, 1.0}, {0.02, -0.01, 1.5}, 0.15};  // cap r = 30 px
    parts[0].candidates.push_back({&crop, 5, Eigen::Matrix4d::Identity(), 1.0});
    parts[1].cylinder = Cylinder{{-0.35, -0.2, 1.0}, {-0.35, -0.2, 1.5}, 0.02};  // flat, apart
    render = RenderReference(camera, parts);
    for (int y = 0; y < 120; ++y)
      for (int x = 0; x < 160; ++x) {
        if (render.part.at(x, y) == 0) {
          ++cap;
          right_of_border += x >= 84;
        }
        flat += render.part.at(x, y) == 1;
      }
  }
  SourceLabels source() const { return {&crop.mask, 40, 20, &labels}; }
  // The truth seen from the render's camera; the cap's face lies at z = 1 m, so border_m
  // spans 200 border_m pixels there.
  SeenParts Seen(const ImageLabel8& seen, double border_m = kDoubledLimbBorderM) const {
    return {.labels = &seen, .focal_px = camera.fx, .border_m = border_m};
  }
  // Cap pixels in columns [x0, x1).
  int CapColumns(int x0, int x1) const {
    int n = 0;
    for (int y = 0; y < 120; ++y)
      for (int x = x0; x < x1; ++x) n += render.part.at(x, y) == 0;
    return n;
  }
};

// The reference renderer's own provenance: exactly the cap pixels right of the label border
// are wrong; the flat-coloured part adds subject pixels, none wrong.
TEST(PartProvenance, MeasuresAReferenceRenderPixelByPixel) {
  const CapOverALabelBorder s;
  ASSERT_GT(s.cap, 2500);
  ASSERT_GT(s.right_of_border, 500);
  ASSERT_GT(s.flat, 10);

  int calls = 0;
  const PartProvenance p =
      MeasurePartProvenance(s.render, s.cylinder_parts, [&](int frame) -> SourceLabels {
        EXPECT_EQ(frame, 5);
        ++calls;
        return s.source();
      });
  EXPECT_EQ(p.subject_pixels, s.cap + s.flat);
  EXPECT_EQ(p.textured_pixels, s.cap);
  EXPECT_EQ(calls, s.cap);
  // Samples land on texel centres up to float rounding of source_pixel (< 1e-4 px).
  EXPECT_NEAR(p.wrong_pixels, s.right_of_border, 1e-3 * s.cap);
  EXPECT_NEAR(p.WrongPartRate(), static_cast<double>(s.right_of_border) / (s.cap + s.flat), 1e-5);
  EXPECT_NEAR(p.UntexturedRate(), static_cast<double>(s.flat) / (s.cap + s.flat), 1e-12);
  EXPECT_EQ(p.wrong_seen_pixels, 0.0);  // not measured without seen labels
  EXPECT_EQ(p.doubled_limb_pixels, 0.0);
}

// The same render is a pixel copy of the stored view: where the viewer sees the torso (right
// of the border) the cap shows the torso's pixels. Against the seen labels nothing is wrong,
// though the drawn part's rate still counts the right side.
TEST(PartProvenance, APixelCopyOfTheSeenViewShowsNoWrongPart) {
  const CapOverALabelBorder s;
  const SeenParts seen = s.Seen(s.labels);
  const PartProvenance p = MeasurePartProvenance(
      s.render, s.cylinder_parts, [&](int) { return s.source(); }, &seen);
  EXPECT_NEAR(p.wrong_pixels, s.right_of_border, 1e-3 * s.cap);
  EXPECT_NEAR(p.wrong_seen_pixels, 0.0, 1e-3 * s.cap);
  EXPECT_NEAR(p.WrongSeenPartRate(), 0.0, 1e-5);
  EXPECT_NEAR(p.DoubledLimbRate(), 0.0, 1e-5);
}

// Seen labels that show the arm everywhere: the torso pixels right of the border are another
// part than the one seen, as they are for the drawn arm. Where the truth shows no subject the
// drawn part is expected, so a seen image of background counts as the drawn rate does. The
// truth shows the wrong texels' part nowhere, so every wrong texel is a doubled limb.
TEST(PartProvenance, SeenLabelsNameThePartExpectedAtEachPixel) {
  const CapOverALabelBorder s;
  for (const int seen_label : {kArm, kBackgroundLabel}) {
    const ImageLabel8 labels(160, 120, 1, static_cast<uint8_t>(seen_label));
    const SeenParts seen = s.Seen(labels);
    const PartProvenance p = MeasurePartProvenance(
        s.render, s.cylinder_parts, [&](int) { return s.source(); }, &seen);
    EXPECT_NEAR(p.wrong_seen_pixels, s.right_of_border, 1e-3 * s.cap) << seen_label;
    EXPECT_NEAR(p.wrong_seen_pixels, p.wrong_pixels, 1e-9) << seen_label;
    EXPECT_NEAR(p.doubled_limb_pixels, p.wrong_seen_pixels, 1e-9) << seen_label;
  }
  const ImageLabel8 torso(160, 120, 1, static_cast<uint8_t>(kTorso));  // the left side wrong
  const SeenParts seen = s.Seen(torso);
  const PartProvenance p = MeasurePartProvenance(
      s.render, s.cylinder_parts, [&](int) { return s.source(); }, &seen);
  EXPECT_NEAR(p.wrong_seen_pixels, s.cap - s.right_of_border, 1e-3 * s.cap);
  EXPECT_NEAR(p.doubled_limb_pixels, p.wrong_seen_pixels, 1e-9);
}

// The truth's border lies 30 px right of the source's (x = 114 against 84): the cap's columns
// 84..113 show torso texels where the arm is seen, all wrong against the part seen. A doubled
// limb only where the torso is seen nowhere within the border: 10.5 px at the cap's depth of
// 1 m (200 px focal length, 5.25 cm), i.e. the columns more than 10.5 px left of 114, 84..103.
TEST(PartProvenance, ASeamNearThePartsBorderIsNotADoubledLimb) {
  const CapOverALabelBorder s;
  ImageLabel8 labels(160, 120, 1, kArm);
  for (int y = 0; y < 120; ++y)
    for (int x = 114; x < 160; ++x) labels.at(x, y) = kTorso;
  const SeenParts seen = s.Seen(labels, 0.0525);
  const PartProvenance p = MeasurePartProvenance(
      s.render, s.cylinder_parts, [&](int) { return s.source(); }, &seen);
  ASSERT_GT(s.CapColumns(104, 114), 100);  // the cap reaches past the seen border's band
  EXPECT_NEAR(p.wrong_seen_pixels, s.CapColumns(84, 114), 1e-3 * s.cap);
  EXPECT_NEAR(p.doubled_limb_pixels, s.CapColumns(84, 104), 1e-3 * s.cap);
  // A border of 0 counts every wrong texel whose part is not under the pixel itself.
  const SeenParts exact = s.Seen(labels, 0);
  EXPECT_NEAR(MeasurePartProvenance(
                  s.render, s.cylinder_parts, [&](int) { return s.source(); }, &exact)
                  .doubled_limb_pixels,
              p.wrong_seen_pixels, 1e-3 * s.cap);
}

// The seen-part rate's two kinds: where the truth shows the drawn arm, a torso texel is the
// texture's error; where it shows the torso, the arm's cylinder stands where the body shows
// another part (the model's geometry) and the texture's rate leaves it out, as it leaves out
// extra pixels (the truth shows no subject there). Seen labels: arm left of x = 100, torso
// from there on, background from x = 120 on.
TEST(PartProvenance, TheTexturesRateCountsOnlyWrongTexelsOnTheRightPart) {
  const CapOverALabelBorder s;
  ImageLabel8 labels(160, 120, 1, kArm);
  for (int y = 0; y < 120; ++y)
    for (int x = 100; x < 160; ++x) labels.at(x, y) = x < 120 ? kTorso : kBackgroundLabel;
  const SeenParts seen = s.Seen(labels);
  const PartProvenance p = MeasurePartProvenance(
      s.render, s.cylinder_parts, [&](int) { return s.source(); }, &seen);
  ASSERT_GT(s.CapColumns(84, 100), 400);
  ASSERT_GT(s.CapColumns(0, 84), 400);
  // Columns 84..99: torso texels on the seen arm. 100..119: seen torso, texels torso, right
  // for the part seen. 120 on: extra pixels, the drawn arm expected, torso texels wrong.
  EXPECT_NEAR(p.wrong_texture_pixels, s.CapColumns(84, 100), 1e-3 * s.cap);
  EXPECT_NEAR(p.wrong_seen_pixels, s.CapColumns(84, 100) + s.CapColumns(120, 160), 1e-3 * s.cap);
  EXPECT_NEAR(p.WrongTextureRate(), p.wrong_texture_pixels / p.subject_pixels, 1e-12);
  // Seen torso everywhere: every wrong texel is the geometry's (the arm drawn on the torso).
  const ImageLabel8 torso(160, 120, 1, static_cast<uint8_t>(kTorso));
  const SeenParts all_torso = s.Seen(torso);
  const PartProvenance q = MeasurePartProvenance(
      s.render, s.cylinder_parts, [&](int) { return s.source(); }, &all_torso);
  EXPECT_GT(q.wrong_seen_pixels, 400);
  EXPECT_EQ(q.wrong_texture_pixels, 0.0);
  // Without seen labels nothing is measured.
  EXPECT_EQ(MeasurePartProvenance(s.render, s.cylinder_parts, [&](int) { return s.source(); })
                .wrong_texture_pixels,
            0.0);
}

// Source texels labelled background (the stored frame's mask wider than its body) are wrong
// against any part seen, but a silhouette error, not another part's texture.
TEST(PartProvenance, BackgroundTexelsAreNotADoubledLimb) {
  CapOverALabelBorder s;
  for (int y = 0; y < 120; ++y)
    for (int x = 84; x < 160; ++x) s.labels.at(x, y) = kBackgroundLabel;
  const ImageLabel8 arm(160, 120, 1, kArm);
  const SeenParts seen = s.Seen(arm);
  const PartProvenance p = MeasurePartProvenance(
      s.render, s.cylinder_parts, [&](int) { return s.source(); }, &seen);
  EXPECT_NEAR(p.wrong_seen_pixels, s.right_of_border, 1e-3 * s.cap);
  EXPECT_EQ(p.doubled_limb_pixels, 0.0);
}

TEST(PartProvenance, SeenLabelsOfAnotherSizeAreABug) {
  const CapOverALabelBorder s;
  const ImageLabel8 small(80, 60, 1, 0);
  const SeenParts seen = s.Seen(small);
  EXPECT_THROW(MeasurePartProvenance(
                   s.render, s.cylinder_parts, [&](int) { return s.source(); }, &seen),
               CheckError);
}

TEST(PartProvenance, ADoubledLimbBorderNeedsAFocalLengthAndABorder) {
  const CapOverALabelBorder s;
  const auto measure = [&](const SeenParts& seen) {
    return MeasurePartProvenance(
        s.render, s.cylinder_parts, [&](int) { return s.source(); }, &seen);
  };
  SeenParts seen = s.Seen(s.labels);
  seen.focal_px = 0;
  EXPECT_THROW(measure(seen), CheckError);
  seen = s.Seen(s.labels, -0.01);
  EXPECT_THROW(measure(seen), CheckError);
  seen = s.Seen(s.labels, std::numeric_limits<double>::quiet_NaN());
  EXPECT_THROW(measure(seen), CheckError);
  seen.labels = nullptr;
  seen.border_m = 0.05;
  EXPECT_THROW(measure(seen), CheckError);
}

// A blended pixel: contributors with shares 1/4 (a texel wholly of another part) and 3/4
// (wholly right) make a wrong share of 1/4; a third, unused channel adds nothing.
TEST(PartProvenance, BlendedContributorsCountByTheirShares) {
  const Fixture f;
  ReferenceRender render;
  render.mask = ImageGray8(1, 1, 1, 255);
  render.part = Image<int32_t>(1, 1, 1, 0);
  render.source_frame = Image<int32_t>(1, 1, 3, -1);
  render.source_pixel = Image<float>(1, 1, 6, -1.0f);
  render.source_weight = Image<float>(1, 1, 3, 0.0f);
  render.source_frame.at(0, 0, 0) = 3;  // crop texel (2, 0): torso
  render.source_pixel.at(0, 0, 0) = 2;
  render.source_pixel.at(0, 0, 1) = 0;
  render.source_weight.at(0, 0, 0) = 0.25f;
  render.source_frame.at(0, 0, 1) = 4;  // crop texel (0, 1): arm
  render.source_pixel.at(0, 0, 2) = 0;
  render.source_pixel.at(0, 0, 3) = 1;
  render.source_weight.at(0, 0, 1) = 0.75f;
  const std::vector<BodyPart> arm = {BodyPart::kLeftForearm};
  std::vector<int> frames;
  const PartProvenance p = MeasurePartProvenance(render, arm, [&](int n) {
    frames.push_back(n);
    return f.source();
  });
  EXPECT_EQ(frames, (std::vector<int>{3, 4}));
  EXPECT_EQ(p.subject_pixels, 1);
  EXPECT_EQ(p.textured_pixels, 1);
  EXPECT_DOUBLE_EQ(p.wrong_pixels, 0.25);
}

TEST(PartProvenance, EmptyRenderHasZeroRates) {
  ReferenceRender render;
  render.mask = ImageGray8(8, 8, 1, 0);
  const PartProvenance p = MeasurePartProvenance(render, {}, [](int) { return SourceLabels{}; });
  EXPECT_EQ(p.subject_pixels, 0);
  EXPECT_DOUBLE_EQ(p.WrongPartRate(), 0.0);
  EXPECT_DOUBLE_EQ(p.UntexturedRate(), 0.0);
}

TEST(PartProvenance, PartIndexWithoutABodyPartIsRejected) {
  const Fixture f;
  ReferenceRender render;
  render.mask = ImageGray8(1, 1, 1, 255);
  render.part = Image<int32_t>(1, 1, 1, 3);
  render.source_frame = Image<int32_t>(1, 1, 1, 0);
  render.source_pixel = Image<float>(1, 1, 2, 0.0f);
  const std::vector<BodyPart> two = {BodyPart::kHead, BodyPart::kUpperTorso};
  EXPECT_THROW(MeasurePartProvenance(render, two, [&](int) { return f.source(); }), CheckError);
}

}  // namespace
}  // namespace reenact::eval
