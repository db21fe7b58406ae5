#include "viewer.hpp"

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "camera_controller.hpp"
#include "cutaway/core/error.hpp"
#include "cutaway/cutters/adaptive.hpp"
#include "cutaway/frame/aov.hpp"
#include "panels/panels.hpp"

namespace cutaway::view {

namespace fs = std::filesystem;

namespace {

constexpr float kOrbitDegreesPerPixel = 0.4f;
constexpr float kZoomPerWheelStep = 1.15f;
constexpr float kClickSlopPixels = 3.0f;  // a press that moved less than this is a click
constexpr glm::vec4 kSelectionColor{1.0f, 0.55f, 0.0f, 1.0f};
constexpr const char* kFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

// Turns a texture into what ImGui draws.
ImTextureID textureId(GLuint texture) {
  return reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(texture));
}

// Draws `texture` (rows bottom to top, as OpenGL stores them) over the whole display.
void drawFullscreen(GLuint texture) {
  ImGui::GetBackgroundDrawList()->AddImage(textureId(texture), ImVec2(0, 0),
                                           ImGui::GetIO().DisplaySize, ImVec2(0, 1), ImVec2(1, 0));
}

void upload(gl::Texture& texture, const Rgba8Image& image) {
  GLint w = 0, h = 0;
  if (texture) {
    glGetTextureLevelParameteriv(texture.id(), 0, GL_TEXTURE_WIDTH, &w);
    glGetTextureLevelParameteriv(texture.id(), 0, GL_TEXTURE_HEIGHT, &h);
  }
  if (!texture || w != image.width || h != image.height)
    texture = gl::Texture::create2D(GL_RGBA8, image.width, image.height);
  glTextureSubImage2D(texture.id(), 0, 0, 0, image.width, image.height, GL_RGBA, GL_UNSIGNED_BYTE,
                      image.pixels.data());
}

std::string formatValue(const float* v, int channels) {
  std::ostringstream s;
  s.precision(6);
  if (channels == 1) {
    s << v[0];
  } else {
    s << "(";
    for (int i = 0; i < channels; ++i) s << (i ? ", " : "") << v[i];
    s << ")";
  }
  return s.str();
}

double millisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

// Appended to an error that a reload, an open or an option change could not survive.
constexpr const char* kKept = " (the last good scene stays)";

}  // namespace

Viewer::Viewer(const ViewerOptions& options) : options_(options) {
  if (!options.script.empty()) script_ = loadScript(options.script);
  Scene scene = loadScene(options.scene);  // first: it names a folder or a device as such
  adopt(std::move(scene), SceneDocument::load(options.scene), options.scene, false);
  state_.showPanels = options.panels;

  const int width = options.width > 0 ? options.width : original_.width;
  const int height = options.height > 0 ? options.height : original_.height;
  try {
    window_ = gl::WindowContext::create(
        {.title = title(), .width = width, .height = height, .vsync = !script_});
  } catch (const Error& e) {
    throw Error(e.reason() + "; without a display, render with `cutaway render " +
                options.scene.string() + " -o OUT.png`");
  }
  state_.rendererName = window_->info().renderer;

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // the layout is fixed; a stray imgui.ini would be clutter
  // DejaVu Sans (Debian's fonts-dejavu-core) has the papers' notation (θ, §, ≥, ×, –), which
  // ImGui's built-in font (Latin-1 only) draws as '?'; without it the built-in font serves.
  static const ImWchar kGlyphRanges[] = {0x0020, 0x00FF, 0x0370, 0x03FF, 0x2000, 0x22FF, 0};
  if (std::error_code ec; fs::exists(kFont, ec))
    io.Fonts->AddFontFromFileTTF(kFont, 14.0f, nullptr, kGlyphRanges);
  ImGui::StyleColorsDark();
  ImGui::GetStyle().WindowRounding = 4.0f;
  ImGui::GetStyle().Colors[ImGuiCol_WindowBg].w = 0.88f;
  ImGui_ImplGlfw_InitForOpenGL(window_->window(), true);
  ImGui_ImplOpenGL3_Init("#version 450 core");
  state_.sceneChanged = true;
}

Viewer::~Viewer() {
  if (!window_) return;
  moving_.reset();
  renderer_.reset();
  aovTexture_.reset();
  overlayTexture_.reset();
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
}

float Viewer::aspect() const {
  return float(state_.scene.width) / float(state_.scene.height);
}

