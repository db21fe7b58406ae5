#include <gtest/gtest.h>

#include <unistd.h>
#include <zlib.h>
#include <algorithm>
#include <cstring>
#include <iterator>
#include <limits>

#include <filesystem>
#include <fstream>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "cutaway/geometry/ground_height.hpp"
#include "cutaway/geometry/mesh.hpp"
#include "cutaway/io/mesh_import.hpp"
#include "expect_error.hpp"
#include "run_command.hpp"

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

// Faces of 1e10 units (a scene may reach 1e15) are neither dropped as degenerate (the cross
// product's squared length overflows) nor given zero normals; zero-area and NaN faces are.
TEST(Mesh, LargeFacesKeepTheirAreaAndNormalsDegenerateOnesAreDropped) {
  for (const float size : {1.0f, 1e10f, 1e14f}) {
    Mesh mesh;
    mesh.positions = {
        {0, 0, 0}, {size, 0, 0}, {0, size, 0}, {2 * size, 0, 0}, {0, std::nanf(""), 0}};
    mesh.triangles = {{0, 1, 2}, {0, 1, 3}, {0, 1, 4}, {0, 0, 2}};
    EXPECT_EQ(dropDegenerateTriangles(mesh), 3u) << size;
    ASSERT_EQ(mesh.triangles.size(), 1u) << size;
    computeVertexNormals(mesh);
    ASSERT_EQ(mesh.normals.size(), 3u) << size;
    for (const glm::vec3& n : mesh.normals) EXPECT_EQ(n, glm::vec3(0, 0, 1)) << size;
  }
}

// analyzeTopology's edge counts against a count written out here: on random triangle soups
// over few positions (shared edges, both directions, three or more uses, repeated corners,
// duplicated positions that weld, −0 with +0), every edge's uses in each direction tallied
// pair by pair.
TEST(Mesh, TopologyCountsEveryEdgesUsesInEachDirection) {
  std::uint32_t state = 12345;
  const auto next = [&](std::uint32_t n) {
    state = state * 1664525u + 1013904223u;
    return (state >> 8) % n;
  };
  for (int round = 0; round < 200; ++round) {
    Mesh mesh;
    const std::uint32_t points = 3 + next(6);
    for (std::uint32_t i = 0; i < points; ++i)
      mesh.positions.emplace_back(float(i % 4), i < 4 ? 0.0f : -0.0f, 0);
    for (std::uint32_t t = 0, n = 1 + next(12); t < n; ++t)
      mesh.triangles.emplace_back(next(points), next(points), next(points));
    // The same edges, pair by pair: positions weld when equal (here i % 4).
    std::vector<std::pair<unsigned, unsigned>> directed;
    for (const glm::uvec3& t : mesh.triangles)
      for (int e = 0; e < 3; ++e) {
        const unsigned a = t[e] % 4, b = t[(e + 1) % 3] % 4;
        if (a != b) directed.emplace_back(a, b);
      }
    std::size_t boundary = 0, nonManifold = 0, misoriented = 0;
    for (unsigned a = 0; a < 4; ++a)
      for (unsigned b = a + 1; b < 4; ++b) {
        const auto forward = std::count(directed.begin(), directed.end(), std::pair{a, b});
        const auto backward = std::count(directed.begin(), directed.end(), std::pair{b, a});
        if (forward + backward == 1) ++boundary;
        if (forward + backward > 2) ++nonManifold;
        if (forward + backward == 2 && forward != 1) ++misoriented;
      }
    analyzeTopology(mesh);
    SCOPED_TRACE("round " + std::to_string(round));
    EXPECT_EQ(mesh.report.boundaryEdges, boundary);
    EXPECT_EQ(mesh.report.nonManifoldEdges, nonManifold);
    EXPECT_EQ(mesh.report.misorientedEdges, misoriented);
    EXPECT_EQ(mesh.report.watertight, boundary + nonManifold + misoriented == 0);
  }
}

