// Footprints extruded to prisms (geometry/extrude.hpp). The roof and floor come from ear
// clipping (Meisters 1975: every simple polygon with more than three vertices has two ears),
// after each hole is joined to the outer boundary by a bridge from its rightmost vertex to a
// visible boundary vertex (Eberly, "Triangulation by Ear Clipping", 2002, §3), which turns a
// polygon with holes into one weakly simple polygon.
#include "cutaway/geometry/extrude.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>

namespace cutaway {

namespace {

using Points = std::vector<glm::dvec2>;

// Twice the signed area of triangle (o, a, b): > 0 for a left (counter-clockwise) turn.
double cross(const glm::dvec2& o, const glm::dvec2& a, const glm::dvec2& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

double ringArea(const Points& p, const std::vector<std::uint32_t>& ring) {
  double twice = 0.0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const glm::dvec2& a = p[ring[i]];
    const glm::dvec2& b = p[ring[(i + 1) % ring.size()]];
    twice += a.x * b.y - b.x * a.y;
  }
  return twice;
}

// The ring's indices without repeated nodes, closing nodes and collinear nodes (including
// spikes that go back on themselves), all of which add no area but break the ear test; empty
// when fewer than three nodes are left.
std::vector<std::uint32_t> cleanRing(const Points& p, std::uint32_t first, std::size_t count) {
  std::vector<std::uint32_t> ring;
  for (std::uint32_t i = first; i < first + count; ++i)
    if (ring.empty() || p[i] != p[ring.back()]) ring.push_back(i);
  while (ring.size() > 1 && p[ring.front()] == p[ring.back()]) ring.pop_back();
  for (bool changed = true; changed && ring.size() >= 3;) {
    changed = false;
    for (std::size_t i = 0; i < ring.size() && ring.size() >= 3;) {
      const std::size_t n = ring.size();
      if (cross(p[ring[(i + n - 1) % n]], p[ring[i]], p[ring[(i + 1) % n]]) == 0.0) {
        ring.erase(ring.begin() + std::ptrdiff_t(i));
        changed = true;
      } else {
        ++i;
      }
    }
  }
  if (ring.size() < 3) ring.clear();
  return ring;
}

// Whether m lies in the wedge of the polygon's interior at corner a → p → b (the polygon is
// counter-clockwise, interior on the left): picks which copy of a bridged vertex to join.
bool locallyInside(const glm::dvec2& a, const glm::dvec2& p, const glm::dvec2& b,
                   const glm::dvec2& m) {
  if (cross(a, p, b) >= 0.0) return cross(a, p, m) >= 0.0 && cross(p, b, m) >= 0.0;
  return cross(a, p, m) >= 0.0 || cross(p, b, m) >= 0.0;
}

// Whether q lies inside the ring or within `near` of its boundary (a hole touching the outer
// ring mid-edge lies a float step to either side of it), by the crossing number.
bool insideOrNear(const Points& p, const std::vector<std::uint32_t>& ring, const glm::dvec2& q,
                  double near) {
  bool inside = false;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const glm::dvec2 &a = p[ring[j]], &b = p[ring[i]];
    const glm::dvec2 ab = b - a;
    const double t = std::clamp(glm::dot(q - a, ab) / std::max(glm::dot(ab, ab), 1e-300), 0.0, 1.0);
    if (glm::length(q - (a + t * ab)) <= near) return true;
    if ((a.y > q.y) != (b.y > q.y) && q.x < a.x + (q.y - a.y) * (b.x - a.x) / (b.y - a.y))
      inside = !inside;
  }
  return inside;
}

bool insideTriangle(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c,
                    const glm::dvec2& q) {
  return cross(a, b, q) >= 0.0 && cross(b, c, q) >= 0.0 && cross(c, a, q) >= 0.0;
}

// Joins `hole` (clockwise) into `polygon` (counter-clockwise) by Eberly's bridge: a ray from
// the hole's rightmost vertex M towards +x meets the nearest boundary edge at I; the edge's
// endpoint P of larger x sees M unless a reflex vertex lies in triangle M, I, P, in which case
// the one of those that makes the smallest angle with the ray does.
void bridgeHole(const Points& p, std::vector<std::uint32_t>& polygon,
                const std::vector<std::uint32_t>& hole) {
  std::size_t mi = 0;
  for (std::size_t i = 1; i < hole.size(); ++i)
    if (p[hole[i]].x > p[hole[mi]].x) mi = i;
  const glm::dvec2 m = p[hole[mi]];
  const std::size_t n = polygon.size();
  double bestX = std::numeric_limits<double>::infinity();
  std::size_t candidate = n;
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec2 a = p[polygon[i]], b = p[polygon[(i + 1) % n]];
    if ((a.y > m.y) == (b.y > m.y) && a.y != m.y && b.y != m.y) continue;
    if (a.y == b.y) {  // along the ray: its nearer end is the hit
      if (a.y != m.y) continue;
      const std::size_t near = a.x <= b.x ? i : (i + 1) % n;
      const double x = std::min(a.x, b.x);
      if (x >= m.x && x < bestX) bestX = x, candidate = near;
      continue;
    }
    const double x = a.x + (m.y - a.y) * (b.x - a.x) / (b.y - a.y);
    if (x < m.x || x >= bestX) continue;
    bestX = x;
    candidate = a.x >= b.x ? i : (i + 1) % n;
  }
  if (candidate == n) return;  // a hole outside the boundary: nothing to join
  const glm::dvec2 hit(bestX, m.y);
  glm::dvec2 chosen = p[polygon[candidate]];
  // Reflex vertices inside triangle (M, I, P) could hide P from M.
  if (chosen != hit) {
    double bestSlope = std::numeric_limits<double>::infinity(), bestDistance = bestSlope;
    const bool upper = chosen.y > m.y;
    const glm::dvec2 a = upper ? m : hit, b = upper ? hit : m;  // counter-clockwise with P
    for (std::size_t i = 0; i < n; ++i) {
      const glm::dvec2 q = p[polygon[i]];
      if (q == chosen || !insideTriangle(a, b, chosen, q) || q == m) continue;
      if (cross(p[polygon[(i + n - 1) % n]], q, p[polygon[(i + 1) % n]]) > 0.0) continue;
      const double slope = std::abs(q.y - m.y) / std::max(q.x - m.x, 1e-300);
      const double distance = glm::length(q - m);
      if (slope < bestSlope || (slope == bestSlope && distance < bestDistance))
        bestSlope = slope, bestDistance = distance, candidate = i;
    }
    chosen = p[polygon[candidate]];
  }
  // A bridged vertex appears more than once: join at the copy whose wedge holds M.
  for (std::size_t i = 0; i < n; ++i)
    if (p[polygon[i]] == chosen &&
        locallyInside(p[polygon[(i + n - 1) % n]], chosen, p[polygon[(i + 1) % n]], m)) {
      candidate = i;
      break;
    }
  std::vector<std::uint32_t> splice;
  for (std::size_t k = 0; k <= hole.size(); ++k) splice.push_back(hole[(mi + k) % hole.size()]);
  splice.push_back(polygon[candidate]);
  polygon.insert(polygon.begin() + std::ptrdiff_t(candidate + 1), splice.begin(), splice.end());
}