int Viewer::run() {
  auto last = std::chrono::steady_clock::now();
  while (!quit_ && !window_->shouldClose()) {
    const bool busy = script_ || state_.playing || state_.sceneChanged || state_.viewChanged ||
                      state_.aovChanged || state_.saveRequested || state_.screenshotRequested ||
                      state_.frameRequested || state_.reloadRequested || state_.flyMode ||
                      shown_ != renderer_.get();  // a frame drawn while moving, to redraw
    // Idle: sleep until an event instead of redrawing an unchanged view.
    if (busy)
      window_->pollEvents();
    else
      window_->waitEvents(0.5);
    const auto now = std::chrono::steady_clock::now();
    const float seconds = std::chrono::duration<float>(now - last).count();
    last = now;

    syncSize();
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    // The view's changes from the mouse, the wheel and the fly keys: the view moves.
    const bool changed = state_.viewChanged;
    state_.viewChanged = false;
    handleInput(seconds);
    if (state_.viewChanged) lastMove_ = now;
    state_.viewChanged = state_.viewChanged || changed;
    if (state_.playing) {
      float duration = state_.scene.duration();
      if (!state_.cameraPath.empty()) duration = std::max(duration, state_.cameraPath.back().time);
      state_.time = duration > 0 ? std::fmod(state_.time + seconds, duration) : 0.0f;
      state_.viewChanged = true;
    }
    if (script_) runScript();
    handleRequests();
    update();
    drawView();
    if (state_.showPanels) drawPanels();
    ImGui::Render();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, width_, height_);
    glDisable(GL_SCISSOR_TEST);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (!pendingWindowShot_.empty()) {
      try {
        windowShot(pendingWindowShot_);
      } catch (const Error& e) {
        scriptFailure_ = e.what();
        quit_ = true;
      }
      pendingWindowShot_.clear();
    }
    window_->swapBuffers();
  }
  if (!scriptFailure_.empty()) {
    std::fprintf(stderr, "cutaway-view: error: %s\n", scriptFailure_.c_str());
    return 1;
  }
  return 0;
}

void Viewer::syncSize() {
  int w = 0, h = 0;
  window_->framebufferSize(w, h);
  if (w <= 0 || h <= 0) return;  // minimised: keep the last size
  if (w == width_ && h == height_) return;
  width_ = w, height_ = h;
  state_.scene.width = w, state_.scene.height = h;
  state_.sceneChanged = true;
}

void Viewer::handleInput(float seconds) {
  const ImGuiIO& io = ImGui::GetIO();
  Camera& camera = state_.scene.camera;
  const float scale = window_->pixelScale();
  if (!io.WantCaptureKeyboard) {
    if (ImGui::IsKeyPressed(GLFW_KEY_TAB, false)) state_.flyMode = !state_.flyMode;
    if (ImGui::IsKeyPressed(GLFW_KEY_F, false)) state_.frameRequested = true;
    if (ImGui::IsKeyPressed(GLFW_KEY_H, false)) state_.showPanels = !state_.showPanels;
    if (ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false)) state_.selection.clear();
    if (ImGui::IsKeyPressed(GLFW_KEY_F12, false)) state_.screenshotRequested = true;
    if (ImGui::IsKeyPressed(GLFW_KEY_F5, false)) state_.reloadRequested = true;
    if (io.KeyCtrl && ImGui::IsKeyPressed(GLFW_KEY_S, false)) state_.saveRequested = true;
    if (!io.KeyCtrl && ImGui::IsKeyPressed(GLFW_KEY_P, false)) {
      camera.setProjection(camera.projection == Projection::Perspective ? Projection::Orthographic
                                                                        : Projection::Perspective);
      state_.viewChanged = true;
    }
    if (state_.flyMode && !io.KeyCtrl) {
      // Half the scene's radius per second; Shift for four times that.
      const float speed =
          0.5f * sceneRadius_ * (io.KeyShift ? 4.0f : 1.0f) * std::min(seconds, 0.1f);
      GLFWwindow* w = window_->window();
      const auto down = [w](int key) { return glfwGetKey(w, key) == GLFW_PRESS ? 1.0f : 0.0f; };
      const glm::vec3 move(down(GLFW_KEY_D) - down(GLFW_KEY_A), down(GLFW_KEY_E) - down(GLFW_KEY_Q),
                           down(GLFW_KEY_W) - down(GLFW_KEY_S));
      if (move != glm::vec3(0.0f)) fly(camera, move * speed), state_.viewChanged = true;
    }
  }
  bool pressed = false;
  for (int button = 0; button < 3; ++button)
    if (ImGui::IsMouseClicked(button)) viewDrag_ = !io.WantCaptureMouse, pressed = true;
  if (!viewDrag_ && io.WantCaptureMouse) return;
  if (!io.WantCaptureMouse && io.MouseWheel != 0.0f) {
    zoom(camera, std::pow(kZoomPerWheelStep, io.MouseWheel));
    state_.viewChanged = true;
  }
  if (!viewDrag_) return;
  const glm::vec2 delta(io.MouseDelta.x * scale, io.MouseDelta.y * scale);
  // The frame of a press also carries the cursor's motion before it (a slow frame on a
  // software rasteriser can hold a long way): a drag starts with the next frame.
  const bool moved = delta != glm::vec2(0.0f) && !pressed;
  if (ImGui::IsMouseDown(0) && !io.KeyShift && moved) {
    if (state_.flyMode)
      look(camera, delta.x * kOrbitDegreesPerPixel * 0.5f, -delta.y * kOrbitDegreesPerPixel * 0.5f);
    else
      orbit(camera, -delta.x * kOrbitDegreesPerPixel, delta.y * kOrbitDegreesPerPixel);
    state_.viewChanged = true;
  }
  if ((ImGui::IsMouseDown(1) || ImGui::IsMouseDown(2) || (ImGui::IsMouseDown(0) && io.KeyShift)) &&
      moved) {
    // The scene follows the cursor: a drag by one view height pans by one view height.
    pan(camera, -delta.x / float(height_), delta.y / float(height_));
    state_.viewChanged = true;
  }
  if (ImGui::IsMouseReleased(0) &&
      io.MouseDragMaxDistanceSqr[0] < kClickSlopPixels * kClickSlopPixels)
    pick(int(io.MousePos.x * scale), int(io.MousePos.y * scale), io.KeyCtrl);
  if (!ImGui::IsMouseDown(0) && !ImGui::IsMouseDown(1) && !ImGui::IsMouseDown(2)) viewDrag_ = false;
}

