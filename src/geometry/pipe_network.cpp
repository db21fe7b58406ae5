#include "cutaway/geometry/pipe_network.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <numeric>
#include <optional>
#include <tuple>

namespace cutaway {

namespace {

constexpr glm::vec3 kUp{0.0f, 1.0f, 0.0f};

// A unit vector perpendicular to `d` (unit), preferring the horizontal.
glm::vec3 anyPerpendicular(const glm::vec3& d) {
  glm::vec3 p = glm::cross(d, kUp);
  if (glm::dot(p, p) < 1e-12f) p = glm::cross(d, glm::vec3(1, 0, 0));
  return glm::normalize(p);
}

glm::vec3 segmentDirection(const std::vector<glm::vec3>& nodes, std::size_t k) {
  return glm::normalize(nodes[k + 1] - nodes[k]);
}

// The direction the billboard is built around at node i: n̂ at the ends, the normalised
// mean of the adjacent segments' n̂ between (eq. 5).
glm::vec3 nodeDirection(const std::vector<glm::vec3>& nodes, std::size_t i) {
  const std::size_t n = nodes.size() - 1;
  if (i == 0) return segmentDirection(nodes, 0);
  if (i == n) return segmentDirection(nodes, n - 1);
  const glm::vec3 sum = segmentDirection(nodes, i - 1) + segmentDirection(nodes, i);
  return glm::dot(sum, sum) < 1e-12f ? segmentDirection(nodes, i) : glm::normalize(sum);
}

glm::vec3 up(const glm::vec3& v, const glm::vec3& direction) {
  const glm::vec3 u = glm::cross(v, direction);
  return glm::dot(u, u) < 1e-12f ? anyPerpendicular(direction) : glm::normalize(u);
}

// Closest points of segments p1q1 and p2q2 (Ericson, Real-Time Collision Detection §5.1.9):
// returns the squared distance and the parameters along each.
float segmentDistance2(glm::vec3 p1, glm::vec3 q1, glm::vec3 p2, glm::vec3 q2, float& s, float& t) {
  const glm::vec3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const float a = glm::dot(d1, d1), e = glm::dot(d2, d2), f = glm::dot(d2, r);
  const float c = glm::dot(d1, r), b = glm::dot(d1, d2), denom = a * e - b * b;
  s = denom > 1e-12f * a * e ? std::clamp((b * f - c * e) / denom, 0.0f, 1.0f) : 0.0f;
  t = (b * s + f) / e;
  if (t < 0.0f) {
    t = 0.0f;
    s = std::clamp(-c / a, 0.0f, 1.0f);
  } else if (t > 1.0f) {
    t = 1.0f;
    s = std::clamp((b - c) / a, 0.0f, 1.0f);
  }
  const glm::vec3 d = (p1 + d1 * s) - (p2 + d2 * t);
  return glm::dot(d, d);
}

}  // namespace

std::vector<glm::vec3> cutStretch(const Pipe& pipe, glm::vec2 range, std::vector<float>* arcs) {
  std::vector<glm::vec3> points;
  if (arcs) arcs->clear();
  const auto add = [&](const glm::vec3& p, float arc) {
    points.push_back(p);
    if (arcs) arcs->push_back(arc);
  };
  float s = 0.0f;
  for (std::size_t k = 0; k + 1 < pipe.nodes.size(); ++k) {
    const float len = glm::length(pipe.nodes[k + 1] - pipe.nodes[k]);
    const float s0 = s, s1 = s + len;
    s = s1;
    if (s1 < range.x || s0 > range.y) continue;
    const auto at = [&](float x) {
      return glm::mix(pipe.nodes[k], pipe.nodes[k + 1], std::clamp((x - s0) / len, 0.0f, 1.0f));
    };
    if (points.empty()) add(at(std::max(range.x, s0)), std::max(range.x, s0));
    add(at(std::min(range.y, s1)), std::min(range.y, s1));
  }
  return points;
}

float Pipe::length() const {
  float s = 0.0f;
  for (std::size_t k = 0; k + 1 < nodes.size(); ++k) s += glm::length(nodes[k + 1] - nodes[k]);
  return s;
}

Bounds PipeNetwork::bounds() const {
  Bounds b;
  for (const Pipe& p : pipes)
    for (const glm::vec3& q : p.nodes) {
      const float r = p.radius * radiusScale;
      b.extend(q - glm::vec3(r)), b.extend(q + glm::vec3(r));
    }
  for (const Shaft& s : shafts) {
    b.extend(s.bottom - glm::vec3(s.radius, 0, s.radius));
    b.extend(glm::vec3(s.bottom.x + s.radius, s.top, s.bottom.z + s.radius));
  }
  return b;
}

std::vector<glm::vec3> billboardUp(const std::vector<glm::vec3>& nodes, const glm::vec3& eye) {
  std::vector<glm::vec3> u(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i)
    u[i] = up(glm::normalize(nodes[i] - eye), nodeDirection(nodes, i));
  return u;
}

std::vector<glm::vec3> billboardUpOrthographic(const std::vector<glm::vec3>& nodes,
                                               const glm::vec3& viewDirection) {
  std::vector<glm::vec3> u(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i)
    u[i] = up(glm::normalize(viewDirection), nodeDirection(nodes, i));
  return u;
}

glm::vec3 billboardFaceNormal(const glm::vec3& u0, const glm::vec3& u1, const glm::vec3& n) {
  return glm::normalize(glm::cross(glm::normalize(u0 + u1), n));
}

glm::vec3 tubeNormal(const glm::vec3& u0, const glm::vec3& u1, float along, float across,
                     const glm::vec3& faceNormal) {
  const glm::vec3 N = across * glm::mix(u0, u1, along);
  return glm::normalize(N + faceNormal);
}

float proxyTriangleDistance(glm::vec2 uv) {
  return glm::length(glm::vec2(0.5f) - uv);
}

ProxyAction proxyTriangle(int pass, float d, float innerRadius, float outerRadius) {
  const float dIn = 0.5f * innerRadius / outerRadius, dOut = 0.5f;
  if (pass == 1) return d > dIn && d < dOut ? ProxyAction::CutSurface : ProxyAction::Discard;
  return d < dIn ? ProxyAction::MarkInside : ProxyAction::Discard;
}

ProxyAction proxyQuad(int pass, float v, float innerRadius, float outerRadius) {
  const float t = 0.5f * (outerRadius - innerRadius) / outerRadius;
  if (pass == 1) return v > 1.0f - t || v < t ? ProxyAction::CutSurface : ProxyAction::Discard;
  return v > t && v < 1.0f - t ? ProxyAction::MarkInside : ProxyAction::Discard;
}

bool shaftWedgeRemoves(const glm::vec3& normal, const glm::vec3& toEye, float coefficient) {
  const glm::vec2 n(normal.x, normal.z), v(toEye.x, toEye.z);
  if (glm::dot(n, n) < 1e-12f || glm::dot(v, v) < 1e-12f) return false;
  return glm::dot(glm::normalize(n), glm::normalize(v)) > coefficient;
}

std::vector<Joint> splitSharpBends(PipeNetwork& network, float maxBendDegrees) {
  const float cosMax = std::cos(glm::radians(maxBendDegrees));
  std::vector<Joint> joints;
  std::vector<Pipe> out;
  for (const Pipe& pipe : network.pipes) {
    std::size_t start = 0;
    float arcStart = 0.0f, arc = 0.0f;
    // The pipe without its nodes: a copy of them each piece would take memory and time
    // quadratic in the bends.
    Pipe bare = pipe;
    bare.nodes = {};
    const auto emit = [&](std::size_t end) {
      Pipe piece = bare;
      piece.nodes.assign(pipe.nodes.begin() + std::ptrdiff_t(start),
                         pipe.nodes.begin() + std::ptrdiff_t(end) + 1);
      piece.cut.reset();
      if (pipe.cut) {
        const float a = std::max(pipe.cut->x, arcStart), b = std::min(pipe.cut->y, arc);
        if (b > a) piece.cut = glm::vec2(a - arcStart, b - arcStart);
      }
      out.push_back(std::move(piece));
    };
    for (std::size_t i = 1; i < pipe.nodes.size(); ++i) {
      arc += glm::length(pipe.nodes[i] - pipe.nodes[i - 1]);
      if (i + 1 == pipe.nodes.size()) break;
      const float c =
          glm::dot(segmentDirection(pipe.nodes, i - 1), segmentDirection(pipe.nodes, i));
      if (c >= cosMax) continue;
      emit(i);
      joints.push_back({pipe.nodes[i], pipe.radius * network.radiusScale});
      start = i, arcStart = arc;
    }
    emit(pipe.nodes.size() - 1);
  }
  network.pipes = std::move(out);
  return joints;
}

int resolveCutIntersections(PipeNetwork& network, float margin) {
  struct Stretch {
    std::size_t pipe;
    std::vector<glm::vec3> points;
    std::vector<float> arcs;
    Bounds box;
  };
  std::vector<Stretch> stretches;
  for (std::size_t i = 0; i < network.pipes.size(); ++i) {
    const Pipe& p = network.pipes[i];
    if (!p.cut) continue;
    Stretch s{i, {}, {}, {}};
    s.points = cutStretch(p, *p.cut, &s.arcs);
    if (s.points.size() < 2) continue;
    for (const glm::vec3& q : s.points) s.box.extend(q);
    stretches.push_back(std::move(s));
  }
  // More important first: larger radius, then earlier.
  std::sort(stretches.begin(), stretches.end(), [&](const Stretch& a, const Stretch& b) {
    const float ra = network.pipes[a.pipe].radius, rb = network.pipes[b.pipe].radius;
    return ra != rb ? ra > rb : a.pipe < b.pipe;
  });
  // Sweep along x over the boxes (grown by the largest reach) so that a city's thousands of
  // stretches are not compared pairwise.
  float maxRadius = 0.0f;
  for (const Pipe& p : network.pipes) maxRadius = std::max(maxRadius, p.radius);
  const float reach = 2.0f * maxRadius + margin;
  std::vector<std::size_t> order(stretches.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return stretches[a].box.min.x < stretches[b].box.min.x;
  });
  std::vector<bool> trimmed(stretches.size(), false);
  std::vector<std::vector<std::size_t>> near(stretches.size());
  for (std::size_t oi = 0; oi < order.size(); ++oi)
    for (std::size_t oj = oi + 1; oj < order.size(); ++oj) {
      const Stretch &a = stretches[order[oi]], &b = stretches[order[oj]];
      if (b.box.min.x > a.box.max.x + reach) break;
      if (b.box.min.y > a.box.max.y + reach || a.box.min.y > b.box.max.y + reach ||
          b.box.min.z > a.box.max.z + reach || a.box.min.z > b.box.max.z + reach)
        continue;
      near[std::min(order[oi], order[oj])].push_back(std::max(order[oi], order[oj]));
    }
  int count = 0;
  // In order of importance: each stretch gives way to the more important ones kept before it.
  for (std::size_t j = 0; j < stretches.size(); ++j) {
    Pipe& pipe = network.pipes[stretches[j].pipe];
    for (std::size_t i = 0; i < j && pipe.cut; ++i) {
      if (trimmed[i] && !network.pipes[stretches[i].pipe].cut) continue;
      if (std::find(near[i].begin(), near[i].end(), j) == near[i].end()) continue;
      const Stretch &keep = stretches[i], &give = stretches[j];
      const float limit = network.pipes[keep.pipe].radius + pipe.radius + margin;
      // The meeting point along `give`: its closest approach to `keep`.
      float best = 1e30f, at = 0.0f;
      for (std::size_t a = 0; a + 1 < keep.points.size(); ++a)
        for (std::size_t b = 0; b + 1 < give.points.size(); ++b) {
          float s, t;
          const float d2 = segmentDistance2(keep.points[a], keep.points[a + 1], give.points[b],
                                            give.points[b + 1], s, t);
          if (d2 < best) best = d2, at = glm::mix(give.arcs[b], give.arcs[b + 1], t);
        }
      if (best >= limit * limit) continue;
      // Keep the longer side of the stretch outside [at − limit, at + limit].
      const glm::vec2 c = *pipe.cut;
      const float before = (at - limit) - c.x, after = c.y - (at + limit);
      if (before <= 0.0f && after <= 0.0f)
        pipe.cut.reset();
      else if (before >= after)
        pipe.cut = glm::vec2(c.x, at - limit);
      else
        pipe.cut = glm::vec2(at + limit, c.y);
      trimmed[j] = true;
      ++count;
    }
  }
  return count;
}

