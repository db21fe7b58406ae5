#include "kinds/volumes/volume_kind.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "cutaway/core/error.hpp"
#include "cutaway/kinds/volume_ray_cast.hpp"
#include "kinds/volumes/volume_blocks.hpp"

namespace cutaway {

namespace {
// Uniform locations of kinds/volumes/volume.frag.
constexpr GLint kWorldToIndex = 0, kDims = 1, kStep = 2, kOpacityExponent = 3, kTransferRange = 4,
                kIsoValue = 6, kJitter = 8, kCutBy = 9, kInterest = 10, kGradientToWorld = 11,
                kVoxel = 14, kStepRearHull = 2, kTheta = 16, kPassSize = 17, kGradientRange = 18;
// Texels of a continuous transfer function's table along the value and, for a two-dimensional
// one, along the gradient magnitude.
constexpr int kTransferSize = 1024, kGradientSize = 256;

// Central differences over one voxel in index space, clamped at the edges, per voxel: the
// shading's gradient, interpolated by the GPU (one fetch per sample instead of six). A label
// volume's is the gradient of its materials' opacity: labels have no order to differentiate.
std::vector<glm::vec4> voxelGradients(const SceneVolume& sv) {
  Volume opacity;
  if (sv.labels) {
    opacity.dims = sv.volume->dims;
    for (float value : sv.volume->values) opacity.values.push_back(sv.material(value).opacity);
  }
  const Volume& v = sv.labels ? opacity : *sv.volume;
  // voxelGradient's differences a row at a time: the neighbouring rows clamped once per row,
  // the row's ends per voxel (the same values, in a loop the compiler vectorises).
  std::vector<glm::vec4> out(v.voxelCount());
  const auto row = [&](int j, int k) {
    return std::size_t(v.dims.x) * (std::size_t(j) + std::size_t(v.dims.y) * std::size_t(k));
  };
  for (int k = 0; k < v.dims.z; ++k)
    for (int j = 0; j < v.dims.y; ++j) {
      const float* here = &v.values[row(j, k)];
      const float* down = &v.values[row(std::max(j - 1, 0), k)];
      const float* up = &v.values[row(std::min(j + 1, v.dims.y - 1), k)];
      const float* back = &v.values[row(j, std::max(k - 1, 0))];
      const float* front = &v.values[row(j, std::min(k + 1, v.dims.z - 1))];
      glm::vec4* o = &out[row(j, k)];
      for (int i = 0; i < v.dims.x; ++i) {
        const int left = std::max(i - 1, 0), right = std::min(i + 1, v.dims.x - 1);
        o[i] = glm::vec4(
            0.5f * glm::vec3(here[right] - here[left], up[i] - down[i], front[i] - back[i]), 0.0f);
      }
    }
  return out;
}

// Empty-space skipping (volume.frag): per block of kVolumeBlock³ voxels, 1 where a sample in
// it can have opacity. The transfer function's opacity over a block's range (volume_blocks.hpp)
// is largest at its ends or at a control point inside (at some gradient magnitude:
// SceneVolume::mayBeVisible), so the flag is conservative.
std::vector<std::uint8_t> occupancy(const SceneVolume& sv, glm::ivec3& grid) {
  const BlockRanges blocks = blockRanges(*sv.volume);
  grid = blocks.grid;
  std::vector<std::uint8_t> out(blocks.range.size(), 0);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const glm::vec2 r = blocks.range[i];
    // NaN voxels make no interval: their blocks are kept.
    out[i] = !(r.x <= r.y) || sv.mayBeVisible(r.x, r.y);
  }
  return out;
}

gl::Texture texture3D(GLenum format, glm::ivec3 dims, GLenum components, const void* data,
                      GLenum filter) {
  gl::Texture t = gl::Texture::create(GL_TEXTURE_3D);
  glTextureStorage3D(t.id(), 1, format, dims.x, dims.y, dims.z);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTextureSubImage3D(t.id(), 0, 0, 0, 0, dims.x, dims.y, dims.z, components, GL_FLOAT, data);
  for (GLenum p : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    glTextureParameteri(t.id(), p, GL_CLAMP_TO_EDGE);
  glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, filter);
  glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, filter);
  return t;
}