// GroundHeight against rays cast straight down (Möller–Trumbore, rayHits) through every
// triangle: a rotated, scaled and moved random grid and a tilted quad over part of it, at
// random points on, between and off them; the highest surface counts.
TEST(GroundHeight, IsTheHighestSurfaceARayFromAboveMeets) {
  std::uint32_t state = 777;
  const auto unit = [&] {
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) / 16777216.0f;
  };
  Mesh grid;
  const int columns = 11, rows = 7;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c) grid.positions.emplace_back(c, 3.0f * unit(), r);
  for (int r = 0; r + 1 < rows; ++r)
    for (int c = 0; c + 1 < columns; ++c) {
      const unsigned a = unsigned(r * columns + c), b = a + 1, d = a + columns, e = d + 1;
      grid.triangles.emplace_back(a, d, b);
      grid.triangles.emplace_back(b, d, e);
    }
  Mesh quad;
  quad.positions = {{2, 1, 1}, {5, 4, 1}, {5, 4, 4}, {2, 1, 4}};
  quad.triangles = {{0, 2, 1}, {0, 3, 2}};
  // A node no triangle keeps, as dropDegenerateTriangles leaves one, may be infinite.
  quad.positions.emplace_back(-std::numeric_limits<float>::infinity(), 0, 0);
  grid.normals.assign(grid.positions.size(), glm::vec3(0, 1, 0));  // one per position
  quad.normals.assign(quad.positions.size(), glm::vec3(0, 1, 0));
  const glm::mat4 gridPlace = glm::scale(
      glm::rotate(glm::translate(glm::mat4(1.0f), {40, -2, 7}), 0.6f, {0, 1, 0}), {3, 1, 2});
  const glm::mat4 quadPlace = glm::translate(gridPlace, {0, 0.5f, 0});
  const GroundHeight ground({&grid, &quad}, {gridPlace, quadPlace});
  ASSERT_FALSE(ground.empty());
  Mesh world;
  world.append(grid, gridPlace);
  world.append(quad, quadPlace);
  const Bounds box = world.bounds();
  int on = 0;
  for (int i = 0; i < 2000; ++i) {
    const glm::vec2 xz(box.min.x - 5 + (box.max.x - box.min.x + 10) * unit(),
                       box.min.z - 5 + (box.max.z - box.min.z + 10) * unit());
    const float top = box.max.y + 10;
    const std::vector<float> hits = rayHits(world, {xz.x, top, xz.y}, {0, -1, 0});
    const std::optional<float> y = ground.at(xz);
    SCOPED_TRACE("at " + std::to_string(xz.x) + ", " + std::to_string(xz.y));
    ASSERT_EQ(y.has_value(), !hits.empty());
    if (!y) continue;
    ++on;
    EXPECT_NEAR(*y, top - *std::min_element(hits.begin(), hits.end()), 1e-3f);
  }
  EXPECT_GT(on, 300);  // the points found the terrain, not only the space around it
  EXPECT_TRUE(GroundHeight({}, {}).empty());
  EXPECT_FALSE(GroundHeight({}, {}).at({0, 0}));
}

namespace {

// A PLY file in the temporary folder with the given text; its path.
std::filesystem::path plyFile(const std::string& name, const std::string& text) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("cutaway-mesh-" + std::to_string(::getpid()) + "-" + name);
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// Importing the file `name` holding `text` fails with an error mentioning every one of `parts`.
void refuse(const std::string& name, const std::string& text,
            std::initializer_list<std::string> parts) {
  const std::filesystem::path file = plyFile(name, text);
  test::expectError([&] { importMeshNodes(file); }, parts);
  std::filesystem::remove(file);
}

const std::string kPlyHeader =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n0 1 0\n";

}  // namespace