void addJunctionShafts(PipeNetwork& network, const ShaftDefaults& defaults,
                       const std::function<float(glm::vec2)>& groundAt) {
  // Pipe nodes welded in plan (x, z) on a grid of the weld distance: pipes at different
  // depths meet at one shaft.
  const float cell = std::max(defaults.weldDistance, 1e-6f);
  struct Site {
    glm::vec3 position;
    std::vector<std::size_t> pipes;
    int ends = 0, incidences = 0;
    float lowest = 1e30f, radius = 0.0f;
  };
  std::map<std::pair<long, long>, Site> sites;
  for (std::size_t i = 0; i < network.pipes.size(); ++i) {
    const Pipe& p = network.pipes[i];
    for (std::size_t k = 0; k < p.nodes.size(); ++k) {
      const glm::vec3& q = p.nodes[k];
      const auto key = std::pair{std::lround(q.x / cell), std::lround(q.z / cell)};
      Site& s = sites[key];
      if (s.pipes.empty()) s.position = q;
      if (std::find(s.pipes.begin(), s.pipes.end(), i) == s.pipes.end()) s.pipes.push_back(i);
      const bool end = k == 0 || k + 1 == p.nodes.size();
      s.ends += end;
      s.incidences += end ? 1 : 2;
      s.lowest = std::min(s.lowest, q.y - p.radius);
      s.radius = std::max(s.radius, p.radius);
    }
  }
  for (const auto& [key, s] : sites) {
    if (s.ends == 0) continue;
    const bool junction = s.incidences >= 3;
    if (!junction && !defaults.ends) continue;
    Shaft shaft;
    shaft.radius = std::max(defaults.radius, s.radius + defaults.wallThickness);
    shaft.wallThickness = std::min(defaults.wallThickness, shaft.radius);
    shaft.bottom = glm::vec3(s.position.x, s.lowest, s.position.z);
    shaft.top = groundAt(glm::vec2(s.position.x, s.position.z));
    shaft.waterLevel = defaults.waterLevel;
    if (shaft.top > shaft.bottom.y) network.shafts.push_back(shaft);
  }
}

