// cutaway/styles/volume_lines.hpp — line drawings from volumes (Burns11 §2.4, after Burns et
// al. 2005): the curves where the isosurface f = φ − τ = 0 (eq. 2.3) meets the zero set of a
// second implicit function g, found per voxel cell by Marching Lines and followed from cell to
// cell (src/styles/volume_lines).
//
// Families (the second function g):
//   contours            c = −∇φ·v̂                 (eq. 2.4), split by the sign of s (eq. 2.6)
//                       into exterior and interior contours;
//   suggestive contours s = ∇(n̂·v̂)·v̂ = 0           (eq. 2.7), kept where D_s > ε on front
//                       faces and D_s < −ε on back faces;
//   cutting planes      h = Ax + By + Cz − D        (eq. 2.8, here in world coordinates: the
//                       volume's placement is affine, so a plane stays a plane).
// n̂ = −∇φ/|∇φ| and v̂ the unit vector from a point to the eye (or the orthographic view
// direction towards the viewer). Gradients are central differences on the lattice, mapped to
// the world by the placement's inverse transpose.
//
//   cutaway::VolumeLineField field(volume, sceneVolume.indexToWorld(),
//                                  cutaway::VolumeLineView::of(camera),
//                                  {.isoValue = 60, .family = cutaway::VolumeLineFamily::Contour});
//   cutaway::VolumeLineTracker tracker;
//   cutaway::VolumeLineSet lines = tracker.extract(field);   // next frame: a new field, again
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cutaway/core/options.hpp"
#include "cutaway/geometry/volume.hpp"
#include "cutaway/scene/camera.hpp"

