// The one interface every cutter implements, and its entry in the registry
// (src/cutters/registry.cpp). A cutter decides, per fragment of the objects it cuts, whether the
// fragment is kept, removed, or shows the solid's cut surface (Diepstraten03's separation of the
// cut from the rendering style): it may prepare buffers in passes of its own before the
// geometry pass, binds what its GLSL reads, sets per-object uniforms, and may draw geometry
// of its own and add passes after the geometry pass.
//
// Its GLSL file (CutterType::glsl) defines, for the composition the registry generates into
// every geometry program:
//   int <name>Fragment(CutFragment f, out vec3 cutPosition, out vec3 cutNormal);
// returning kKeep, kDiscard or kCutSurface (cutters/fate.glsl), and for each G-buffer channel
// its constructor adds (GBuffer::addChannel), `float <name>Channel<k>(CutFragment f)` (k: 0,
// 1, … in the order added), the channel's value on the fragments of the objects it cuts.
// Optionally, for the volumes' rays, a span of a view ray in which it removes every point, so
// that the ray skips it instead of asking per sample (Burns11 §5.2.5: rays start at the
// cutaway surface): `#define <NAME>_REMOVED_SPAN` and
//   vec2 <name>RemovedSpan(vec3 origin, vec3 direction, vec2 window, vec2 range);
// (distances along the unit direction from the origin; empty where x ≥ y; `window`: the ray's
// pixel, as gl_FragCoord.xy; `range`: the part of the ray the caller samples), conservative:
// every point inside is one <name>Fragment discards as a front face.
//
// Adding a cutter: its folder (options, this interface, GLSL, README citing the equations) and
// one line in registry.cpp (docs/architecture.md).
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cutaway/frame/aov.hpp"
#include "core/json_reader.hpp"
#include "cutaway/frame/frame.hpp"
#include "frame/frame_setup.hpp"
#include "frame/frame_uniforms.hpp"

namespace cutaway {

// How the cut of one object looks where this cutter made it.
struct CutLook {
  bool cutSurface = false;  // back faces seen through its cut are the solid's cut surface
  glm::vec3 cutColor{0.0f};
  // Back faces that are no cut surface (an open or hollow inside); unset: the object's colour.
  std::optional<glm::vec3> backColor;
  // Its GLSL's kCutSurface on a back face says only that its cut lies in front (Burns08's C
  // spreads over the whole view). On a mesh that is not watertight that also holds for a back
  // face seen through the mesh's own opening, so there the mesh kind shows its cut surfaces
  // only where a front fragment of the mesh was removed (kinds/meshes: removal marks). Fixed
  // for a renderer's life (it prepares the marks' program and stencil); `skipsMarks` leaves
  // them out for a frame, every back face behind the cut then a cut surface (two draws fewer
  // an open mesh).
  bool marksOpenMeshes = false;
  bool skipsMarks = false;
};

// A G-buffer of removed material whose feature lines the composer draws faded over the image
// (Burns08 §4.3's ghost lines): each sample's line weight is stored with its normal.
struct GhostBuffers {
  Target normal, objectId;            // multisampled, as the scene G-buffer's
  std::function<float()> opacity;     // read every frame
};

struct ActiveCutter;

// What a geometry program needs at the moment it draws.
struct GeometryDraw {
  float time;                                // the objects' animation time
  const std::vector<ActiveCutter>* cutters;  // the frame's, for geometry others cut too
};

class Cutter {
 public:
  virtual ~Cutter() = default;

  // Once the geometry programs' shading is known (FrameSetup::geometryProgram): builds the
  // geometry programs of its own (Trapp13's caps).
  virtual void prepareGeometryPrograms() {}
  // Per frame, before any pass: the camera (e.g. wedges facing it) and live options.
  virtual void beginFrame(const FrameState&) {}
  // Its passes before the geometry pass, in order.
  virtual void addPreparationPasses(Frame&) {}
  // The targets its GLSL reads in the geometry pass (written by its preparation passes).
  virtual std::vector<Target> geometryInputs() const { return {}; }
  // In the geometry pass, before anything is drawn: binds its textures, images and blocks,
  // clears its per-pixel images.
  virtual void bindForGeometry() const {}
  // Uniforms of its GLSL in a geometry program, set before the program draws.
  virtual void setProgramUniforms(GLuint /*program*/) const {}
  // Compile-time choices of its GLSL (`#define` lines, from options a change of which rebuilds
  // the renderer), written before its file in cutters/composition.glsl: llvmpipe runs both
  // sides of a branch on a uniform.
  virtual std::string glslDefines() const { return {}; }
  // Whether the cut position its GLSL gives lies on the view ray behind the fragment (the
  // terrain opening's trench wall): the composition then makes that point's window depth the
  // fragment's (gCutFragDepth, written by mesh.frag), so that what stands in front of it wins.
  virtual bool cutSurfaceBehind() const { return false; }