namespace {

// How far along `nodes` (from the first) the polyline leaves the disc of radius `r` around
// `centre` in plan (x, z); nullopt if it never does.
std::optional<float> leaveDisc(const std::vector<glm::vec3>& nodes, glm::vec2 centre, float r) {
  float arc = 0.0f;
  for (std::size_t k = 0; k + 1 < nodes.size(); ++k) {
    const glm::vec2 a = glm::vec2(nodes[k].x, nodes[k].z) - centre;
    const glm::vec2 d = glm::vec2(nodes[k + 1].x - nodes[k].x, nodes[k + 1].z - nodes[k].z);
    const float segment = glm::length(nodes[k + 1] - nodes[k]);
    // |a + t d|² = r², the larger root: where the segment crosses the circle outwards.
    const float qa = glm::dot(d, d), qb = 2.0f * glm::dot(a, d), qc = glm::dot(a, a) - r * r;
    if (qa > 0.0f && qb * qb - 4.0f * qa * qc >= 0.0f) {
      const float t = (-qb + std::sqrt(qb * qb - 4.0f * qa * qc)) / (2.0f * qa);
      if (t >= 0.0f && t <= 1.0f) return arc + t * segment;
    }
    arc += segment;
  }
  return std::nullopt;
}

}  // namespace

