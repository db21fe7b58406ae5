// cutaway/cutters/clip_surfaces.hpp — 2.5D clip surfaces with cap surfaces (Trapp & Döllner
// 2013): a clip surface is a plane offset by a height map; the solid's parts on its back side
// are clipped per fragment, and a cap surface (the displaced plane itself) covers the cut
// where a volumetric parity test against a layered depth image says it is inside the solid.
//
// The per-fragment test (eqs. 1–3) lives here in C++ too, mirroring
// src/cutters/clip_surfaces/clip_surfaces.glsl, so tests compare the two on the same points.
//
//   cutaway::ClipSurface cs{.origin = {-1, 0, -1}, .u = {2, 0, 0}, .v = {0, 0, 2}};
//   cs.offsetMap = cutaway::makeOffsetMap({.pattern = cutaway::OffsetPattern::Ridged});
//   scene.cutters.enable<cutaway::ClipSurfaceOptions>().surfaces = {cs};
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "cutaway/core/image.hpp"
#include "cutaway/core/options.hpp"
#include "cutaway/geometry/mesh.hpp"

namespace cutaway {

// Procedural offset maps (Trapp13 §4.2, Fig. 5), tileable so GL_REPEAT shows no seams.
enum class OffsetPattern {
  Flat,      // 0 everywhere: a plain clipping plane
  Sawtooth,  // a zig-zag (triangle wave) along u: jagged cuts
  Noise,     // fractal value noise: clouds
  Ridged,    // ridged fractal noise: broken material
};
struct OffsetMapRecipe {
  OffsetPattern pattern = OffsetPattern::Noise;
  int size = 256;     // texels per side
  int frequency = 4;  // periods (lattice cells) across the map
  int octaves = 5;
  unsigned seed = 1;
};
FloatImage makeOffsetMap(const OffsetMapRecipe& recipe);

// Blending operations that combine offset maps (§4.2: "offset maps can be easily combined
// using standard image blending operations"); the result takes the larger size, the other
// map resampled with sampleRepeat. Results are clamped to [0, 1].
enum class OffsetBlend { Add, Multiply, Max, Min, Mix, Screen };
FloatImage blendOffsetMaps(const FloatImage& a, const FloatImage& b, OffsetBlend op,
                           float weight = 0.5f);

// One clip surface CS = (O, U, V, S, OM) (§4.1).
struct ClipSurface {
  glm::vec3 origin{0.0f};  // O: a corner of the cap's extent
  glm::vec3 u{1, 0, 0};    // U, V: orthogonal; N = Û × V̂; the cap spans O + [0,1]·U + [0,1]·V
  glm::vec3 v{0, 1, 0};
  glm::vec3 scale{1, 1, 0.05f};   // S: offset-map repeats along U and V; S_z: height in scene units
  FloatImage offsetMap{1, 1, 1};  // OM: heights in [0, 1]
  bool enabled = true;
  std::optional<glm::vec3> capColor;  // default: the capped object's colour, darker
  // §6.1: a diffuse map over the cap, sampled at T (eq. 2) like the offset map; multiplies the
  // cap colour. Empty: none.
  Rgba8Image diffuseMap;