std::vector<glm::uvec3> clipEars(const Points& p, const std::vector<std::uint32_t>& polygon) {
  const std::size_t n = polygon.size();
  std::vector<std::size_t> prev(n), next(n);
  for (std::size_t i = 0; i < n; ++i) prev[i] = (i + n - 1) % n, next[i] = (i + 1) % n;
  const auto at = [&](std::size_t i) { return p[polygon[i]]; };
  const auto corner = [&](std::size_t i) { return cross(at(prev[i]), at(i), at(next[i])); };
  std::vector<glm::uvec3> triangles;
  const auto clip = [&](std::size_t i) {
    const std::uint32_t a = polygon[prev[i]], b = polygon[i], c = polygon[next[i]];
    if (a != b && b != c && c != a) triangles.emplace_back(a, b, c);
    next[prev[i]] = next[i];
    prev[next[i]] = prev[i];
  };
  // An ear: a strictly convex corner whose triangle holds no other vertex (only reflex or
  // collinear ones can be inside; copies of the corner's own vertices do not count).
  const auto isEar = [&](std::size_t i) {
    if (corner(i) <= 0.0) return false;
    const glm::dvec2 a = at(prev[i]), b = at(i), c = at(next[i]);
    for (std::size_t j = next[next[i]]; j != prev[i]; j = next[j]) {
      const glm::dvec2 q = at(j);
      if (q == a || q == b || q == c || corner(j) > 0.0) continue;
      if (insideTriangle(a, b, c, q)) return false;
    }
    return true;
  };
  std::size_t remaining = n, current = 0, stalled = 0;
  while (remaining > 3) {
    if (isEar(current)) {
      clip(current);
      current = next[current];
      --remaining;
      stalled = 0;
      continue;
    }
    current = next[current];
    if (++stalled < remaining) continue;
    // No ear in a whole turn: rounding or a bridge made the polygon only weakly simple. Clip
    // a flat corner (no area lost), else any convex one, so that the loop always ends.
    std::size_t pick = current;
    for (std::size_t k = 0, j = current; k < remaining; ++k, j = next[j])
      if (corner(j) == 0.0) {
        pick = j;
        break;
      }
    if (corner(pick) != 0.0)
      for (std::size_t k = 0, j = current; k < remaining; ++k, j = next[j])
        if (corner(j) > 0.0) {
          pick = j;
          break;
        }
    clip(pick);
    current = next[pick];
    --remaining;
    stalled = 0;
  }
  if (remaining == 3 && corner(current) > 0.0) clip(current);
  return triangles;
}