int trimAtShafts(PipeNetwork& network) {
  int moved = 0;
  for (Pipe& pipe : network.pipes)
    for (const bool front : {true, false})
      for (const Shaft& shaft : network.shafts) {
        const glm::vec3 end = front ? pipe.nodes.front() : pipe.nodes.back();
        const glm::vec2 axis(shaft.bottom.x, shaft.bottom.z);
        const float r = shaft.innerRadius();
        if (glm::length(glm::vec2(end.x, end.z) - axis) >= r ||
            end.y < shaft.bottom.y - pipe.radius || end.y > shaft.top + pipe.radius)
          continue;
        std::vector<glm::vec3> walk = pipe.nodes;
        if (!front) std::reverse(walk.begin(), walk.end());
        const std::optional<float> out = leaveDisc(walk, axis, r);
        const float length = pipe.length();
        if (!out || *out >= length) continue;
        // The part of the pipe from `out` on, in the walk's direction.
        std::vector<glm::vec3> kept;
        float arc = 0.0f;
        for (std::size_t k = 0; k + 1 < walk.size(); ++k) {
          const float segment = glm::length(walk[k + 1] - walk[k]);
          if (arc + segment > *out) {
            if (kept.empty())
              kept.push_back(walk[k] + (walk[k + 1] - walk[k]) * ((*out - arc) / segment));
            kept.push_back(walk[k + 1]);
          }
          arc += segment;
        }
        if (!front) std::reverse(kept.begin(), kept.end());
        pipe.nodes = std::move(kept);
        if (pipe.cut) {
          // Arc lengths count from the first node: a trimmed front shifts them.
          glm::vec2 c = front ? *pipe.cut - *out : *pipe.cut;
          c = glm::clamp(c, 0.0f, length - *out);
          pipe.cut = c.y > c.x ? std::optional<glm::vec2>(c) : std::nullopt;
        }
        ++moved;
      }
  return moved;
}

