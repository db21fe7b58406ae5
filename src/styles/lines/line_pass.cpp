#include "styles/lines/line_pass.hpp"

#include <algorithm>
#include <cmath>

#include "frame/samples.hpp"

namespace cutaway {

namespace {

std::map<std::string, std::string> defines(bool outlines, int samples) {
  return sampleDefines(samples, outlines ? std::map<std::string, std::string>{{"CUT_OUTLINES", "1"}}
                                         : std::map<std::string, std::string>{});
}

}  // namespace

LinePass::LinePass(bool outlines, int samples)
    : samples_(samples),
      outlines_(outlines),
      program_(buildFullscreenProgram("styles/lines/lines.frag", defines(outlines, samples))),
      pixels_(buildFullscreenProgram("styles/lines/line_pixels.frag", defines(outlines, samples))) {
}

void LinePass::draw(const Frame& frame, Target normal, Target objectId,
                    std::optional<Target> cutMask, const LineStyle& l, bool featureLines,
                    bool skipEmpty) const {
  glBindTextureUnit(0, frame.texture(normal).id());
  glBindTextureUnit(1, frame.texture(objectId).id());
  if (cutMask) glBindTextureUnit(2, frame.texture(*cutMask).id());
  if (skipEmpty) {
    // The full-screen triangle lies at depth ½: line_pixels.frag writes it where a line may
    // be, over a depth of 0, and lines.frag is drawn where the depth equals it.
    const float zero[4] = {}, cleared = 0.0f;
    glDepthMask(GL_TRUE);
    glClearBufferfv(GL_DEPTH, 0, &cleared);
    for (int i = 0; i < (outlines_ ? 2 : 1); ++i) glClearBufferfv(GL_COLOR, i, zero);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_ALWAYS);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glUseProgram(pixels_.id());
    glProgramUniform1i(pixels_.id(), 0, samples_);
    glProgramUniform1i(pixels_.id(), 1, featureLines && (l.silhouettes || l.creases));
    fullscreen_.draw();
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_FALSE);
    glDepthFunc(GL_EQUAL);
  } else {
    glDisable(GL_DEPTH_TEST);
  }
  const GLuint program = program_.id();
  glUseProgram(program);
  glProgramUniform1i(program, 0, samples_);
  glProgramUniform1i(program, 1, std::max(1, int(std::lround(l.width))));
  glProgramUniform1f(program, 2, std::cos(glm::radians(l.creaseAngle)));
  glProgramUniform1f(program, 3, l.depthThreshold);
  glProgramUniform1i(program, 4, featureLines && l.silhouettes);
  glProgramUniform1i(program, 5, featureLines && l.creases);
  fullscreen_.draw();
  if (skipEmpty) {
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
  }
}

}  // namespace cutaway
