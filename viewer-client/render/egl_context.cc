#include "viewer-client/render/egl_context.h"

#include <cstdio>
#include <cstring>
#include <string>

#include <epoxy/egl.h>

namespace reenact::viewer {

struct EglContext::State {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  ~State() {
    if (context != EGL_NO_CONTEXT) {
      if (eglGetCurrentContext() == context) {
        eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      }
      eglDestroyContext(display, context);
    }
  }
};

namespace {

std::string EglErrorHex() {
  char text[16];
  std::snprintf(text, sizeof(text), "0x%04X", static_cast<unsigned>(eglGetError()));
  return text;
}

bool HasExtension(const char* extensions, const char* name) {
  if (extensions == nullptr) return false;
  const size_t length = std::strlen(name);
  for (const char* p = extensions; (p = std::strstr(p, name)) != nullptr; p += length) {
    const bool starts = p == extensions || p[-1] == ' ';
    const bool ends = p[length] == '\0' || p[length] == ' ';
    if (starts && ends) return true;
  }
  return false;
}

Error Unavailable(const std::string& what) { return MakeError("gl_unavailable", what); }

// Initialises `display` and creates a current 3.3 core context on it, or says why not.
Expected<std::unique_ptr<EglContext::State>> ContextOn(EGLDisplay display) {
  if (display == EGL_NO_DISPLAY) return Unavailable("no display");
  auto state = std::make_unique<EglContext::State>();
  state->display = display;
  EGLint major = 0, minor = 0;
  if (!eglInitialize(display, &major, &minor)) {
    return Unavailable("eglInitialize failed (" + EglErrorHex() + ")");
  }
  const char* extensions = eglQueryString(display, EGL_EXTENSIONS);
  for (const char* needed : {"EGL_KHR_no_config_context", "EGL_KHR_surfaceless_context"}) {
    if (!HasExtension(extensions, needed)) return Unavailable(std::string(needed) + " missing");
  }
  if (!eglBindAPI(EGL_OPENGL_API)) return Unavailable("eglBindAPI(EGL_OPENGL_API) failed");
  const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3,
                               EGL_CONTEXT_MINOR_VERSION, 3,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK,
                               EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                               EGL_NONE};
  state->context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
  if (state->context == EGL_NO_CONTEXT) {
    return Unavailable("no OpenGL 3.3 core context (" + EglErrorHex() + ")");
  }
  if (eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, state->context) != EGL_TRUE) {
    return Unavailable("eglMakeCurrent failed (" + EglErrorHex() + ")");
  }
  return state;
}

}  // namespace

EglContext::EglContext(std::unique_ptr<State> state) : state_(std::move(state)) {}
EglContext::EglContext(EglContext&&) noexcept = default;
EglContext& EglContext::operator=(EglContext&&) noexcept = default;
EglContext::~EglContext() = default;

Expected<EglContext> EglContext::Create(EglPlatform platform) {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  std::string why;
  if (platform != EglPlatform::kDevice) {
    if (HasExtension(client, "EGL_MESA_platform_surfaceless")) {
      auto state = ContextOn(eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA,
                                                      EGL_DEFAULT_DISPLAY, nullptr));
      if (state) return EglContext(std::move(state).value());
      why += "surfaceless: " + state.error().message + ". ";
    } else {
      why += "EGL_MESA_platform_surfaceless is not offered. ";
    }
  }
  if (platform != EglPlatform::kSurfaceless) {
    if (HasExtension(client, "EGL_EXT_device_enumeration") &&
        HasExtension(client, "EGL_EXT_platform_device")) {
      EGLDeviceEXT devices[8];
      EGLint count = 0;
      if (!eglQueryDevicesEXT(8, devices, &count)) count = 0;
      for (EGLint i = 0; i < count; ++i) {
        auto state = ContextOn(eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i],
                                                        nullptr));
        if (state) return EglContext(std::move(state).value());
        why += "device " + std::to_string(i) + ": " + state.error().message + ". ";
      }
      if (count == 0) why += "no EGL device found. ";
    } else {
      why += "EGL_EXT_platform_device is not offered. ";
    }
  }
  return MakeError("gl_unavailable", "headless OpenGL (EGL) unavailable: " + why +
                                         "Install Mesa's EGL (libegl-mesa0) or a GPU driver "
                                         "with EGL, or filter out the Gl* tests.");
}

bool EglContext::MakeCurrent() const {
  if (eglGetCurrentContext() == state_->context) return true;
  return eglMakeCurrent(state_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, state_->context) ==
         EGL_TRUE;
}

}  // namespace reenact::viewer
