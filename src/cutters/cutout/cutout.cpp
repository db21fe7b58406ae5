#include "cutters/cutout/cutout.hpp"

#include <map>
#include <memory>

#include "cutaway/core/error.hpp"

namespace cutaway {

namespace {

// The material of a volume for its main axis: in each row of voxels along i, the first and the
// last that the transfer function does not make clear. Every material voxel lies between the
// two of its row, so their convex hull is that of all the material, from ≤ 2·dims.y·dims.z
// points.
std::vector<glm::vec3> volumeHullPoints(const SceneVolume& v) {
  const Volume& vol = *v.volume;
  const glm::mat4 m = v.indexToWorld();
  std::vector<glm::vec3> points;
  for (int k = 0; k < vol.dims.z; ++k)
    for (int j = 0; j < vol.dims.y; ++j) {
      int first = -1, last = -1;
      for (int i = 0; i < vol.dims.x; ++i)
        if (v.mayBeVisible(vol.at({i, j, k}))) {
          if (first < 0) first = i;
          last = i;
        }
      if (first < 0) continue;
      for (const int i : {first, last})
        points.push_back(glm::vec3(m * glm::vec4(float(i), float(j), float(k), 1.0f)));
    }
  return points;
}

}  // namespace

std::vector<ExteriorUnit> exteriorUnits(const Scene& scene, float time) {
  std::vector<ExteriorUnit> units;
  std::map<std::string, std::size_t> unitOfGroup;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& o = scene.objects[i];
    if (o.proxy || o.role != Role::Exterior) continue;
    if (o.group.empty()) {
      units.push_back({o.name, {i}, {}, {}});
      continue;
    }
    const auto [it, added] = unitOfGroup.emplace(o.group, units.size());
    if (added) units.push_back({o.group, {}, {}, {}});
    units[it->second].objects.push_back(i);
  }
  for (std::size_t i = 0; i < scene.volumes.size(); ++i)
    if (scene.volumes[i].role == Role::Exterior)
      units.push_back({scene.volumes[i].name, {}, {i}, {}});
  for (auto& unit : units) {
    std::vector<glm::vec3> points;
    for (const std::size_t i : unit.objects) {
      const SceneObject& o = scene.objects[i];
      const glm::mat4 m = o.transformAt(time);
      for (const auto& p : o.mesh->positions) points.push_back(glm::vec3(m * glm::vec4(p, 1.0f)));
    }
    for (const std::size_t i : unit.volumes) {
      const std::vector<glm::vec3> hull = volumeHullPoints(scene.volumes[i]);
      if (hull.empty())
        throw Error(scene.file.string(), "/volumes/" + std::to_string(i),
                    "exterior \"" + unit.name +
                        "\" shows no material: its transfer function makes every voxel clear");
      points.insert(points.end(), hull.begin(), hull.end());
    }
    try {
      unit.axes = principalAxes(points);
    } catch (const Error&) {  // the convex hull has no volume
      const std::string place =
          unit.objects.empty()
              ? "/volumes/" + std::to_string(unit.volumes.front())
              : "/objects/" + std::to_string(unit.objects.front()) +
                    (scene.objects[unit.objects.front()].group.empty() ? "" : "/group");
      throw Error(scene.file.string(), place,
                  "exterior \"" + unit.name +
                      "\" is flat (its points lie in one plane or on one line): it has no main "
                      "axis and no inside to show");
    }
  }
  return units;
}

CutterType cutoutCutterType() {
  return {.key = "cutout",
          .title = "Cutout (Diepstraten03)",
          .glsl = "cutters/cutout/cutout.glsl",
          .name = "cutout",
          .schema = &cutoutSchema(),
          // Diepstraten03 rule 1: the cutters need the inside/outside classification.
          .complete = [](const json_reader::Context& ctx, const std::string& pointer,
                         Scene& s) { requireExterior(ctx, pointer, s); },
          .create = [](FrameSetup& setup) -> std::unique_ptr<Cutter> {
            return std::make_unique<Cutout>(setup);
          }};
}

