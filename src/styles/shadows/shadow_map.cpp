#include "styles/shadows/shadow_map.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "cutaway/gl/shader.hpp"
#include "frame/frame_uniforms.hpp"

namespace cutaway {

namespace {

// Any unit vector not parallel to `d`, for the light view's up.
glm::vec3 upFor(const glm::vec3& d) {
  return std::abs(d.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
}

}  // namespace

glm::vec4 farLightAsDirectional(const glm::vec4& lightVector, const Bounds& bounds) {
  if (lightVector.w == 0.0f) return lightVector;
  const glm::dvec3 along = glm::dvec3(bounds.center()) - glm::dvec3(lightVector);
  const double distance = glm::length(along);
  const double radius = std::max(double(bounds.radius()), 1e-6);
  if (!(distance > 1e4 * radius)) return lightVector;
  return glm::vec4(glm::vec3(along / distance), 0.0f);
}

LightFrustum keyLightFrustum(const glm::vec4& lightVector, const Bounds& bounds) {
  const glm::vec3 center = bounds.center();
  const float radius = std::max(bounds.radius(), 1e-6f);
  // A perspective map from a point light beyond 1e4 radii would hold the scene within a few
  // float steps of its distance (two units at 3e7): it casts as the directional light.
  if (const glm::vec4 far = farLightAsDirectional(lightVector, bounds); far.w != lightVector.w)
    return keyLightFrustum(far, bounds);
  LightFrustum f{};
  if (lightVector.w == 0.0f) {
    // Directional: an orthographic box around the bounds' corners in light view space, so the
    // map's texels cover the scene and nothing else.
    const glm::vec3 d = glm::normalize(glm::vec3(lightVector));
    f.view = glm::lookAt(center - d * (2.0f * radius), center, upFor(d));
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (int i = 0; i < 8; ++i) {
      const glm::vec3 corner((i & 1) ? bounds.max.x : bounds.min.x,
                             (i & 2) ? bounds.max.y : bounds.min.y,
                             (i & 4) ? bounds.max.z : bounds.min.z);
      const glm::vec3 v = glm::vec3(f.view * glm::vec4(corner, 1.0f));
      lo = glm::min(lo, v), hi = glm::max(hi, v);
    }
    // A margin of 1% keeps the outermost casters off the map's border texels.
    const glm::vec3 margin = 0.01f * (hi - lo) + glm::vec3(1e-6f * radius);
    lo -= margin, hi += margin;
    f.orthographic = true;
    f.near = -hi.z, f.far = -lo.z;  // view space looks down −z
    f.projection = glm::ortho(lo.x, hi.x, lo.y, hi.y, f.near, f.far);
    return f;
  }
  // Point: a perspective frustum from the light towards the bounds' centre, wide enough for
  // the bounding sphere. A light inside the sphere cannot see all of it in one frustum; the
  // angle is held at 150°, so parts far off the axis are left unshadowed (lit).
  const glm::vec3 p(lightVector);
  glm::vec3 axis = center - p;
  const float distance = glm::length(axis);
  axis = distance > 1e-6f * radius ? axis / distance : glm::vec3(0, -1, 0);
  f.view = glm::lookAt(p, p + axis, upFor(axis));
  const float halfAngle =
      std::min(distance > radius ? std::asin(radius / distance) * 1.02f : glm::radians(75.0f),
               glm::radians(75.0f));
  // Near: the bounds' nearest point to the light, times cos(half angle) since off-axis points
  // are nearer along the axis than in distance; as far out as that allows, because the depth
  // precision of a perspective map is set by near / far. Far: the farthest corner.
  const float nearest = glm::length(p - glm::clamp(p, bounds.min, bounds.max));
  float farthest = 0.0f;
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 corner((i & 1) ? bounds.max.x : bounds.min.x,
                           (i & 2) ? bounds.max.y : bounds.min.y,
                           (i & 4) ? bounds.max.z : bounds.min.z);
    farthest = std::max(farthest, glm::length(p - corner));
  }
  f.orthographic = false;
  f.near = std::max(0.99f * nearest * std::cos(halfAngle), 1e-3f * radius);
  f.far = 1.01f * farthest;
  f.projection = glm::perspective(2.0f * halfAngle, 1.0f, f.near, f.far);
  return f;
}

glm::mat4 shadowMatrix(const LightFrustum& frustum) {
  // Clip space [−1, 1]³ → [0, 1]³ (texture coordinates and the default depth range).
  const glm::mat4 toUnit = glm::translate(glm::mat4(1.0f), glm::vec3(0.5f)) *
                           glm::scale(glm::mat4(1.0f), glm::vec3(0.5f));
  return toUnit * frustum.projection * frustum.view;
}

bool castsShadow(const SceneObject& object) {
  if (object.proxy) return false;
  const auto it = object.params.find("castsShadow");
  if (it != object.params.end()) return std::get<bool>(it->second);
  return object.role != Role::Exterior;
}

ShadowMap::ShadowMap(FrameSetup& setup)
    : setup_(setup), unit_(setup.bindings.textureUnit("SHADOW_MAP")) {
  program_ = gl::buildProgram({.stages = {{GL_VERTEX_SHADER, "frame/mesh.vert"},
                                          {GL_FRAGMENT_SHADER, "styles/shadows/shadow_map.frag"}}});
  lightUniforms_ =
      gl::Buffer::create(GLsizeiptr(sizeof(FrameUniforms)), nullptr, GL_DYNAMIC_STORAGE_BIT);
  const int n = style().size;
  Frame& frame = setup.frame;
  map_ = frame.declare("shadowMap",
                {.format = GL_R32F,
                 .width = n,
                 .height = n,
                 .meaning = "depth from the key light along its axis, scene units, of the "
                            "nearest shadow caster (objects of role exterior and those with "
                            "castsShadow false are not drawn); 0 where no caster (" +
                            std::to_string(n) + "x" + std::to_string(n) +
                            " shadow map, light-space texels)"});
  depth_ = frame.declare("shadowDepth", {.format = GL_DEPTH_COMPONENT32F, .width = n, .height = n});
  const GLuint depth = frame.texture(depth_).id();
  // Hardware percentage-closer filtering: each lookup compares the 2×2 nearest texels and
  // filters the results bilinearly; shadow_lookup.glsl averages a grid of such lookups.
  glTextureParameteri(depth, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTextureParameteri(depth, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  glTextureParameteri(depth, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(depth, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  // Outside the map nothing was drawn: lit.
  const float border[4] = {1, 1, 1, 1};
  glTextureParameteri(depth, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
  glTextureParameteri(depth, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
  glTextureParameterfv(depth, GL_TEXTURE_BORDER_COLOR, border);
}

void ShadowMap::addPass(Frame& frame) {
  frame.addPass({.name = "shadowMap",
                 .writes = {map_, depth_},
                 .run = [this](const PassContext& pass) {
                   const float zero[4] = {0, 0, 0, 0}, one = 1.0f;
                   glClearNamedFramebufferfv(pass.framebuffer, GL_COLOR, 0, zero);
                   glClearNamedFramebufferfv(pass.framebuffer, GL_DEPTH, 0, &one);
                   if (!active_) return;
                   GLint frameUniforms = 0;
                   glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, 0, &frameUniforms);
                   glBindBufferBase(GL_UNIFORM_BUFFER, 0, lightUniforms_.id());
                   glEnable(GL_DEPTH_TEST);
                   glDepthFunc(GL_LESS);
                   glDepthMask(GL_TRUE);
                   glDisable(GL_CULL_FACE);  // open meshes cast from both sides
                   // Slope-scaled bias: a caster's depth is pushed back by slopeBias × its
                   // depth slope (plus a few units of depth resolution), so lit surfaces do
                   // not shadow themselves ("shadow acne") where they are at a grazing angle
                   // to the light and the PCF taps reach across a texel.
                   glEnable(GL_POLYGON_OFFSET_FILL);
                   glPolygonOffset(style().slopeBias, 4.0f);
                   setup_.meshes.draw(
                       program_.id(),
                       [](const SceneObject& o, std::size_t) { return castsShadow(o); },
                       [](const SceneObject&, std::size_t) {});
                   if (setup_.drawShadowCasters) setup_.drawShadowCasters();
                   glDisable(GL_POLYGON_OFFSET_FILL);
                   glBindBufferBase(GL_UNIFORM_BUFFER, 0, GLuint(frameUniforms));
                 }});
}

void ShadowMap::bindForLookup() const {
  glBindTextureUnit(unit_, setup_.frame.texture(depth_).id());
}

}  // namespace cutaway