  glm::vec3 normal() const {
    return glm::normalize(glm::cross(glm::normalize(u), glm::normalize(v)));
  }
};

// Trapp13 eqs. 1–3: P·N − N·O + f(OM, T)·S_z, with T from the projection P_N of P onto the
// plane; the point is clipped (χ = 1) where it is < 0.
float clipSurfaceFunction(const ClipSurface& cs, const glm::vec3& p);
// The texture coordinate T of eq. 2 for point p.
glm::vec2 clipSurfaceTexCoord(const ClipSurface& cs, const glm::vec3& p);

// Cap stylization (§6.1): the derived normal map shades the relief; the derived occlusion map
// darkens its hollows; a procedural solid texture (Perlin-style marble veins, §6.1 Fig. 11)
// varies the cap colour through the material.
struct CapStyle {
  bool normalMap = true;
  float occlusion = 1.0f;  // strength of the occlusion map in [0, 1]
  bool solidTexture = false;
  float solidTextureScale = 4.0f;  // veins per scene-bounds radius
};

struct ClipSurfaceOptions {
  static constexpr const char* kKey = "clipSurfaces";
  std::vector<ClipSurface> surfaces;  // at most kMaxClipSurfaces, evaluated in one pass (§4.5)
  // A point is clipped when any enabled surface clips it (union of the clipped half-spaces),
  // or, with Intersection, only when every enabled surface clips it.
  enum class Combine { Union, Intersection } combine = Combine::Union;
  bool caps = true;  // cap surfaces over the cuts of watertight objects (§5)
  // Static: one layered depth image per mesh, built once in object space (§5.2). PerFrame:
  // rebuilt every frame, peeled along the first clip surface's normal in world space, for
  // moving or deforming objects (Trapp13 §6.3, future work).
  enum class Parity { Static, PerFrame } parity = Parity::Static;
  int depthSpriteResolution = 512;  // texels per side of each layer
  CapStyle capStyle;
};
inline constexpr int kMaxClipSurfaces = 4;
const OptionsSchema& clipSurfacesSchema();

// Whether `p` is clipped by the enabled surfaces under `options.combine`.
bool clippedBySurfaces(const ClipSurfaceOptions& options, const glm::vec3& p);
// Whether no point of `box` (world space) is clipped under `options.combine`, whatever each
// enabled surface's relief within `heights[i]` (its offset map's least and greatest h): eq. 1's
// least value over the box, with a margin for the shaders' 32-bit rounding.
bool clipSurfacesKeepBox(const ClipSurfaceOptions& options, const std::vector<glm::vec2>& heights,
                         const Bounds& box);
// Where one enabled surface alone decides the points of `box` (the others keep it whole, under
// a union), the world planes between which its relief lies, margins included: every point with
// kept·(x, 1) ≥ 0 is kept, every point with removed·(x, 1) < 0 is clipped.
struct ClipSurfaceSlab {
  glm::vec4 kept, removed;
};
std::optional<ClipSurfaceSlab> clipSurfacesSlab(const ClipSurfaceOptions& options,
                                                const std::vector<glm::vec2>& heights,
                                                const Bounds& box);

// A surface's derived maps (§4.2; the renderer derives them again when S changes), one RGBA
// texel per offset-map texel: r = height h, g = ∂h/∂s and b = ∂h/∂t (per unit of texture
// coordinate, so the shader turns them into the displaced surface's normal for any S, U, V),
// a = ambient occlusion of the relief in [0, 1] (horizon-based, in scene units of this
// surface).
FloatImage deriveReliefMaps(const ClipSurface& cs);

// A volumetric depth sprite (§5.2): the layers of a watertight mesh's depth complexity seen
// along parallel rays, for the volumetric parity test (§5.3).
struct VolumetricDepthSprite {
  glm::mat4 toTexture{1.0f};  // M = T(C)·S·B·T(−G): object (or world) space → LDI space [0,1]³
  int width = 0, height = 0;
  int depthComplexity = 0;    // d: number of layers
  std::vector<float> layers;  // d × height × width window depths, rows bottom to top; 1 = empty
};

// The VPT of §5.3: inside when an odd number of layers lie in front of the point along its ray.
bool volumetricParityTest(const VolumetricDepthSprite& vds, const glm::vec3& p);

// Ray parity against the triangles themselves (the reference for the VPT): a ray from p along
// a fixed, generic direction crosses a closed mesh an odd number of times when p is inside.
bool insideMesh(const Mesh& mesh, const glm::vec3& p);

// The least and greatest bilinear, repeating sample of `map` (sampleRepeat's) over the texture
// coordinates [lo, hi] (eq. 2's T, map repeats included): those of the texels whose footprint
// reaches them, so the relief there lies within the range. A cap's prism (§5.1) spans it.
glm::vec2 reliefRangeOver(const FloatImage& map, glm::vec2 lo, glm::vec2 hi);

// Which tiles of a cap grid can hold a cap of `mesh` (watertight, object space, placed in the
// world by `model`) on surface `cs` (§5.1: the grid spans `rect` = (s0, t0, s1, t1) of its
// [0,1]² extent in tiles.x × tiles.y tiles): the tiles one of its triangles, grown by `margin`
// (world units), crosses within the slab the displaced surface lies in (S_z·[h_min, h_max]
// behind the plane; `relief` = (h_min, h_max)), and the tiles of every other connected run whose
// prism lies inside the solid (one ray-parity test per run: no surface crosses it, so all of it
// is in or all out). A cap lies only inside the solid, so nowhere else. Row-major, rows of
// increasing t; 1: draw the tile.
std::vector<std::uint8_t> capTiles(const Mesh& mesh, const glm::mat4& model, const ClipSurface& cs,
                                   glm::vec2 relief, glm::vec4 rect, glm::ivec2 tiles,
                                   float margin);

}  // namespace cutaway