Cutout::Cutout(FrameSetup& setup)
    : setup_(setup),
      method_(options().method),
      units_(exteriorUnits(setup.scene)),
      unitOfObject_(setup.scene.objects.size(), -1),
      unitOfVolume_(setup.scene.volumes.size(), -1),
      imageUnit_(setup.bindings.textureUnit("CUTOUT_IMAGE")),
      planesLocation_(setup.bindings.uniformLocation("CUTOUT_PLANES", kMaxCutoutPlanes)),
      planeCountLocation_(setup.bindings.uniformLocation("CUTOUT_PLANE_COUNT")),
      originLocation_(setup.bindings.uniformLocation("CUTOUT_ORIGIN")),
      axisLocation_(setup.bindings.uniformLocation("CUTOUT_AXIS")),
      jitterLocation_(setup.bindings.uniformLocation("CUTOUT_JITTER")) {
  for (std::size_t u = 0; u < units_.size(); ++u) {
    for (const std::size_t i : units_[u].objects) {
      unitOfObject_[i] = int(u);
      animated_ = animated_ || !setup.scene.objects[i].animation.empty();
    }
    for (const std::size_t i : units_[u].volumes) unitOfVolume_[i] = int(u);
  }
  wedges_.resize(units_.size());
  const CutoutJitter& jitter = options().jitter;
  if (jitter.pattern == CutoutJitter::Pattern::Image) {
    const FloatImage& image = jitter.imageData;
    setup.requireTextureFits("/cutters/cutout/jitter/image", "a jitter image", image.width,
                             image.height);
    imageTexture_ = gl::Texture::create(GL_TEXTURE_2D);
    const GLuint id = imageTexture_.id();
    glTextureStorage2D(id, 1, GL_R32F, image.width, image.height);
    glTextureSubImage2D(id, 0, 0, 0, image.width, image.height, GL_RED, GL_FLOAT,
                        image.data.data());
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_REPEAT);
  }
  if (method_ == CutoutOptions::Method::Texture)
    setup.gbuffer.addChannel(
        {.name = "cutoutDistance",
         .meaning = "signed distance of the visible exterior surface to the cutout wedge, "
                    "perturbed by the jitter (Diepstraten03 §4.5), scene units; > 0 would be "
                    "removed, so visible surfaces are <= 0; NaN where no exterior object is "
                    "visible; sample 0"});
}

void Cutout::beginFrame(const FrameState& state) {
  if (animated_ && state.time != unitsTime_) {  // the units' axes at this frame's pose
    units_ = exteriorUnits(setup_.scene, state.time);
    unitsTime_ = state.time;
  }
  const Camera& camera = state.camera;
  for (std::size_t u = 0; u < units_.size(); ++u) {
    const PrincipalAxes& axes = units_[u].axes;
    const glm::vec3 towardsViewer = camera.projection == Projection::Orthographic
                                        ? camera.eye - camera.target
                                        : camera.eye - axes.center;
    wedges_[u] = cutoutWedge(axes, options(), towardsViewer);
  }
  const Scene& scene = setup_.scene;
  slabs_.assign(scene.objects.size(), std::nullopt);
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const Bounds& local = setup_.meshes.mesh(i).bounds();
    if (local.empty() || !cuts(i)) continue;
    const Bounds box = shadedBox(scene, local, i, state.time, state.uniforms);
    // Two pixels beyond the planes: the cutter decides a pixel's samples by its centre (a
    // fragment is shaded once), so a kept part reaching the planes would draw the samples past
    // them of rim pixels it removes; two pixels off, only where the surface grazes the view.
    const float pixel = worldPixel(box, state.uniforms);
    std::vector<glm::vec4> kept = cutoutKeptHalfSpaces(wedges_[std::size_t(unitOfObject_[i])],
                                                       options().jitter, box, 2.0f * pixel);
    if (!kept.empty())
      slabs_[i] =
          Slab{.kept = std::move(kept), .overlap = pixel, .backFaces = !scene.objects[i].solid()};
  }
}

