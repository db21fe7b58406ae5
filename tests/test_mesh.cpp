#include <gtest/gtest.h>

#include "cutaway/geometry/mesh.hpp"

using namespace cutaway;

TEST(Mesh, BoxIsWatertightWithOutwardNormals) {
  Mesh box = makeBox({0, 0, 0}, {1, 2, 3});
  EXPECT_TRUE(box.report.watertight);
  EXPECT_EQ(box.triangles.size(), 12u);
  for (const auto& t : box.triangles) {
    const glm::vec3 c = glm::cross(box.positions[t.y] - box.positions[t.x],
                                   box.positions[t.z] - box.positions[t.x]);
    const glm::vec3 centroid =
        (box.positions[t.x] + box.positions[t.y] + box.positions[t.z]) / 3.0f;
    EXPECT_GT(glm::dot(c, centroid - glm::vec3(0.5f, 1.0f, 1.5f)), 0.0f);
  }
}
