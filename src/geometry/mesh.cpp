#include "cutaway/geometry/mesh.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <map>
#include <numeric>
#include <utility>

namespace cutaway {

Bounds Bounds::transformed(const glm::mat4& m) const {
  Bounds out;
  if (empty()) return out;
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 corner{(i & 1) ? max.x : min.x, (i & 2) ? max.y : min.y,
                           (i & 4) ? max.z : min.z};
    out.extend(glm::vec3(m * glm::vec4(corner, 1.0f)));
  }
  return out;
}

Bounds Mesh::bounds() const {
  // Non-finite positions are left out: their triangles were dropped (dropDegenerateTriangles),
  // and one infinite coordinate made the whole object's bounds, then its box, empty.
  Bounds b;
  for (const auto& p : positions)
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) b.extend(p);
  return b;
}

void Mesh::append(const Mesh& other, const glm::mat4& m) {
  // A grid's implied triangles are stored first: the result is no grid.
  if (impliedTriangles()) {
    std::vector<glm::uvec3> own(triangleCount());
    for (std::size_t i = 0; i < own.size(); ++i) own[i] = triangle(i);
    triangles = std::move(own);
  }
  grid.reset();
  const auto base = unsigned(positions.size());
  const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(m)));
  // A mirroring transform flips the winding; restore outward-facing orientation.
  const bool mirrored = glm::determinant(glm::mat3(m)) < 0.0f;
  for (std::size_t i = 0; i < other.positions.size(); ++i) {
    positions.push_back(glm::vec3(m * glm::vec4(other.positions[i], 1.0f)));
    const glm::vec3 n = normalMatrix * other.normals[i];
    const float len = glm::length(n);
    normals.push_back(len > 0.0f ? n / len : n);
  }
  for (std::size_t i = 0, n = other.triangleCount(); i < n; ++i) {
    const glm::uvec3 t = other.triangle(i);
    triangles.push_back(mirrored ? glm::uvec3(t.x, t.z, t.y) + base : t + base);
  }
}

std::size_t dropDegenerateTriangles(Mesh& mesh) {
  std::size_t kept = 0;
  for (const auto& t : mesh.triangles) {
    if (t.x == t.y || t.y == t.z || t.x == t.z) continue;
    const glm::vec3 c = glm::cross(mesh.positions[t.y] - mesh.positions[t.x],
                                   mesh.positions[t.z] - mesh.positions[t.x]);
    // Component by component: dot(c, c) overflows for edges of some 4e9 units, far within
    // the 1e15 a scene may reach.
    const bool zero = c.x == 0.0f && c.y == 0.0f && c.z == 0.0f;
    if (zero) continue;
    if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z)) {
      // Non-finite corners, or edges beyond ~1e19 whose products overflow: those stay for
      // the scene's reach check to name, rather than leave a file "without triangles".
      const glm::dvec3 a(mesh.positions[t.x]), b(mesh.positions[t.y]), d(mesh.positions[t.z]);
      const glm::dvec3 wide = glm::cross(b - a, d - a);
      if (!std::isfinite(wide.x) || !std::isfinite(wide.y) || !std::isfinite(wide.z) ||
          wide == glm::dvec3(0.0))
        continue;
    }
    mesh.triangles[kept++] = t;
  }
  const std::size_t dropped = mesh.triangles.size() - kept;
  mesh.triangles.resize(kept);
  // A grid that lost stored triangles is none; left empty, it would read as implied ones.
  if (dropped > 0) mesh.grid.reset();
  return dropped;
}