Mesh pipeMesh(const PipeNetwork& network, int sides) {
  Mesh m;
  const auto ring = [&](const glm::vec3& c, const glm::vec3& side, const glm::vec3& dir, float r) {
    const glm::vec3 other = glm::cross(dir, side);
    for (int k = 0; k < sides; ++k) {
      const float a = 2.0f * std::numbers::pi_v<float> * float(k) / float(sides);
      const glm::vec3 n = std::cos(a) * side + std::sin(a) * other;
      m.positions.push_back(c + r * n);
      m.normals.push_back(n);
    }
  };
  // A flat disc closing the ring that starts at `rim`, its rim copied from the ring so that
  // the two weld; `reversed` winds it about −dir (the pipe's start).
  const auto cap = [&](const glm::vec3& c, unsigned rim, const glm::vec3& outward, bool reversed) {
    const auto centre = unsigned(m.positions.size());
    m.positions.push_back(c);
    m.normals.push_back(outward);
    for (int k = 0; k < sides; ++k) {
      m.positions.push_back(m.positions[rim + unsigned(k)]);
      m.normals.push_back(outward);
    }
    for (int k = 0; k < sides; ++k) {
      const unsigned a = centre + 1 + unsigned(k), b = centre + 1 + unsigned((k + 1) % sides);
      if (reversed)
        m.triangles.emplace_back(centre, b, a);
      else
        m.triangles.emplace_back(centre, a, b);
    }
  };
  for (const Pipe& p : network.pipes) {
    const float r = p.radius * network.radiusScale;
    const auto first = unsigned(m.positions.size());
    glm::vec3 side = anyPerpendicular(nodeDirection(p.nodes, 0));
    for (std::size_t i = 0; i < p.nodes.size(); ++i) {
      const glm::vec3 dir = nodeDirection(p.nodes, i);
      // Parallel transport of the ring's frame: no twist along the pipe.
      side = glm::normalize(side - glm::dot(side, dir) * dir);
      ring(p.nodes[i], side, dir, r);
    }
    for (std::size_t i = 0; i + 1 < p.nodes.size(); ++i)
      for (int k = 0; k < sides; ++k) {
        const unsigned a = first + unsigned(i * std::size_t(sides) + std::size_t(k));
        const unsigned b = first + unsigned(i * std::size_t(sides) + std::size_t((k + 1) % sides));
        m.triangles.emplace_back(a, b, b + unsigned(sides));
        m.triangles.emplace_back(a, b + unsigned(sides), a + unsigned(sides));
      }
    cap(p.nodes.front(), first, -nodeDirection(p.nodes, 0), true);
    cap(p.nodes.back(), first + unsigned((p.nodes.size() - 1) * std::size_t(sides)),
        nodeDirection(p.nodes, p.nodes.size() - 1), false);
  }
  return m;
}