gl::Texture texture2D(GLenum format, glm::ivec2 size, const void* data, GLenum filter) {
  gl::Texture t = gl::Texture::create(GL_TEXTURE_2D);
  glTextureStorage2D(t.id(), 1, format, size.x, size.y);
  glTextureSubImage2D(t.id(), 0, 0, 0, size.x, size.y, format == GL_RGBA32F ? GL_RGBA : GL_RED,
                      GL_FLOAT, data);
  glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, filter);
  glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, filter);
  glTextureParameteri(t.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(t.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return t;
}
}  // namespace

TransferTable transferTable(const SceneVolume& v) {
  const TransferFunction& tf = v.transfer;
  TransferTable table;
  // The value range over every row's points; one control point in all: a constant, over any range.
  table.first = std::numeric_limits<float>::infinity(), table.last = -table.first;
  for (const TransferFunction::Row& row : tf.rows) {
    table.first = std::min(table.first, row.points.front().value);
    table.last = std::max(table.last, row.points.back().value);
  }
  if (table.last == table.first) table.last = table.first + 1.0f;
  // Labels: one texel per label, and a clear one beyond each end, which the lookup's clamping
  // gives every label outside the listed range.
  const std::vector<TransferPoint>& points = tf.rows.front().points;
  if (v.labels) table.first = points.front().value - 1.0f, table.last = points.back().value + 1.0f;
  table.width = v.labels ? int(table.last - table.first) + 1 : kTransferSize;
  table.height = tf.twoDimensional() ? kGradientSize : 1;
  table.firstGradient = tf.rows.front().gradient, table.lastGradient = tf.rows.back().gradient;
  for (int j = 0; j < table.height; ++j) {
    const float g = table.height > 1 ? float(j) / float(table.height - 1) : 0.0f;
    const float gradient = table.firstGradient + g * (table.lastGradient - table.firstGradient);
    for (int i = 0; i < table.width; ++i) {
      const float t = float(i) / float(table.width - 1);
      const TransferPoint p = v.material(table.first + t * (table.last - table.first), gradient);
      table.colorOpacity.emplace_back(p.color, p.opacity);
      table.importance.push_back(p.importance);
    }
  }
  return table;
}

VolumeKind::VolumeKind(FrameSetup& setup)
    : setup_(setup),
      occupancyUnit_(setup.bindings.textureUnit("VOLUME_OCCUPANCY")),
      previousTransmittanceUnit_(setup.bindings.textureUnit("VOLUME_PREVIOUS_TRANSMITTANCE")) {
  GLint maxSize = 0;
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &maxSize);
  for (std::size_t i = 0; i < setup.scene.volumes.size(); ++i) {
    const SceneVolume& v = setup.scene.volumes[i];
    const Volume& data = *v.volume;
    if (glm::any(glm::greaterThan(data.dims, glm::ivec3(maxSize))))
      throw Error(setup.scene.file.string(), "/volumes/" + std::to_string(i) + "/file",
                  v.source + ": a volume of " + std::to_string(data.dims.x) + "×" +
                      std::to_string(data.dims.y) + "×" + std::to_string(data.dims.z) +
                      " voxels exceeds the GPU's 3-D texture size of " + std::to_string(maxSize));
    VolumeGpu gpu;
    const bool outOfMemory = gl::outOfMemory([&] {
      // Labels are sampled at the nearest voxel: interpolating between two would invent a
      // third.
      gpu.values = texture3D(GL_R32F, data.dims, GL_RED, data.values.data(),
                             v.labels ? GL_NEAREST : GL_LINEAR);
      if (!v.labels)
        gpu.gradient =
            texture3D(GL_RGBA16F, data.dims, GL_RGBA, voxelGradients(v).data(), GL_LINEAR);
      volumes_.push_back(std::move(gpu));
      uploadTransfer(volumes_.size() - 1);
    });
    if (outOfMemory)
      throw Error(setup.scene.file.string(), "/volumes/" + std::to_string(i) + "/file",
                  v.source + ": a volume of " + std::to_string(data.voxelCount() * 12 / (1 << 20)) +
                      " MiB (values and gradients) does not fit in the GPU's memory");
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
  transmittance_ = aov("volumeLightTransmittance",
                       "the fraction of the key light that reaches the sample of volumeHitDepth "
                       "through the volume's material (volumes with \"shadows\"; 1 without, "
                       "unshaded samples included); NaN where no hit");
  if (VolumeLinesPass::present(setup.scene))
    lines_ = std::make_unique<VolumeLinesPass>(
        setup, [this](GLuint program, std::size_t i) { bindVolume(program, i); });
}

