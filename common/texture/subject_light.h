#pragma once
// The light on the recorded subject, fitted from a clip's stored frames, so that a stored
// colour seen under one pose can be shown under another (issue 9, relighting: a texture of the
// back taken while the back faced the light must look shaded when the reenacted back faces
// away from it).
//
// Shading model, in the stored colour values (8-bit, per channel): a surface point of albedo
// a and unit outward world normal n shows
//   c = a * SubjectShade(n, L),   SubjectShade(n, L) = 1 + max(0, n . L)
// with the ambient share normalised to 1: L (world frame) points towards one directional
// light and |L| is its strength relative to the ambient light. L = 0 is flat light. (A
// Lambert scene with ambient share k and light direction l has L = l (1 - k) / k.)
// Relighting a stored colour c_then seen at normal n_then to normal n_now:
//   c_now = c_then * SubjectShade(n_now, L) / SubjectShade(n_then, L)
// a factor in [1 / (1 + |L|), 1 + |L|]: bounded, and exactly 1 when L = 0.
//
// The fit (FitSubjectLight): samples of one grey value each (mean of R, G, B), with the world
// normal and a surface bin (a patch of the body fixed to it, LightSampleBin) seen in several
// frames under different normals. For a candidate L every bin's albedo has the closed
// least-squares form a_b = sum c s / sum s^2 (s = SubjectShade(n, L)); the cost is the sum of
// squared residuals c - a_b s. L is searched over `directions` unit directions (a Fibonacci
// sphere) times `strengths` strengths geometric from max_strength / 2^(strengths-1) to
// max_strength, then refined by a pattern search on L (step halved on failure, down to 1e-3,
// at most 1000 evaluations). Then twice: every sample is reweighted by its residual under the
// L found (Cauchy weights, scale 1.4826 times the median |residual| but at least 2 grey levels)
// and L searched again with the weighted cost, so that pixels labelled with the wrong part or
// bin (another patch's colour) do not tilt it. gain = 1 - cost(L) / cost(0) under the last
// weights. The light is found when gain >= min_gain; otherwise L = 0 (no relighting) with the
// reason. A subject that never turns against the light, or flat light, gives no gain and so
// no light. Observability: normals of surfaces parallel to an axis measure only the part of L
// across it, so for an upright subject turning about the vertical the horizontal part of L
// is well determined and the vertical part only by the surfaces that face up or down.

#include <Eigen/Core>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"
#include "common/skeleton/skeleton.h"

namespace reenact {

// 1 + max(0, n . light); n unit (any length is used as given). Finite for finite input.
inline double SubjectShade(const Eigen::Vector3d& n, const Eigen::Vector3d& light) {
  const double d = n.dot(light);
  return 1.0 + (d > 0 ? d : 0.0);
}

struct LightSample {
  int bin = 0;                                                 // surface bin, >= 0
  Eigen::Vector3d normal_in_world = Eigen::Vector3d::UnitZ();  // unit, outward
  double value = 0;                                            // grey value, [0, 255]
};

struct SubjectLightFitOptions {
  int directions = 256;     // search directions, >= 8
  int strengths = 6;        // search strengths per direction, >= 1
  double max_strength = 4;  // largest |L| searched, > 0 (refinement may exceed it)
  double min_gain = 0.05;   // in [0, 1)
  int min_samples = 200;    // fewer usable samples: no light, >= 1
  int min_bins = 10;        // fewer bins seen in at least 2 samples: no light, >= 1