void computeVertexNormals(Mesh& mesh, float creaseAngle) {
  const float cosCrease = std::cos(glm::radians(creaseAngle));
  std::vector<glm::vec3> faceNormals(mesh.triangles.size());  // unnormalised: |n| = 2 area
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    faceNormals[f] = glm::cross(mesh.positions[t.y] - mesh.positions[t.x],
                                mesh.positions[t.z] - mesh.positions[t.x]);
  }
  auto unit = [](const glm::vec3& n) {
    const float len = glm::length(n);
    if (len > 0.0f && std::isfinite(len)) return n / len;
    // |n| overflowed (faces of some 1e10 units) or underflowed: scaled to its largest
    // component first.
    const float largest = std::max({std::abs(n.x), std::abs(n.y), std::abs(n.z)});
    if (!(largest > 0.0f) || !std::isfinite(largest)) return glm::vec3(0.0f, 0.0f, 1.0f);
    return glm::normalize(n / largest);
  };
  // Faces around each vertex index.
  std::vector<std::vector<unsigned>> facesOf(mesh.positions.size());
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
    for (int k = 0; k < 3; ++k) facesOf[mesh.triangles[f][k]].push_back(unsigned(f));

  std::vector<glm::vec3> faceUnits(faceNormals.size());
  for (std::size_t f = 0; f < faceNormals.size(); ++f) faceUnits[f] = unit(faceNormals[f]);
  // The smoothed normal of vertex v for a face of unit normal `own`, once per distinct `own`:
  // the faces of a fan or a triangulated polygon share one normal, and summing over all of
  // them for each of their corners was quadratic in the vertex's valence (a 3100-gon: 0.3 s).
  std::vector<std::map<std::array<float, 3>, glm::vec3>> smoothed(mesh.positions.size());
  auto smoothedNormal = [&](unsigned v, const glm::vec3& own) {
    const auto [it, fresh] = smoothed[v].try_emplace({own.x, own.y, own.z});
    if (fresh) {
      glm::vec3 sum(0.0f);
      for (unsigned g : facesOf[v])
        if (glm::dot(faceUnits[g], own) >= cosCrease) sum += faceNormals[g];
      it->second = glm::length(sum) > 0.0f ? unit(sum) : own;
    }
    return it->second;
  };

  std::vector<glm::vec3> positions, normals;
  std::map<std::pair<unsigned, std::array<float, 3>>, unsigned> corners;  // (vertex, normal) → new
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const glm::vec3 own = faceUnits[f];
    for (int k = 0; k < 3; ++k) {
      const unsigned v = mesh.triangles[f][k];
      const glm::vec3 n = smoothedNormal(v, own);
      const auto [it, inserted] = corners.emplace(
          std::make_pair(v, std::array<float, 3>{n.x, n.y, n.z}), unsigned(positions.size()));
      if (inserted) {
        positions.push_back(mesh.positions[v]);
        normals.push_back(n);
      }
      mesh.triangles[f][k] = it->second;
    }
  }
  mesh.positions = std::move(positions);
  mesh.normals = std::move(normals);
}

void analyzeTopology(Mesh& mesh) {
  // Welding: positions sorted by their coordinates' bits (−0 read as +0) share an index where
  // equal; a position with a NaN equals none. Sorting, not hashing: a hash node per position
  // made large terrains slow to load.
  struct Key {
    std::array<std::uint32_t, 3> bits;
    unsigned position;
  };
  std::vector<Key> keys;
  keys.reserve(mesh.positions.size());
  std::vector<unsigned> welded(mesh.positions.size());
  unsigned welds = 0;
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3& p = mesh.positions[i];
    if (std::isnan(p.x) || std::isnan(p.y) || std::isnan(p.z)) {
      welded[i] = welds++;
      continue;
    }
    Key k{{}, unsigned(i)};
    for (int c = 0; c < 3; ++c) k.bits[std::size_t(c)] = std::bit_cast<std::uint32_t>(p[c] + 0.0f);
    keys.push_back(k);
  }
  std::sort(keys.begin(), keys.end(), [](const Key& x, const Key& y) { return x.bits < y.bits; });
  for (std::size_t i = 0; i < keys.size(); ++i) {
    if (i > 0 && keys[i].bits != keys[i - 1].bits) ++welds;
    welded[keys[i].position] = welds;
  }
  if (!keys.empty()) ++welds;
  // Each undirected edge's uses in each direction (low→high, high→low), grouped by the edge's
  // lower end and sorted within the group: a few words per use, where a map's node per edge
  // made large terrains slow to load.
  const auto forEachEdge = [&](const auto& f) {
    for (std::size_t i = 0, n = mesh.triangleCount(); i < n; ++i) {
      const glm::uvec3 t = mesh.triangle(i);
      const unsigned v[3] = {welded[t.x], welded[t.y], welded[t.z]};
      for (int e = 0; e < 3; ++e)
        if (v[e] != v[(e + 1) % 3]) f(v[e], v[(e + 1) % 3]);
    }
  };
  std::vector<std::size_t> start(welds + 1, 0);
  forEachEdge([&](unsigned a, unsigned b) { ++start[std::min(a, b) + 1]; });
  std::partial_sum(start.begin(), start.end(), start.begin());
  // The higher end and, in the lowest bit, whether the use runs high→low.
  std::vector<std::uint64_t> uses(start.back());
  std::vector<std::size_t> next(start.begin(), start.end() - 1);
  forEachEdge([&](unsigned a, unsigned b) {
    uses[next[std::min(a, b)]++] = std::uint64_t(std::max(a, b)) << 1 | std::uint64_t(a > b);
  });
  MeshReport& r = mesh.report;
  r.boundaryEdges = r.nonManifoldEdges = r.misorientedEdges = 0;
  for (std::size_t low = 0; low + 1 < start.size(); ++low) {
    const auto first = uses.begin() + std::ptrdiff_t(start[low]),
               last = uses.begin() + std::ptrdiff_t(start[low + 1]);
    std::sort(first, last);
    for (auto i = first; i != last;) {
      int count[2] = {0, 0};
      const std::uint64_t high = *i >> 1;
      for (; i != last && *i >> 1 == high; ++i) ++count[*i & 1];
      const int total = count[0] + count[1];
      if (total == 1)
        ++r.boundaryEdges;
      else if (total > 2)
        ++r.nonManifoldEdges;
      else if (count[0] != 1)
        ++r.misorientedEdges;
    }
  }
  r.watertight = mesh.triangleCount() > 0 && r.boundaryEdges == 0 && r.nonManifoldEdges == 0 &&
                 r.misorientedEdges == 0;
}

