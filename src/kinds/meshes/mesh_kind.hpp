// Triangle meshes as a geometry kind: every visible scene object drawn into the G-buffer with
// the style and the active cutters composed into kinds/meshes/mesh.frag. Burns08 §4.1's
// order: the secondary objects first, cut; the objects of interest after, whole. An object a
// cutter clips with hardware clip planes (Diepstraten03 §4.3) is drawn once per plane.
#pragma once

#include "kinds/kind.hpp"

namespace cutaway {

class MeshKind : public GeometryKind {
 public:
  explicit MeshKind(FrameSetup& setup) : setup_(setup) {}
  void prepare(const std::vector<ActiveCutter>& cutters) override;
  void drawGeometry(const std::vector<ActiveCutter>& cutters,
                    const GeometryDraw& draw) const override;

 private:
  FrameSetup& setup_;
  gl::Program program_;
};

}  // namespace cutaway
