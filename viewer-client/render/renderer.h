#pragma once
// The viewer's OpenGL renderer: textured cylinders (thesis Eq. 16 per fragment, with the
// candidates and texturing modes of common/render/texturing.h), an optional
// floor grid (free viewpoint) or camera image behind (AR), and a skeleton overlay on top.
// One code path serves headless rendering (EGL surfaceless, owned context) and the window
// (render/window.h, the window's context). Every geometric quantity is in the viewer camera
// frame, OpenCV convention (x right, y down, z forward, metres).
//
// Drawing order: clear; background image (AR) as a full-screen quad, no depth; floor (depth
// tested and written); cylinders (the shaped unit mesh of common/render/cylinder_mesh.h,
// placed by ViewerFromUnitCylinder; depth tested, GL_LESS, the nearer fragment wins; discarded
// fragments write nothing); bones and joints on top, no depth. Only cylinder fragments set
// the subject mask. The projection is GlProjectionFromPinhole(camera) (near 0.05 m, far
// 50 m): a point that PinholeCamera::Project maps to (u, v) lights output pixel
// (round(u), round(v)). Distortion of either camera is ignored on the GPU.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/error/expected.h"
#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"
#include "common/model/cylinder_model.h"
#include "common/render/texturing.h"
#include "common/skeleton/skeleton.h"
#include "viewer-client/render/egl_context.h"

namespace reenact::viewer {

// One stored frame's subject crop, uploaded to the GPU once.
struct StoredTexture {
  ImageRgb8 color;       // channels 3
  ImageGray8 mask;       // channels 1, same size as color; 255 = subject, 0 = not
  PinholeCamera camera;  // intrinsics of this crop (Cropped() of the colour camera)
  // Visibility data (common/render/texturing.h; common/texture/visibility_maps.h makes
  // both), each empty or channels 1 of the crop's size: the posed cylinder model's part
  // labels (PartLabel or kBackgroundLabel; empty: no point counts as visible) and the
  // stored depth in metres (0 = no reading; empty: the depth test always passes).
  ImageLabel8 part_labels;
  Image<float> depth_m;
  // Relighting (common/render/texturing.h): the stored surface's normal at each texel, crop
  // camera frame, unit, (0, 0, 0) where unknown (common/texture/subject_light.h
  // DepthNormalMap); empty or channels 3 of the crop's size.
  Image<float> normals;
};

// One texture candidate of a cylinder (common/render/texturing.h).
struct TextureCandidate {
  int texture = 0;  // index returned by Renderer::UploadTexture
  // Similarity mapping a viewer-frame point on this cylinder to the stored frame's sensor
  // frame (thesis Eq. 16, p_n = Q Omega p*); bottom row (0, 0, 0, 1).
  Eigen::Matrix4d stored_from_viewer = Eigen::Matrix4d::Identity();
  double weight = 1;  // >= 0; used by TexturingMode::kBlendVisible
  // The subject light as this stored frame saw it, in the viewer frame (relighting,
  // common/render/texturing.h); finite. Zero with FrameDraw::subject_light zero: no relighting.
  Eigen::Vector3d stored_light = Eigen::Vector3d::Zero();
  // A fallback candidate (common/render/texturing.h): after every ranked one.
  bool fallback = false;
};

// One body-part cylinder to draw.
struct CylinderDraw {
  Eigen::Vector3d a = Eigen::Vector3d::Zero();  // axis end points, viewer frame, metres
  Eigen::Vector3d b = Eigen::Vector3d::UnitZ();
  double radius = 0.05;  // metres, > 0
  // Cross-sections along the axis (common/model/cylinder_model.h; default the plain
  // cylinder), values finite and > 0, and the unit direction the width runs along
  // (orthogonal to the axis; nullopt: the helper rule of common/render/cylinder_mesh.h).
  PartShape shape{};
  std::optional<Eigen::Vector3d> width_direction{};
  // Texture candidates, ranked then fallback ones, at most kMaxTextureCandidates; empty =
  // untextured.
  std::vector<TextureCandidate> candidates;
  BodyPart part = BodyPart::kHead;  // the body part modelled (visibility test (a))
  TexturingMode texturing = TexturingMode::kFirst;
  Eigen::Vector3f color{0.7f, 0.7f, 0.7f};  // flat colour (linear RGB in [0, 1]) when
                                            // untextured or FrameDraw::textured is false
};

// A grid on the floor plane for free-viewpoint presentation.
struct FloorGrid {
  Eigen::Isometry3d viewer_from_world = Eigen::Isometry3d::Identity();
  Eigen::Vector3d up_in_world = -Eigen::Vector3d::UnitY();   // floor normal, any length > 0
  Eigen::Vector3d point_on_floor_in_world = Eigen::Vector3d::Zero();  // a grid line crossing
  double extent_m = 3;     // half side of the square drawn around point_on_floor, metres
  double spacing_m = 0.5;  // grid line spacing, metres
};

// Everything one output frame shows.
struct FrameDraw {
  PinholeCamera camera;  // the viewer camera; its image size is the output size
  std::vector<CylinderDraw> cylinders;
  std::optional<FloorGrid> floor;          // free-viewpoint presentation
  const ImageRgb8* background = nullptr;   // AR: the viewer's camera image, camera's size
  Eigen::Vector3f clear_color{0.16f, 0.17f, 0.19f};
  bool textured = true;                    // false: bare cylinders in flat colours
  // Visibility test (b) of common/render/texturing.h, metres; finite, >= 0.
  double depth_tolerance_m = kDefaultDepthToleranceM;
  // The subject light as the viewer sees it now, viewer frame (relighting,
  // common/render/texturing.h); finite.
  Eigen::Vector3d subject_light = Eigen::Vector3d::Zero();
  // Skeleton overlay line segments (viewer frame), drawn on top with joint dots.
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> bones;
  Eigen::Vector3f bone_color{1.0f, 0.85f, 0.1f};
};

struct RenderedFrame {
  ImageRgb8 color;          // camera size, channels 3
  ImageGray8 subject_mask;  // 255 where a cylinder fragment was kept, else 0
};

// Move-only. All methods must run on the thread that created the renderer; a headless
// renderer makes its own context current on every call, a window renderer expects the
// window's context to be current.
class Renderer {
 public:
  // Owns a headless EGL context (egl_context.h; kAuto: Mesa surfaceless, else an EGL
  // device). Errors: "gl_unavailable" (no EGL / GL 3.3), "gl_shader".
  static Expected<Renderer> CreateHeadless(int width, int height,
                                           EglPlatform platform = EglPlatform::kAuto);
  // Uses the GL 3.3+ core context current on this thread (e.g. a GLFW window's).
  // Errors: "gl_unavailable" if none is current or it is older than 3.3, "gl_shader".
  static Expected<Renderer> CreateForCurrentContext(int width, int height);