void Cutout::bindForGeometry() const {
  if (imageTexture_.id()) glBindTextureUnit(imageUnit_, imageTexture_.id());
}

const CutoutWedge* Cutout::wedgeOf(int unit) const {
  return unit < 0 ? nullptr : &wedges_[std::size_t(unit)];
}

bool Cutout::cuts(std::size_t index) const {
  return method_ == CutoutOptions::Method::Texture && unitOfObject_[index] >= 0 &&
         setup_.scene.objects[index].mayBeCutBy(CutoutOptions::kKey);
}

// Ray samples have no hardware clip planes: a volume is cut by §4.5's per-sample test whatever
// the method (without jitter under the clip-plane method, as its meshes are).
bool Cutout::cutsVolume(std::size_t index) const {
  return unitOfVolume_[index] >= 0 && setup_.scene.volumes[index].mayBeCutBy(CutoutOptions::kKey);
}

int Cutout::clipPasses(std::size_t index) const {
  return method_ == CutoutOptions::Method::ClipPlanes && unitOfObject_[index] >= 0 &&
                 setup_.scene.objects[index].mayBeCutBy(CutoutOptions::kKey)
             ? kMaxCutoutPlanes
             : 0;
}

glm::vec4 Cutout::clipPlane(std::size_t index, int pass) const {
  // Diepstraten03 §4.3: each pass keeps the far side of one plane (n·x + w <= 0); the union of
  // the passes is everything outside the wedge. A wedge with fewer planes clips the pass away.
  const CutoutWedge* w = wedgeOf(unitOfObject_[index]);
  return w && pass < int(w->planes.size()) ? -w->planes[std::size_t(pass)]
                                           : glm::vec4(0, 0, 0, -1);
}

CutLook Cutout::look(std::size_t index) const {
  // Rule 5: a solid exterior shows its cut wall, in a colour unlike any object's (rule 1);
  // a hollow one its inside.
  const SceneObject& o = setup_.scene.objects[index];
  return {.cutSurface = o.solid(),
          .cutColor = options().wallColor.value_or(kDefaultWallColor),
          .backColor = options().insideColor.value_or(o.material.color * 0.55f)};
}

void Cutout::setObjectUniforms(GLuint program, std::size_t index) const {
  setWedgeUniforms(program, wedgeOf(unitOfObject_[index]));
}

void Cutout::setVolumeUniforms(GLuint program, std::size_t index) const {
  setWedgeUniforms(program, wedgeOf(unitOfVolume_[index]));
}

int Cutout::jitterPattern() const {
  return method_ == CutoutOptions::Method::Texture ? int(options().jitter.pattern) : 0;
}

std::string Cutout::glslDefines() const {
  return "#define CUTOUT_JITTER_PATTERN " + std::to_string(jitterPattern()) + "\n";
}

void Cutout::setWedgeUniforms(GLuint program, const CutoutWedge* w) const {
  if (!w) {
    glProgramUniform1i(program, planeCountLocation_, 0);
    return;
  }
  glProgramUniform4fv(program, planesLocation_, GLsizei(w->planes.size()), &w->planes[0][0]);
  glProgramUniform1i(program, planeCountLocation_, GLint(w->planes.size()));
  glProgramUniform4f(program, originLocation_, w->origin.x, w->origin.y, w->origin.z,
                     w->axisLength);
  glProgramUniform3fv(program, axisLocation_, 1, &w->axis[0]);
  const CutoutJitter& j = options().jitter;
  glProgramUniform4f(program, jitterLocation_, float(jitterPattern()), j.amplitude * w->axisLength,
                     j.frequency / w->axisLength, float(j.octaves));
}

}  // namespace cutaway
