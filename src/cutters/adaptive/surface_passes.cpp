#include "cutters/adaptive/surface_passes.hpp"

#include <algorithm>
#include <new>
#include <string>

#include "cutaway/core/error.hpp"
#include "frame/fullscreen.hpp"

namespace cutaway {

namespace {

// How an n×n buffer lies over the view, whatever its aspect.
std::string bufferText(int n) {
  const std::string side = std::to_string(n);
  return " (" + side + "x" + side +
         " cutaway buffer over the whole view, stretched to its aspect: pixel (i, j), j from "
         "the bottom, has its centre at NDC ((i + ½)·2/" +
         side + " − 1, (j + ½)·2/" + side + " − 1))";
}

std::string anchorConeMeaning(const std::string& of, const std::string& size) {
  return "per seed texel: its cone: NDC depth z (−1: not seeded), the slope m_E of the "
         "edge-compressed angle θ_e (Burns11 eqs. 5.7–5.8) and m_F after the directional "
         "constraint (eqs. 6.1–6.2), NDC depth per view-plane unit" +
         of + size;
}

}  // namespace

struct CutawaySurfacePasses::Programs {
  gl::Program anchors, jfaInit, jumpFlooding, cutawayDepth, dilate;
  FullscreenTriangle fullscreen;
};

CutawaySurfacePasses::CutawaySurfacePasses(Frame& frame, int bufferSize,
                                           fields::JumpFloodingVariant variant, bool cpu,
                                           Options options)
    : frame_(frame),
      minAngle_([] { return 0.0f; }),
      bufferSize_(bufferSize),
      variant_(variant),
      cpu_(cpu),
      options_(std::move(options)),
      programs_(std::make_unique<Programs>()) {
  const int n = bufferSize_;
  const std::string size = bufferText(n);
  seedDepth_ = frame.declare("seedDepth",
                             {.format = GL_R32F,
                              .width = n,
                              .height = n,
                              .meaning = "window depth in [0,1] of the region of interest's rear "
                                         "hull (greater-than depth test); 0 = near plane, no "
                                         "seed" +
                                         size});
  seedAngle_ = frame.declare(
      "seedAngle", {.format = GL_R32F,
                    .width = n,
                    .height = n,
                    .meaning = "local cutaway angle θ of the seeding object, radians" + size});
  declareSurface();
}

CutawaySurfacePasses::CutawaySurfacePasses(const CutawaySurfacePasses& seed, std::string suffix,
                                           std::function<float()> minAngle)
    : frame_(seed.frame_),
      suffix_(std::move(suffix)),
      minAngle_(std::move(minAngle)),
      bufferSize_(seed.bufferSize_),
      variant_(seed.variant_),
      cpu_(seed.cpu_),
      options_(seed.options_),
      seedDepth_(seed.seedDepth_),
      seedAngle_(seed.seedAngle_),
      programs_(std::make_unique<Programs>()) {
  declareSurface();
}

void CutawaySurfacePasses::declareSurface() {
  Frame& frame = frame_;
  const int n = bufferSize_;
  const std::string size = bufferText(n);
  const std::string of = suffix_.empty() ? "" : ", every seed's angle at least θ₂ (" + suffix_ + ")";
  cutawayDepth_ = frame.declare("cutawayDepth" + suffix_,
                                {.format = GL_R32F,
                                 .width = n,
                                 .height = n,
                                 .meaning = "cutaway surface C(p) as window depth in [0,1] (0 = "
                                            "near plane: nothing cut); fragments nearer than it "
                                            "are removed. Burns11 eq. 4.2 in NDC depth: C(p) = "
                                            "max over seeds q of z_q − m_q·‖p − q‖, ‖·‖ in "
                                            "view-plane units (values: viewPlanePerPixelX/Y per "
                                            "buffer pixel), z_q and m_q in anchorCone; window "
                                            "depth = (NDC + 1)/2" +
                                            of + size});
  cutawayDilated_ = frame.declare("cutawayDilated" + suffix_,
                                  {.format = GL_R32F,
                                   .width = n,
                                   .height = n,
                                   .meaning = "1-pixel minimum of cutawayDepth" + suffix_ +
                                              ", window depth, used for back faces" + size});
  for (const Target t : {cutawayDepth_, cutawayDilated_}) {
    const GLuint id = frame.texture(t).id();
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR);  // Burns08 §6: interpolated
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  }
  Programs& p = *programs_;
  p.dilate = buildFullscreenProgram("cutters/adaptive/dilate.frag");
  if (cpu_) return;
  anchorCone_ = frame.declare("anchorCone" + suffix_, {.format = GL_RGBA32F,
                                                       .width = n,
                                                       .height = n,
                                                       .meaning = anchorConeMeaning(of, size),
                                                       .aovChannels = 3});
  anchorFloor_ = frame.declare("anchorFloor" + suffix_, {.format = GL_RG32F, .width = n, .height = n});
  anchorsA_ = frame.declare("anchorsA" + suffix_, {.format = GL_R32I, .width = n, .height = n});
  anchorsB_ = frame.declare("anchorsB" + suffix_, {.format = GL_R32I, .width = n, .height = n});
  p.anchors = buildFullscreenProgram("cutters/adaptive/anchors.frag");
  p.jfaInit = buildFullscreenProgram("cutters/adaptive/jfa_init.frag");
  p.jumpFlooding =
      gl::buildProgram({.stages = {{GL_COMPUTE_SHADER, "cutters/adaptive/jump_flooding.comp"}}});
  p.cutawayDepth = buildFullscreenProgram("cutters/adaptive/cutaway_depth.frag");
}

