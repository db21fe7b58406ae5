// cutaway/gl/window_context.hpp — an OpenGL 4.5 core context with a window (GLFW), for the
// interactive viewer; the headless EGL context (context.hpp) stays the one for everything else.
//
// Only programs that link `cutaway-window` (and so GLFW) get it: the library and the CLI do
// not depend on a display server.
//
//   auto window = cutaway::gl::WindowContext::create({.title = "view", .width = 800,
//                                                     .height = 600});   // throws cutaway::Error
//   cutaway::Renderer renderer(scene, window->info());
//   while (!window->shouldClose()) { window->pollEvents(); …; window->swapBuffers(); }
#pragma once

#include <memory>
#include <string>

#include "cutaway/gl/context.hpp"

struct GLFWwindow;

namespace cutaway::gl {

struct WindowOptions {
  std::string title = "cutaway";
  int width = 800, height = 600;  // window size in screen coordinates
  bool vsync = true;
};

class WindowContext {
 public:
  // Opens the window and makes its 4.5 core context current; throws cutaway::Error with a
  // one-line reason (e.g. no display) when that fails.
  static std::unique_ptr<WindowContext> create(const WindowOptions& options);
  ~WindowContext();
  WindowContext(const WindowContext&) = delete;
  WindowContext& operator=(const WindowContext&) = delete;

  GLFWwindow* window() const { return window_; }
  const ContextInfo& info() const { return info_; }
  bool shouldClose() const;
  void requestClose();
  void pollEvents();
  // Blocks until an event arrives or `seconds` pass (nothing to redraw in between).
  void waitEvents(double seconds);
  void swapBuffers();
  void setVsync(bool on);
  // Size of the default framebuffer in pixels (differs from the window size on HiDPI).
  void framebufferSize(int& width, int& height) const;
  // Framebuffer pixels per window coordinate (cursor positions are in window coordinates).
  float pixelScale() const;

 private:
  WindowContext() = default;
  GLFWwindow* window_ = nullptr;
  ContextInfo info_;
};

}  // namespace cutaway::gl