void VolumeKind::uploadTransfer(std::size_t i) const {
  const SceneVolume& v = setup_.scene.volumes[i];
  VolumeGpu& gpu = volumes_[i];
  // A label table holds a texel per label of its span and a clear one at each end (as
  // transferTable builds it): beyond the GPU's 2-D texture size it would sample as black.
  if (v.labels) {
    const std::vector<TransferPoint>& points = v.transfer.rows.front().points;
    const double first = points.front().value, last = points.back().value;
    GLint maxWidth = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxWidth);
    if (last - first + 3.0 > double(maxWidth))
      throw Error(setup_.scene.file.string(), "/volumes/" + std::to_string(i) + "/transferFunction",
                  "its labels span " + std::to_string(long(last - first) + 1) + " values (" +
                      std::to_string(long(first)) + " to " + std::to_string(long(last)) +
                      "), beyond the " + std::to_string(maxWidth - 2) +
                      " that this GPU's 2-D texture size of " + std::to_string(maxWidth) +
                      " allows (a texel per label and a clear one at each end)");
  }
  const TransferTable table = transferTable(v);
  // A label volume's gradient is that of its materials' opacity.
  if (v.labels)
    gpu.gradient =
        texture3D(GL_RGBA16F, v.volume->dims, GL_RGBA, voxelGradients(v).data(), GL_LINEAR);
  glm::ivec3 grid;
  const std::vector<std::uint8_t> blocks = occupancy(v, grid);
  gpu.occupancy = gl::Texture::create(GL_TEXTURE_3D);
  glTextureStorage3D(gpu.occupancy.id(), 1, GL_R8UI, grid.x, grid.y, grid.z);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage3D(gpu.occupancy.id(), 0, 0, 0, 0, grid.x, grid.y, grid.z, GL_RED_INTEGER,
                      GL_UNSIGNED_BYTE, blocks.data());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  // An integer texture is complete only without mipmap filtering.
  glTextureParameteri(gpu.occupancy.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(gpu.occupancy.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  const glm::ivec2 size(table.width, table.height);
  const GLenum filter = v.labels ? GL_NEAREST : GL_LINEAR;
  gpu.transfer = texture2D(GL_RGBA32F, size, table.colorOpacity.data(), filter);
  gpu.importance = texture2D(GL_R32F, size, table.importance.data(), filter);
  gpu.transferRange = {table.first, table.last};
  gpu.gradientRange = {table.firstGradient, table.lastGradient};
  gpu.uploaded = v.transfer;
}

void VolumeKind::updateTransfers() const {
  for (std::size_t i = 0; i < volumes_.size(); ++i)
    if (!(volumes_[i].uploaded == setup_.scene.volumes[i].transfer)) uploadTransfer(i);
}

int VolumeKind::cutBy(const std::vector<ActiveCutter>& cutters, std::size_t volume) {
  int bits = 0;
  for (const ActiveCutter& c : cutters)
    if (c.cutter->cutsVolume(volume)) bits |= 1 << c.slot;
  return bits;
}

namespace {
// A volume's program variant: what volume.frag compiles in (TRANSFER_2D, SHADOWS, MODE,
// SHADING, CUT); the rear hulls' programs take only the transfer function's dimension.
struct Variant {
  bool twoDimensional = false, shadows = false, shading = false, cut = false;
  int mode = 0;
  int key() const {
    return int(twoDimensional) | int(shadows) << 1 | int(shading) << 2 | int(cut) << 3 | mode << 4;
  }
  std::map<std::string, std::string> defines(bool cast = true) const {
    std::map<std::string, std::string> d;
    if (cast) d["MODE"] = std::to_string(mode);
    if (twoDimensional) d["TRANSFER_2D"] = "1";
    if (shadows) d["SHADOWS"] = "1";
    if (shading) d["SHADING"] = "1";
    if (cut) d["CUT"] = "1";
    return d;
  }
};
}  // namespace

GLuint VolumeKind::castProgram(const SceneVolume& v, bool cut) const {
  const Variant variant{.twoDimensional = v.transfer.twoDimensional(),
                        .shadows = v.shadows,
                        .shading = v.shading,
                        .cut = cut,
                        .mode = int(v.mode)};
  gl::Program& p = castPrograms_[variant.key()];
  if (!p.id())
    p = gl::buildProgram(setup_.geometryProgram({{GL_VERTEX_SHADER, "frame/fullscreen.vert"},
                                                 {GL_FRAGMENT_SHADER, "kinds/volumes/volume.frag"}},
                                                variant.defines()));
  return p.id();
}

GLuint VolumeKind::rearHullProgram(const SceneVolume& v) const {
  const Variant variant{.twoDimensional = v.transfer.twoDimensional()};
  gl::Program& p = rearHullPrograms_[variant.key()];
  if (!p.id())
    p = setup_.bindings.build(
        {.stages = {{GL_VERTEX_SHADER, "frame/fullscreen.vert"},
                    {GL_FRAGMENT_SHADER, "kinds/volumes/volume_rear_hull.frag"}},
         .defines = variant.defines(false)});
  return p.id();
}

void VolumeKind::prepare(const std::vector<ActiveCutter>& cutters) {
  cutters_ = &cutters;
  for (std::size_t i = 0; i < setup_.scene.volumes.size(); ++i) {
    const SceneVolume& v = setup_.scene.volumes[i];
    castProgram(v, cutBy(cutters, i) != 0);
    if (v.role == Role::Interest) rearHullProgram(v);
  }
  if (lines_) lines_->prepare(cutters);
  const int w = setup_.frame.width(), h = setup_.frame.height();
  previousEntry_ = gl::Texture::create2D(GL_R32F, w, h);
  previousHit_ = gl::Texture::create2D(GL_R32F, w, h);
  previousOpacity_ = gl::Texture::create2D(GL_R32F, w, h);
  previousTransmittance_ = gl::Texture::create2D(GL_R32F, w, h);
}

void VolumeKind::addPassesAfterComposite(Frame& frame) {
  frame.addPass(
      {.name = "volumes",
       .reads = {setup_.gbuffer.depth()},
       .writes = {setup_.gbuffer.finalColor(), entryDepth_, hitDepth_, opacity_, transmittance_},
       .run = [this](const PassContext&) { draw(*cutters_); }});
  if (lines_) lines_->addPasses(frame);
}

void VolumeKind::beginFrame(const FrameState& state) {
  if (lines_) lines_->beginFrame(state);
}

VolumeLineDrawing VolumeKind::lineDrawing() const {
  return lines_ ? lines_->drawing()
                : VolumeLineDrawing{setup_.frame.width(), setup_.frame.height(), {}};
}

void VolumeKind::draw(const std::vector<ActiveCutter>& cutters) const {
  updateTransfers();
  const Frame& frame = setup_.frame;
  const float nan = std::numeric_limits<float>::quiet_NaN(), zero = 0.0f;
  glClearTexImage(frame.texture(entryDepth_).id(), 0, GL_RED, GL_FLOAT, &nan);
  glClearTexImage(frame.texture(hitDepth_).id(), 0, GL_RED, GL_FLOAT, &nan);
  glClearTexImage(frame.texture(opacity_).id(), 0, GL_RED, GL_FLOAT, &zero);
  glClearTexImage(frame.texture(transmittance_).id(), 0, GL_RED, GL_FLOAT, &nan);
  // The cutters' textures and images stay bound from the geometry pass (units from 8 up are
  // theirs for the whole frame: frame/bindings.hpp); the style's are bound again.
  setup_.bindShading();
  glBindTextureUnit(0, frame.texture(setup_.gbuffer.depth()).id());
  glDisable(GL_DEPTH_TEST);
  glEnablei(GL_BLEND, 0);  // "over" the final colour; the AOVs are written as they are
  glBlendFunci(0, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  // Those of interest first: the others' rays stop at their material.
  std::vector<std::size_t> order(volumes_.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_partition(order.begin(), order.end(), [&](std::size_t i) {
    return setup_.scene.volumes[i].role == Role::Interest;
  });
  const int w = frame.width(), h = frame.height();
  for (const std::size_t i : order) {
    const SceneVolume& v = setup_.scene.volumes[i];
    if (v.lines && v.lines->only) continue;  // its lines alone
    const int cuts = cutBy(cutters, i);
    const GLuint program = castProgram(v, cuts != 0);
    glUseProgram(program);
    for (const ActiveCutter& c : cutters) c.cutter->setProgramUniforms(program);
    for (const ActiveCutter& c : cutters)
      if (c.cutter->cutsVolume(i)) c.cutter->setVolumeUniforms(program, i);
    for (const auto& [aov, copy] :
         {std::pair{entryDepth_, previousEntry_.id()}, std::pair{hitDepth_, previousHit_.id()},
          std::pair{opacity_, previousOpacity_.id()},
          std::pair{transmittance_, previousTransmittance_.id()}})
      glCopyImageSubData(frame.texture(aov).id(), GL_TEXTURE_2D, 0, 0, 0, 0, copy, GL_TEXTURE_2D, 0,
                         0, 0, 0, w, h, 1);
    bindVolume(program, i);
    const float spacing = smallestVoxelSpacing(v);
    glProgramUniform1f(program, kStep, v.sampleDistance * spacing);
    glProgramUniform1f(program, kVoxel, spacing);
    glProgramUniform1f(program, kOpacityExponent, v.sampleDistance / v.opacityDistance);
    glProgramUniform1f(program, kIsoValue, v.isoValue);
    glProgramUniform1i(program, kJitter, v.jitter);
    glProgramUniform1i(program, kCutBy, cuts);
    glProgramUniform1i(program, kInterest, v.role == Role::Interest);
    glBindTextureUnit(occupancyUnit_, volumes_[i].occupancy.id());
    glBindTextureUnit(5, previousHit_.id());
    glBindTextureUnit(6, previousEntry_.id());
    glBindTextureUnit(7, previousOpacity_.id());
    glBindTextureUnit(previousTransmittanceUnit_, previousTransmittance_.id());
    fullscreen_.draw();
  }
  glDisablei(GL_BLEND, 0);
}

void VolumeKind::bindVolume(GLuint program, std::size_t i) const {
  const SceneVolume& v = setup_.scene.volumes[i];
  const VolumeGpu& gpu = volumes_[i];
  const glm::mat4 worldToIndex = v.worldToIndex();
  const glm::vec3 dims(v.volume->dims);
  const glm::mat3 gradientToWorld = glm::transpose(glm::mat3(worldToIndex));
  glProgramUniformMatrix4fv(program, kWorldToIndex, 1, GL_FALSE, &worldToIndex[0][0]);
  glProgramUniform3fv(program, kDims, 1, &dims[0]);
  glProgramUniform2fv(program, kTransferRange, 1, &gpu.transferRange[0]);
  glProgramUniform2fv(program, kGradientRange, 1, &gpu.gradientRange[0]);
  glProgramUniformMatrix3fv(program, kGradientToWorld, 1, GL_FALSE, &gradientToWorld[0][0]);
  glBindTextureUnit(1, gpu.values.id());
  glBindTextureUnit(2, gpu.transfer.id());
  glBindTextureUnit(3, gpu.importance.id());
  glBindTextureUnit(4, gpu.gradient.id());
}

void VolumeKind::drawInterestRearHulls(const RearHullRequest& request) const {
  updateTransfers();
  GLint viewport[4];
  glGetIntegerv(GL_VIEWPORT, viewport);
  for (std::size_t i = 0; i < volumes_.size(); ++i) {
    const SceneVolume& v = setup_.scene.volumes[i];
    if (v.role != Role::Interest) continue;
    const GLuint program = rearHullProgram(v);
    glUseProgram(program);
    glProgramUniform2f(program, kPassSize, float(viewport[2]), float(viewport[3]));
    glProgramUniform1f(program, kTheta, request.theta(nullptr));
    bindVolume(program, i);
    glProgramUniform1f(program, kStepRearHull, v.sampleDistance * smallestVoxelSpacing(v));
    fullscreen_.draw();
  }
}

}  // namespace cutaway
