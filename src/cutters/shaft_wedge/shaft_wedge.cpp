#include "cutters/shaft_wedge/shaft_wedge.hpp"

#include <algorithm>

namespace cutaway {

namespace {
bool isShaft(const SceneObject& o) {
  return o.networkPart == NetworkPart::ShaftOuter || o.networkPart == NetworkPart::ShaftInner;
}
}  // namespace

CutterType shaftWedgeCutterType() {
  return {.key = "shaftWedge",
          .title = "Shaft wedge (Konev18)",
          .glsl = "cutters/shaft_wedge/shaft_wedge.glsl",
          .name = "shaft",
          // The networks' shafts switch it on; its options are the networks' own.
          .active = [](const Scene& s) { return std::any_of(s.objects.begin(), s.objects.end(), isShaft); },
          .create = [](FrameSetup& setup) -> std::unique_ptr<Cutter> {
            return std::make_unique<ShaftWedge>(setup);
          }};
}

ShaftWedge::ShaftWedge(FrameSetup& setup)
    : setup_(setup),
      openingLocation_(setup.bindings.uniformLocation("SHAFT_OPENING")),
      innerLocation_(setup.bindings.uniformLocation("SHAFT_INNER")) {}

bool ShaftWedge::cuts(std::size_t index) const {
  const SceneObject& o = setup_.scene.objects[index];
  return isShaft(o) && o.mayBeCutBy("shaftWedge");
}

CutLook ShaftWedge::look(std::size_t index) const {
  // §7: the wedge's cut surface in the network's cut colour, the inside in its own.
  const PipeNetwork& net = setup_.scene.networks[std::size_t(setup_.scene.objects[index].network)];
  return {.cutSurface = true, .cutColor = net.cutColor, .backColor = net.insideColor};
}

void ShaftWedge::setObjectUniforms(GLuint program, std::size_t index) const {
  const SceneObject& o = setup_.scene.objects[index];
  glProgramUniform1f(program, openingLocation_,
                     setup_.scene.networks[std::size_t(o.network)].shaftOpening);
  glProgramUniform1i(program, innerLocation_, o.networkPart == NetworkPart::ShaftInner);
}

}  // namespace cutaway
