// The interactive viewer: a GLFW window showing the scene through the same Renderer as
// `cutaway render`, with Dear ImGui panels (panels/), mouse and key camera control
// (camera_controller.hpp), picking through the object-id AOV, the AOV inspector, timings,
// screenshots and scene saving (cutaway/scene/scene_writer.hpp), and scripted sessions (script.hpp).
//
// The renderer renders at the window's framebuffer size; the live Scene is the viewer's
// copy, and a change of a cutter, style or object option rebuilds the renderer (it builds
// its passes and programs from the scene), while camera moves only render again.
//
//   cutaway::view::Viewer viewer({.scene = "examples/engine-cutaway.json"});   // throws
//   return viewer.run();
#pragma once

#include <array>
#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "cutaway/core/image.hpp"
#include "cutaway/gl/objects.hpp"
#include "cutaway/gl/window_context.hpp"
#include "cutaway/render/renderer.hpp"
#include "cutaway/scene/scene_writer.hpp"
#include "script.hpp"
#include "viewer_state.hpp"

namespace cutaway::view {

struct ViewerOptions {
  std::filesystem::path scene;
  std::filesystem::path script;  // empty: interactive
  int width = 0, height = 0;     // window size; 0: the scene's resolution
  bool panels = true;
  // While the view moves, frames slower than this rate are drawn at a lower resolution and
  // stretched; the view is drawn at full size once it rests. 0: always at full size.
  float interactiveFps = 10.0f;
};

class Viewer {
 public:
  // Loads the scene (and script), opens the window; throws cutaway::Error (a bad scene or
  // script, no display).
  explicit Viewer(const ViewerOptions& options);
  ~Viewer();
  Viewer(const Viewer&) = delete;
  Viewer& operator=(const Viewer&) = delete;

  // The event loop; returns the exit status (non-zero when a script line failed).
  int run();

 private:
  void handleInput(float seconds);
  void runScript();
  void execute(const ScriptCommand& command);
  void handleRequests();
  void syncSize();
  // Rebuilds, renders and recolours as the state's flags say; `full`: the frame at the
  // window's size even while the view moves (screenshots, picking, AOVs written).
  void update(bool full = false);
  void renderFull();
  void renderMoving();
  bool moving() const;
  void readFrameBuffers();
  void refreshAov();
  void refreshOverlay();
  void drawView();
  void drawPanels();

  void pick(int x, int y, bool add);
  std::string valueAt(int x, int y) const;  // of the shown buffer, framebuffer pixel, top-down
  void saveScene(const std::filesystem::path& path);
  // Makes `loaded` (read from `path`) the viewer's scene: the file's camera, or the current
  // view when `keepView`.
  void adopt(Scene loaded, SceneDocument document, const std::filesystem::path& path,
             bool keepView);
  // Reads `path` as the viewer's scene (reload, open). A file that fails to load, or that the
  // device cannot render, leaves the last good scene on screen, the error in the status line
  // and on stderr.
  void openScene(const std::filesystem::path& path, bool keepView);
  // A new renderer for the live scene, and the state that follows it (AOV names, compute
  // path, a frame to draw); when it cannot be made, the scene the last renderer drew comes
  // back with it and the error is reported. Returns whether the new one was made.
  bool rebuild();
  // Draws the live scene with `renderer`. When that fails (an Error, or no memory for the
  // frame's buffers) after an earlier scene drew, that scene comes back with a renderer of
  // its own (restoreRendered), the failure is reported, and false is returned.
  bool drawLive(Renderer& renderer);
  void restoreRendered(const std::string& why);
  // What an `open` or a reload replaced, kept until its scene has drawn: a failure before
  // then (the device refuses the scene, or its first frame fails) puts it all back.
  struct Replaced {
    Scene original;
    std::optional<SceneDocument> document;
    ViewerState state;
    std::filesystem::path path;
    float radius = 1.0f;
  };
  void rollBackOpen(const Replaced& replaced);
  // "cutaway-view — FILE" for the scene file, and the window showing it.
  std::string title() const;
  void showTitle();
  void report(const std::string& message);
  void screenshot(const std::filesystem::path& path);
  void windowShot(const std::filesystem::path& path);
  void frameSelection();
  float aspect() const;

  ViewerOptions options_;
  Scene original_;  // as loaded, for saving
  // The live scene as a renderer last drew it in full: what a scene that cannot be made or
  // drawn (the device refuses it, its buffers do not fit in memory) gives way to.
  std::optional<Scene> rendered_;
  std::optional<Camera> drawnCamera_;  // the live scene's camera when last drawn, or opened
  std::optional<Replaced> replaced_;
  std::optional<SceneDocument> document_;
  ViewerState state_;
  std::optional<Script> script_;
  std::size_t scriptNext_ = 0;
  int waitFrames_ = 0;
  std::string scriptFailure_;

  std::unique_ptr<gl::WindowContext> window_;
  std::unique_ptr<Renderer> renderer_;
  // Interactive resolution (ParaView's LOD render, by resolution): while the view moves and
  // a full frame misses options_.interactiveFps, `moving_` draws it at 1/movingDivisor_ of
  // the window's size from `movingScene_` (the live scene at that size); once the view
  // rests, renderer_ draws it again. `shown_` drew what the window shows.
  std::unique_ptr<Renderer> moving_;
  Scene movingScene_;
  // The meshes' simplified versions that movingScene_ draws (addSimplifiedVersions), made on
  // the first frame drawn while moving and kept until another scene opens.
  SimplifiedCache simplified_;
  static constexpr int kMaxMovingDivisor = 8;
  int movingDivisor_ = 0;  // 0: not chosen since the last rebuild
  // Wall time of the last frame at each divisor since it was chosen ([1]: the full frame).
  std::array<double, kMaxMovingDivisor + 1> movingMs_{};
  Renderer* shown_ = nullptr;
  std::chrono::steady_clock::time_point lastMove_;  // of the mouse, the wheel or a fly key
  bool scriptMoving_ = false;                       // the script's `moving on`
  int width_ = 0, height_ = 0;  // framebuffer = render size
  float sceneRadius_ = 1.0f;    // of the visible objects' bounds, world units
  double rebuildMs_ = 0;        // wall time of the last renderer rebuild and its first frame

  std::vector<float> objectIds_;  // last frame's objectId AOV, rows bottom to top
  FloatImage aovImage_;           // the shown AOV, rows bottom to top
  gl::Texture aovTexture_, overlayTexture_;
  std::set<std::size_t> overlaySelection_;
  bool overlayVisible_ = false;
  bool viewDrag_ = false;  // a mouse press that started on the view, not on a panel
  std::string pendingWindowShot_;
  bool quit_ = false;
};

}  // namespace cutaway::view
