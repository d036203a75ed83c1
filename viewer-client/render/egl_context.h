#pragma once
// A headless OpenGL 3.3 core context through EGL: no window, no display server; rendering
// goes to framebuffer objects. Platforms: Mesa's surfaceless platform
// (EGL_MESA_platform_surfaceless, e.g. llvmpipe in CI), else an EGL device
// (EGL_EXT_platform_device, as NVIDIA's driver offers on GPU servers without a display).
// The context has no config (EGL_KHR_no_config_context) and no surface
// (EGL_KHR_surfaceless_context). Move-only; the context is destroyed with its owner. EGL
// displays are process-wide and never terminated (other contexts may share them).

#include <memory>

#include "common/error/expected.h"

namespace reenact::viewer {

enum class EglPlatform {
  kAuto,         // surfaceless, then each EGL device in turn
  kSurfaceless,  // EGL_MESA_platform_surfaceless only
  kDevice,       // EGL_EXT_platform_device only (first device that gives a context)
};

class EglContext {
 public:
  // Errors (code "gl_unavailable") when no platform tried gives a 3.3 core context; the
  // message says what each attempt lacked. The new context is made current.
  static Expected<EglContext> Create(EglPlatform platform = EglPlatform::kAuto);

  EglContext(EglContext&&) noexcept;
  EglContext& operator=(EglContext&&) noexcept;
  ~EglContext();

  // Makes this context current on the calling thread (no surface). Cheap if it already is.
  // Returns false if EGL refuses.
  bool MakeCurrent() const;

  struct State;  // opaque: EGL display and context

 private:
  explicit EglContext(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace reenact::viewer
