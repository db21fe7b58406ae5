// cutaway/gl/context.hpp — an OpenGL 4.5 core context.
//
// Headless contexts come from EGL: the EGL device platform when a vendor driver exposes a
// hardware device, otherwise Mesa's surfaceless platform (llvmpipe on machines without a
// GPU). Windowed contexts (the viewer) come from GLFW and are made elsewhere; both end as a
// current context with libepoxy resolving the entry points.
//
//   auto context = cutaway::gl::HeadlessContext::create();   // throws cutaway::Error
//   std::puts(context->info().renderer.c_str());
#pragma once

#include <cstdint>
#include <memory>
#include <string>

namespace cutaway::gl {

// What the current context is; valid once a context is current.
struct ContextInfo {
  std::string vendor, renderer, version;
  // True for Mesa's software rasterisers (llvmpipe, softpipe): timer queries need a flush
  // after glBeginQuery there, and CPU kernels may beat fragment shaders.
  bool software = false;
  // Render target limits (0: none known): the largest texture side, and the most samples of
  // a colour, depth or integer multisample texture.
  int maxTextureSize = 0, maxColorSamples = 0, maxDepthSamples = 0, maxIntegerSamples = 0;
  static ContextInfo query();
  // Bytes of memory the device can give new textures now, 0 when it does not say: a GPU's free
  // video memory (GL_NVX_gpu_memory_info, GL_ATI_meminfo), or for a software rasteriser, whose
  // textures live in main memory, /proc/meminfo's MemAvailable.
  std::uint64_t availableMemory() const;
};

class HeadlessContext {
 public:
  // Creates and makes current a 4.5 core context; throws cutaway::Error with a one-line
  // reason when none can be had.
  static std::unique_ptr<HeadlessContext> create();
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

  const ContextInfo& info() const { return info_; }
  // Makes the context current on the calling thread. EGL lets a context be current on one
  // thread at a time: the thread that had it must release() it first.
  void makeCurrent() const;
  // Leaves the calling thread without a current context.
  void release() const;
  // "device" (EGL device platform) or "surfaceless" (Mesa surfaceless platform).
  const std::string& platform() const { return platform_; }

 private:
  HeadlessContext() = default;
  void* display_ = nullptr;
  void* context_ = nullptr;
  std::string platform_;
  ContextInfo info_;
};

}  // namespace cutaway::gl
