// What the viewer knows and what its panels, mouse, keys and script change: the live scene,
// the selection, the camera path being recorded, the AOV shown, the last frame's timings.
// Plain data, so that the panels are functions of it and the actions can be tested without
// a window. Changes are flagged (`sceneChanged`: rebuild the renderer; `viewChanged`: render
// again) and the viewer acts on the flags once per frame.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "colormap.hpp"
#include "cutaway/frame/frame.hpp"
#include "cutaway/scene/scene.hpp"
#include "parameters.hpp"

namespace cutaway::view {

struct ViewerState {
  Scene scene;                      // the live scene: its camera is the viewer's (fit off, no path)
  std::set<std::size_t> selection;  // indices into scene.objects
  std::vector<CameraKey> cameraPath;  // recorded keys, saved as camera.path
  bool previewPath = false;           // the view follows cameraPath at `time`
  float nextKeyTime = 0.0f;           // the camera panel's time for the next key
  float time = 0.0f;                  // scene time (animation, path), seconds
  bool playing = false;
  bool flyMode = false;
  bool showPanels = true;

  // AOV inspector: "" shows the final colour.
  std::string aov;
  Colormap colormap = Colormap::Auto;
  Colormap shownColormap = Colormap::Turbo;  // `colormap` resolved for the shown buffer
  bool autoRange = true;
  ValueRange range;
  std::vector<std::string> aovNames;  // of the current frame
  std::map<std::string, std::string> aovMeanings;
  std::string cursorValue;  // the shown buffer's value under the cursor, for the UI

  // Measurements of the last rendered frame.
  std::vector<PassTiming> timings;
  double renderMs = 0;  // wall time of the last render, timer queries included
  double fullMs = 0;    // the same for the last frame at the window's size
  // The last frame was drawn at 1/shownDivisor of the window's size (1: at its size) while
  // the view moved; `movingSize` is that size.
  int shownDivisor = 1;
  int movingWidth = 0, movingHeight = 0;
  std::string rendererName, computePath;

  // The transfer-function editor: the volume, its gradient row and point being edited (-1:
  // none).
  std::size_t transferVolume = 0, transferRow = 0;
  int transferPoint = -1;

  // Files.
  std::string savePath, screenshotPath;
  std::string status;  // last outcome ("saved …", or an error), shown in the UI

  // Flags for the viewer.
  bool sceneChanged = false;  // a cutter, style or object option: rebuild the renderer
  bool viewChanged = false;   // camera or time: render again
  bool aovChanged = false;    // inspector buffer or colour map: recolour
  bool saveRequested = false, screenshotRequested = false, frameRequested = false;
  bool reloadRequested = false;  // read the scene file again (F5, the file panel)
};

// Objects called `name`, else the objects of group `name`; empty if neither exists.
std::vector<std::size_t> objectsNamed(const Scene& scene, const std::string& name);
// Groups in first-appearance order, "" (no group) included if any object has none.
std::vector<std::string> groupsOf(const Scene& scene);

// Actions on the selected objects; each flags sceneChanged when it changes anything.
void setRole(ViewerState& state, Role role);
void setImportance(ViewerState& state, float importance);
// The local cutaway angle (object parameter cutawayAngle); nullopt: the cutter's angle.
void setLocalAngle(ViewerState& state, std::optional<float> degrees);
// Sets `p` to `value` on the scene and flags what must follow: a live parameter renders again,
// any other rebuilds the renderer.
void setParameter(ViewerState& state, const Parameter& p, const ParameterValue& value);
// Bounds of the selection, or of the whole scene when nothing is selected.
Bounds selectionBounds(const ViewerState& state);
// Appends a key with the current camera; throws cutaway::Error unless `time` is later than
// the last key's.
void addCameraKey(ViewerState& state, float time);
// The camera to render now: the path's at `time` when previewing it, else the scene's.
Camera viewCamera(const ViewerState& state);

}  // namespace cutaway::view
