// cutaway/scene/settings.hpp — a scene's options of its techniques by key: each enabled
// cutter's options struct under "cutters" (the key is the struct's kKey), held by value, so
// that the scene model knows no technique and a new cutter needs no change here.
//
//   scene.cutters.enable<cutaway::AdaptiveCutawayOptions>().angle = 30.0f;
//   if (const auto* a = scene.cutters.find<cutaway::AdaptiveCutawayOptions>()) use(a->angle);
//   scene.cutters.disable<cutaway::CutoutOptions>();
#pragma once

#include <any>
#include <string>
#include <utility>
#include <vector>

namespace cutaway {

class TechniqueSettings {
 public:
  template <class O>
  const O* find() const {
    const std::any* a = find(O::kKey);
    return a ? std::any_cast<O>(a) : nullptr;
  }
  template <class O>
  O* find() {
    std::any* a = find(O::kKey);
    return a ? std::any_cast<O>(a) : nullptr;
  }
  // The options, enabled with their defaults if they were not.
  template <class O>
  O& enable() {
    if (!find(O::kKey)) set(O::kKey, O{});
    return *find<O>();
  }
  template <class O>
  void disable() {
    erase(O::kKey);
  }

  // By key, for code that goes through the schemas (the reader, the viewer, the CLI).
  const std::any* find(const std::string& key) const;
  std::any* find(const std::string& key);
  void set(const std::string& key, std::any options);
  void erase(const std::string& key);
  void clear() { entries_.clear(); }
  bool empty() const { return entries_.empty(); }
  std::vector<std::string> keys() const;

 private:
  std::vector<std::pair<std::string, std::any>> entries_;
};

}  // namespace cutaway