Points concatenate(const Footprint& footprint) {
  Points p(footprint.outer.begin(), footprint.outer.end());
  for (const auto& hole : footprint.holes) p.insert(p.end(), hole.begin(), hole.end());
  return p;
}

// A valid polygon's hole may touch the outer ring or another hole at a point (OGC simple
// features): the block would be pinched there, its walls meeting along one vertical edge (not
// a manifold), or, where the hole's node lies mid-edge, leave a T-junction (open). Each hole
// node on another ring moves into its own hole, along the bisector of its corner, by a few
// float steps past the nearness tolerance: the rings part by a sliver no picture shows, and
// the block is watertight. An outer ring's node on a hole's edge first becomes a node of the
// hole too, so that it parts the same way.
void separateTouchingHoles(Footprint& f, double outerSize) {
  double reach = 0.0;  // the largest coordinate: float steps grow with it
  for (const glm::vec2& v : f.outer)
    reach = std::max({reach, double(std::abs(v.x)), double(std::abs(v.y))});
  const double step = double(std::nextafter(float(reach), 2.0f * float(reach) + 1.0f)) - reach;
  const double near = std::max(1e-6 * outerSize, 4.0 * step), apart = 4.0 * near;
  const auto onRing = [&](const std::vector<glm::vec2>& ring, const glm::dvec2& q) {
    for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
      const glm::dvec2 a(ring[j]), ab = glm::dvec2(ring[i]) - a;
      const double t =
          std::clamp(glm::dot(q - a, ab) / std::max(glm::dot(ab, ab), 1e-300), 0.0, 1.0);
      if (glm::length(q - (a + t * ab)) <= near) return true;
    }
    return false;
  };
  for (auto& hole : f.holes)
    for (std::size_t i = 0; i < hole.size(); ++i) {
      const glm::dvec2 a(hole[i]), ab = glm::dvec2(hole[(i + 1) % hole.size()]) - a;
      for (const glm::vec2& node : f.outer) {
        const double t = glm::dot(glm::dvec2(node) - a, ab) / std::max(glm::dot(ab, ab), 1e-300);
        if (t > 0.0 && t < 1.0 && glm::length(glm::dvec2(node) - (a + t * ab)) <= near &&
            glm::length(glm::dvec2(node) - a) > near &&
            glm::length(glm::dvec2(node) - (a + ab)) > near) {
          hole.insert(hole.begin() + std::ptrdiff_t(i + 1), node);
          break;  // the edge is split: its halves are looked at next
        }
      }
    }
  const std::vector<std::vector<glm::vec2>> before = f.holes;
  for (std::size_t h = 0; h < f.holes.size(); ++h) {
    std::vector<glm::vec2>& hole = f.holes[h];
    const std::size_t n = hole.size();
    for (std::size_t i = 0; i < n; ++i) {
      const glm::dvec2 v(before[h][i]);
      bool touches = onRing(f.outer, v);
      for (std::size_t k = 0; k < before.size() && !touches; ++k)
        touches = k != h && onRing(before[k], v);
      if (!touches) continue;
      // A hole runs clockwise: its inside is right of each edge.
      const glm::dvec2 u(before[h][(i + n - 1) % n]), w(before[h][(i + 1) % n]);
      const auto right = [](const glm::dvec2& d) { return glm::normalize(glm::dvec2(d.y, -d.x)); };
      const glm::dvec2 bisector = right(v - u) + right(w - v);
      if (!(glm::length(bisector) > 1e-12)) continue;
      hole[i] = glm::vec2(v + apart * glm::normalize(bisector));
    }
  }
}

}  // namespace

double twiceSignedArea(const std::vector<glm::vec2>& ring) {
  const Points p(ring.begin(), ring.end());
  std::vector<std::uint32_t> all(ring.size());
  std::iota(all.begin(), all.end(), 0u);
  return ringArea(p, all);
}

