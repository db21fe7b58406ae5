// The define that programs reading the frame's per-sample targets need (frame/samples.glsl).
#pragma once

#include <map>
#include <string>

namespace cutaway {

// `defines` with SINGLE_SAMPLE added at one sample, when those targets are plain 2-D textures.
inline std::map<std::string, std::string> sampleDefines(
    int samples, std::map<std::string, std::string> defines = {}) {
  if (samples == 1) defines["SINGLE_SAMPLE"] = "1";
  return defines;
}

}  // namespace cutaway