  // Whether its GLSL decides the fragments of scene object `index` (a mesh object): by its
  // own rule, and only if the object allows it (SceneObject::mayBeCutBy its key).
  virtual bool cuts(std::size_t index) const = 0;
  // Whether its GLSL may remove or cut any fragment of object `index` (one it cuts) in this
  // frame, as beginFrame found it; where not (the object lies wholly where it keeps
  // everything), the object draws without its code: llvmpipe runs a cutter's code for every
  // fragment it decides, and a `discard` in a program delays its depth writes on any GPU.
  virtual bool reaches(std::size_t /*index*/) const { return true; }
  // Where it reaches object `index`, the world slab its decisions may differ in this frame: it
  // keeps every point where kept[j]·x ≥ 0 for some j (a union of at most kMostKept
  // half-spaces) and removes every point where removed·x < 0 (a clip surface's plane lifted by
  // its relief's least and greatest offset; the outside of a cutout's wedge). The mesh kind
  // then draws each kept half-space without its code and leaves the removed one out, by
  // hardware clip distances; nullopt: no such slab.
  struct Slab {
    static constexpr int kMostKept = 4;
    std::vector<glm::vec4> kept;
    glm::vec4 removed{0.0f, 0.0f, 0.0f, 1.0f};  // by default none
    float overlap = 0.0f;  // world units the slab's draw reaches into the kept part (no cracks)
    // Whether the back faces split too; false where a kept back face may still be the cutter's
    // to shade (Diepstraten03's wall, seen through the cut wherever it lies).
    bool backFaces = true;
  };
  virtual std::optional<Slab> slab(std::size_t /*index*/) const { return std::nullopt; }
  // Whether its GLSL decides the ray samples of scene volume `index` (kinds/volumes), each
  // sample a front-facing CutFragment at its position, its window position CUT_FRAG_COORD
  // (cutters/fate.glsl); per volume, its GLSL reads the bits and setVolumeUniforms'.
  virtual bool cutsVolume(std::size_t /*index*/) const { return false; }
  // Diepstraten03 §4.3's classic method: the object drawn this many times, each pass with one
  // hardware clip plane (kept where plane·x ≥ 0); 0: drawn once.
  virtual int clipPasses(std::size_t /*index*/) const { return 0; }
  virtual glm::vec4 clipPlane(std::size_t /*index*/, int /*pass*/) const { return glm::vec4(0, 0, 0, -1); }
  // The look of its cuts of object `index` (called for the objects it cuts or clips).
  virtual CutLook look(std::size_t index) const = 0;
  virtual void setObjectUniforms(GLuint /*program*/, std::size_t /*index*/) const {}
  // Uniforms of its GLSL for scene volume `index`, set before the volume's rays are cast.
  virtual void setVolumeUniforms(GLuint /*program*/, std::size_t /*index*/) const {}
  // 0 when its GLSL decides every fragment (for the renderer's life); else it leaves fragments
  // partly reduced (Burns11 ch. 2's translucency, edge highlights, lines), and this is the most
  // translucent layers to peel per pixel (read every frame). Such a cutter's GLSL defines
  //   vec2 <name>Opacity(CutFragment f, vec3 normal, vec3 toEye);  // surface's, lines'
  // the composition's cutOpacity() is the least over the grading cutters of an object, the
  // geometry pass keeps the fragments whose surface is opaque, and the frame's translucent
  // layers (frame/translucent_layers.hpp) draw the others with their lines.
  virtual int translucentLayers() const { return 0; }

