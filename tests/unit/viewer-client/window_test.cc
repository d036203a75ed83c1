#include "viewer-client/render/window.h"

#include <cstdlib>
#include <optional>
#include <string>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <gtest/gtest.h>

namespace reenact::viewer {
namespace {

TEST(WindowKeys, MapsThePlayerKeys) {
  EXPECT_EQ(CommandForKey(GLFW_KEY_SPACE), ViewerCommand::kTogglePlay);
  EXPECT_EQ(CommandForKey(GLFW_KEY_LEFT), ViewerCommand::kStepBackward);
  EXPECT_EQ(CommandForKey(GLFW_KEY_RIGHT), ViewerCommand::kStepForward);
  EXPECT_EQ(CommandForKey(GLFW_KEY_EQUAL), ViewerCommand::kFaster);
  EXPECT_EQ(CommandForKey(GLFW_KEY_KP_ADD), ViewerCommand::kFaster);
  EXPECT_EQ(CommandForKey(GLFW_KEY_MINUS), ViewerCommand::kSlower);
  EXPECT_EQ(CommandForKey(GLFW_KEY_KP_SUBTRACT), ViewerCommand::kSlower);
  EXPECT_EQ(CommandForKey(GLFW_KEY_S), ViewerCommand::kToggleSkeleton);
  EXPECT_EQ(CommandForKey(GLFW_KEY_C), ViewerCommand::kToggleBareCylinders);
  EXPECT_EQ(CommandForKey(GLFW_KEY_T), ViewerCommand::kToggleTexture);
  EXPECT_EQ(CommandForKey(GLFW_KEY_ESCAPE), ViewerCommand::kQuit);
  EXPECT_EQ(CommandForKey(GLFW_KEY_A), std::nullopt);
}

// Unsets an environment variable for the scope, then puts it back.
class ScopedUnsetEnv {
 public:
  explicit ScopedUnsetEnv(const char* name) : name_(name) {
    if (const char* value = std::getenv(name)) saved_ = value;
    unsetenv(name);
  }
  ~ScopedUnsetEnv() {
    if (saved_) setenv(name_, saved_->c_str(), 1);
  }

 private:
  const char* name_;
  std::optional<std::string> saved_;
};

TEST(WindowNoDisplay, CreateFailsWithAClearError) {
  const ScopedUnsetEnv display("DISPLAY"), wayland("WAYLAND_DISPLAY");
  Expected<Window> window = Window::Create(WindowOptions{});
  ASSERT_FALSE(window.ok());
  EXPECT_EQ(window.error().code, "no_display");
  EXPECT_NE(window.error().message.find("--headless"), std::string::npos);
  // A second attempt fails the same way (GLFW is left uninitialised, nothing leaks).
  Expected<Window> again = Window::Create(WindowOptions{});
  ASSERT_FALSE(again.ok());
  EXPECT_EQ(again.error().code, "no_display");
}

TEST(WindowNoDisplay, RejectsANonPositiveSize) {
  WindowOptions options;
  options.width = 0;
  EXPECT_THROW(options.Check(), CheckError);
}

}  // namespace
}  // namespace reenact::viewer
