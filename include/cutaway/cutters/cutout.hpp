// cutaway/cutters/cutout.hpp — cutout illustrations (Diepstraten, Weiskopf, Ertl 2003, §4):
// each exterior object (or group of exterior objects) loses a wedge: the intersection of a
// few half-spaces whose planes meet in a line on the object's main axis; interior objects
// are never cut. Optional jittering perturbs the signed distance so the cut boundary is
// sawtooth-shaped or rough; back faces of solid exteriors seen through the cut are shaded as
// the cut wall.
//
// The per-fragment decision lives here in C++ too (cutoutDistance), mirroring
// src/cutters/cutout/cutout.glsl, so tests compare the two pixel by pixel.
//
//   scene.cutters.enable<cutaway::CutoutOptions>().angle = 90.0f;
//   cutaway::Renderer renderer(scene, context->info());
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cutaway/core/image.hpp"
#include "cutaway/core/options.hpp"
#include "cutaway/geometry/main_axis.hpp"
#include "cutaway/geometry/mesh.hpp"

namespace cutaway {

struct CutoutJitter {
  // Diepstraten03 §4.5: the signed distance is displaced by a perturbation texture. Sawtooth:
  // the paper's tiny repeated texture under bilinear filtering (a triangle wave); noise:
  // fractal value noise (their "clouds"); image: any PNG (grey level, repeated).
  enum class Pattern { None, Sawtooth, Noise, Image } pattern = Pattern::None;
  float amplitude = 0.03f;      // displacement, as a fraction of the main axis' extent
  float frequency = 12.0f;      // pattern repeats per main-axis extent
  int octaves = 4;              // noise
  std::filesystem::path image;  // Image: the PNG it was loaded from
  FloatImage imageData;         // Image: its grey levels, loaded with the scene (readPngGray)
};

struct CutoutOptions {
  static constexpr const char* kKey = "cutout";
  // Texture: per-fragment signed distances (Diepstraten03 §4.5), with jitter and cut walls.
  // ClipPlanes: the classic method (§4.3): the exterior drawn once per plane with a hardware
  // clip plane; no jitter and no walls are possible.
  enum class Method { Texture, ClipPlanes } method = Method::Texture;
  float angle = 90.0f;            // relative angle between the two wedge planes, degrees
  std::optional<float> rotation;  // about the main axis, degrees from the second axis;
                                  // unset: the wedge faces the camera
  // Two more planes perpendicular to the main axis limit the cut to this part of the axis'
  // extent (0 = one end, 1 = the other); unset: the whole length.
  std::optional<glm::vec2> axialRange;
  CutoutJitter jitter;
  std::optional<glm::vec3> wallColor;    // default: kDefaultWallColor
  std::optional<glm::vec3> insideColor;  // back faces of hollow exteriors; default: darker
};

const OptionsSchema& cutoutSchema();

// Cut walls of Diepstraten03 are shown in a colour unlike any object's, so inside and
// outside stay distinguishable (rule 1).
inline constexpr glm::vec3 kDefaultWallColor{0.82f, 0.32f, 0.26f};

// One exterior unit's wedge for a frame: planes (n, w) with n·x + w > 0 on the removed side;
// a point is removed when it lies on the removed side of every plane.
struct CutoutWedge {
  glm::vec3 origin{0.0f};   // centre of the hull surface (on the main axis)
  glm::vec3 axis{0.0f};     // main axis, unit
  float axisLength = 1.0f;  // extent of the hull along the axis
  std::vector<glm::vec4> planes;
};
inline constexpr int kMaxCutoutPlanes = 4;

// The wedge of an object with `axes` for a viewer in direction `towardsViewer` from the
// object's centre (used when the rotation is unset; a direction along the axis falls back
// to the second axis).
CutoutWedge cutoutWedge(const PrincipalAxes& axes, const CutoutOptions& options,
                        const glm::vec3& towardsViewer);

// The jitter's displacement in [−1, 1] at world point x (times amplitude · axisLength).
float cutoutPerturbation(const CutoutWedge& wedge, const CutoutJitter& jitter, const glm::vec3& x);

// Signed distance of x to the removed region, perturbed: min_i (n_i·x + w_i) plus the
// jitter; > 0 means removed.
float cutoutDistance(const CutoutWedge& wedge, const CutoutJitter& jitter, const glm::vec3& x);

// The half-spaces k (k·x ≥ 0) outside the wedge that keep every point of theirs whatever the
// jitter: each plane turned and moved out by the jitter's amplitude, a rounding pad and
// `beyond`, those of them that hold some of `box`. A point of the box in none of them may be
// removed or cut; the mesh kind draws the rest without the cutter's code (Cutter::Slab).
std::vector<glm::vec4> cutoutKeptHalfSpaces(const CutoutWedge& wedge, const CutoutJitter& jitter,
                                            const Bounds& box, float beyond = 0.0f);

// Rule 3: the wedge lies on the main axis of the outside object. Exterior objects of one
// group share one wedge (the axes of their joint hull); an ungrouped exterior object has its
// own. Axes are taken at the objects' pose at `time` (the frame's: an animated exterior takes
// its wedge along). An exterior volume is a unit of its own, its hull that of its material:
// the voxels its transfer function does not make clear.
struct ExteriorUnit {
  std::string name;                  // the group, or the object's or volume's name
  std::vector<std::size_t> objects;  // indices into scene.objects
  std::vector<std::size_t> volumes;  // indices into scene.volumes
  PrincipalAxes axes;
};
std::vector<ExteriorUnit> exteriorUnits(const struct Scene& scene, float time = 0.0f);

}  // namespace cutaway
