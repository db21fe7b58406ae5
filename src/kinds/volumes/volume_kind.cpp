#include "kinds/volumes/volume_kind.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "cutaway/core/error.hpp"

namespace cutaway {

namespace {
// Uniform locations of kinds/volumes/volume.frag.
constexpr GLint kWorldToIndex = 0, kDims = 1, kStep = 2, kOpacityExponent = 3, kTransferRange = 4,
                kMode = 5, kIsoValue = 6, kShading = 7, kJitter = 8, kCutBy = 9, kInterest = 10,
                kGradientToWorld = 11, kVoxel = 14;
constexpr int kTransferSize = 1024;

// Central differences over one voxel in index space, clamped at the edges, per voxel: the
// shading's gradient, interpolated by the GPU (one fetch per sample instead of six).
std::vector<glm::vec4> voxelGradients(const Volume& v) {
  std::vector<glm::vec4> out(v.voxelCount());
  const glm::ivec3 hi = v.dims - 1;
  std::size_t n = 0;
  for (int k = 0; k < v.dims.z; ++k)
    for (int j = 0; j < v.dims.y; ++j)
      for (int i = 0; i < v.dims.x; ++i, ++n) {
        const auto at = [&](int x, int y, int z) {
          return v.at(glm::clamp(glm::ivec3(x, y, z), glm::ivec3(0), hi));
        };
        out[n] = glm::vec4(0.5f * (at(i + 1, j, k) - at(i - 1, j, k)),
                           0.5f * (at(i, j + 1, k) - at(i, j - 1, k)),
                           0.5f * (at(i, j, k + 1) - at(i, j, k - 1)), 0.0f);
      }
  return out;
}

gl::Texture texture3D(GLenum format, glm::ivec3 dims, GLenum components, const void* data) {
  gl::Texture t = gl::Texture::create(GL_TEXTURE_3D);
  glTextureStorage3D(t.id(), 1, format, dims.x, dims.y, dims.z);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTextureSubImage3D(t.id(), 0, 0, 0, 0, dims.x, dims.y, dims.z, components, GL_FLOAT, data);
  for (GLenum p : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    glTextureParameteri(t.id(), p, GL_CLAMP_TO_EDGE);
  glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  return t;
}

gl::Texture texture1D(GLenum format, GLenum type, int size, const void* data) {
  gl::Texture t = gl::Texture::create(GL_TEXTURE_1D);
  glTextureStorage1D(t.id(), 1, format, size);
  glTextureSubImage1D(t.id(), 0, 0, size, format == GL_RGBA32F ? GL_RGBA : GL_RED, type, data);
  glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(t.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  return t;
}

// The smallest world length of a voxel step: the ray's step is set in these.
float smallestSpacing(const SceneVolume& v) {
  const glm::mat3 m(v.indexToWorld());
  return std::min({glm::length(m[0]), glm::length(m[1]), glm::length(m[2])});
}
}  // namespace

TransferTable transferTable(const TransferFunction& tf, int size) {
  TransferTable table;
  table.first = tf.points.front().value;
  // One control point: a constant, over any range.
  table.last = tf.points.size() > 1 ? tf.points.back().value : table.first + 1.0f;
  for (int i = 0; i < size; ++i) {
    const float t = float(i) / float(size - 1);
    const TransferPoint p = tf.at(table.first + t * (table.last - table.first));
    table.colorOpacity.emplace_back(p.color, p.opacity);
    table.importance.push_back(p.importance);
  }
  return table;
}

VolumeKind::VolumeKind(FrameSetup& setup) : setup_(setup) {
  GLint maxSize = 0;
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &maxSize);
  while (glGetError() != GL_NO_ERROR) {
  }
  for (const SceneVolume& v : setup.scene.volumes) {
    const Volume& data = *v.volume;
    if (glm::any(glm::greaterThan(data.dims, glm::ivec3(maxSize))))
      throw Error(v.source, "",
                  "volume of " + std::to_string(data.dims.x) + "×" + std::to_string(data.dims.y) +
                      "×" + std::to_string(data.dims.z) +
                      " voxels exceeds the GPU's 3-D texture size of " + std::to_string(maxSize));
    VolumeGpu gpu;
    gpu.values = texture3D(GL_R32F, data.dims, GL_RED, data.values.data());
    gpu.gradient = texture3D(GL_RGBA16F, data.dims, GL_RGBA, voxelGradients(data).data());
    if (glGetError() == GL_OUT_OF_MEMORY)
      throw Error(v.source, "",
                  "volume of " + std::to_string(data.voxelCount() * 12 / (1 << 20)) +
                      " MiB (values and gradients) does not fit in the GPU's memory");
    const TransferTable table = transferTable(v.transfer, kTransferSize);
    gpu.transfer = texture1D(GL_RGBA32F, GL_FLOAT, kTransferSize, table.colorOpacity.data());
    gpu.importance = texture1D(GL_R32F, GL_FLOAT, kTransferSize, table.importance.data());
    gpu.transferRange = {table.first, table.last};
    volumes_.push_back(std::move(gpu));
  }
  const auto aov = [&](const char* name, const char* meaning) {
    return setup.frame.declare(name, {.format = GL_R32F, .meaning = meaning});
  };
  entryDepth_ = aov("volumeEntryDepth",
                    "linear view depth (world units) of the first ray sample of a volume that is "
                    "material (composite: of non-zero opacity) and that the cutters keep; NaN "
                    "where there is none (Burns11 §5.2.5: rays start at the cutaway surface)");
  hitDepth_ = aov("volumeHitDepth",
                  "linear view depth where a volume's accumulated opacity reaches 0.5 "
                  "(composite), of the isosurface (isosurface) or of the maximum (maximum); NaN "
                  "where none");
  opacity_ = aov("volumeOpacity", "accumulated opacity of the volumes' rays in [0, 1]");
}

void VolumeKind::prepare(const std::vector<ActiveCutter>& cutters) {
  cutters_ = &cutters;
  program_ =
      gl::buildProgram(setup_.geometryProgram({{GL_VERTEX_SHADER, "frame/fullscreen.vert"},
                                               {GL_FRAGMENT_SHADER, "kinds/volumes/volume.frag"}}));
}

void VolumeKind::addPassesAfterComposite(Frame& frame) {
  frame.addPass({.name = "volumes",
                 .reads = {setup_.gbuffer.depth()},
                 .writes = {setup_.gbuffer.finalColor(), entryDepth_, hitDepth_, opacity_},
                 .run = [this](const PassContext&) { draw(*cutters_); }});
}

void VolumeKind::draw(const std::vector<ActiveCutter>& cutters) const {
  const Frame& frame = setup_.frame;
  const float nan = std::numeric_limits<float>::quiet_NaN(), zero = 0.0f;
  glClearTexImage(frame.texture(entryDepth_).id(), 0, GL_RED, GL_FLOAT, &nan);
  glClearTexImage(frame.texture(hitDepth_).id(), 0, GL_RED, GL_FLOAT, &nan);
  glClearTexImage(frame.texture(opacity_).id(), 0, GL_RED, GL_FLOAT, &zero);
  const GLuint program = program_.id();
  glUseProgram(program);
  // The cutters' textures and images stay bound from the geometry pass (units from 8 up are
  // theirs for the whole frame: frame/bindings.hpp); the style's are bound again.
  setup_.bindShading();
  for (const ActiveCutter& c : cutters) c.cutter->setProgramUniforms(program);
  glBindTextureUnit(0, frame.texture(setup_.gbuffer.depth()).id());
  glDisable(GL_DEPTH_TEST);
  glEnablei(GL_BLEND, 0);  // "over" the final colour; the AOVs are written as they are
  glBlendFunci(0, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  for (std::size_t i = 0; i < volumes_.size(); ++i) {
    const SceneVolume& v = setup_.scene.volumes[i];
    const VolumeGpu& gpu = volumes_[i];
    int cutBy = 0;
    for (const ActiveCutter& c : cutters)
      if (c.cutter->cutsVolume(i)) cutBy |= 1 << c.slot;
    const glm::mat4 indexToWorld = v.indexToWorld();
    const glm::mat4 worldToIndex = glm::inverse(indexToWorld);
    const glm::mat3 gradientToWorld = glm::transpose(glm::mat3(worldToIndex));
    const glm::vec3 dims(v.volume->dims);
    const float spacing = smallestSpacing(v);
    glProgramUniformMatrix4fv(program, kWorldToIndex, 1, GL_FALSE, &worldToIndex[0][0]);
    glProgramUniform3fv(program, kDims, 1, &dims[0]);
    glProgramUniform1f(program, kStep, v.sampleDistance * spacing);
    glProgramUniform1f(program, kVoxel, spacing);
    glProgramUniform1f(program, kOpacityExponent, v.sampleDistance / v.opacityDistance);
    glProgramUniform2fv(program, kTransferRange, 1, &gpu.transferRange[0]);
    glProgramUniform1i(program, kMode, int(v.mode));
    glProgramUniform1f(program, kIsoValue, v.isoValue);
    glProgramUniform1i(program, kShading, v.shading);
    glProgramUniform1i(program, kJitter, v.jitter);
    glProgramUniform1i(program, kCutBy, cutBy);
    glProgramUniform1i(program, kInterest, v.role == Role::Interest);
    glProgramUniformMatrix3fv(program, kGradientToWorld, 1, GL_FALSE, &gradientToWorld[0][0]);
    glBindTextureUnit(1, gpu.values.id());
    glBindTextureUnit(2, gpu.transfer.id());
    glBindTextureUnit(3, gpu.importance.id());
    glBindTextureUnit(4, gpu.gradient.id());
    fullscreen_.draw();
  }
  glDisablei(GL_BLEND, 0);
}

}  // namespace cutaway