void Viewer::runScript() {
  if (waitFrames_ > 0) {
    --waitFrames_;
    return;
  }
  if (scriptNext_ >= script_->commands.size()) {
    quit_ = true;  // a script that ends without "quit" still ends the session
    return;
  }
  const ScriptCommand& command = script_->commands[scriptNext_++];
  try {
    execute(command);
  } catch (const Error& e) {
    scriptFailure_ = script_->file + ": line " + std::to_string(command.line) + ": " + e.what();
    quit_ = true;
  }
}

void Viewer::execute(const ScriptCommand& c) {
  using Kind = ScriptCommand::Kind;
  Camera& camera = state_.scene.camera;
  const auto& n = c.numbers;
  switch (c.kind) {
    case Kind::Wait:
      waitFrames_ = int(n[0]);
      break;
    case Kind::Orbit:
      orbit(camera, n[0], n[1]), state_.viewChanged = true;
      break;
    case Kind::Look:
      look(camera, n[0], n[1]), state_.viewChanged = true;
      break;
    case Kind::Pan:
      pan(camera, n[0], n[1]), state_.viewChanged = true;
      break;
    case Kind::Zoom:
      zoom(camera, n[0]), state_.viewChanged = true;
      break;
    case Kind::Fly:
      fly(camera, glm::vec3(n[0], n[1], n[2])), state_.viewChanged = true;
      break;
    case Kind::Projection:
      camera.setProjection(c.text == "orthographic" ? Projection::Orthographic
                                                    : Projection::Perspective);
      state_.viewChanged = true;
      break;
    case Kind::Frame:
      frameSelection();
      break;
    case Kind::Select: {
      const auto found = objectsNamed(state_.scene, c.text);
      if (found.empty()) throw Error("no object or group named " + quote(c.text));
      state_.selection = {found.begin(), found.end()};
      break;
    }
    case Kind::Deselect:
      state_.selection.clear();
      break;
    case Kind::Pick:
      update(true);
      // Compared as read: a coordinate past INT_MAX would turn negative as an int.
      if (n[0] >= width_ || n[1] >= height_)
        throw Error("pixel (" + formatOptionValue(n[0]) + ", " + formatOptionValue(n[1]) +
                    ") is outside the " + std::to_string(width_) + "×" + std::to_string(height_) +
                    " view");
      pick(int(n[0]), int(n[1]), false);
      std::printf("pick %d %d: %s\n", int(n[0]), int(n[1]),
                  state_.selection.empty()
                      ? "background"
                      : state_.scene.objects[*state_.selection.begin()].name.c_str());
      break;
    case Kind::Role: {
      if (state_.selection.empty()) throw Error("\"role\" needs a selection");
      Role role = Role::Context;
      parseRole(c.text, role);
      setRole(state_, role);
      break;
    }
    case Kind::Importance:
      if (state_.selection.empty()) throw Error("\"importance\" needs a selection");
      setImportance(state_, n[0]);
      break;
    case Kind::Angle:
      if (state_.selection.empty()) throw Error("\"angle\" needs a selection");
      setLocalAngle(state_, c.text == "off" ? std::nullopt : std::optional<float>(n[0]));
      break;
    case Kind::Set: {
      // As `cutaway render --set`: the scene must still pass the checks across it (a cutter
      // without the roles it needs is refused, not drawn as if it were off).
      Scene checked = state_.scene;
      if (c.parameter->absent)  // an array entry past the end: said as such
        if (const std::string why = c.parameter->absent(&checked); !why.empty())
          throw Error(c.parameter->key, "", why);
      c.parameter->assign(checked, c.value);
      checkScene(checked, "set");
      setParameter(state_, *c.parameter, c.value);
      break;
    }
    case Kind::Aov:
      update();
      if (c.text == "off") {
        state_.aov.clear();
      } else {
        if (std::find(state_.aovNames.begin(), state_.aovNames.end(), c.text) ==
            state_.aovNames.end()) {
          std::string list;
          for (const auto& name : state_.aovNames) list += (list.empty() ? "" : ", ") + name;
          throw Error("this frame has no buffer " + quote(c.text) + " (it has: " + list + ")");
        }
        state_.aov = c.text;
      }
      if (!c.colormap.empty()) parseColormap(c.colormap, state_.colormap);
      state_.aovChanged = true;
      break;
    case Kind::Probe:
      update();
      if (n[0] >= width_ || n[1] >= height_)
        throw Error("pixel (" + formatOptionValue(n[0]) + ", " + formatOptionValue(n[1]) +
                    ") is outside the " + std::to_string(width_) + "×" + std::to_string(height_) +
                    " view");
      std::printf("probe %d %d: %s\n", int(n[0]), int(n[1]), valueAt(int(n[0]), int(n[1])).c_str());
      std::fflush(stdout);
      break;
    case Kind::Time:
      state_.time = n[0], state_.viewChanged = true;
      break;
    case Kind::Key:
      addCameraKey(state_, n[0]);
      break;
    case Kind::ClearPath:
      state_.cameraPath.clear();
      break;
    case Kind::Screenshot:
      screenshot(c.text);
      break;
    case Kind::ScreenshotWindow:
      // The window is read back after this frame's panels are drawn.
      pendingWindowShot_ = c.text;
      break;
    case Kind::Save:
      saveScene(c.text);
      break;
    case Kind::Reload:
      openScene(options_.scene, true);
      break;
    case Kind::Open:
      openScene(c.text, false);
      break;
    case Kind::SaveAovs:
      update(true);
      writeAovs(c.text, renderer_->readAovs(), viewCamera(state_), aspect());
      std::printf("wrote AOVs to %s\n", c.text.c_str());
      break;
    case Kind::Panels:
      state_.showPanels = c.on;
      break;
    case Kind::Moving:
      scriptMoving_ = c.on;
      break;
    case Kind::Timings: {
      const bool moving = state_.shownDivisor > 1;
      std::printf("timings: %dx%d%s, %.1f ms;", moving ? state_.movingWidth : width_,
                  moving ? state_.movingHeight : height_, moving ? " (while moving)" : "",
                  state_.renderMs);
      for (const PassTiming& t : state_.timings) std::printf(" %s %.1f", t.name.c_str(), t.gpuMs);
      std::printf("\n");
      std::fflush(stdout);
      break;
    }
    case Kind::Quit:
      quit_ = true;
      break;
  }
}

