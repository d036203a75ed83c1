#include "viewer-client/render/window.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <functional>
#include <vector>

namespace reenact::viewer {
namespace {

int live_windows = 0;  // GLFW is initialised while a window lives (main thread only)

std::string GlfwError() {
  const char* description = nullptr;
  glfwGetError(&description);
  return description != nullptr ? description : "unknown GLFW error";
}

}  // namespace

std::optional<ViewerCommand> CommandForKey(int glfw_key) {
  switch (glfw_key) {
    case GLFW_KEY_SPACE: return ViewerCommand::kTogglePlay;
    case GLFW_KEY_LEFT: return ViewerCommand::kStepBackward;
    case GLFW_KEY_RIGHT: return ViewerCommand::kStepForward;
    case GLFW_KEY_EQUAL:
    case GLFW_KEY_KP_ADD: return ViewerCommand::kFaster;
    case GLFW_KEY_MINUS:
    case GLFW_KEY_KP_SUBTRACT: return ViewerCommand::kSlower;
    case GLFW_KEY_S: return ViewerCommand::kToggleSkeleton;
    case GLFW_KEY_C: return ViewerCommand::kToggleBareCylinders;
    case GLFW_KEY_T: return ViewerCommand::kToggleTexture;
    case GLFW_KEY_ESCAPE:
    case GLFW_KEY_Q: return ViewerCommand::kQuit;
    default: return std::nullopt;
  }
}

void WindowOptions::Check() const {
  REENACT_CHECK(width > 0 && height > 0, "window size must be positive");
  REENACT_CHECK(render_width > 0 && render_height > 0, "render size must be positive");
}

struct Window::State {
  GLFWwindow* window = nullptr;
  // Events collected by the GLFW callbacks during glfwPollEvents, then delivered.
  std::vector<std::function<void(WindowListener&)>> pending;
  bool dragging = false;
  double last_x = 0, last_y = 0;

  ~State() {
    if (window != nullptr) glfwDestroyWindow(window);
    if (--live_windows == 0) glfwTerminate();
  }
  void MakeCurrent() const {
    if (glfwGetCurrentContext() != window) glfwMakeContextCurrent(window);
  }
};

Expected<Window> Window::Create(const WindowOptions& options) {
  options.Check();
  if (live_windows == 0 && glfwInit() != GLFW_TRUE) {
    return MakeError("no_display", "cannot open a window: " + GlfwError() +
                                       " (set DISPLAY or WAYLAND_DISPLAY, or use --headless)");
  }
  auto state = std::make_unique<State>();
  ++live_windows;
  glfwDefaultWindowHints();
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  state->window =
      glfwCreateWindow(options.width, options.height, options.title.c_str(), nullptr, nullptr);
  if (state->window == nullptr) {
    return MakeError("no_display",
                     "cannot open a window with an OpenGL 3.3 core context: " + GlfwError());
  }
  glfwSetWindowUserPointer(state->window, state.get());
  using StatePtr = State*;
  static constexpr auto StateOf = [](GLFWwindow* w) {
    return static_cast<StatePtr>(glfwGetWindowUserPointer(w));
  };
  glfwMakeContextCurrent(state->window);
  glfwSwapInterval(options.vsync ? 1 : 0);

  glfwSetKeyCallback(state->window, [](GLFWwindow* w, int key, int, int action, int) {
    if (action == GLFW_RELEASE) return;
    const std::optional<ViewerCommand> command = CommandForKey(key);
    if (!command) return;
    const bool repeats =
        *command == ViewerCommand::kStepBackward || *command == ViewerCommand::kStepForward;
    if (action == GLFW_REPEAT && !repeats) return;
    StateOf(w)->pending.push_back([c = *command](WindowListener& l) { l.OnCommand(c); });
  });
  glfwSetMouseButtonCallback(state->window, [](GLFWwindow* w, int button, int action, int) {
    if (button != GLFW_MOUSE_BUTTON_LEFT) return;
    State* s = StateOf(w);
    s->dragging = action == GLFW_PRESS;
    glfwGetCursorPos(w, &s->last_x, &s->last_y);
  });
  glfwSetCursorPosCallback(state->window, [](GLFWwindow* w, double x, double y) {
    State* s = StateOf(w);
    if (!s->dragging) return;
    const double dx = x - s->last_x, dy = y - s->last_y;
    s->last_x = x;
    s->last_y = y;
    s->pending.push_back([dx, dy](WindowListener& l) { l.OnOrbit(dx, dy); });
  });
  glfwSetScrollCallback(state->window, [](GLFWwindow* w, double, double dy) {
    StateOf(w)->pending.push_back([dy](WindowListener& l) { l.OnZoom(dy); });
  });

  Expected<Renderer> renderer =
      Renderer::CreateForCurrentContext(options.render_width, options.render_height);
  if (!renderer) return renderer.error();
  return Window(std::move(state), std::move(renderer).value());
}

Window::Window(std::unique_ptr<State> state, Renderer renderer)
    : state_(std::move(state)), renderer_(std::move(renderer)) {}
Window::Window(Window&&) noexcept = default;
Window& Window::operator=(Window&& other) noexcept {
  if (this != &other) {
    if (state_) state_->MakeCurrent();
    renderer_.reset();
    state_ = std::move(other.state_);
    renderer_ = std::move(other.renderer_);
  }
  return *this;
}
Window::~Window() {
  if (state_) state_->MakeCurrent();
  renderer_.reset();
}

Renderer& Window::renderer() {
  state_->MakeCurrent();
  return *renderer_;
}

bool Window::ShouldClose() const { return glfwWindowShouldClose(state_->window) == GLFW_TRUE; }

void Window::RequestClose() { glfwSetWindowShouldClose(state_->window, GLFW_TRUE); }

void Window::PollEvents(WindowListener& listener) {
  glfwPollEvents();
  std::vector<std::function<void(WindowListener&)>> events;
  events.swap(state_->pending);
  for (const auto& deliver : events) deliver(listener);
}

void Window::Present() {
  state_->MakeCurrent();
  const auto [w, h] = framebuffer_size();
  renderer_->BlitToDefaultFramebuffer(w, h);
  glfwSwapBuffers(state_->window);
}

std::pair<int, int> Window::framebuffer_size() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(state_->window, &w, &h);
  return {w, h};
}

}  // namespace reenact::viewer
