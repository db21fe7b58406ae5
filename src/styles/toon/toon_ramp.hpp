// The toon style's 1-D ramp texture (Lake, Marshall, Harris, Blackstein 2000, "Stylized
// rendering techniques for scalable real-time 3D animation", §3.1): the diffuse term
// max(n·l, 0) is the texture coordinate, and nearest filtering makes the bands hard.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "cutaway/gl/objects.hpp"
#include "cutaway/styles/toon.hpp"

namespace cutaway {

// The ramp's texels, dark to light: one per tone, RGB multipliers of the object colour.
std::vector<glm::vec3> toonRampTexels(const ToonStyle& style);

// Which texel a fragment with diffuse term `nDotL` reads: the ramp splits [0, 1] into
// ramp.size() equal intervals (Lake00 §3.1), as GL_NEAREST on a clamped 1-D texture does;
// back-facing light (n·l < 0) reads the darkest tone.
int toonRampIndex(int rampSize, float nDotL);

// The ramp as a GL_RGBA8 1-D texture, nearest filtering, clamped at both ends.
gl::Texture createToonRampTexture(const ToonStyle& style);

}  // namespace cutaway
