// cutaway/kinds/volume_ray_cast.hpp — a CPU ray caster for scene volumes: the reference
// that the GPU's (src/kinds/volumes/volume.frag) is checked against pixel by pixel. The same
// rays (through pixel centres), the same samples (the same per-pixel jitter), trilinear
// interpolation as GL's linear filter with clamped edges, the transfer function evaluated
// exactly (a two-dimensional one at the interpolated gradient's magnitude), opacity corrected
// for the step, front-to-back compositing with early termination.
// Colours are the transfer function's (emission only: no shading, no emphasis).
//
//   cutaway::VolumeRay r = cutaway::castVolumeRay(scene.volumes[0], camera.view(),
//                                                 camera.projectionMatrix(aspect), {w, h}, {x, y});
#pragma once

#include <functional>
#include <limits>

#include <glm/glm.hpp>

#include "cutaway/scene/scene.hpp"

namespace cutaway {

struct VolumeRay {
  // View depths: the first sample of material the cutters keep (as the volumeEntryDepth AOV),
  // and as the volumeHitDepth AOV.
  float entryDepth = std::numeric_limits<float>::quiet_NaN();
  float hitDepth = std::numeric_limits<float>::quiet_NaN();
  float opacity = 0.0f;
  glm::vec3 color{0.0f};  // premultiplied by opacity
};

// The smallest world length of a voxel step of a scene volume (placement included): ray steps,
// opacity distances and tolerances are set in these.
float smallestVoxelSpacing(const SceneVolume& volume);

// Trilinear interpolation at index-space point p (voxel centres at integers), clamped to the
// grid as GL_CLAMP_TO_EDGE clamps.
float sampleVolume(const Volume& v, glm::vec3 p);

// The central difference of the values over one voxel at voxel v (index space, clamped at the
// edges): the gradient that the GPU stores per voxel.
glm::vec3 voxelGradient(const Volume& v, glm::ivec3 voxel);
// Those differences interpolated trilinearly at index-space point p, as the GPU filters them.
glm::vec3 sampleGradient(const Volume& v, glm::vec3 p);

// The per-pixel ray start offset in [0, 1) (pixel in GL window coordinates: x right, y up).
float volumeJitter(glm::uvec2 pixel);

// The ray through the centre of `pixel` (GL window coordinates) of a frame of `size`;
// `opaqueDepth`: the window depth of the opaque surfaces there (1: none); `keep`: whether the
// cutters keep a world point (empty: everything kept).
VolumeRay castVolumeRay(const SceneVolume& volume, const glm::mat4& view,
                        const glm::mat4& projection, glm::ivec2 size, glm::ivec2 pixel,
                        float opaqueDepth = 1.0f,
                        const std::function<bool(const glm::vec3&)>& keep = {});

}  // namespace cutaway