// The project's PLY reader (src/io/ply_reader.hpp) on what it reads: ASCII with any line
// ending, binary of either byte order with normals and an element it reads past, polygons
// as fans, triangle strips with restarts; faces of fewer than three vertices dropped.
TEST(PlyReader, AsciiAndBinaryFilesOfEitherByteOrderLoad) {
  const auto load = [](const std::string& name, const std::string& text) {
    const std::filesystem::path file = plyFile(name, text);
    auto nodes = importMeshNodes(file);
    std::filesystem::remove(file);
    EXPECT_EQ(nodes.size(), 1u) << name;
    return std::move(nodes.front());
  };
  std::ifstream in(CUTAWAY_TEST_DATA "/fuzz/mesh-ply/valid-tetra.ply", std::ios::binary);
  const std::string tetra{std::istreambuf_iterator<char>(in), {}};
  for (const std::string ending : {"\n", "\r\n", "\r"}) {
    std::string text;
    for (char c : tetra) text += c == '\n' ? ending : std::string(1, c);
    const ImportedNode node = load("tetra.ply", text);
    EXPECT_TRUE(node.name.ends_with("tetra")) << node.name;
    EXPECT_EQ(node.mesh.triangles.size(), 4u);
    EXPECT_TRUE(node.mesh.report.watertight);
    EXPECT_TRUE(node.mesh.report.normalsComputed);
  }
  // Binary: four vertices of x, y, z and normals, an edge, four faces; little- and big-endian.
  const auto binary = [](bool big, std::uint32_t secondCount) {
    std::string out =
        std::string("ply\nformat binary_") + (big ? "big" : "little") +
        "_endian 1.0\ncomment made by hand\nelement vertex 4\nproperty float x\n"
        "property float y\nproperty float z\nproperty float nx\nproperty float ny\n"
        "property float nz\nelement edge 1\nproperty int vertex1\n"
        "property int vertex2\nelement face 4\nproperty list uint int vertex_indices\n"
        "end_header\n";
    const auto put = [&](std::uint32_t v) {
      for (int b = 0; b < 4; ++b) out += char(v >> (8 * (big ? 3 - b : b)) & 0xFF);
    };
    const float corners[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (const auto& c : corners)
      for (int k = 0; k < 6; ++k) {
        const float f = k < 3 ? c[k] : k == 5 ? 1.0f : 0.0f;
        std::uint32_t bits;
        std::memcpy(&bits, &f, 4);
        put(bits);
      }
    put(0), put(1);
    const std::uint32_t faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    for (int f = 0; f < 4; ++f) {
      put(f == 1 ? secondCount : 3);
      for (std::uint32_t v : faces[f]) put(v);
    }
    return out;
  };
  for (const bool big : {false, true}) {
    const ImportedNode node = load(big ? "big.ply" : "little.ply", binary(big, 3));
    ASSERT_EQ(node.mesh.positions.size(), 4u);
    EXPECT_EQ(node.mesh.positions[3], glm::vec3(0, 0, 1)) << big;
    EXPECT_EQ(node.mesh.triangles.size(), 4u) << big;
    EXPECT_EQ(node.mesh.triangles[3], glm::uvec3(1, 2, 3)) << big;
    // The file's normals, all +z, are kept.
    EXPECT_FALSE(node.mesh.report.normalsComputed);
    EXPECT_EQ(node.mesh.normals[0], glm::vec3(0, 0, 1)) << big;
  }
  refuse("long-binary.ply", binary(false, 0xFFFFFFF0u),
         {"long-binary.ply", "face 1",
          "the file ends early: a list of 4294967280 values in the 44 bytes left"});
  refuse("long-big.ply", binary(true, 1000u), {"long-big.ply", "face 1", "a list of 1000 values"});
  // A pentagon as a fan of three, a line (two vertices) dropped; a strip of 0 1 2 3, a restart,
  // 4 5 6: triangles (0 1 2), (2 1 3) with alternate winding, (4 5 6).
  const std::string six =
      "ply\nformat ascii 1.0\nelement vertex 7\nproperty float x\nproperty float y\n"
      "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n2 1 0\n1 2 0\n0 1 0\n0 0 1\n1 1 1\n5 0 1 2 3 4\n2 5 6\n";
  const ImportedNode fan = load("fan.ply", six);
  EXPECT_EQ(fan.mesh.triangles, (std::vector<glm::uvec3>{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}}));
  const std::string strips =
      "ply\nformat ascii 1.0\nelement vertex 7\nproperty float x\nproperty float y\n"
      "property float z\nelement tristrips 1\nproperty list int int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 0 1\n1 0 1\n0 1 1\n8 0 1 2 3 -1 4 5 6\n";
  const ImportedNode strip = load("strip.ply", strips);
  EXPECT_EQ(strip.mesh.triangles, (std::vector<glm::uvec3>{{0, 1, 2}, {2, 1, 3}, {4, 5, 6}}));
}