std::vector<glm::uvec3> triangulateFootprint(const Footprint& footprint) {
  const Points p = concatenate(footprint);
  std::vector<std::uint32_t> polygon = cleanRing(p, 0, footprint.outer.size());
  if (polygon.empty()) return {};
  if (ringArea(p, polygon) < 0.0) std::reverse(polygon.begin(), polygon.end());
  std::vector<std::vector<std::uint32_t>> holes;
  std::uint32_t first = std::uint32_t(footprint.outer.size());
  for (const auto& h : footprint.holes) {
    std::vector<std::uint32_t> hole = cleanRing(p, first, h.size());
    first += std::uint32_t(h.size());
    if (hole.empty()) continue;
    if (ringArea(p, hole) > 0.0) std::reverse(hole.begin(), hole.end());
    holes.push_back(std::move(hole));
  }
  // Rightmost holes first, so that each bridge can only cross holes already joined.
  const auto maxX = [&](const std::vector<std::uint32_t>& ring) {
    double x = -std::numeric_limits<double>::infinity();
    for (std::uint32_t i : ring) x = std::max(x, p[i].x);
    return x;
  };
  std::sort(holes.begin(), holes.end(),
            [&](const auto& a, const auto& b) { return maxX(a) > maxX(b); });
  for (const auto& hole : holes) bridgeHole(p, polygon, hole);
  return clipEars(p, polygon);
}

Mesh extrudeFootprint(const Footprint& footprint, float base, float top) {
  // Clean and orient the rings once, so that roof, floor and walls share the same edges.
  const Points p = concatenate(footprint);
  Footprint clean;
  std::vector<std::vector<glm::vec2>> rings;
  std::vector<std::uint32_t> outerRing;
  double outerSize = 0.0;  // its box's diagonal
  std::uint32_t first = 0;
  for (std::size_t r = 0; r <= footprint.holes.size(); ++r) {
    const std::size_t count = r == 0 ? footprint.outer.size() : footprint.holes[r - 1].size();
    std::vector<std::uint32_t> ring = cleanRing(p, first, count);
    first += std::uint32_t(count);
    if (r == 0 && ring.empty()) return {};
    if (ring.empty()) continue;
    // A hole with a node outside the outer ring (an invalid polygon) is left out: its walls
    // would stand alone, open, and the cap cannot take it. Within a millionth of the outer
    // ring's size counts as on it.
    if (r > 0 && !std::all_of(ring.begin(), ring.end(), [&](std::uint32_t i) {
          return insideOrNear(p, outerRing, p[i], 1e-6 * outerSize);
        }))
      continue;
    if (r == 0) {
      outerRing = ring;
      glm::dvec2 lo(std::numeric_limits<double>::max()), hi(-lo);
      for (std::uint32_t i : ring) lo = glm::min(lo, p[i]), hi = glm::max(hi, p[i]);
      outerSize = glm::length(hi - lo);
    }
    // Outer counter-clockwise, holes clockwise: the solid is always left of an edge.
    if ((ringArea(p, ring) > 0.0) != (r == 0)) std::reverse(ring.begin(), ring.end());
    std::vector<glm::vec2> nodes;
    for (std::uint32_t i : ring) nodes.push_back(glm::vec2(p[i]));
    (r == 0 ? clean.outer : clean.holes.emplace_back()) = std::move(nodes);
  }
  separateTouchingHoles(clean, outerSize);
  rings.push_back(clean.outer);
  rings.insert(rings.end(), clean.holes.begin(), clean.holes.end());

  Mesh mesh;
  const std::vector<glm::uvec3> cap = triangulateFootprint(clean);
  const auto addCapVertices = [&](float y, float normalY) {
    const auto start = std::uint32_t(mesh.positions.size());
    for (const auto& ring : rings)
      for (const glm::vec2& v : ring) {
        mesh.positions.emplace_back(v.x, y, v.y);
        mesh.normals.emplace_back(0.0f, normalY, 0.0f);
      }
    return start;
  };
  // Counter-clockwise in (x, z) faces −y: the floor as is, the roof reversed.
  const std::uint32_t floorStart = addCapVertices(base, -1.0f);
  for (const glm::uvec3& t : cap) mesh.triangles.push_back(t + floorStart);
  const std::uint32_t roofStart = addCapVertices(top, 1.0f);
  for (const glm::uvec3& t : cap)
    mesh.triangles.emplace_back(t.x + roofStart, t.z + roofStart, t.y + roofStart);
  for (const auto& ring : rings)
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const glm::vec2 a = ring[i], b = ring[(i + 1) % ring.size()];
      // The solid is left of a → b in (x, z), so the outward normal is to the right.
      const glm::vec3 normal = glm::normalize(glm::vec3(b.y - a.y, 0.0f, a.x - b.x));
      const auto start = std::uint32_t(mesh.positions.size());
      for (const glm::vec3& v : {glm::vec3(a.x, base, a.y), glm::vec3(b.x, base, b.y),
                                 glm::vec3(b.x, top, b.y), glm::vec3(a.x, top, a.y)}) {
        mesh.positions.push_back(v);
        mesh.normals.push_back(normal);
      }
      mesh.triangles.emplace_back(start, start + 2, start + 1);
      mesh.triangles.emplace_back(start, start + 3, start + 2);
    }
  return mesh;
}

}  // namespace cutaway