Mesh shaftMesh(const PipeNetwork& network, bool inner, int sides) {
  Mesh m;
  for (const Shaft& s : network.shafts) {
    const float r = inner ? s.innerRadius() : s.radius;
    const auto first = unsigned(m.positions.size());
    for (int k = 0; k < sides; ++k) {
      const float a = 2.0f * std::numbers::pi_v<float> * float(k) / float(sides);
      const glm::vec3 n(std::cos(a), 0.0f, -std::sin(a));
      m.positions.push_back(s.bottom + r * n);
      m.positions.push_back(glm::vec3(s.bottom.x, s.top, s.bottom.z) + r * n);
      m.normals.push_back(n), m.normals.push_back(n);
    }
    for (int k = 0; k < sides; ++k) {
      const unsigned a = first + 2 * unsigned(k), b = first + 2 * unsigned((k + 1) % sides);
      m.triangles.emplace_back(a, b, b + 1);
      m.triangles.emplace_back(a, b + 1, a + 1);
    }
    if (!inner) continue;
    // The floor closes the inner cylinder: seen from inside it is a back face, shaded as the
    // shaft's interior.
    const auto centre = unsigned(m.positions.size());
    m.positions.push_back(s.bottom);
    m.normals.push_back(-kUp);
    for (int k = 0; k < sides; ++k) {
      const float a = 2.0f * std::numbers::pi_v<float> * float(k) / float(sides);
      m.positions.push_back(s.bottom + r * glm::vec3(std::cos(a), 0.0f, -std::sin(a)));
      m.normals.push_back(-kUp);
    }
    for (int k = 0; k < sides; ++k)
      m.triangles.emplace_back(centre, centre + 1 + unsigned((k + 1) % sides),
                               centre + 1 + unsigned(k));
  }
  return m;
}

Mesh jointMesh(const std::vector<Joint>& joints, int rings, int sides) {
  Mesh m;
  for (const Joint& j : joints) {
    const auto first = unsigned(m.positions.size());
    for (int i = 0; i <= rings; ++i) {
      const float theta = std::numbers::pi_v<float> * float(i) / float(rings);
      // Exactly 0 at the poles (sin π is not, in float), so that each pole is one point.
      const float st = i == 0 || i == rings ? 0.0f : std::sin(theta);
      const float ct = i == 0 ? 1.0f : i == rings ? -1.0f : std::cos(theta);
      for (int k = 0; k <= sides; ++k) {
        // The seam's last column repeats the first exactly, so that the two weld.
        const float phi = 2.0f * std::numbers::pi_v<float> * float(k % sides) / float(sides);
        const glm::vec3 n(st * std::cos(phi), ct, -st * std::sin(phi));
        m.positions.push_back(j.position + j.radius * n);
        m.normals.push_back(n);
      }
    }
    const auto at = [&](int i, int k) { return first + unsigned(i * (sides + 1) + k); };
    for (int i = 0; i < rings; ++i)
      for (int k = 0; k < sides; ++k) {
        // The triangles that would have both corners on a pole are left out.
        if (i + 1 < rings) m.triangles.emplace_back(at(i, k), at(i + 1, k), at(i + 1, k + 1));
        if (i > 0) m.triangles.emplace_back(at(i, k), at(i + 1, k + 1), at(i, k + 1));
      }
  }
  return m;
}

}  // namespace cutaway