// Issue 16: each malformed PLY is a one-line error naming the file, the place and the reason,
// and no count is believed beyond the bytes that could hold it (Debian's Assimp reader, used
// before, allocated 34 GB for an ASCII count of "9999…3", looped at the end of files and wrote
// past its arrays; its fuzzed inputs are replayed by FuzzCorpus).
TEST(PlyReader, BadFilesAreRefusedWithTheirPlaceAndReason) {
  const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 3\n" + xyz;
  refuse("magic.ply", "solid x\nendsolid x\n", {"magic.ply", "not a PLY"});
  refuse("header.ply", "ply\nformat ascii 1.0\n", {"header.ply", "no end_header line"});
  refuse("format.ply", "ply\nformat ascii 2.0\nend_header\n", {"format.ply", "header line 2"});
  refuse("no-format.ply", "ply\nelement vertex 0\nend_header\n", {"no-format.ply", "no format"});
  refuse("count.ply",
         "ply\nformat binary_little_endian 1.0\nelement vertex 2147483648\nproperty float x\n"
         "end_header\n",
         {"count.ply", "header line 3", "claims 2147483648 vertex elements in a file of 90 bytes"});
  refuse("huge.ply", "ply\nformat ascii 1.0\nelement vertex 42949667294949667294\nend_header\n",
         {"huge.ply", "header line 3", "COUNT a whole number"});
  refuse("keyword.ply", "ply\nformat ascii 1.0\nelemeNt vertex 3\nend_header\n",
         {"keyword.ply", "header line 3", "unknown header keyword \"elemeNt\""});
  refuse("type.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty flo@t x\nend_header\n",
         {"type.ply", "header line 4", "unknown property type"});
  refuse("float-count.ply",
         head + "element face 1\nproperty list float int vertex_indices\nend_header\n",
         {"float-count.ply", "header line 8", "integer type"});
  refuse("float-index.ply",
         head + "element face 1\nproperty list uchar float vertex_indices\nend_header\n",
         {"float-index.ply", "header line 7", "vertex indices need an integer type"});
  refuse("orphan.ply", "ply\nformat ascii 1.0\nproperty float x\nend_header\n",
         {"orphan.ply", "header line 3", "before any element"});
  refuse("two-vertex.ply",
         "ply\nformat ascii 1.0\nelement vertex 1\n" + xyz + "element vertex 1\n" + xyz +
             "end_header\n0 0 0\n1 0 0\n",
         {"two-vertex.ply", "header line 7", "a second \"vertex\" element"});
  refuse("no-vertex.ply", "ply\nformat ascii 1.0\nelement face 0\nend_header\n",
         {"no-vertex.ply", "no vertex element"});
  refuse("no-z.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n1\n",
         {"no-z.ply", "header line 3", "no x, y and z"});
  // The data.
  refuse("index.ply", kPlyHeader + "3 0 1 100000\n",
         {"index.ply", "face 0", "vertex index 100000 out of range (3 vertices)"});
  refuse("long-ascii.ply", kPlyHeader + "99999999999999999999 0 1 2\n",
         {"long-ascii.ply", "face 0", "a list of 1e+20 values in the"});
  refuse("negative.ply", kPlyHeader + "-3 0 1 2\n", {"negative.ply", "face 0", "a list of -3"});
  refuse("early.ply", kPlyHeader + "3 0 1\n", {"early.ply", "face 0", "the file ends early"});
  refuse("ends-at-header.ply", kPlyHeader.substr(0, kPlyHeader.find("0 0 0")),
         {"ends-at-header.ply", "vertex 0", "the file ends early"});
  refuse("word.ply", kPlyHeader.substr(0, kPlyHeader.find("0 1 0")) + "0 1 zero\n3 0 1 2\n",
         {"word.ply", "vertex 2", "\"zero\" is not a number"});
  refuse("fraction.ply", kPlyHeader + "3 0 1 1.5\n", {"fraction.ply", "face 0", "not an integer"});
  refuse("range.ply", kPlyHeader + "3 0 1 1e999\n", {"range.ply", "face 0", "out of range"});
  refuse("lines.ply", kPlyHeader + "2 0 1\n", {"lines.ply", "contains no triangles"});
  refuse("flat.ply", kPlyHeader + "3 0 1 1\n", {"flat.ply", "its one triangle has no area ("});
  refuse("nan.ply",
         kPlyHeader.substr(0, kPlyHeader.find("0 0 0")) + "nan 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
         {"nan.ply: vertex 0: a triangle's corner at (nan, 0, 0) is not finite in 32-bit floats"});
}