bool orientOutward(Mesh& mesh) {
  if (!mesh.report.watertight || mesh.triangles.empty()) return false;
  // Six times the signed volume, relative to a vertex (exact for a closed mesh wherever the
  // origin lies; nearer numbers round less).
  const glm::dvec3 o(mesh.positions[mesh.triangles.front().x]);
  const auto at = [&](unsigned i) { return glm::dvec3(mesh.positions[i]) - o; };
  double volume = 0.0;
  for (const glm::uvec3& t : mesh.triangles)
    volume += glm::dot(at(t.x), glm::cross(at(t.y), at(t.z)));
  if (!(volume < 0.0)) return false;
  // Normals that agree with the inward winding (computed from it) turn with it; a file's
  // normals that already point out (its winding alone reversed) stay.
  const bool normals = mesh.normals.size() == mesh.positions.size();
  double agreement = 0.0;
  for (glm::uvec3& t : mesh.triangles) {
    std::swap(t.y, t.z);
    const glm::dvec3 face = glm::cross(at(t.y) - at(t.x), at(t.z) - at(t.x));
    if (normals)
      agreement +=
          glm::dot(face, glm::dvec3(mesh.normals[t.x] + mesh.normals[t.y] + mesh.normals[t.z]));
  }
  if (agreement < 0.0)
    for (glm::vec3& n : mesh.normals) n = -n;
  mesh.report.windingReversed = true;
  return true;
}

Mesh makeBox(const glm::vec3& lo, const glm::vec3& hi) {
  Mesh m;
  // Each face: outward normal n and in-plane axes un, vn = n × un, so un × vn = n and the
  // quad winds counter-clockwise seen from outside.
  const glm::vec3 normals[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  const glm::vec3 center = (lo + hi) * 0.5f, half = (hi - lo) * 0.5f;
  for (const auto& n : normals) {
    const glm::vec3 un = glm::abs(n.x) > 0.5f   ? glm::vec3(0, 1, 0) * n.x
                         : glm::abs(n.y) > 0.5f ? glm::vec3(0, 0, 1) * n.y
                                                : glm::vec3(1, 0, 0) * n.z;
    const glm::vec3 vn = glm::cross(n, un);
    const auto base = unsigned(m.positions.size());
    const glm::vec2 corners[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (const auto& c : corners) {
      m.positions.push_back(center + half * (n + c.x * un + c.y * vn));
      m.normals.push_back(n);
    }
    m.triangles.push_back({base, base + 1, base + 2});
    m.triangles.push_back({base, base + 2, base + 3});
  }
  analyzeTopology(m);
  return m;
}

std::vector<float> rayHits(const Mesh& mesh, const glm::vec3& origin, const glm::vec3& direction) {
  std::vector<float> hits;
  for (std::size_t i = 0, n = mesh.triangleCount(); i < n; ++i) {
    const glm::uvec3 tri = mesh.triangle(i);
    const glm::vec3 p0 = mesh.positions[tri.x];
    const glm::vec3 e1 = mesh.positions[tri.y] - p0, e2 = mesh.positions[tri.z] - p0;
    const glm::vec3 q = glm::cross(direction, e2);
    const double det = glm::dot(e1, q);
    if (std::abs(det) < 1e-14) continue;  // parallel to the triangle's plane
    const glm::vec3 s = origin - p0;
    const double a = glm::dot(s, q) / det;
    const glm::vec3 r = glm::cross(s, e1);
    const double b = glm::dot(direction, r) / det, t = glm::dot(e2, r) / det;
    if (a >= 0.0 && b >= 0.0 && a + b <= 1.0 && t > 0.0) hits.push_back(float(t));
  }
  return hits;
}

}  // namespace cutaway