CutawaySurfacePasses::~CutawaySurfacePasses() = default;

void CutawaySurfacePasses::addPasses() {
  if (cpu_)
    frame_.addPass({.name = "cutawayCpu" + suffix_,
                   .reads = {seedDepth_, seedAngle_},
                   .writes = {cutawayDepth_},
                   .run = [this](const PassContext&) { computeOnCpu(); }});
  else
    addGpuPasses();
  frame_.addPass({.name = "cutawayDilate" + suffix_,
                 .reads = {cutawayDepth_},
                 .writes = {cutawayDilated_},
                 .run = [this](const PassContext&) {
                   glDisable(GL_DEPTH_TEST);
                   glUseProgram(programs_->dilate.id());
                   glBindTextureUnit(0, frame_.texture(cutawayDepth_).id());
                   programs_->fullscreen.draw();
                 }});
}

void CutawaySurfacePasses::addGpuPasses() {
  auto bindCone = [this](GLuint program) {
    glUseProgram(program);
    glBindTextureUnit(0, frame_.texture(anchorCone_).id());
    glBindTextureUnit(1, frame_.texture(anchorFloor_).id());
    // View-plane units per buffer pixel: Δndc / P00 horizontally, Δndc / P11 vertically.
    const float n = float(bufferSize_);
    glProgramUniform2f(program, 0, 2.0f / n / camera_.projection[0][0],
                       2.0f / n / camera_.projection[1][1]);
    glDisable(GL_DEPTH_TEST);
  };
  frame_.addPass({.name = "cutawayAnchors" + suffix_,
                 .reads = {seedDepth_, seedAngle_},
                 .writes = {anchorCone_, anchorFloor_},
                 .run = [this](const PassContext&) {
                   const AdaptiveCutawayOptions& o = options_();
                   const GLuint program = programs_->anchors.id();
                   glUseProgram(program);
                   glBindTextureUnit(0, frame_.texture(seedDepth_).id());
                   glBindTextureUnit(1, frame_.texture(seedAngle_).id());
                   const glm::vec3 floor = glm::normalize(camera_.viewRotation * o.floorNormal);
                   glProgramUniform1i(program, 0, o.edgeCompression);
                   glProgramUniform1f(program, 1, o.edgeRegion);
                   glProgramUniform1i(program, 2, o.directionalConstraint);
                   glProgramUniform3fv(program, 3, 1, &floor[0]);
                   glProgramUniform1i(program, 4, o.perspectiveCompensation);
                   glProgramUniform1i(program, 5, camera_.orthographic);
                   const glm::mat4 inverse = glm::inverse(camera_.projection);
                   glProgramUniformMatrix4fv(program, 6, 1, GL_FALSE, &camera_.projection[0][0]);
                   glProgramUniformMatrix4fv(program, 7, 1, GL_FALSE, &inverse[0][0]);
                   glProgramUniform1f(program, 8, minAngle_());
                   glDisable(GL_DEPTH_TEST);
                   programs_->fullscreen.draw();
                 }});
  frame_.addPass({.name = "jumpFloodingInit" + suffix_,
                 .reads = {anchorCone_},
                 .writes = {anchorsA_},
                 .run = [this](const PassContext&) {
                   glUseProgram(programs_->jfaInit.id());
                   glBindTextureUnit(0, frame_.texture(anchorCone_).id());
                   glDisable(GL_DEPTH_TEST);
                   programs_->fullscreen.draw();
                 }});
  // One compute pass per step, ping-ponging the anchor buffers.
  Target current = anchorsA_, next = anchorsB_;
  for (int step : fields::stepSizes(bufferSize_, bufferSize_, variant_)) {
    frame_.addPass({.name = "jumpFlooding" + suffix_ + "/" + std::to_string(step),
                   .reads = {anchorCone_, anchorFloor_, current},
                   .writes = {next},
                   .run =
                       [this, bindCone, step, current, next](const PassContext& pass) {
                         const GLuint program = programs_->jumpFlooding.id();
                         bindCone(program);
                         glBindTextureUnit(2, frame_.texture(current).id());
                         glBindImageTexture(0, frame_.texture(next).id(), 0, GL_FALSE, 0,
                                            GL_WRITE_ONLY, GL_R32I);
                         glProgramUniform1i(program, 1, step);
                         glDispatchCompute(GLuint(pass.width + 7) / 8, GLuint(pass.height + 7) / 8, 1);
                       },
                   .compute = true});
    std::swap(current, next);
  }
  frame_.addPass({.name = "cutawayDepth" + suffix_,
                 .reads = {anchorCone_, anchorFloor_, current},
                 .writes = {cutawayDepth_},
                 .run = [this, bindCone, current](const PassContext&) {
                   bindCone(programs_->cutawayDepth.id());
                   glBindTextureUnit(2, frame_.texture(current).id());
                   programs_->fullscreen.draw();
                 }});
}