  // Throws CheckError when a field is out of range.
  void Check() const;
};

struct SubjectLightFit {
  Eigen::Vector3d light = Eigen::Vector3d::Zero();  // L, world frame; zero unless found
  bool found = false;
  double gain = 0;     // 1 - cost(L) / cost(0) of the best L searched (also when not found)
  int samples = 0;     // samples used: finite values, unit-length (within 1e-3) normals, bin >= 0
  int bins = 0;        // bins seen in at least 2 used samples (only their samples enter the cost)
  std::string reason;  // why no light was found; empty when found
};

// Fits L to the samples (see above). Samples with a non-finite value or normal, or a normal
// not of unit length within 1e-3, or a negative bin, are skipped. Precondition (CHECK):
// options pass Check().
SubjectLightFit FitSubjectLight(std::span<const LightSample> samples,
                                const SubjectLightFitOptions& options = {});

// Surface bins fixed to the body: part p, the height fraction t along the part's axis
// (PartJoints(p).first -> .second, clamped to [0, 1]) in axial_bins, and the angle about the
// axis in angular_bins, measured from the body's left direction (l_shoulder - r_shoulder
// for the arms, head and upper torso, l_hip - r_hip for the lower torso and legs) made
// orthogonal to the axis, turning towards axis x left. Bin index
// ((Index(p) * axial_bins) + axial) * angular_bins + angular.
struct LightSampleBins {
  // Defaults: bins of about 5 cm along a limb and 22.5 degrees about it. On the synthetic
  // CesiumMan clips 8 x 16 (stride 2) fits the scene's light to 3.6 / 0.9 degrees
  // (turn-and-kick / walk-handheld) where 4 x 8 (stride 3) gave 10.1 / 3.2: coarser bins
  // hold more albedo pattern. (The relit pictures differed by less than 0.03 dB.)
  int axial_bins = 8;     // >= 1 (kBodyPartCount * axial_bins * angular_bins fits in an int)
  int angular_bins = 16;  // >= 1
  // The left direction must be at least this far from parallel to the axis (sine of the
  // angle); below it the part's points get no bin, [0, 1).
  double min_sine = 0.3;
  void Check() const;
};

// The bin of a point x (sensor frame) of part `part` posed by skeleton_in_sensor; -1 when a
// joint the bin needs is missing, the axis is shorter than kMinBoneLength, the left
// direction is too close to the axis (or of zero length), or x is not finite.
// Precondition (CHECK): bins pass Check().
int LightSampleBin(const Skeleton& skeleton_in_sensor, BodyPart part, const Eigen::Vector3d& x,
                   const LightSampleBins& bins);

// One stored frame, as the clip holds it.
struct LightSampleFrame {
  const Skeleton* skeleton_in_sensor = nullptr;  // not null
  const PinholeCamera* camera = nullptr;         // the crop's camera, not null
  const ImageRgb8* color = nullptr;              // the crop, not null
  const ImageLabel8* part_labels = nullptr;      // the posed model's labels (visibility_maps.h)
  const Image<float>* depth_m = nullptr;         // metres, 0 = no reading
  Eigen::Matrix3d world_from_sensor = Eigen::Matrix3d::Identity();  // rotation (CHECK: 1e-6)
};

struct LightSampleOptions {
  int stride = 2;                  // every stride-th pixel in x and y, >= 1
  int normal_step = 2;             // pixels to each side for the depth normal, >= 1
  double max_depth_jump_m = 0.03;  // neighbours farther in depth than this x step: no normal
  int max_value = 250;             // any channel above: saturated, skipped; [1, 255]
  LightSampleBins bins;
  void Check() const;
};

// The surface normal at pixel (x, y) of a stored frame (sensor frame, unit, turned towards the
// camera): the cross product of the back-projected central differences normal_step pixels to
// each side in x and y. nullopt unless the pixel is labelled with a part (1..kBodyPartCount)
// and has a depth reading, and all four neighbours lie in the image, carry the same label and
// a reading within max_depth_jump_m * normal_step of the centre's depth.
std::optional<Eigen::Vector3d> DepthNormal(const Image<float>& depth_m,
                                           const ImageLabel8& part_labels,
                                           const PinholeCamera& camera, int x, int y,
                                           const LightSampleOptions& options);

// DepthNormal at every pixel (3 channels, sensor frame), (0, 0, 0) where there is none: the
// stored surface's own normals, which relighting carries to the viewer with the texture
// (common/render/texturing.h). Preconditions (CHECK): options and camera pass Check(), depth
// and labels 1 channel of the camera's size.
Image<float> DepthNormalMap(const Image<float>& depth_m, const ImageLabel8& part_labels,
                            const PinholeCamera& camera, const LightSampleOptions& options = {});

// Appends the frame's samples, in row-major pixel order: pixels on the stride grid (x and y
// multiples of stride) labelled with a part (labels outside 1..kBodyPartCount count as none),
// none of R, G, B above max_value, and with a DepthNormal (PinholeCamera::Unproject,
// distortion included), rotated to the world. The value is (R + G + B) / 3. The bin is
// LightSampleBin of the back-projected point; pixels without a bin are skipped.
// Preconditions (CHECK): options pass Check(); pointers (samples too) not null; camera passes
// Check(); colour 3 channels and labels and depth 1 channel of the camera's size;
// world_from_sensor a rotation (orthonormal within 1e-6, determinant > 0).
void AppendLightSamples(const LightSampleFrame& frame, const LightSampleOptions& options,
                        std::vector<LightSample>* samples);

}  // namespace reenact