void Viewer::handleRequests() {
  if (state_.frameRequested) frameSelection(), state_.frameRequested = false;
  if (state_.reloadRequested) openScene(options_.scene, true), state_.reloadRequested = false;
  if (state_.saveRequested) {
    state_.saveRequested = false;
    try {
      saveScene(state_.savePath);
    } catch (const Error& e) {
      state_.status = e.what();
    }
  }
  if (state_.screenshotRequested) {
    state_.screenshotRequested = false;
    try {
      screenshot(state_.screenshotPath);
    } catch (const Error& e) {
      state_.status = e.what();
    }
  }
}

void Viewer::frameSelection() {
  frameBounds(state_.scene.camera, selectionBounds(state_), aspect());
  state_.viewChanged = true;
}

void Viewer::update(bool full) {
  // While a slider is dragged, a machine that needs longer than this for a new renderer and
  // its frame (llvmpipe: about a second for the engine) rebuilds when the slider is let go,
  // so that the slider follows the mouse; a faster one updates live.
  constexpr double kLiveRebuildMs = 150.0;
  const bool dragging = ImGui::GetCurrentContext() && ImGui::IsAnyItemActive() && !script_;
  if (state_.sceneChanged && renderer_ && dragging && rebuildMs_ > kLiveRebuildMs) return;
  if (state_.viewChanged && drawnCamera_) {
    // A move that 32-bit floats cannot draw (a zoom of 1e30, a pan of 1e300) is undone; a
    // file just opened with such a camera goes back whole, as when its frame fails.
    if (const std::string why =
            viewCamera(state_).unresolvable(aspect(), deepestDepthRange(state_.scene));
        !why.empty()) {
      if (replaced_) {
        restoreRendered("camera: " + why);
      } else {
        report("the view stays where it was (camera: " + why + ")");
        state_.scene.camera = *drawnCamera_;
      }
    }
  }
  const bool rebuilding = state_.sceneChanged;
  if (rebuilding) {
    const auto start = std::chrono::steady_clock::now();
    rebuild();
    rebuildMs_ = millisecondsSince(start);
  }
  // The inspector's buffers are read at the window's size: an AOV shown keeps it.
  const bool reduce = !full && moving() && state_.aov.empty() && options_.interactiveFps > 0 &&
                      state_.fullMs > 1000.0 / options_.interactiveFps;
  if (state_.viewChanged && reduce) {
    renderMoving();
  } else if (state_.viewChanged || (shown_ != renderer_.get() && (full || !moving()))) {
    renderFull();
    if (rebuilding) rebuildMs_ += state_.renderMs;
  }
  if (state_.aovChanged) refreshAov(), state_.aovChanged = false;
  if (shown_ == renderer_.get() &&
      (state_.selection != overlaySelection_ || (!overlayVisible_ && !state_.selection.empty())))
    refreshOverlay();
}

void Viewer::renderFull() {
  const auto start = std::chrono::steady_clock::now();
  // A resting view draws every object in scene order: an object that came into view would
  // otherwise be drawn after the others (exact depth ties), src/frame/occlusion_culling.hpp.
  renderer_->setOcclusionCulling(moving());
  if (!drawLive(*renderer_)) renderer_->render(viewCamera(state_), state_.time);
  if (shown_ != renderer_.get()) rendered_ = state_.scene, replaced_.reset();  // its first frame
  drawnCamera_ = state_.scene.camera;
  state_.timings = renderer_->timings();  // waits for the frame's timer queries
  state_.renderMs = state_.fullMs = millisecondsSince(start);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  readFrameBuffers();
  shown_ = renderer_.get();
  state_.shownDivisor = 1;
  state_.viewChanged = false;
  state_.aovChanged = true;
  overlaySelection_.clear();
  overlayVisible_ = false;
}