// A triangle's corner 32-bit floats cannot hold (NaN or infinite in the file, or finite there
// and beyond float's range) is refused with its place, in PLY (its vertex) and through Assimp
// (its mesh and face), rather than the triangle dropped without a word; as are glTF faces naming
// vertices past the end, which Assimp drops and reports only in its log. OBJ faces of one or
// two vertices are points and lines: dropped, the triangle kept.
TEST(MeshImport, NonFiniteVerticesAndFacesPastTheEndAreRefused) {
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
      "1 0 0\n0 1 0\n1 1 0\n";
  for (const std::string x : {"inf", "nan", "1e39"})
    refuse("x.ply", ply + x + " 0 0\n3 0 1 2\n3 1 3 2\n",
           {"x.ply", "vertex 3", "not finite in 32-bit floats"});
  refuse("x.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1e300 1 0\nf 1 2 3\nf 2 4 3\n",
         {"x.obj", "mesh 0, face 1", "not finite in 32-bit floats"});
  // The corner as the file gives it, not after the node's transform mixed it into NaNs.
  refuse("x.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 inf 0\nf 1 2 3\nf 2 4 3\n",
         {"x.obj", "mesh 0, face 1", "(1, inf, 0) is not finite in 32-bit floats"});
  // A lone triangle's NaN corner, which Assimp's join merged into another corner: the
  // triangle was refused as having no area.
  refuse("x.obj", "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n",
         {"x.obj", "mesh 0, face 0", "(nan, 1, 0) is not finite in 32-bit floats"});
  // triangleGltf's buffer with an index buffer naming vertex 60000 in its second triangle.
  const std::string gltf =
      R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
          "nodes": [{"mesh": 0}],
          "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
          "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                         "min": [0, 0, 0], "max": [1, 1, 0]},
                        {"bufferView": 1, "componentType": 5125, "count": 6, "type": "SCALAR"}],
          "bufferViews": [{"buffer": 0, "byteLength": 36},
                          {"buffer": 0, "byteOffset": 36, "byteLength": 24}],
          "buffers": [{"byteLength": 60, "uri": "data:application/octet-stream;base64,)"
      "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAEAAAACAAAAAAAAAGDqAAACAAAA\"}]}";
  refuse("past.gltf", gltf, {"past.gltf", "faces name vertices past the end of their mesh"});
  // A vertex no triangle uses may be anything (a depth sensor's mesh keeps NaN for pixels
  // without depth).
  const std::filesystem::path unused =
      plyFile("unused.ply", ply + "nan nan nan\n3 0 1 2\n3 2 1 0\n");
  EXPECT_EQ(importMeshNodes(unused).at(0).mesh.triangles.size(), 2u);
  std::filesystem::remove(unused);
  const std::filesystem::path obj =
      plyFile("lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2\nf 3\n");
  const std::vector<ImportedNode> nodes = importMeshNodes(obj);
  std::filesystem::remove(obj);
  ASSERT_EQ(nodes.size(), 1u);
  EXPECT_EQ(nodes[0].mesh.triangles.size(), 1u);
}

// A model a micrometre across comes through Assimp as the file gives it: Assimp joins vertices
// less than 1e-5 apart (absolute), and a cube scaled by 1e-8 lost corners (10 triangles, two
// "degenerate", a collapsed corner) while `info` still called it watertight.
TEST(MeshImport, TinyModelsKeepEveryVertex) {
  const std::vector<glm::vec3> corners = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                          {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const char* faces =
      "f 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
      "f 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";
  for (const float scale : {1e-8f, 3e-7f, 1e-20f, 0.5f, 1e6f}) {
    SCOPED_TRACE(scale);
    std::string obj;
    char line[96];
    for (const glm::vec3& c : corners) {
      std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", double(c.x * scale),
                    double(c.y * scale), double(c.z * scale));
      obj += line;
    }
    const std::filesystem::path file = plyFile("tiny.obj", obj + faces);
    const std::vector<ImportedNode> nodes = importMeshNodes(file);
    std::filesystem::remove(file);
    ASSERT_EQ(nodes.size(), 1u);
    const Mesh& m = nodes[0].mesh;
    EXPECT_EQ(m.triangles.size(), 12u);
    EXPECT_EQ(m.report.droppedDegenerate, 0u);
    EXPECT_TRUE(m.report.watertight);
    // The corners exactly as the file writes them (the join's scaling is by a power of two).
    std::snprintf(line, sizeof line, "%.9g", double(scale));
    const Bounds box = m.bounds();
    EXPECT_EQ(box.min, glm::vec3(0.0f));
    EXPECT_EQ(box.max, glm::vec3(std::strtof(line, nullptr)));
  }
}

// A file's material colour beyond [0, 1] is clamped (OBJ Kd 5 rendered white as before, now
// said in the docs); one that is not a number is refused with its material, where the scene
// blamed the object's colour "[nan, nan, nan]".
TEST(MeshImport, MaterialColoursAreClampedAndNaNRefused) {
  const std::filesystem::path mtl = plyFile("colour.mtl", "");
  const std::string obj =
      "mtllib " + mtl.filename().string() + "\nusemtl paint\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  std::ofstream(mtl) << "newmtl paint\nKd 5 -1 0.5\n";
  const std::filesystem::path file = plyFile("colour.obj", obj);
  const std::vector<ImportedNode> nodes = importMeshNodes(file);
  ASSERT_EQ(nodes.size(), 1u);
  ASSERT_TRUE(nodes[0].color.has_value());
  EXPECT_EQ(*nodes[0].color, glm::vec3(1.0f, 0.0f, 0.5f));
  std::ofstream(mtl) << "newmtl paint\nKd nan 0 0\n";
  test::expectError([&] { importMeshNodes(file); },
                    {file.string(), "material \"paint\"", "is not finite"});
  std::filesystem::remove(file);
  std::filesystem::remove(mtl);
}

// A path that is there but holds no file (a folder, a device) says so, not "not found".
TEST(MeshImport, APathThatIsNoFileIsNamedSo) {
  test::expectError([] { importMeshNodes("/dev/null"); },
                    {"/dev/null", "mesh file is not a regular file"});
  test::expectError([] { importMeshNodes(std::filesystem::temp_directory_path() / "."); },
                    {"mesh file is not a regular file"});
  test::expectError([] { importMeshNodes("/no/such/mesh.obj"); },
                    {"/no/such/mesh.obj", "mesh file not found"});
  // A link to itself is there but leads nowhere: its reason, not "not found".
  const std::filesystem::path loop = test::scratchPath("mesh", "loop.obj");
  std::filesystem::remove(loop);
  std::filesystem::create_symlink("loop.obj", loop);
  test::expectError([&] { importMeshNodes(loop); },
                    {loop.string(), "mesh file cannot be read: Too many levels of symbolic links"});
}

// A glTF file whose `nodes` (JSON) each draw mesh 0, one triangle (0, 0, 0), (1, 0, 0),
// (0, 1, 0).
std::string triangleGltf(const std::string& nodes) {
  std::string scene;
  for (std::size_t i = 0, n = std::count(nodes.begin(), nodes.end(), '{'); i < n; ++i)
    scene += (i ? ", " : "") + std::to_string(i);
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [)" + scene +
         R"(]}], "nodes": [)" + nodes +
         R"(],
          "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
          "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                         "min": [0, 0, 0], "max": [1, 1, 0]}],
          "bufferViews": [{"buffer": 0, "byteLength": 36}],
          "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,)"
         "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA\"}]}";
}

// A triangle moved 1e20 away collapses in floats: the error says where it went.
TEST(MeshImport, TrianglesBeyondTheFloatsReachAreNamedSo) {
  refuse("far.gltf", triangleGltf(R"({"mesh": 0, "translation": [1e20, 0, 0]})"),
         {"far.gltf", "its triangles lie 1e+20 from the origin", "at most 1e15"});
}

// Repeated node names take "#2", "#3", … but never a name the file gives another node.
TEST(MeshImport, RepeatedNodeNamesStayUnique) {
  const std::string gltf = triangleGltf(
      R"({"name": "a", "mesh": 0}, {"name": "a#2", "mesh": 0}, {"name": "a", "mesh": 0},
         {"name": "a", "mesh": 0})");
  const std::filesystem::path file = plyFile("names.gltf", gltf);
  std::vector<std::string> names;
  for (const ImportedNode& node : importMeshNodes(file)) names.push_back(node.name);
  std::filesystem::remove(file);
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"a", "a#2", "a#3", "a#4"}));
}