// The same computation as the GPU passes: the seed read back, cones from anchorCone()
// (cutaway_function.cpp mirrors anchors.frag), fields::jumpFlooding, and the result uploaded.
void CutawaySurfacePasses::computeOnCpu() {
  const int n = bufferSize_;
  std::vector<float> angle = frame_.read(seedAngle_, 1);
  for (float& a : angle) a = std::max(a, minAngle_());
  fields::CutawayField field;
  try {
    field = fields::jumpFlooding(
        makeSeedImage(frame_.read(seedDepth_, 1), angle, n, options_(), camera_), -1.0f, variant_);
  } catch (const std::bad_alloc&) {
    throw Error(
        "", "cutters.adaptive.bufferSize",
        "out of memory for the " + std::to_string(n) + "x" + std::to_string(n) +
            " cutaway buffer on the CPU; use a smaller bufferSize, or \"compute\": \"gpu\"");
  }
  for (float& z : field.depth) z = z * 0.5f + 0.5f;  // NDC → window depth
  glTextureSubImage2D(frame_.texture(cutawayDepth_).id(), 0, 0, 0, n, n, GL_RED, GL_FLOAT,
                      field.depth.data());
  greatest_ = GreatestDepth(std::move(field.depth), n);
}

void CutawaySurfacePasses::describeAovs(std::vector<Aov>& aovs) const {
  const int n = bufferSize_;
  const std::string of =
      suffix_.empty() ? "" : ", every seed's angle at least θ₂ (" + suffix_ + ")";
  if (cpu_) {
    std::vector<float> angle = frame_.read(seedAngle_, 1);
    for (float& a : angle) a = std::max(a, minAngle_());
    const fields::SeedImage seeds =
        makeSeedImage(frame_.read(seedDepth_, 1), angle, n, options_(), camera_);
    FloatImage cone(n, n, 3);
    for (std::size_t i = 0; i < seeds.depth.size(); ++i) {
      cone.data[3 * i] = seeds.seeded[i] ? seeds.depth[i] : -1.0f;
      cone.data[3 * i + 1] = seeds.slopeE[i];
      cone.data[3 * i + 2] = seeds.slopeF[i];
    }
    cone.flipVertically();  // AOVs run top to bottom
    aovs.push_back({"anchorCone" + suffix_, anchorConeMeaning(of, bufferText(n)), std::move(cone)});
  }
  const std::map<std::string, double> values = {
      {"bufferSize", n},
      {"viewPlanePerPixelX", 2.0 / double(n) / double(camera_.projection[0][0])},
      {"viewPlanePerPixelY", 2.0 / double(n) / double(camera_.projection[1][1])}};
  for (Aov& aov : aovs)
    if (aov.name == "cutawayDepth" + suffix_ || aov.name == "cutawayDilated" + suffix_ ||
        aov.name == "anchorCone" + suffix_ ||
        (suffix_.empty() && (aov.name == "seedDepth" || aov.name == "seedAngle")))
      aov.values = values;
}

}  // namespace cutaway