  // Geometry of its own, drawn into the G-buffer after the kinds' objects (Trapp13's caps).
  virtual void drawGeometry(const GeometryDraw&) const {}
  // Its passes after the geometry passes (e.g. an AOV made from the G-buffer).
  virtual void addPassesAfterGeometry(Frame&) {}
  // Occlusion culling of its own passes' scene meshes (frame/occlusion_culling.hpp), as the
  // renderer's (Renderer::setOcclusionCulling).
  virtual void setOcclusionCulling(bool) {}
  // Whether the line pass outlines the cut surfaces it makes (Burns08 §4.2), and in which
  // colour.
  virtual std::optional<glm::vec3> cutOutlineColor() const { return std::nullopt; }
  // Its ghost G-buffer, written by its passes after the geometry pass.
  virtual std::optional<GhostBuffers> ghosts() const { return std::nullopt; }
  // Buffers of its own that are no frame target, as AOVs.
  virtual std::vector<Aov> extraAovs() const { return {}; }
  // Once the frame's AOVs are read (its targets', every cutter's and kind's extra ones): adds
  // the frame's numbers they depend on (Aov::values) and AOVs derived from them.
  virtual void describeAovs(std::vector<Aov>& /*aovs*/) const {}
  // Facts about how it runs, for `cutaway bench` and the viewer (e.g. "computePath": "cpu").
  virtual std::vector<std::pair<std::string, std::string>> facts() const { return {}; }
};

// Scene object `index`'s world box at `time`, grown by worldPixel on every side: it holds every
// point a fragment of the object may be shaded at (for Cutter::reaches and Cutter::slab).
inline Bounds shadedBox(const Scene& scene, const Bounds& local, std::size_t index, float time,
                        const FrameUniforms& u) {
  Bounds box = local.transformed(scene.objects[index].transformAt(time));
  const float pixel = worldPixel(box, u);
  box.min -= glm::vec3(pixel);
  box.max += glm::vec3(pixel);
  return box;
}

// A registered cutter.
struct CutterType {
  std::string key;    // "adaptive": its JSON key under "cutters", the viewer's and CLI's prefix
  std::string title;  // for panels: "Adaptive cutaway (Burns08/11)"
  std::string glsl;   // its GLSL file, e.g. "cutters/adaptive/clip.glsl"
  std::string name;   // GLSL prefix: <name>Fragment, <name>Channel<k>
  // Its options (the struct in scene.cutters under `key`); null: none of its own, and it is
  // switched on by what the scene holds (`active`).
  const OptionsSchema* schema = nullptr;
  bool (*active)(const Scene&) = nullptr;
  // After the scene file's objects and networks are read: the checks and completions across
  // the scene (roles it needs, the network it opens above); errors name `pointer`.
  void (*complete)(const json_reader::Context&, const std::string& pointer, Scene&) = nullptr;
  // The deepest perspective depth range (far / near) its cut resolves, where it keeps its cut
  // in window depths (Camera::unresolvable, deepestDepthRange); 0: any.
  float deepestDepthRange = 0.0f;
  std::unique_ptr<Cutter> (*create)(FrameSetup&);
};

// A check for CutterType::complete: fails at `pointer` unless a visible object has `role`.
inline void requireRole(const json_reader::Context& ctx, const std::string& pointer,
                        const Scene& scene, Role role, const std::string& why) {
  for (const SceneObject& o : scene.objects)
    if (!o.proxy && o.role == role) return;
  ctx.fail(pointer, "no object has role \"" + std::string(roleName(role)) + "\": " + why);
}

// Diepstraten03 rule 1 for the cutters that cut exterior objects and exterior volumes (the
// cutout, the breakaway): fails unless one of either has that role.
inline void requireExterior(const json_reader::Context& ctx, const std::string& pointer,
                            const Scene& scene) {
  for (const SceneVolume& v : scene.volumes)
    if (v.role == Role::Exterior) return;
  requireRole(ctx, pointer, scene, Role::Exterior,
              "nothing to cut (give the outside objects or volumes that role, or match objects "
              "by name with \"overrides\")");
}

// How the active cutters cut one mesh object: the uniforms of the geometry programs'
// composition (kinds/meshes/mesh.frag; the caps read the bits alone).
struct ObjectCut {
  int cutBy = 0;        // bit per slot: its GLSL decides the object's fragments
  int cutSurfaces = 0;  // bit per slot: its cuts show cut surfaces
  int marksBy = 0;      // bit per slot: its look's marksOpenMeshes
  int clipPasses = 0;   // Diepstraten03 §4.3: hardware clip passes (the most any cutter asks)
  std::vector<std::pair<int, glm::vec3>> cutColors;  // per slot that cuts or clips it
  std::optional<glm::vec3> backColor;                // the first cutter's that gives one
};
// `exceptSlot`: a cutter left out (the one whose own geometry is drawn: Trapp13's caps).
ObjectCut objectCut(const std::vector<ActiveCutter>& cutters, std::size_t object,
                    int exceptSlot = -1);
// Sets the program's cut uniforms for `object`: the bits at `cutByLocation` (and, when the
// look locations are given, the cut surfaces' bits and colours and the back colour), and
// each cutter's own object uniforms.
struct CutUniformLocations {
  GLint cutBy, cutSurfaces = -1, backColor = -1, cutColors = -1;  // -1: the program has none
};
void setCutUniforms(GLuint program, const CutUniformLocations& at,
                    const std::vector<ActiveCutter>& cutters, const ObjectCut& cut,
                    std::size_t object, glm::vec3 objectColor);

// Whether `type` is on in `scene`: its options are there, or `active` says so.
inline bool cutterActive(const CutterType& type, const Scene& scene) {
  return type.active ? type.active(scene) : scene.cutters.find(type.key) != nullptr;
}

// An active cutter of one renderer: its slot (the registry index: its bit in uCutBy and its
// index in the per-cutter uniform arrays) and the instance.
struct ActiveCutter {
  int slot;
  const CutterType* type;
  std::unique_ptr<Cutter> cutter;
  std::vector<int> channels;  // the G-buffer channels it added, in order
};

}  // namespace cutaway
