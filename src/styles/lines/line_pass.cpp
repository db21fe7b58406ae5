#include "styles/lines/line_pass.hpp"

#include <algorithm>
#include <cmath>

#include "frame/samples.hpp"

namespace cutaway {

LinePass::LinePass(bool outlines, int samples)
    : samples_(samples),
      program_(buildFullscreenProgram(
          "styles/lines/lines.frag",
          sampleDefines(samples, outlines
                                     ? std::map<std::string, std::string>{{"CUT_OUTLINES", "1"}}
                                     : std::map<std::string, std::string>{}))) {}

void LinePass::draw(const Frame& frame, Target normal, Target objectId,
                    std::optional<Target> cutMask, const LineStyle& l, bool featureLines) const {
  const GLuint program = program_.id();
  glDisable(GL_DEPTH_TEST);
  glUseProgram(program);
  glBindTextureUnit(0, frame.texture(normal).id());
  glBindTextureUnit(1, frame.texture(objectId).id());
  if (cutMask) glBindTextureUnit(2, frame.texture(*cutMask).id());
  glProgramUniform1i(program, 0, samples_);
  glProgramUniform1i(program, 1, std::max(1, int(std::lround(l.width))));
  glProgramUniform1f(program, 2, std::cos(glm::radians(l.creaseAngle)));
  glProgramUniform1f(program, 3, l.depthThreshold);
  glProgramUniform1i(program, 4, featureLines && l.silhouettes);
  glProgramUniform1i(program, 5, featureLines && l.creases);
  fullscreen_.draw();
}

}  // namespace cutaway
