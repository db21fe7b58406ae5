// Image-space feature lines over a multisampled G-buffer (styles/lines/lines.frag):
// silhouettes and creases per sample, averaged into a coverage; optionally the outline of the
// cut surfaces (Burns08 §4.2) from the cut mask. The composer runs it over the scene G-buffer
// ("lines") and over a cutter's ghost G-buffer ("ghostLines", Burns08 §4.3).
#pragma once

#include <optional>

#include "cutaway/frame/frame.hpp"
#include "cutaway/gl/objects.hpp"
#include "cutaway/scene/scene.hpp"
#include "frame/fullscreen.hpp"

namespace cutaway {

class LinePass {
 public:
  // `outlines`: also the cut outlines, into a second output; `samples`: the G-buffer's.
  LinePass(bool outlines, int samples);
  // Into the bound targets (the coverage, then the outlines' coverage): the lines of the
  // G-buffer `normal`, `objectId` (id and view depth, frame/gbuffer.glsl) and `cutMask` with
  // outlines; `featureLines` false draws only the outlines. With `skipEmpty`, the bound
  // framebuffer has a one-sample depth attachment, which it overwrites: the pixels where no
  // line can be (no sample with a line weight > 0 or of the cut mask) are cleared to 0 and
  // the line shader skips them; the coverage is the same.
  void draw(const Frame& frame, Target normal, Target objectId, std::optional<Target> cutMask,
            const LineStyle& style, bool featureLines, bool skipEmpty) const;

 private:
  int samples_;
  bool outlines_;
  gl::Program program_, pixels_;
  FullscreenTriangle fullscreen_;
};

}  // namespace cutaway
