#include "cutaway/geometry/convex_hull.hpp"

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

#include <cstdio>
#include <cstdlib>
#include <string>
#include <unordered_map>

#include "cutaway/core/error.hpp"

namespace cutaway {

Mesh convexHull(const std::vector<glm::vec3>& points) {
  if (points.size() < 4)
    throw Error("convex hull needs at least 4 points, got " + std::to_string(points.size()));
  std::vector<coordT> coords;
  coords.reserve(points.size() * 3);
  for (const auto& p : points) coords.insert(coords.end(), {p.x, p.y, p.z});

  char* errorText = nullptr;
  std::size_t errorSize = 0;
  std::FILE* errorStream = open_memstream(&errorText, &errorSize);
  qhT qhStorage;
  qhT* qh = &qhStorage;
  qh_zero(qh, errorStream);
  // Qt: triangulated facets; the hull is a closed triangle mesh.
  char options[] = "qhull Qt";
  const int status =
      qh_new_qhull(qh, 3, int(points.size()), coords.data(), False, options, nullptr, errorStream);
  Mesh hull;
  if (status == 0) {
    std::unordered_map<int, unsigned> vertexIndex;
    auto indexOf = [&](vertexT* v) {
      const int id = qh_pointid(qh, v->point);
      auto [it, inserted] = vertexIndex.emplace(id, unsigned(hull.positions.size()));
      if (inserted) hull.positions.push_back(points[std::size_t(id)]);
      return it->second;
    };
    facetT* facet;
    FORALLfacets {
      if (facet->upperdelaunay || qh_setsize(qh, facet->vertices) != 3) continue;
      unsigned idx[3];
      int k = 0;
      vertexT *vertex, **vertexp;
      FOREACHvertex_(facet->vertices) idx[k++] = indexOf(vertex);
      glm::uvec3 tri(idx[0], idx[1], idx[2]);
      const glm::vec3 n(float(facet->normal[0]), float(facet->normal[1]), float(facet->normal[2]));
      const glm::vec3 c = glm::cross(hull.positions[tri.y] - hull.positions[tri.x],
                                     hull.positions[tri.z] - hull.positions[tri.x]);
      if (glm::dot(c, n) < 0.0f) std::swap(tri.y, tri.z);  // outward winding
      hull.triangles.push_back(tri);
    }
  }
  qh_freeqhull(qh, !qh_ALL);
  int curlong = 0, totlong = 0;
  qh_memfreeshort(qh, &curlong, &totlong);
  std::fclose(errorStream);
  std::string message = errorText ? errorText : "";
  std::free(errorText);
  if (status != 0) {
    if (auto nl = message.find('\n'); nl != std::string::npos) message.resize(nl);
    throw Error("convex hull failed (points coplanar or collinear?): " + message);
  }
  computeVertexNormals(hull);
  analyzeTopology(hull);
  return hull;
}

}  // namespace cutaway