namespace cutaway {

// How a scene volume's lines are drawn (its "lines" in the scene file): polylines over the
// final colour, after the volume, hidden lines removed against the nearest isosurface of the
// ones drawn (and the opaque surfaces), white halos (Appel et al. 1979) for depth, clipped by
// the cutters that cut the volume (kinds/volumes/volume_lines_pass.hpp).
struct VolumeLinePen {
  glm::vec3 color{0.0f};
  float width = 1.5f;  // pixels
  friend bool operator==(const VolumeLinePen&, const VolumeLinePen&) = default;
};
struct VolumeLineIso {
  float value = 0.0f;     // τ, in the volume's units
  glm::vec3 color{0.0f};  // its exterior contours'
  float width = 1.5f;
  friend bool operator==(const VolumeLineIso&, const VolumeLineIso&) = default;
};
struct VolumeLinePlane {  // eq. 2.8: normal·x − distance = 0, world coordinates
  glm::vec3 normal{0.0f, 0.0f, 1.0f};
  float distance = 0.0f;
  friend bool operator==(const VolumeLinePlane&, const VolumeLinePlane&) = default;
};
enum class HiddenLines { Removed, Dimmed, Shown };
struct VolumeLineStyle {
  std::vector<VolumeLineIso> isoValues;
  bool contours = true;     // eq. 2.4, exterior and interior (eq. 2.6)
  bool suggestive = false;  // eq. 2.7
  float epsilon = 0.002f;   // VolumeLineQuery::epsilon
  std::vector<VolumeLinePlane> planes;
  HiddenLines hidden = HiddenLines::Removed;
  float dimmedOpacity = 0.3f;
  float halo = 2.0f;  // pixels on each side; 0: none
  glm::vec3 haloColor{1.0f};
  bool only = false;  // the lines alone: the volume's material is not drawn
  VolumeLinePen interiorContour{{0.45f, 0.45f, 0.45f}, 1.0f};
  VolumeLinePen suggestiveContour{{0.15f, 0.15f, 0.15f}, 1.0f};
  VolumeLinePen planeCut{{0.1f, 0.3f, 0.7f}, 1.5f};
  // Every frame walks from the previous frame's cells with eq. 2.5 probes (§2.4.1.3–2.4.1.4);
  // off, every frame is extracted by brute force.
  bool walk = true;
  // The most segments a frame's lines of the volume may hold, all families together (a
  // segment costs ~300 bytes from extraction to the GPU); past it the frame fails with an error.
  int mostSegments = 4'000'000;
  friend bool operator==(const VolumeLineStyle&, const VolumeLineStyle&) = default;
};
const OptionsSchema& volumeLineStyleSchema();

enum class VolumeLineFamily { Contour, Suggestive, Plane };
// What a drawn run of segments is; each is styled apart.
enum class VolumeLineKind { Contour, InteriorContour, SuggestiveContour, PlaneCut };
const char* volumeLineKindName(VolumeLineKind kind);

// The viewer that v̂ points to, in world coordinates.
struct VolumeLineView {
  glm::vec3 eye{0.0f};
  bool orthographic = false;
  glm::vec3 towardsViewer{0.0f, 0.0f, 1.0f};  // orthographic: unit, from the scene to the eye
  static VolumeLineView of(const Camera& camera);
  glm::vec3 at(const glm::vec3& world) const;  // v̂ at a world point
};

struct VolumeLineQuery {
  float isoValue = 0.0f;  // τ
  VolumeLineFamily family = VolumeLineFamily::Contour;
  glm::vec4 plane{0.0f, 0.0f, 1.0f, 0.0f};  // (A, B, C, D) of eq. 2.8, world coordinates
  // The suggestive contours' derivative threshold ε (eq. 2.7), per squared voxel: D_s is
  // compared with ε / h², h the mean voxel spacing, so that one ε suits any scan's units.
  float epsilon = 0.002f;
  // The most segments the extraction may hold (cells read and their segments, ~50 bytes
  // each, and as many drawn); past it, cutaway::Error. Noise-like data would otherwise fill
  // the memory: every cell of white noise holds some.
  std::size_t mostSegments = ~std::size_t(0);
};

// One piece of the curve in one cell: from where it enters the cell to where it leaves, each
// a point on a cell face (index space) with an id that the neighbouring cell shares.
struct CellSegment {
  glm::vec3 entry{0.0f}, exit{0.0f};
  std::uint64_t entryId = 0, exitId = 0;
  std::int8_t entryFace = 0, exitFace = 0;  // 0..5: −i, +i, −j, +j, −k, +k
  // The VolumeLineKind it is drawn as, or −1: not drawn (a suggestive contour failing D_s).
  std::int8_t kind = -1;
};

// A cell's segments: on each face at most two segments of f = 0 and two of g = 0, so at most
// four crossings per face, 24 on the six faces, and so at most 12 entries paired with exits.
struct CellSegments {
  static constexpr int kCapacity = 12;
  std::array<CellSegment, kCapacity> items;
  int count = 0;
  const CellSegment* begin() const { return items.data(); }
  const CellSegment* end() const { return items.data() + count; }
  std::size_t size() const { return std::size_t(count); }
  bool empty() const { return count == 0; }
  const CellSegment& operator[](std::size_t i) const { return items[i]; }
};

// φ and the second function on the lattice, for one view: Marching Lines per cell.
// Cell c spans the voxel centres c … c + (1, 1, 1); cells run over [0, dims − 1) per axis.
class VolumeLineField {
 public:
  VolumeLineField(const Volume& volume, const glm::mat4& indexToWorld, VolumeLineView view,
                  VolumeLineQuery query);

  const Volume& volume() const { return volume_; }
  const VolumeLineQuery& query() const { return query_; }
  const glm::mat4& indexToWorld() const { return indexToWorld_; }
  glm::ivec3 cells() const { return volume_.dims - 1; }
  bool validCell(glm::ivec3 c) const;
  std::uint64_t cellIndex(glm::ivec3 c) const;
  glm::ivec3 cellAt(std::uint64_t index) const;

  // Whether f changes sign over the cell's corners: the cheap test before g is evaluated.
  bool mayHoldSurface(glm::ivec3 cell) const;
  // The curve's segments in the cell: the intersections of f = 0 and g = 0 on each face
  // (marching squares on both, then the crossings of the two), oriented along ∇f × ∇g so that
  // a segment's exit is the next cell's entry, and paired entry to exit within the cell; each
  // with the kind it is drawn as (eqs. 2.6, 2.7).
  CellSegments segments(glm::ivec3 cell) const;

  // Eq. 2.5's linear walk from index-space point p towards f = 0 (step = 0) or g = 0 (step = 1),
  // on the trilinear interpolants of the cell that holds p.
  glm::vec3 walkTowardsZero(glm::vec3 p, int function) const;

  glm::vec3 toWorld(glm::vec3 index) const { return glm::vec3(indexToWorld_ * glm::vec4(index, 1)); }

  // φ − τ and g at a lattice node (exposed for tests).
  float f(glm::ivec3 node) const;
  float g(glm::ivec3 node) const;
  // s (eq. 2.6) at a lattice node.
  float s(glm::ivec3 node) const;

