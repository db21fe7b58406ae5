// Saving the viewer's scene: the original JSON document with the keys the viewer changes
// patched in, so that everything else in the file (comments aside: JSON has none) stays as
// the author wrote it, and `cutaway render` of the saved file reproduces the viewer's image.
//
// Keys keep their order (nlohmann::ordered_json). Patched keys: `camera` (always: the viewer's
// camera, and the recorded path), `resolution` (when the view's size differs), objects' and
// proxies' `role`, `importance` and `params` (on the entry, or for objects split into nodes as an
// override matching exactly that node, appended last so that it wins), `cutters.adaptive` and
// `style` (when changed; other keys of `cutters` and `style` are kept). Relative mesh paths are
// made absolute when the file is saved to another folder. The result is validated by parsing it
// again (parseScene, which also imports the meshes) and comparing what the viewer changed before it
// is written atomically.
//
//   SceneDocument document = SceneDocument::load("examples/engine-cutaway.json");
//   document.save(originalScene, viewerScene, "out/saved.json");   // throws cutaway::Error
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "cutaway/scene/scene.hpp"

namespace cutaway::view {

class SceneDocument {
 public:
  static SceneDocument load(const std::filesystem::path& path);
  SceneDocument(nlohmann::ordered_json document, std::filesystem::path path);

  // The patched document: `original` is the scene as loaded from this document, `current`
  // the viewer's (same objects in the same order; its camera's path is written as is).
  nlohmann::ordered_json patched(const Scene& original, const Scene& current,
                                 const std::filesystem::path& target) const;
  // Patches, re-parses and checks, then writes `target` atomically; throws cutaway::Error.
  void save(const Scene& original, const Scene& current, const std::filesystem::path& target) const;

  const std::filesystem::path& path() const { return path_; }

 private:
  nlohmann::ordered_json document_;
  std::filesystem::path path_;
};

// The scene-format JSON of each part, with floats written in their shortest exact form.
nlohmann::ordered_json cameraJson(const Camera& camera);
nlohmann::ordered_json styleJson(const Style& style);
nlohmann::ordered_json adaptiveJson(const AdaptiveCutawayOptions& options);
// `name` as a regular expression that matches exactly it (ECMAScript, as the format uses).
std::string escapeRegex(const std::string& name);

}  // namespace cutaway::view