void Viewer::renderMoving() {
  const double goalMs = 1000.0 / options_.interactiveFps;
  // First guess: the cost in proportion to the pixels (vertex-bound scenes gain less; the
  // frames below correct it).
  if (movingDivisor_ == 0) {
    movingDivisor_ =
        std::clamp(int(std::ceil(std::sqrt(state_.fullMs / goalMs))), 2, kMaxMovingDivisor);
    movingMs_.fill(0.0);
    movingMs_[1] = state_.fullMs;
  }
  const int width = std::max(1, width_ / movingDivisor_);
  const int height = std::max(1, height_ / movingDivisor_);
  // The live scene at the reduced size: live options reach moving_ as they reach renderer_.
  const bool built = !moving_ || movingScene_.width != width || movingScene_.height != height;
  movingScene_ = state_.scene;
  addSimplifiedVersions(movingScene_, simplified_);
  // The adaptive cut's buffer no finer than the smaller image (its size is free, Burns08 §6),
  // and open meshes' back faces behind the cut all cut surfaces: their removal marks cost two
  // draws an open mesh and change a few pixels of the cut's rim.
  if (auto* adaptive = movingScene_.cutters.find<AdaptiveCutawayOptions>()) {
    adaptive->bufferSize =
        std::min(adaptive->bufferSize, int(std::bit_ceil(unsigned(std::max(width, height)))));
    using CutSurfaces = AdaptiveCutawayOptions::CutSurfaces;
    if (adaptive->cutSurfaces == CutSurfaces::All) adaptive->cutSurfaces = CutSurfaces::Unmarked;
  }
  movingScene_.width = width, movingScene_.height = height;
  movingScene_.samples = 1;  // stretched and soon redrawn: no multisampling
  if (built) {
    moving_.reset();
    try {
      moving_ = std::make_unique<Renderer>(movingScene_, window_->info());
    } catch (const Error& e) {
      report(std::string("frames at the window's size only: ") + e.what());
      options_.interactiveFps = 0;
      renderFull();
      return;
    }
    std::printf(
        "while the view moves: %dx%d (1/%d of %dx%d); a full frame took %.0f ms, the "
        "goal is %.0f ms\n",
        width, height, movingDivisor_, width_, height_, state_.fullMs, goalMs);
    std::fflush(stdout);
  }
  const auto start = std::chrono::steady_clock::now();
  if (!drawLive(*moving_)) {
    renderFull();
    return;
  }
  drawnCamera_ = state_.scene.camera;
  state_.timings = moving_->timings();
  state_.renderMs = millisecondsSince(start);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  // Stretched to the window: bilinear rather than blocks.
  glTextureParameteri(moving_->colorTexture(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  shown_ = moving_.get();
  state_.shownDivisor = movingDivisor_;
  state_.movingWidth = width, state_.movingHeight = height;
  state_.viewChanged = false;
  overlayVisible_ = false;  // the selection's outline follows the full frame's ids
  // Adapt the divisor for the next frame, from the second frame of a renderer on (its first
  // compiles shaders). Coarser while over the goal, unless the last step coarser saved under
  // 15% (the vertices, not the pixels, cost: a coarser image would only look worse); finer
  // when the next finer size would take under 80% of the goal (measured, or cost ∝ pixels
  // within half of it).
  if (built) return;
  const int d = movingDivisor_;
  const double t = movingMs_[std::size_t(d)] = state_.renderMs;
  const double finer = movingMs_[std::size_t(d - 1)];
  if (t > 1.25 * goalMs && d < kMaxMovingDivisor && !(finer > 0 && t > 0.85 * finer))
    ++movingDivisor_;
  else if (d > 2 &&
           (finer > 0 ? finer < 0.8 * goalMs : t * d * d / ((d - 1) * (d - 1)) < 0.5 * goalMs))
    --movingDivisor_;
}

bool Viewer::moving() const {
  // The view rests once the mouse lets go of it and this long after the last mouse, wheel or
  // fly-key change (a drag held still would otherwise start a full frame it must wait for).
  constexpr auto kRest = std::chrono::milliseconds(200);
  return scriptMoving_ || state_.playing || viewDrag_ ||
         std::chrono::steady_clock::now() - lastMove_ < kRest;
}

void Viewer::readFrameBuffers() {
  objectIds_ = renderer_->frame().read("objectId", 1);
}

void Viewer::refreshAov() {
  if (state_.aov.empty()) {
    aovImage_ = FloatImage();
    return;
  }
  const Frame& frame = renderer_->frame();
  if (frame.has(state_.aov)) {
    const TargetDesc& d = frame.desc(state_.aov);
    const int channels = d.aovChannels ? d.aovChannels : 1;
    aovImage_ = FloatImage(d.width ? d.width : frame.width(), d.height ? d.height : frame.height(),
                           channels);
    aovImage_.data = frame.read(state_.aov, channels);
  } else {
    // A cutter's own buffer (the terrain's distance texture, the clip surfaces' sprites):
    // rows top-down like a PFM, the view's bottom-up.
    for (Aov& extra : renderer_->extraAovs())
      if (extra.name == state_.aov) aovImage_ = std::move(extra.image);
    aovImage_.flipVertically();
  }
  const int channels = aovImage_.channels;
  const Colormap map = resolveColormap(state_.colormap, state_.aov, channels);
  state_.shownColormap = map;
  if (state_.autoRange) {
    // Over the pixels that show an object: background values (0 view depth, depth 1, zero
    // positions) would squeeze the objects' values into a sliver of the colour map. Buffers
    // of another size (the n×n cutaway buffer) have no background to leave out.
    std::vector<std::uint8_t> objects;
    if (aovImage_.width == width_ && aovImage_.height == height_ &&
        objectIds_.size() == std::size_t(width_) * std::size_t(height_)) {
      objects.resize(objectIds_.size());
      for (std::size_t i = 0; i < objects.size(); ++i) objects[i] = objectIds_[i] >= 0.0f;
    }
    state_.range =
        finiteRange(aovImage_, map == Colormap::Rgb || map == Colormap::Normals ? -1 : 0, objects);
  }
  upload(aovTexture_, applyColormap(aovImage_, map, state_.range));
}

void Viewer::refreshOverlay() {
  overlaySelection_ = state_.selection;
  overlayVisible_ = !state_.selection.empty() && int(objectIds_.size()) == width_ * height_;
  if (!overlayVisible_) return;
  // The selection's outline (2 pixels inside its silhouette) and a light tint, from the
  // object-id AOV, so that it follows the cut exactly.
  Rgba8Image overlay(width_, height_);
  const auto selected = [&](int x, int y) {
    if (x < 0 || y < 0 || x >= width_ || y >= height_) return false;
    const float id = objectIds_[std::size_t(y) * width_ + x];
    return id >= 0 && state_.selection.count(std::size_t(std::lround(id))) != 0;
  };
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) {
      if (!selected(x, y)) continue;
      bool edge = false;
      for (int dy = -2; dy <= 2 && !edge; ++dy)
        for (int dx = -2; dx <= 2 && !edge; ++dx) edge = !selected(x + dx, y + dy);
      std::uint8_t* p = overlay.at(x, y);
      for (int i = 0; i < 3; ++i) p[i] = std::uint8_t(kSelectionColor[i] * 255.0f);
      p[3] = edge ? 255 : 50;
    }
  upload(overlayTexture_, overlay);
}

void Viewer::drawView() {
  if (!shown_) return;
  drawFullscreen(state_.aov.empty() ? shown_->colorTexture() : aovTexture_.id());
  if (overlayVisible_ && state_.aov.empty()) drawFullscreen(overlayTexture_.id());
  const ImGuiIO& io = ImGui::GetIO();
  const float scale = window_->pixelScale();
  const int x = int(io.MousePos.x * scale), y = int(io.MousePos.y * scale);
  state_.cursorValue =
      x >= 0 && y >= 0 && x < width_ && y < height_ && !io.WantCaptureMouse ? valueAt(x, y) : "";
  // The inspected buffer's value follows the cursor (not while dragging the camera).
  if (!state_.aov.empty() && !state_.cursorValue.empty() && !viewDrag_)
    ImGui::SetTooltip("%s", state_.cursorValue.c_str());
}

std::string Viewer::valueAt(int x, int y) const {
  const int row = height_ - 1 - y;  // buffers are stored bottom to top
  std::string out;
  const auto objectAt = [&](int id) {
    return id >= 0 && std::size_t(id) < state_.scene.objects.size()
               ? state_.scene.objects[std::size_t(id)].name
               : std::string("background");
  };
  if (state_.aov.empty() || aovImage_.data.empty()) {
    if (objectIds_.size() != std::size_t(width_) * height_) return "";
    const int id = int(std::lround(objectIds_[std::size_t(row) * width_ + x]));
    return "pixel (" + std::to_string(x) + ", " + std::to_string(y) + "): " + objectAt(id);
  }
  // AOVs of another size (the cutaway buffer is n×n over the whole view) are stretched: the
  // texel under the pixel's centre.
  const auto under = [](int pixel, int pixels, int texels) {
    return std::min(texels - 1,
                    int((2 * std::int64_t(pixel) + 1) * texels / (2 * std::int64_t(pixels))));
  };
  const int tx = under(x, width_, aovImage_.width), ty = under(row, height_, aovImage_.height);
  const float* v = aovImage_.at(tx, ty);
  // The texel as [column, row] with rows from the top, as in the saved PFM's image.
  out = state_.aov + " [" + std::to_string(tx) + ", " + std::to_string(aovImage_.height - 1 - ty) +
        "] = " + formatValue(v, aovImage_.channels);
  if (state_.aov == "objectId") out += " (" + objectAt(int(std::lround(v[0]))) + ")";
  return out;
}

void Viewer::pick(int x, int y, bool add) {
  // The ids are the last frame's: after a resize they wait for the next render.
  if (x < 0 || y < 0 || x >= width_ || y >= height_ ||
      objectIds_.size() != std::size_t(width_) * std::size_t(height_))
    return;
  const float id = objectIds_[std::size_t(height_ - 1 - y) * width_ + x];
  if (!add) state_.selection.clear();
  if (id >= 0) {
    const std::size_t i = std::size_t(std::lround(id));
    if (add && state_.selection.count(i))
      state_.selection.erase(i);
    else
      state_.selection.insert(i);
  }
}

void Viewer::adopt(Scene loaded, SceneDocument document, const fs::path& path, bool keepView) {
  const Camera view = state_.scene.camera;
  original_ = std::move(loaded);
  document_ = std::move(document);
  options_.scene = path;
  state_.scene = original_;
  // The viewer's camera is explicit: "fit" resolved once, a path kept aside to be edited,
  // near/far left as the file has them (derived when absent).
  Camera& camera = state_.scene.camera;
  const Camera resolved = original_.resolvedCamera(0.0f);
  state_.cameraPath = camera.path;
  camera.path.clear();
  camera.fit = false;
  camera.eye = resolved.eye, camera.target = resolved.target, camera.height = resolved.height;
  if (keepView) camera = view;
  // Before the first frame (a script's first command), a move that cannot be drawn goes back
  // to the camera the file opened with.
  if (!drawnCamera_) drawnCamera_ = camera;
  // The frame keeps the window's size (resized, --size), not the file's resolution.
  if (width_ > 0) state_.scene.width = width_, state_.scene.height = height_;
  // Indices into the scene's objects and volumes of before.
  state_.selection.clear();
  state_.transferVolume = state_.transferRow = 0;
  state_.transferPoint = -1;
  // Bounds walk every vertex: once, for the fly speed (they cover the whole animation).
  sceneRadius_ = std::max(original_.bounds().radius(), 1e-3f);
  const fs::path stem = path.stem();
  state_.savePath = (path.parent_path() / (stem.string() + ".view.json")).string();
  state_.screenshotPath = stem.string() + "-view.png";
  state_.sceneChanged = true;
}

void Viewer::report(const std::string& message) {
  state_.status = message;
  // In a script, what went wrong followed its last command: name that line.
  std::string where;
  if (script_ && scriptNext_ > 0)
    where =
        script_->file + ": line " + std::to_string(script_->commands[scriptNext_ - 1].line) + ": ";
  std::fprintf(stderr, "cutaway-view: %s%s\n", where.c_str(), message.c_str());
}

void Viewer::openScene(const fs::path& path, bool keepView) {
  std::optional<Scene> loaded;
  std::optional<SceneDocument> document;
  try {
    loaded = loadScene(path);
    document = SceneDocument::load(path);
  } catch (const Error& e) {
    report(e.what() + std::string(kKept));
    return;
  }
  Replaced previous{original_, document_, state_, options_.scene, sceneRadius_};
  adopt(std::move(*loaded), std::move(*document), path, keepView);
  if (!rebuild()) {
    rollBackOpen(previous);  // the device refused it
    return;
  }
  replaced_ = std::move(previous);  // until its first frame has drawn
  showTitle();
  state_.status = (keepView ? "reloaded " : "opened ") + path.string();
  std::printf("%s\n", state_.status.c_str());
  std::fflush(stdout);
}

bool Viewer::rebuild() {
  // The renderer keeps a reference to the scene and builds its passes from it: a new one,
  // made after the old one is gone (two frames' targets may not fit together; glFinish lets
  // the driver free them before the new frame reads the free memory).
  moving_.reset();
  movingDivisor_ = 0;  // chosen again, with movingMs_, by the next frame drawn while moving
  shown_ = nullptr;
  renderer_.reset();
  glFinish();
  bool made = true;
  try {
    renderer_ = std::make_unique<Renderer>(state_.scene, window_->info());
  } catch (const Error& e) {
    if (!rendered_) throw;  // the first scene: nothing to go back to
    report(e.what() + std::string(kKept));
    state_.scene = *rendered_;
    // It drew before; should it fail now, the device is gone and the error ends the viewer.
    renderer_ = std::make_unique<Renderer>(state_.scene, window_->info());
    made = false;
  }
  const char* path = renderer_->cutawayComputePath();
  state_.computePath = path ? path : "";
  state_.aovNames = renderer_->frame().aovNames();
  state_.aovMeanings.clear();
  for (const auto& name : state_.aovNames)
    state_.aovMeanings[name] = renderer_->frame().desc(name).meaning;
  for (const Aov& extra : renderer_->extraAovs()) {
    state_.aovNames.push_back(extra.name);
    state_.aovMeanings[extra.name] = extra.meaning;
  }
  if (!state_.aov.empty() && std::find(state_.aovNames.begin(), state_.aovNames.end(),
                                       state_.aov) == state_.aovNames.end())
    state_.aov.clear();  // e.g. the cutter's buffers after turning it off
  state_.sceneChanged = false;
  state_.viewChanged = true;
  return made;
}

bool Viewer::drawLive(Renderer& renderer) {
  try {
    renderer.render(viewCamera(state_), state_.time);
    return true;
  } catch (const Error& e) {
    if (!rendered_) throw;  // the first scene: nothing to go back to
    restoreRendered(e.what());
  } catch (const std::bad_alloc&) {
    if (!rendered_) throw;
    restoreRendered("out of memory for this scene's frame");
  }
  return false;
}

void Viewer::restoreRendered(const std::string& why) {
  report(why + std::string(kKept));
  if (replaced_) {
    rollBackOpen(*replaced_);  // a scene just opened: its file, document and view go too
    replaced_.reset();
  } else {
    state_.scene = *rendered_;
    state_.sceneChanged = true;
  }
  rebuild();  // renderer_ anew, moving_ gone
}

std::string Viewer::title() const {
  return "cutaway-view — " + options_.scene.filename().string();
}

void Viewer::showTitle() {
  if (window_) glfwSetWindowTitle(window_->window(), title().c_str());
}

void Viewer::rollBackOpen(const Replaced& replaced) {
  // Everything as it was, the error kept in the status line.
  const std::string status = state_.status;
  original_ = replaced.original, document_ = replaced.document, state_ = replaced.state;
  options_.scene = replaced.path, sceneRadius_ = replaced.radius;
  state_.status = status;
  // The fallback renderer was made from the last good scene; an edit that was waiting
  // needs a new one.
  state_.sceneChanged = true;
  showTitle();
}

void Viewer::saveScene(const fs::path& path) {
  Scene saved = state_.scene;
  saved.camera.path = state_.cameraPath;
  document_->save(original_, saved, path);
  state_.status = "saved " + path.string();
  std::printf("%s\n", state_.status.c_str());
  std::fflush(stdout);
}

void Viewer::screenshot(const fs::path& path) {
  if (!isPngName(path)) throw Error(path.string(), "", "only PNG is written: give it a .png name");
  update(true);
  writePng(path, renderer_->readColor());
  state_.status = "wrote " + path.string() + " (" + std::to_string(width_) + "x" +
                  std::to_string(height_) + ", " + state_.rendererName + ")";
  std::printf("%s\n", state_.status.c_str());
  std::fflush(stdout);
}

void Viewer::windowShot(const fs::path& path) {
  Rgba8Image image(width_, height_);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, image.pixels.data());
  image.flipVertically();
  for (std::size_t i = 3; i < image.pixels.size(); i += 4) image.pixels[i] = 255;
  writePng(path, image);
  std::printf("wrote %s (window, %dx%d)\n", path.string().c_str(), width_, height_);
  std::fflush(stdout);
}

