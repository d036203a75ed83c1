#pragma once
// A generic CPU triangle rasteriser for an undistorted PinholeCamera, with a z-buffer and a
// per-pixel callback ("fragment shader"). Shared by the synthetic RGB-D scene and the CPU
// reference renderer of the cylinder model.
//
// Frames and units: vertices are given in the camera frame (OpenCV: x right, y down,
// z forward, metres). Pixel centres lie at integer coordinates (as PinholeCamera): pixel
// (x, y) is sampled at exactly u = x, v = y.
//
// Pipeline, per triangle:
//   1. Optional face culling, decided in 3D: a triangle (a, b, c) is front-facing when its
//      normal (b - a) x (c - a) points towards the camera centre, i.e. dot(n, a) < 0.
//   2. Clipping in the camera frame against the near plane z = near_z, the far plane
//      z = far_z (when finite) and four guard-band planes one image size outside the image
//      borders. So triangles behind the camera or crossing z = 0 draw exactly their part
//      with z >= near_z. Attributes are clipped linearly in 3D, which keeps them exact for
//      attributes that are affine over the 3D triangle.
//   3. Projection and snapping to 1/256 pixel; coverage from exact integer edge functions
//      with the top-left fill rule (a pixel centre on an edge belongs to the triangle only
//      if that edge is a top or a left edge), so triangles that share an edge draw each
//      pixel along it exactly once, and zero-area triangles draw nothing.
//   4. Perspective-correct interpolation: with screen-space barycentrics l_i,
//      1/z = sum l_i / z_i and attr = z * sum l_i attr_i / z_i.
//   5. Depth test (strictly closer than the buffer passes), then the shader; a shader that
//      returns true keeps the fragment and its depth is written; false discards it.
// Shading happens before later triangles may cover the pixel (early z), so a shader that
// writes colour must write unconditionally on keep: the last kept fragment wins, and the
// depth test guarantees it is the closest drawn so far.

#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <type_traits>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"

namespace reenact {

inline constexpr int kMaxRasterAttributes = 8;
using RasterAttributes = std::array<float, kMaxRasterAttributes>;

struct RasterVertex {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // camera frame, metres
  RasterAttributes attributes{};                       // the first attribute_count are used
};

// What the shader receives for one covered pixel that passed the depth test.
struct RasterFragment {
  int x = 0;                      // pixel column
  int y = 0;                      // pixel row
  double depth = 0;               // camera z of the surface at the pixel centre, metres
  RasterAttributes attributes{};  // perspective-correct; entries >= attribute_count are 0
  int primitive_id = 0;           // the caller's id of the triangle
  bool front_facing = true;       // see step 1 above
};

enum class CullMode { kNone, kBack, kFront };

struct RasterOptions {
  // Near clipping plane, metres along z; > 0. Default 0.01.
  double near_z = 0.01;
  // Far clipping plane, metres along z; > near_z or +infinity (no far plane). Default inf.
  double far_z = std::numeric_limits<double>::infinity();
  // How many attributes are interpolated, [0, kMaxRasterAttributes]. Default all 8.
  int attribute_count = kMaxRasterAttributes;
  // Which faces are dropped before rasterising. Default none.
  CullMode cull = CullMode::kNone;
  // Depth test against the buffer (strictly closer passes). Default on.
  bool depth_test = true;
  // Kept fragments write their depth. Default on.
  bool depth_write = true;

  // Throws CheckError when a field is out of range.
  void Check() const;
};

// A non-owning reference to any callable bool(const RasterFragment&); valid only while the
// callable it was made from lives (pass a lambda straight into a Draw call).
class FragmentShader {
 public:
  template <typename F>
    requires(!std::is_same_v<std::remove_cvref_t<F>, FragmentShader> &&
             std::is_invocable_r_v<bool, F&, const RasterFragment&>)
  FragmentShader(F&& f)  // NOLINT: implicit by design, like std::function_ref
      : object_(const_cast<void*>(static_cast<const void*>(&f))),
        call_([](void* o, const RasterFragment& fragment) -> bool {
          return (*static_cast<std::remove_reference_t<F>*>(o))(fragment);
        }) {}

  bool operator()(const RasterFragment& fragment) const { return call_(object_, fragment); }

 private:
  void* object_;
  bool (*call_)(void*, const RasterFragment&);
};

class Rasterizer {
 public:
  // camera: must pass Check() and have no distortion. The depth buffer starts cleared.
  explicit Rasterizer(const PinholeCamera& camera, const RasterOptions& options = {});

  const PinholeCamera& camera() const { return camera_; }
  const RasterOptions& options() const { return options_; }

  // Resets every depth to +infinity.
  void Clear();

  // Camera z in metres of the closest kept fragment per pixel; +infinity where none.
  const Image<double>& depth() const { return depth_; }

  // Draws one triangle. Throws CheckError if a vertex is not finite.
  void DrawTriangle(const RasterVertex& a, const RasterVertex& b, const RasterVertex& c,
                    int primitive_id, FragmentShader shader);

  // Draws an indexed mesh: triangle t uses vertices[triangles[t][0..2]] and the id
  // primitive_ids[t], or t itself when primitive_ids is empty. Throws CheckError on an index
  // out of range or a primitive_ids size that is neither 0 nor triangles.size().
  void DrawMesh(std::span<const RasterVertex> vertices,
                std::span<const Eigen::Vector3i> triangles, std::span<const int> primitive_ids,
                FragmentShader shader);

  // Counters since construction (for tests and benchmarks).
  struct Stats {
    int64_t triangles_submitted = 0;
    int64_t triangles_rasterized = 0;  // screen triangles after culling and clipping
    int64_t fragments_shaded = 0;      // shader calls
  };
  const Stats& stats() const { return stats_; }

 private:
  void RasterizeClipped(const RasterVertex& a, const RasterVertex& b, const RasterVertex& c,
                        int primitive_id, bool front_facing, FragmentShader shader);

  PinholeCamera camera_;
  RasterOptions options_;
  Image<double> depth_;
  Stats stats_;
};

}  // namespace reenact
