#include "cutaway/scene/settings.hpp"

#include <algorithm>

namespace cutaway {

const std::any* TechniqueSettings::find(const std::string& key) const {
  for (const auto& [k, v] : entries_)
    if (k == key) return &v;
  return nullptr;
}

std::any* TechniqueSettings::find(const std::string& key) {
  for (auto& [k, v] : entries_)
    if (k == key) return &v;
  return nullptr;
}

void TechniqueSettings::set(const std::string& key, std::any options) {
  if (std::any* a = find(key))
    *a = std::move(options);
  else
    entries_.emplace_back(key, std::move(options));
}

void TechniqueSettings::erase(const std::string& key) {
  std::erase_if(entries_, [&](const auto& e) { return e.first == key; });
}

std::vector<std::string> TechniqueSettings::keys() const {
  std::vector<std::string> out;
  for (const auto& [k, v] : entries_) out.push_back(k);
  return out;
}

}  // namespace cutaway