void Viewer::drawPanels() {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  constexpr float kMargin = 8.0f, kLeftWidth = 300.0f, kRightWidth = 330.0f;
  constexpr ImGuiWindowFlags kFlags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize;
  const float sceneHeight = std::max(200.0f, (display.y - 3 * kMargin) * 0.5f);

  ImGui::SetNextWindowPos(ImVec2(kMargin, kMargin), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(kLeftWidth, sceneHeight), ImGuiCond_Always);
  if (ImGui::Begin("Scene", nullptr, kFlags)) scenePanel(state_);
  ImGui::End();

  // What the frame holds and costs, under the scene: the AOV inspector and the timings.
  ImGui::SetNextWindowPos(ImVec2(kMargin, sceneHeight + 2 * kMargin), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(kLeftWidth, display.y - sceneHeight - 3 * kMargin),
                           ImGuiCond_Always);
  if (ImGui::Begin("Inspector", nullptr, kFlags)) {
    ImGui::PushItemWidth(-100.0f);
    if (ImGui::CollapsingHeader("AOV inspector", ImGuiTreeNodeFlags_DefaultOpen)) aovPanel(state_);
    ImGui::PopItemWidth();
    if (ImGui::CollapsingHeader("Timings", ImGuiTreeNodeFlags_DefaultOpen))
      timingsPanel(state_, ImGui::GetIO().Framerate);
  }
  ImGui::End();

  ImGui::SetNextWindowPos(ImVec2(display.x - kRightWidth - kMargin, kMargin), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(kRightWidth, display.y - 2 * kMargin), ImGuiCond_Always);
  if (ImGui::Begin("Controls", nullptr, kFlags)) {
    ImGui::PushItemWidth(-130.0f);
    if (ImGui::CollapsingHeader("File", ImGuiTreeNodeFlags_DefaultOpen)) filePanel(state_);
    if (ImGui::CollapsingHeader("Camera", ImGuiTreeNodeFlags_DefaultOpen)) cameraPanel(state_);
    // Every technique's panel, generated from the registries: the cutters (those the scene
    // uses start open), the pipe networks, the volumes, then the style with the current
    // shading style's options.
    const auto enabled = [&](const ParameterGroup& g) {
      if (g.name == "networks") return !state_.scene.networks.empty();
      if (g.name == "volumes") return !state_.scene.volumes.empty();
      const Parameter* on = findParameter(g.name);
      return on && std::get<bool>(on->value(state_.scene));
    };
    for (const ParameterGroup& group : parameterGroups()) {
      if (group.name == "style" || group.name.rfind("style.", 0) == 0) continue;
      if (ImGui::CollapsingHeader(group.title.c_str(),
                                  enabled(group) ? ImGuiTreeNodeFlags_DefaultOpen : 0))
        techniquePanel(group, state_);
    }
    if (ImGui::CollapsingHeader("Style"))
      for (const ParameterGroup& group : parameterGroups())
        if (group.name == "style" || group.style == state_.scene.style.name)
          techniquePanel(group, state_);
    ImGui::PopItemWidth();
  }
  ImGui::End();
}

}  // namespace cutaway::view
