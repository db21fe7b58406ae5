// Marching Lines (Thirion and Gourdon 1996, as Burns11 §2.4.1.1 uses it): the intersection of
// two implicit functions, sampled at the lattice nodes, found on the faces of each cell.
#include <algorithm>
#include <cassert>
#include <cmath>

#include <glm/gtc/matrix_inverse.hpp>

#include "cutaway/kinds/volume_ray_cast.hpp"
#include "cutaway/styles/volume_lines.hpp"

namespace cutaway {

const char* volumeLineKindName(VolumeLineKind kind) {
  switch (kind) {
    case VolumeLineKind::Contour: return "contour";
    case VolumeLineKind::InteriorContour: return "interiorContour";
    case VolumeLineKind::SuggestiveContour: return "suggestiveContour";
    case VolumeLineKind::PlaneCut: return "planeCut";
  }
  return "";
}

VolumeLineView VolumeLineView::of(const Camera& camera) {
  VolumeLineView v;
  v.eye = camera.eye;
  v.orthographic = camera.projection == Projection::Orthographic;
  const glm::vec3 back = camera.eye - camera.target;
  if (glm::dot(back, back) > 0.0f) v.towardsViewer = glm::normalize(back);
  return v;
}

glm::vec3 VolumeLineView::at(const glm::vec3& world) const {
  if (orthographic) return towardsViewer;
  const glm::vec3 d = eye - world;
  const float l = glm::length(d);
  return l > 0.0f ? d / l : towardsViewer;
}

namespace {

constexpr int kMaxFacePoints = 4;  // ≤ 2 segments of f = 0 × ≤ 2 of g = 0 on a face

glm::ivec3 axisStep(int a) {
  glm::ivec3 e(0);
  e[a] = 1;
  return e;
}

// The corner k of a cell: bit 0 along i, bit 1 along j, bit 2 along k.
glm::ivec3 cornerOffset(int k) { return {k & 1, (k >> 1) & 1, (k >> 2) & 1}; }

float trilinear(const float v[8], glm::vec3 t) {
  const float x00 = glm::mix(v[0], v[1], t.x), x10 = glm::mix(v[2], v[3], t.x);
  const float x01 = glm::mix(v[4], v[5], t.x), x11 = glm::mix(v[6], v[7], t.x);
  return glm::mix(glm::mix(x00, x10, t.y), glm::mix(x01, x11, t.y), t.z);
}

glm::vec3 trilinearGradient(const float v[8], glm::vec3 t) {
  glm::vec3 d;
  d.x = glm::mix(glm::mix(v[1] - v[0], v[3] - v[2], t.y), glm::mix(v[5] - v[4], v[7] - v[6], t.y),
                 t.z);
  d.y = glm::mix(glm::mix(v[2] - v[0], v[3] - v[1], t.x), glm::mix(v[6] - v[4], v[7] - v[5], t.x),
                 t.z);
  d.z = glm::mix(glm::mix(v[4] - v[0], v[5] - v[1], t.x), glm::mix(v[6] - v[2], v[7] - v[3], t.x),
                 t.y);
  return d;
}

struct Segment2 {
  glm::vec2 a, b;
};

// Marching squares on a face: the zero set of the bilinear interpolant of v[u][w] as at most
// two segments; a saddle is split by the sign at the face's centre.
int zeroSegments(const float v[2][2], Segment2 out[2]) {
  const auto crossing = [](float a, float b) { return a / (a - b); };
  const bool p00 = v[0][0] > 0, p10 = v[1][0] > 0, p11 = v[1][1] > 0, p01 = v[0][1] > 0;
  glm::vec2 e[4];
  bool has[4] = {p00 != p10, p10 != p11, p01 != p11, p00 != p01};
  if (has[0]) e[0] = {crossing(v[0][0], v[1][0]), 0.0f};
  if (has[1]) e[1] = {1.0f, crossing(v[1][0], v[1][1])};
  if (has[2]) e[2] = {crossing(v[0][1], v[1][1]), 1.0f};
  if (has[3]) e[3] = {0.0f, crossing(v[0][0], v[0][1])};
  const int count = has[0] + has[1] + has[2] + has[3];
  if (count == 2) {
    int first = -1, second = -1;
    for (int i = 0; i < 4; ++i)
      if (has[i]) (first < 0 ? first : second) = i;
    out[0] = {e[first], e[second]};
    return 1;
  }
  if (count == 4) {
    const bool centre = (v[0][0] + v[1][0] + v[1][1] + v[0][1]) > 0;
    if (centre == p00) {  // the p00–p11 diagonal is joined: cut off corners 10 and 01
      out[0] = {e[0], e[1]};
      out[1] = {e[2], e[3]};
    } else {
      out[0] = {e[0], e[3]};
      out[1] = {e[1], e[2]};
    }
    return 2;
  }
  return 0;
}

bool intersect(const Segment2& p, const Segment2& q, glm::vec2& at) {
  const glm::vec2 r = p.b - p.a, s = q.b - q.a;
  const float d = r.x * s.y - r.y * s.x;
  if (d == 0.0f) return false;
  const glm::vec2 qp = q.a - p.a;
  const float t = (qp.x * s.y - qp.y * s.x) / d, u = (qp.x * r.y - qp.y * r.x) / d;
  if (!(t >= 0.0f && t <= 1.0f && u >= 0.0f && u <= 1.0f)) return false;  // NaN: no point
  at = p.a + t * r;
  return true;
}

glm::vec2 bilinearGradient(const float v[2][2], glm::vec2 p) {
  return {glm::mix(v[1][0] - v[0][0], v[1][1] - v[0][1], p.y),
          glm::mix(v[0][1] - v[0][0], v[1][1] - v[1][0], p.x)};
}

struct FacePoint {
  glm::vec3 at;  // index space
  std::uint64_t id;
  int face;   // 0..5 as CellSegment's
  bool exit;  // the curve leaves the cell here
};

}  // namespace

VolumeLineField::VolumeLineField(const Volume& volume, const glm::mat4& indexToWorld,
                                 VolumeLineView view, VolumeLineQuery query)
    : volume_(volume),
      indexToWorld_(indexToWorld),
      // In doubles, as SceneVolume::worldToIndex.
      gradientToWorld_(glm::inverseTranspose(glm::dmat3(indexToWorld))),
      view_(view),
      query_(query) {
  const float h = (glm::length(glm::vec3(indexToWorld[0])) + glm::length(glm::vec3(indexToWorld[1])) +
                   glm::length(glm::vec3(indexToWorld[2]))) /
                  3.0f;
  epsilonWorld_ = query.epsilon / (h * h);
}

bool VolumeLineField::validCell(glm::ivec3 c) const {
  return glm::all(glm::greaterThanEqual(c, glm::ivec3(0))) && glm::all(glm::lessThan(c, cells()));
}

std::uint64_t VolumeLineField::cellIndex(glm::ivec3 c) const {
  const glm::u64vec3 n(cells());
  return std::uint64_t(c.x) + n.x * (std::uint64_t(c.y) + n.y * std::uint64_t(c.z));
}

glm::ivec3 VolumeLineField::cellAt(std::uint64_t index) const {
  const glm::u64vec3 n(cells());
  return {int(index % n.x), int(index / n.x % n.y), int(index / (n.x * n.y))};
}

float VolumeLineField::f(glm::ivec3 node) const { return volume_.at(node) - query_.isoValue; }

glm::vec3 VolumeLineField::worldGradient(glm::ivec3 node) const {
  return gradientToWorld_ * voxelGradient(volume_, node);
}

float VolumeLineField::facing(glm::ivec3 node) const {
  const glm::vec3 g = worldGradient(node);
  const float l = glm::length(g);
  if (l == 0.0f) return 0.0f;
  return glm::dot(-g / l, view_.at(toWorld(node)));
}

float VolumeLineField::s(glm::ivec3 node) const {
  // ∇(n̂·v̂) by central differences on the lattice (clamped as the gradient is), to the world.
  glm::vec3 d;
  for (int a = 0; a < 3; ++a) {
    const glm::ivec3 e = axisStep(a);
    const glm::ivec3 lo = glm::max(node - e, glm::ivec3(0));
    const glm::ivec3 hi = glm::min(node + e, volume_.dims - 1);
    d[a] = hi[a] == lo[a] ? 0.0f : (facing(hi) - facing(lo)) / float(hi[a] - lo[a]);
  }
  return glm::dot(gradientToWorld_ * d, view_.at(toWorld(node)));
}

float VolumeLineField::g(glm::ivec3 node) const {
  switch (query_.family) {
    case VolumeLineFamily::Contour: return -glm::dot(worldGradient(node), view_.at(toWorld(node)));
    case VolumeLineFamily::Suggestive: return s(node);
    case VolumeLineFamily::Plane:
      return glm::dot(glm::vec3(query_.plane), toWorld(node)) - query_.plane.w;
  }
  return 0.0f;
}

void VolumeLineField::corners(glm::ivec3 cell, float fv[8], float gv[8], float facingv[8]) const {
  for (int k = 0; k < 8; ++k) {
    const glm::ivec3 n = cell + cornerOffset(k);
    fv[k] = f(n);
    if (!gv) continue;
    if (query_.family != VolumeLineFamily::Contour || !facingv) {
      gv[k] = g(n);
      continue;
    }
    // c = −∇φ·v̂ and n̂·v̂ = c / |∇φ| from one gradient.
    const glm::vec3 gradient = worldGradient(n);
    const float length = glm::length(gradient);
    gv[k] = -glm::dot(gradient, view_.at(toWorld(n)));
    facingv[k] = length == 0.0f ? 0.0f : gv[k] / length;
  }
}

bool VolumeLineField::mayHoldSurface(glm::ivec3 cell) const {
  float fv[8];
  corners(cell, fv, nullptr);
  bool positive = false, negative = false;
  for (float v : fv) {
    if (std::isnan(v)) return false;  // no surface through a missing value
    (v > 0 ? positive : negative) = true;
  }
  return positive && negative;
}

CellSegments VolumeLineField::segments(glm::ivec3 cell) const {
  CellSegments out;
  // g only where f changes sign: most cells a walk or brute force reads hold no surface.
  if (!mayHoldSurface(cell)) return out;
  float fv[8], gv[8], facingv[8];
  corners(cell, fv, gv, facingv);
  FacePoint points[6 * kMaxFacePoints];
  int pointCount = 0;
  for (int a = 0; a < 3; ++a) {
    const int u = (a + 1) % 3, w = (a + 2) % 3;  // e_u × e_w = e_a
    for (int side = 0; side < 2; ++side) {
      // The face's values, indexed [u][w], from its own four nodes only: both cells that
      // share it find the same points with the same ids.
      float ff[2][2], gg[2][2];
      for (int du = 0; du < 2; ++du)
        for (int dw = 0; dw < 2; ++dw) {
          const int k = (side << a) | (du << u) | (dw << w);
          ff[du][dw] = fv[k], gg[du][dw] = gv[k];
        }
      Segment2 fs[2], gs[2];
      const int nf = zeroSegments(ff, fs);
      if (nf == 0) continue;
      const int ng = zeroSegments(gg, gs);
      const glm::ivec3 base = cell + side * axisStep(a);
      const std::uint64_t faceKey =
          ((std::uint64_t(base.x) + std::uint64_t(volume_.dims.x) *
                                        (std::uint64_t(base.y) +
                                         std::uint64_t(volume_.dims.y) * std::uint64_t(base.z))) *
               3 +
           std::uint64_t(a)) *
          kMaxFacePoints;
      int found = 0;
      for (int i = 0; i < nf; ++i)
        for (int j = 0; j < ng; ++j) {
          glm::vec2 p;
          if (!intersect(fs[i], gs[j], p)) continue;
          // The curve runs along ∇f × ∇g; its component along e_a from the face's gradients.
          const glm::vec2 df = bilinearGradient(ff, p), dg = bilinearGradient(gg, p);
          const float along = df.x * dg.y - df.y * dg.x;
          glm::vec3 at(cell);
          at[a] += float(side), at[u] += p.x, at[w] += p.y;
          // The curve leaves through the +e_a face along e_a, through the −e_a face against it;
          // the two cells that share the face disagree even where `along` is 0 or NaN.
          const bool exit = side == 1 ? along > 0.0f : !(along > 0.0f);
          points[pointCount++] = {at, faceKey + std::uint64_t(found++), 2 * a + side, exit};
        }
    }
  }
  // Pair each entry with the nearest free exit (in the face order above: consistent).
  bool used[6 * kMaxFacePoints] = {};
  for (int i = 0; i < pointCount; ++i) {
    const FacePoint& in = points[i];
    if (in.exit) continue;
    int best = -1;
    float bestDistance = 0.0f;
    for (int j = 0; j < pointCount; ++j) {
      if (!points[j].exit || used[j]) continue;
      const glm::vec3 d = points[j].at - in.at;
      const float distance = glm::dot(d, d);
      if (best < 0 || distance < bestDistance) best = j, bestDistance = distance;
    }
    if (best < 0) continue;
    used[best] = true;
    const FacePoint& to = points[best];
    assert(out.count < CellSegments::kCapacity);
    CellSegment& segment = out.items[std::size_t(out.count++)];
    segment = {in.at, to.at, in.id, to.id, std::int8_t(in.face), std::int8_t(to.face)};
    segment.kind = kindOf(cell, segment, gv, facingv);
  }
  return out;
}

std::int8_t VolumeLineField::kindOf(glm::ivec3 cell, const CellSegment& segment, const float gv[8],
                                    const float facingv[8]) const {
  const glm::vec3 t = 0.5f * (segment.entry + segment.exit) - glm::vec3(cell);
  const glm::vec3 p = glm::vec3(cell) + t;
  switch (query_.family) {
    case VolumeLineFamily::Plane:
      return std::int8_t(VolumeLineKind::PlaneCut);
    case VolumeLineFamily::Contour: {
      // Eq. 2.6: s has the sign of the radial curvature, negative on interior contours; here
      // the derivative along v̂ of the cell's trilinear interpolant of n̂·v̂.
      const float s =
          glm::dot(gradientToWorld_ * trilinearGradient(facingv, t), view_.at(toWorld(p)));
      return std::int8_t(s < 0.0f ? VolumeLineKind::InteriorContour : VolumeLineKind::Contour);
    }
    case VolumeLineFamily::Suggestive: {
      // s reads n̂·v̂ a node away, and n̂ a node further: nearer the border than that, the
      // clamped differences make zeros of s that are not the surface's.
      if (glm::any(glm::lessThan(cell, glm::ivec3(2))) ||
          glm::any(glm::greaterThan(cell + 1, volume_.dims - 3)))
        return -1;
      const glm::vec3 gradient = gradientToWorld_ * sampleGradient(volume_, p);
      if (glm::dot(gradient, gradient) == 0.0f) return -1;
      const glm::vec3 n = -glm::normalize(gradient), v = view_.at(toWorld(p));
      // D_s: the derivative of s along the view vector's projection onto the tangent plane
      // (DeCarlo et al. 2003's w), negated on back faces (eq. 2.7).
      glm::vec3 w = v - glm::dot(n, v) * n;
      if (glm::dot(w, w) < 1e-12f) return -1;
      w = glm::normalize(w);
      const float ds = glm::dot(gradientToWorld_ * trilinearGradient(gv, t), w);
      const bool kept = glm::dot(n, v) >= 0.0f ? ds > epsilonWorld_ : ds < -epsilonWorld_;
      return kept ? std::int8_t(VolumeLineKind::SuggestiveContour) : std::int8_t(-1);
    }
  }
  return -1;
}

glm::vec3 VolumeLineField::walkTowardsZero(glm::vec3 p, int function) const {
  if (glm::any(glm::lessThanEqual(cells(), glm::ivec3(0)))) return p;
  const glm::ivec3 cell = glm::clamp(glm::ivec3(glm::floor(p)), glm::ivec3(0), cells() - 1);
  float fv[8], gv[8];
  corners(cell, fv, function == 0 ? nullptr : gv);
  const float* v = function == 0 ? fv : gv;
  const glm::vec3 t = p - glm::vec3(cell);
  // Eq. 2.5 (in index space, where the interpolants live): one linear step to the zero.
  const glm::vec3 d = trilinearGradient(v, t);
  const float dd = glm::dot(d, d);
  if (dd == 0.0f) return p;
  return p - trilinear(v, t) / dd * d;
}

}  // namespace cutaway