// A UTF-8 byte-order mark before a text model's first line (some editors write one): the model
// reads as it does without it. Assimp's OBJ reader took the mark into the first line, dropped
// that vertex and drew the face from the others, saying nothing (its STL reader drops it).
TEST(MeshImport, ATextModelAfterAByteOrderMarkReadsAsWithoutIt) {
  const std::string bom = "\xEF\xBB\xBF";
  const std::string obj = "v 5 5 5\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 2 3 4\n";
  const std::string stl =
      "solid t\nfacet normal 0 0 1\nouter loop\nvertex 5 5 5\nvertex 0 0 0\nvertex 1 0 0\n"
      "endloop\nendfacet\nendsolid t\n";
  for (const auto& [name, text] : {std::pair{"bom.obj", obj}, std::pair{"bom.stl", stl}}) {
    const std::filesystem::path plain = plyFile(std::string("plain-") + name, text),
                                marked = plyFile(name, bom + text);
    const Mesh a = importMeshNodes(plain).at(0).mesh, b = importMeshNodes(marked).at(0).mesh;
    std::filesystem::remove(plain);
    std::filesystem::remove(marked);
    EXPECT_EQ(b.positions, a.positions) << name;
    EXPECT_EQ(b.triangles, a.triangles) << name;
    EXPECT_EQ(b.bounds().max, glm::vec3(5.0f)) << name;
  }
  // The same gzipped.
  const std::filesystem::path gz = std::filesystem::temp_directory_path() /
                                   ("cutaway-bom-" + std::to_string(::getpid()) + ".obj.gz");
  gzFile out = gzopen(gz.c_str(), "wb");
  const std::string marked = bom + obj;
  ASSERT_EQ(gzwrite(out, marked.data(), unsigned(marked.size())), int(marked.size()));
  gzclose(out);
  const Mesh m = importMeshNodes(gz).at(0).mesh;
  std::filesystem::remove(gz);
  EXPECT_EQ(m.bounds().max, glm::vec3(5.0f));
}

