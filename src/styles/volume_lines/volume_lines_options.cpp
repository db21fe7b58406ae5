// A volume's lines as the scene file, the viewer and the CLI name them (Burns11 §2.4.2).
#include "cutaway/styles/volume_lines.hpp"

namespace cutaway {

namespace {

const OptionsSchema& isoSchema() {
  using O = VolumeLineIso;
  static const OptionsSchema schema =
      OptionsBuilder<O>()
          .number("value", &O::value, -1e30, 1e30,
                  {.label = "isovalue",
                   .doc = "τ of the isosurface φ − τ = 0 (eq. 2.3), in the volume's units.",
                   .live = true,
                   .required = true})
          .color("color", &O::color,
                 {.label = "contour colour", .doc = "Its exterior contours' colour.", .live = true})
          .number(
              "width", &O::width, 0.5, 16,
              {.label = "contour width (px)", .doc = "Its exterior contours' width.", .live = true})
          .build();
  return schema;
}

const OptionsSchema& planeSchema() {
  using O = VolumeLinePlane;
  static const OptionsSchema schema =
      OptionsBuilder<O>()
          .direction(
              "normal", &O::normal,
              {.doc = "(A, B, C) of eq. 2.8's plane h = Ax + By + Cz − D, world coordinates.",
               .live = true})
          .number(
              "distance", &O::distance, -1e12, 1e12,
              {.doc = "D of eq. 2.8: the plane's distance from the origin along the unit normal.",
               .live = true})
          .build();
  return schema;
}

const OptionsSchema& penSchema() {
  using O = VolumeLinePen;
  static const OptionsSchema schema =
      OptionsBuilder<O>()
          .color("color", &O::color, {.doc = "Line colour.", .live = true})
          .number("width", &O::width, 0.5, 16,
                  {.label = "width (px)", .doc = "Line width.", .live = true})
          .build();
  return schema;
}

}  // namespace

const OptionsSchema& volumeLineStyleSchema() {
  using O = VolumeLineStyle;
  static const OptionsSchema schema =
      OptionsBuilder<O>()
          .array("isoValues", &O::isoValues, 1, 8, isoSchema(),
                 {.doc = "The isosurfaces whose lines are drawn, each with its contours' pen.",
                  .required = true})
          .value("contours", &O::contours,
                 {.doc = "Contours: the isosurface meets c = −∇φ·v̂ = 0 (eq. 2.4); interior ones "
                         "(s < 0, eq. 2.6) get their own pen.",
                  .live = true})
          .value("suggestive", &O::suggestive,
                 {.doc = "Suggestive contours: s = ∇(n̂·v̂)·v̂ = 0 where D_s > ε (eq. 2.7).",
                  .live = true})
          .number("epsilon", &O::epsilon, 0, 1,
                  {.label = "suggestive ε",
                   .doc = "Eq. 2.7's threshold on D_s, per squared voxel.",
                   .live = true,
                   .sliderMax = 0.05})
          .array(
              "planes", &O::planes, 0, 4, planeSchema(),
              {.doc =
                   "Cutting planes (eq. 2.8) whose intersections with the isosurfaces are drawn."})
          .choice(
              "hidden", &O::hidden,
              {{"removed", HiddenLines::Removed},
               {"dimmed", HiddenLines::Dimmed},
               {"shown", HiddenLines::Shown}},
              {.doc = "Lines behind the nearest drawn isosurface or an opaque surface: left out, "
                      "drawn faint, or drawn as the others.",
               .live = true})
          .number("dimmedOpacity", &O::dimmedOpacity, 0, 1,
                  {.label = "dimmed opacity",
                   .doc = "Opacity of hidden lines when dimmed.",
                   .live = true})
          .number("halo", &O::halo, 0, 16,
                  {.label = "halo (px)",
                   .doc = "White halos (Appel et al. 1979): a line is broken where a nearer one "
                          "crosses it.",
                   .live = true})
          .color("haloColor", &O::haloColor,
                 {.label = "halo colour", .doc = "Usually the paper's.", .live = true})
          .value("only", &O::only,
                 {.doc = "The lines alone: the volume's material is not drawn.", .live = true})
          .group("interiorContour", &O::interiorContour, penSchema(),
                 {.doc = "Pen of interior contours."})
          .group("suggestiveContour", &O::suggestiveContour, penSchema(),
                 {.doc = "Pen of suggestive contours."})
          .group("planeCut", &O::planeCut, penSchema(),
                 {.doc = "Pen of the cutting planes' lines."})
          .value("walk", &O::walk,
                 {.doc = "Follow the lines from the previous frame's cells with eq. 2.5 probes "
                         "(§2.4.1.3–2.4.1.4); off: brute force every frame. A first frame is brute "
                         "force.",
                  .live = true})
          .number("mostSegments", &O::mostSegments, 1000, 100'000'000,
                  {.label = "most segments",
                   .doc = "The most segments a frame's lines of this volume may hold, all "
                          "isovalues and families together (~300 bytes each); past it the frame "
                          "fails with an error rather than fill the memory (noise-like data "
                          "holds lines in nearly every cell)."})
          .build();
  return schema;
}

}  // namespace cutaway
