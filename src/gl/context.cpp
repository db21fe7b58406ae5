#include "cutaway/gl/context.hpp"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <vector>

#include "cutaway/core/error.hpp"

namespace cutaway::gl {

namespace {

bool hasExtension(const char* list, const char* name) {
  if (!list) return false;
  const std::size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)); p += n)
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

// A hardware EGL device, if a vendor driver exposes one (Mesa's software device is skipped:
// the surfaceless platform gives the same rasteriser with fewer requirements).
EGLDisplay hardwareDeviceDisplay() {
  const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!hasExtension(clientExtensions, "EGL_EXT_device_enumeration") ||
      !hasExtension(clientExtensions, "EGL_EXT_platform_device"))
    return EGL_NO_DISPLAY;
  EGLint count = 0;
  if (!eglQueryDevicesEXT(0, nullptr, &count) || count <= 0) return EGL_NO_DISPLAY;
  std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
  eglQueryDevicesEXT(count, devices.data(), &count);
  for (EGLint i = 0; i < count; ++i) {
    const char* deviceExtensions = eglQueryDeviceStringEXT(devices[std::size_t(i)], EGL_EXTENSIONS);
    if (hasExtension(deviceExtensions, "EGL_MESA_device_software")) continue;
    EGLDisplay display =
        eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[std::size_t(i)], nullptr);
    EGLint major = 0, minor = 0;
    if (display != EGL_NO_DISPLAY && eglInitialize(display, &major, &minor)) return display;
  }
  return EGL_NO_DISPLAY;
}

EGLDisplay surfacelessDisplay() {
  const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!hasExtension(clientExtensions, "EGL_MESA_platform_surfaceless")) return EGL_NO_DISPLAY;
  EGLDisplay display =
      eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  EGLint major = 0, minor = 0;
  if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor)) return EGL_NO_DISPLAY;
  return display;
}

}  // namespace

ContextInfo ContextInfo::query() {
  ContextInfo info;
  auto str = [](GLenum e) {
    const auto* s = reinterpret_cast<const char*>(glGetString(e));
    return std::string(s ? s : "");
  };
  info.vendor = str(GL_VENDOR);
  info.renderer = str(GL_RENDERER);
  info.version = str(GL_VERSION);
  info.software = info.renderer.find("llvmpipe") != std::string::npos ||
                  info.renderer.find("softpipe") != std::string::npos;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &info.maxTextureSize);
  glGetIntegerv(GL_MAX_COLOR_TEXTURE_SAMPLES, &info.maxColorSamples);
  glGetIntegerv(GL_MAX_DEPTH_TEXTURE_SAMPLES, &info.maxDepthSamples);
  glGetIntegerv(GL_MAX_INTEGER_SAMPLES, &info.maxIntegerSamples);
  return info;
}

std::uint64_t ContextInfo::availableMemory() const {
  if (software) {
    std::ifstream meminfo("/proc/meminfo");
    std::string key;
    std::uint64_t kib = 0;
    while (meminfo >> key >> kib) {
      if (key == "MemAvailable:") return kib * 1024;
      meminfo.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
    }
    return 0;
  }
  GLint kib[4] = {0, 0, 0, 0};
  if (epoxy_has_gl_extension("GL_NVX_gpu_memory_info"))
    glGetIntegerv(GL_GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX, kib);
  else if (epoxy_has_gl_extension("GL_ATI_meminfo"))
    glGetIntegerv(GL_TEXTURE_FREE_MEMORY_ATI, kib);  // [0]: the total free, KiB
  return kib[0] > 0 ? std::uint64_t(kib[0]) * 1024 : 0;
}

std::unique_ptr<HeadlessContext> HeadlessContext::create() {
  std::unique_ptr<HeadlessContext> self(new HeadlessContext);
  EGLDisplay display = hardwareDeviceDisplay();
  self->platform_ = "device";
  if (display == EGL_NO_DISPLAY) {
    display = surfacelessDisplay();
    self->platform_ = "surfaceless";
  }
  if (display == EGL_NO_DISPLAY)
    throw Error("no headless EGL display: neither an EGL device nor Mesa's surfaceless platform");
  self->display_ = display;
  if (!eglBindAPI(EGL_OPENGL_API)) throw Error("EGL cannot bind the desktop OpenGL API");

  const EGLint configAttributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint configCount = 0;
  const bool noConfig =
      hasExtension(eglQueryString(display, EGL_EXTENSIONS), "EGL_KHR_no_config_context");
  if (!noConfig &&
      (!eglChooseConfig(display, configAttributes, &config, 1, &configCount) || configCount == 0))
    throw Error("EGL has no config for desktop OpenGL");

  const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                      4,
                                      EGL_CONTEXT_MINOR_VERSION,
                                      5,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                      EGL_NONE};
  EGLContext context = eglCreateContext(display, noConfig ? EGL_NO_CONFIG_KHR : config,
                                        EGL_NO_CONTEXT, contextAttributes);
  if (context == EGL_NO_CONTEXT)
    throw Error("no OpenGL 4.5 core context available (EGL " + self->platform_ +
                " platform, eglCreateContext failed)");
  self->context_ = context;
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context))
    throw Error("cannot make the OpenGL context current without a surface");
  if (epoxy_gl_version() < 45)
    throw Error("OpenGL 4.5 core required, the driver gives " +
                std::to_string(epoxy_gl_version() / 10) + "." +
                std::to_string(epoxy_gl_version() % 10));
  self->info_ = ContextInfo::query();
  return self;
}

void HeadlessContext::makeCurrent() const {
  if (eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) return;
  char code[16];
  std::snprintf(code, sizeof code, "0x%04X", unsigned(eglGetError()));
  throw Error(std::string("cannot make the OpenGL context current on this thread (EGL error ") +
              code + ")");
}

void HeadlessContext::release() const {
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

HeadlessContext::~HeadlessContext() {
  if (display_) {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (context_) eglDestroyContext(display_, context_);
    // No eglTerminate: it unloads Mesa's driver, whose once-per-process allocations then
    // show up as leaks; displays are per process anyway and are released at exit.
  }
}

}  // namespace cutaway::gl