  Renderer(Renderer&&) noexcept;
  Renderer& operator=(Renderer&&) noexcept;
  ~Renderer();

  // Uploads a crop (premultiplied RGBA: mask in alpha, linear filtering) and its visibility
  // and normal data (one RGBA32F texture: label or -1 without labels, depth in metres, the
  // normal's octahedral coordinates or 4 where none; nearest sampling) and returns its index,
  // counting from 0.
  // Preconditions (CHECK): colour has 3 channels, mask 1 channel and the same size, not empty,
  // camera has the crop's size and passes Check(), part labels and depth each empty or 1
  // channel and normals empty or 3 channels of the crop's size and finite.
  int UploadTexture(const StoredTexture& texture);
  size_t texture_count() const;
  // Frees every uploaded texture; indices start again at 0.
  void ClearTextures();

  // Draw + ReadBack.
  RenderedFrame Render(const FrameDraw& frame);
  // Draws into the offscreen framebuffer (resized to the camera if needed). Preconditions
  // (CHECK): camera passes Check(); at most kMaxTextureCandidates candidates per cylinder,
  // their texture indices uploaded, matrices, stored lights and weights finite, weights >= 0,
  // subject_light finite; radii > 0,
  // shape values finite and > 0, width directions and every point finite; depth_tolerance_m
  // finite and >= 0; background, if set, is RGB with the camera's size. A cylinder whose end
  // points coincide draws nothing.
  void Draw(const FrameDraw& frame);
  // The last Draw, rows flipped to top-down.
  RenderedFrame ReadBack() const;
  // Copies the last Draw to the current context's default framebuffer of the given size,
  // letterboxed to keep the aspect ratio (the window path).
  void BlitToDefaultFramebuffer(int framebuffer_width, int framebuffer_height) const;

  int width() const;
  int height() const;
  // The driver, as GL_RENDERER and GL_VERSION say, e.g. "llvmpipe (LLVM 15.0.6, 256 bits),
  // 4.5 (Core Profile) Mesa 22.3.6".
  std::string driver() const;

 private:
  struct Impl;
  explicit Renderer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace reenact::viewer
