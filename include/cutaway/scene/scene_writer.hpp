// cutaway/scene/scene_writer.hpp — writing a scene back into its file: the original JSON
// document with the keys a program changed patched in, so that everything else in the file
// (comments aside: JSON has none) stays as the author wrote it, and rendering the saved file
// reproduces the changed scene. The cutters' and styles' keys are written through their
// schemas (cutaway/core/options.hpp), the same that read them.
//
// Keys keep their order (nlohmann::ordered_json). Patched keys: `camera` (always, with its
// path), `resolution` (when the size differs), objects' and proxies' `role`, `importance` and
// `params` (on the entry, or for objects split into nodes as an override matching exactly that
// node, appended last so that it wins), every cutter under `cutters` (added, removed, or its
// changed keys merged in, so that keys a schema does not write, such as a terrain opening's
// network layers or a clip surface's offset map, stay as written), `style` (its changed keys
// merged in the same way) and the pipe networks' run-time keys. Relative mesh paths are made
// absolute when the file is saved to another folder. `save` validates the result by parsing it
// again (parseScene, which also imports the meshes) and comparing what changed before it is
// written atomically.
//
//   SceneDocument document = SceneDocument::load("examples/engine-cutaway.json");
//   document.save(originalScene, editedScene, "out/saved.json");   // throws cutaway::Error
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "cutaway/scene/scene.hpp"

namespace cutaway {

class SceneDocument {
 public:
  static SceneDocument load(const std::filesystem::path& path);
  SceneDocument(nlohmann::ordered_json document, std::filesystem::path path);

  // The patched document: `original` is the scene as loaded from this document, `current`
  // the edited one (same objects in the same order; its camera's path is written as is).
  nlohmann::ordered_json patched(const Scene& original, const Scene& current,
                                 const std::filesystem::path& target) const;
  // Patches, re-parses and checks, then writes `target` atomically; throws cutaway::Error.
  void save(const Scene& original, const Scene& current, const std::filesystem::path& target) const;

  const std::filesystem::path& path() const { return path_; }

 private:
  nlohmann::ordered_json document_;
  std::filesystem::path path_;
};

// A float as the shortest decimal that reads back as it (0.1f writes 0.1, not
// 0.10000000149011612; 35 stays 35).
double shortestDecimal(float f);
// The scene-format JSON of a camera, with floats written in their shortest exact form.
nlohmann::ordered_json cameraJson(const Camera& camera);
// Every cutter's and style's keys as their schemas write them (what `patched` compares).
nlohmann::ordered_json cuttersJson(const Scene& scene);
nlohmann::ordered_json styleJson(const Style& style);
// `name` as a regular expression that matches exactly it (ECMAScript, as the format uses).
std::string escapeRegex(const std::string& name);

}  // namespace cutaway