// Gzip and binary glTF files that lie about their sizes.
TEST(MeshImport, BadGzipAndBinaryGltfFilesAreRefused) {
  // .gz files that are not gzip, or hold nothing (Assimp said "Invalid parameters passed to
  // ReadFileFromMemory()").
  refuse("plain.stl.gz", "solid x\nendsolid x\n", {"plain.stl.gz", "not a gzip file"});
  refuse("empty.stl.gz",
         std::string("\x1f\x8b\x08\x00\x00\x00\x00\x00\x00\x03\x03\x00"
                     "\x00\x00\x00\x00\x00\x00\x00\x00",
                     20),
         {"empty.stl.gz", "empty after gzip"});
  refuse("cut.stl.gz", "\x1f\x8b\x08\x00\x00\x00", {"cut.stl.gz", "gzip"});
  // A whole OBJ gzipped, then cut within its data, or only its 8-byte trailer (CRC, size)
  // taken off: zlib hands over what it inflated (half a mesh) and only records the error.
  const std::filesystem::path whole = std::filesystem::temp_directory_path() /
                                      ("cutaway-whole-" + std::to_string(::getpid()) + ".obj.gz");
  {
    gzFile gz = gzopen(whole.c_str(), "wb");
    std::string obj;
    for (int i = 0; i < 400; ++i)
      obj += "v " + std::to_string(i) + " 0 0\nv " + std::to_string(i) + " 1 0\nv " +
             std::to_string(i) + " 0 1\nf " + std::to_string(3 * i + 1) + " " +
             std::to_string(3 * i + 2) + " " + std::to_string(3 * i + 3) + "\n";
    ASSERT_EQ(gzwrite(gz, obj.data(), unsigned(obj.size())), int(obj.size()));
    gzclose(gz);
  }
  std::ifstream in(whole, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), {});
  std::filesystem::remove(whole);
  refuse("half.obj.gz", bytes.substr(0, bytes.size() / 2), {"half.obj.gz", "truncated gzip"});
  refuse("no-trailer.obj.gz", bytes.substr(0, bytes.size() - 8),
         {"no-trailer.obj.gz", "truncated gzip"});
  // A binary glTF whose JSON chunk claims 1.2 GB (Assimp allocated it; found by fuzzing), one
  // whose header claims more than the file, and one cut inside its chunk table (after an empty
  // first chunk).
  const auto header = [](std::uint32_t length) {
    std::string h("glTF\x02\x00\x00\x00", 8);
    for (int i = 0; i < 4; ++i) h += char(length >> (8 * i) & 0xff);
    return h;
  };
  refuse("chunk.glb", header(36) + std::string("\xdc\x01\x01\x4aJSON{}", 10) + std::string(14, ' '),
         {"chunk.glb", "chunk at byte 12", "claims 1241579996 bytes"});
  refuse("length.glb", header(65535), {"length.glb", "claims 65535 bytes, the file has 12"});
  refuse("cut.glb", header(22) + std::string("\0\0\0\0JSON\x04\x04", 10),
         {"cut.glb", "byte 20", "ends early"});
  // A header claiming 1 byte in a 541-byte file: the chunk table went unchecked and Assimp
  // took 1.8 GB and 12 s for the JSON chunk's claimed length (fuzzing).
  refuse("short.glb", header(1) + std::string("\0\0\0\x6eJSON{}", 10) + std::string(519, ' '),
         {"short.glb", "header", "claims 1 bytes, less than its 20-byte header"});
}
