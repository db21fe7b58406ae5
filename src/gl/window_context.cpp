#include "cutaway/gl/window_context.hpp"

#include <dlfcn.h>
#include <epoxy/gl.h>
#include <link.h>
// After epoxy: GLFW must not include the system GL header itself.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <string>
#include <string_view>
#include <vector>

#include "cutaway/core/error.hpp"

namespace cutaway::gl {

namespace {

// GLFW reports failures through a callback; the last one becomes the exception's reason.
std::string& lastGlfwError() {
  static std::string message;
  return message;
}

void onGlfwError(int, const char* description) {
  lastGlfwError() = description ? description : "unknown GLFW error";
}

// The DRI drivers that GLX loaded for this context stay loaded to the end of the process (as
// the headless context keeps EGL's, see context.cpp): glfwTerminate unloads libGL, which
// unloads the driver, and the driver's once-per-process allocations then read as leaks to
// LeakSanitizer (Mesa's swrast_dri.so under Xvfb).
void keepDriversLoaded() {
  std::vector<std::string> drivers;
  dl_iterate_phdr(
      [](dl_phdr_info* info, std::size_t, void* out) {
        const std::string_view name = info->dlpi_name ? info->dlpi_name : "";
        if (name.ends_with("_dri.so"))
          static_cast<std::vector<std::string>*>(out)->emplace_back(name);
        return 0;
      },
      &drivers);
  // Outside dl_iterate_phdr, which holds the loader's lock.
  for (const auto& driver : drivers)
    dlopen(driver.c_str(), RTLD_LAZY | RTLD_NOLOAD | RTLD_NODELETE);
}

}  // namespace

std::unique_ptr<WindowContext> WindowContext::create(const WindowOptions& options) {
  glfwSetErrorCallback(onGlfwError);
  lastGlfwError().clear();
  if (!glfwInit()) throw Error("no display for a window (" + lastGlfwError() + ")");
  std::unique_ptr<WindowContext> self(new WindowContext);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  // The renderer resolves its own multisample targets; the window needs none.
  glfwWindowHint(GLFW_SAMPLES, 0);
  self->window_ =
      glfwCreateWindow(options.width, options.height, options.title.c_str(), nullptr, nullptr);
  if (!self->window_) {
    glfwTerminate();
    throw Error("cannot open an OpenGL 4.5 core window (" + lastGlfwError() + ")");
  }
  glfwMakeContextCurrent(self->window_);
  if (epoxy_gl_version() < 45)
    throw Error("OpenGL 4.5 core required, the window's driver gives " +
                std::to_string(epoxy_gl_version() / 10) + "." +
                std::to_string(epoxy_gl_version() % 10));
  keepDriversLoaded();
  self->setVsync(options.vsync);
  self->info_ = ContextInfo::query();
  return self;
}

WindowContext::~WindowContext() {
  if (window_) glfwDestroyWindow(window_);
  glfwTerminate();
}

bool WindowContext::shouldClose() const {
  return glfwWindowShouldClose(window_);
}

void WindowContext::requestClose() {
  glfwSetWindowShouldClose(window_, GLFW_TRUE);
}

void WindowContext::pollEvents() {
  glfwPollEvents();
}

void WindowContext::waitEvents(double seconds) {
  glfwWaitEventsTimeout(seconds);
}

void WindowContext::swapBuffers() {
  glfwSwapBuffers(window_);
}

void WindowContext::setVsync(bool on) {
  glfwSwapInterval(on ? 1 : 0);
}

void WindowContext::framebufferSize(int& width, int& height) const {
  glfwGetFramebufferSize(window_, &width, &height);
}

float WindowContext::pixelScale() const {
  int fw = 0, fh = 0, ww = 0, wh = 0;
  glfwGetFramebufferSize(window_, &fw, &fh);
  glfwGetWindowSize(window_, &ww, &wh);
  return ww > 0 ? float(fw) / float(ww) : 1.0f;
}

}  // namespace cutaway::gl