 private:
  glm::vec3 worldGradient(glm::ivec3 node) const;  // ∇φ in world units
  float facing(glm::ivec3 node) const;               // n̂·v̂
  // f and (where gv is given) g at a cell's corners; for contours also n̂·v̂ (in facingv).
  void corners(glm::ivec3 cell, float fv[8], float gv[8], float facingv[8] = nullptr) const;
  std::int8_t kindOf(glm::ivec3 cell, const CellSegment& segment, const float gv[8],
                     const float facingv[8]) const;

  const Volume& volume_;
  glm::mat4 indexToWorld_;
  glm::mat3 gradientToWorld_;  // inverse transpose of the linear part
  VolumeLineView view_;
  VolumeLineQuery query_;
  float epsilonWorld_;
};

// A polyline of one kind, in world coordinates.
struct VolumeLine {
  VolumeLineKind kind = VolumeLineKind::Contour;
  std::vector<glm::vec3> points;
  bool closed = false;  // the last point joins the first
};

struct VolumeLineSet {
  std::vector<VolumeLine> lines;
  // Every segment found, by its entry id (unique: a face point is one cell's entry), sorted:
  // what brute force and walking are compared by.
  std::vector<std::uint64_t> segments;
  std::vector<std::uint64_t> cells;  // the cells that hold segments (next frame's seeds)
  std::size_t cellsExamined = 0;     // cost: cells whose corners were read
  std::size_t segmentCount() const { return segments.size(); }
  bool contains(std::uint64_t segment) const;
  // How many of this set's segments `other` holds too.
  std::size_t countFoundIn(const VolumeLineSet& other) const;
};

// The reference: every cell of the volume examined.
VolumeLineSet extractVolumeLinesBruteForce(const VolumeLineField& field);

// Seeds for the walk (§2.4.1.3–2.4.1.4).
struct VolumeLineSeeding {
  bool previousCells = true;       // the cells that held lines in the previous frame
  int probesFromPrevious = 0;      // gradient-descent probes started at previous cells
  int randomProbes = 0;            // … and at random cells of the volume
  int probeIterations = 5;         // eq. 2.5 steps per probe, alternating f and g
  bool bruteForceFirstFrame = true;  // a tracker's first frame is brute force
};

// Walks loops from seed cells, remembering this frame's cells as the next frame's seeds.
class VolumeLineTracker {
 public:
  VolumeLineTracker() : VolumeLineTracker(1) {}
  explicit VolumeLineTracker(std::uint64_t randomSeed) : random_(randomSeed) {}
  VolumeLineSet extract(const VolumeLineField& field, const VolumeLineSeeding& seeding = {});
  bool hasHistory() const { return ran_; }
  void reset() { previous_.clear(), ran_ = false; }

 private:
  std::vector<std::uint64_t> previous_;
  bool ran_ = false;  // a frame was extracted (not only one that found lines)
  std::mt19937_64 random_;
};

// Walks every loop through the given seed cells (the core of the tracker; also used by tests)
// into `into`, which starts empty (segments it already holds would be walked again).
void walkVolumeLines(const VolumeLineField& field, const std::vector<glm::ivec3>& seeds,
                     VolumeLineSet& into);

// A frame's lines as drawn (Renderer::volumeLineDrawing), in window pixels with y down, as
// in the image: each run of segments that the cutters keep, visible or hidden.
struct DrawnVolumeLine {
  VolumeLineKind kind = VolumeLineKind::Contour;
  glm::vec3 color{0.0f};
  float width = 1.0f;    // pixels
  float opacity = 1.0f;  // below 1: a hidden line, dimmed
  bool hidden = false;   // behind the nearest drawn isosurface or an opaque surface
  float halo = 0.0f;     // pixels on each side
  glm::vec3 haloColor{1.0f};
  float depth = 0.0f;  // mean view depth: drawn far to near
  std::vector<glm::vec2> points;
};
struct VolumeLineDrawing {
  int width = 0, height = 0;
  std::vector<DrawnVolumeLine> lines;
};

// The drawing as SVG: far lines first, each with its halo under it (so that a nearer line's
// halo breaks the lines behind it), round joins; the viewBox is the image's.
std::string volumeLineSvg(const VolumeLineDrawing& drawing);
// Writes it atomically (a temporary file renamed); throws cutaway::Error naming the path.
void writeVolumeLineSvg(const std::string& path, const VolumeLineDrawing& drawing);

}  // namespace cutaway
