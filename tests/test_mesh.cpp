#include <gtest/gtest.h>

#include <unistd.h>
#include <algorithm>
#include <cstring>
#include <iterator>

#include <filesystem>
#include <fstream>
#include <string>

#include "cutaway/geometry/mesh.hpp"
#include "cutaway/io/mesh_import.hpp"
#include "expect_error.hpp"

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

// The lists in a PLY's data against the bytes left: Assimp allocated what a face's count
// claimed (34 GB for an ASCII "9999…3"; fuzzing). Binary files of either byte order, with
// normals and an element Assimp does not read, still load.
TEST(MeshImport, PlyListsLongerThanTheFileAreRefused) {
  refuse("long-ascii.ply", kPlyHeader + "99999999999999999999 0 1 2\n",
         {"long-ascii.ply", "face 0", "a list of 1e+20 values in the"});
  refuse("negative.ply", kPlyHeader + "-3 0 1 2\n", {"negative.ply", "face 0", "a list of -3"});
  // A property of a type Assimp does not know: Assimp ends the element's layout there and still
  // reads the faces (fuzzing).
  refuse("unknown-type.ply",
         "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
         "property flo@t z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
         "0 0 0\n1 0 0\n0 1 0\n99999999999 0 1 2\n",
         {"unknown-type.ply", "face 0", "a list of 99999999999 values"});
  // A number beyond 64 bits: Assimp's parser stopped inside it and read its other digits as the
  // next word, a list's count (fuzzing).
  refuse("long-number.ply",
         kPlyHeader.substr(0, kPlyHeader.find("0 0 0")) +
             "133333333333333333333333 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
         {"long-number.ply", "vertex 0", "a number of 24 digits, beyond 64 bits"});
  // Data that ends early: Assimp parses its last line again for every instance left, so that
  // line's first word became the face's count (fuzzing).
  refuse("stale.ply",
         "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
         "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
         "0 0 0\n99999999999 1 0\n",
         {"stale.ply", "face 0", "a list of 99999999999 values"});
  // Lines ended by carriage returns alone, as Assimp cuts them too: the tetrahedron loads.
  {
    std::ifstream in(CUTAWAY_TEST_DATA "/fuzz/mesh-ply/valid-tetra.ply", std::ios::binary);
    std::string text{std::istreambuf_iterator<char>(in), {}};
    std::replace(text.begin(), text.end(), '\n', '\r');
    const std::filesystem::path file = plyFile("cr.ply", text);
    const auto nodes = importMeshNodes(file);
    std::filesystem::remove(file);
    ASSERT_EQ(nodes.size(), 1u);
    EXPECT_EQ(nodes[0].mesh.triangles.size(), 4u);
  }
  // Binary: four vertices of x, y, z and normals, an edge, four faces; little- and big-endian.
  const auto binary = [](bool big, std::uint32_t secondCount) {
    std::string out = std::string("ply\nformat binary_") + (big ? "big" : "little") +
                      "_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                      "property float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
                      "element edge 1\nproperty int vertex1\nproperty int vertex2\n"
                      "element face 4\nproperty list uint int vertex_indices\nend_header\n";
    const auto put = [&](std::uint32_t v) {
      for (int b = 0; b < 4; ++b) out += char(v >> (8 * (big ? 3 - b : b)) & 0xFF);
    };
    const float corners[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (const auto& c : corners)
      for (int k = 0; k < 6; ++k) {
        const float f = k < 3 ? c[k] : 0.0f;
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
    const std::filesystem::path file = plyFile(big ? "big.ply" : "little.ply", binary(big, 3));
    const auto nodes = importMeshNodes(file);
    std::filesystem::remove(file);
    ASSERT_EQ(nodes.size(), 1u);
    EXPECT_EQ(nodes[0].mesh.triangles.size(), 4u) << big;
  }
  refuse("long-binary.ply", binary(false, 0xFFFFFFF0u),
         {"long-binary.ply", "face 1", "a list of 4294967280 values in the 44 bytes left"});
  refuse("long-big.ply", binary(true, 1000u), {"long-big.ply", "face 1", "a list of 1000 values"});
}

// Issue 16's crashes and hangs in Assimp's PLY path and its gzip messages: each a one-line
// error naming the file.
TEST(MeshImport, BadPlyFilesAreRefusedWithoutCrashingOrHanging) {
  // A face index beyond the vertices (crashed in Assimp's post-processing and in our normals).
  refuse("index.ply", kPlyHeader + "3 0 1 100000\n", {"index.ply"});
  // The first two header lines alone (Assimp's reader looped forever).
  refuse("header.ply", "ply\nformat ascii 1.0\n", {"header.ply", "end_header"});
  // A count no file of this size can hold (Assimp allocated it).
  refuse("count.ply",
         "ply\nformat binary_little_endian 1.0\nelement vertex 2147483648\nproperty float x\n"
         "end_header\n",
         {"count.ply", "header line 3", "2147483648"});
  // A count beyond every integer type: the message quotes it as written (converting it to an
  // integer was undefined; fuzzing).
  refuse("huge.ply",
         "ply\nformat binary_little_endian 1.0\nelemeNt vertex 42949667294949667294\nend_header\n",
         {"huge.ply", "header line 3", "claims 42949667294949667294 vertex elements"});
  refuse("magic.ply", "solid x\nendsolid x\n", {"magic.ply", "not a PLY"});
  // Keywords in another case, "end_header" only inside another line (Assimp hung; fuzzing).
  refuse("case.ply",
         "ply\nformat binary_little_endian 1.0\nelemeNt vertex 4294967294\npropend_headererty x\n",
         {"case.ply", "header line 3", "4294967294"});
  refuse("inline.ply", "ply\nformat ascii 1.0\ncomment end_header\n",
         {"inline.ply", "end_header line"});
  // "end_header" in another case ends nothing for Assimp, which read on and looped at the end
  // of the file (fuzzing).
  refuse("upper.ply", "ply\nformat ascii 1.0\nend_headEr\n", {"upper.ply", "end_header line"});
  // An element whose name Assimp does not know takes its count from the name's digits.
  refuse("digits.ply",
         "ply\nformat ascii 1.0\nelement 66666666666666face 8\nproperty float x\nend_header\n0\n",
         {"digits.ply", "header line 3", "an element named \"66666666666666face\""});
  // Nor does "end_header" followed by a vertical tab (Assimp hung; fuzzing).
  refuse("vtab.ply", kPlyHeader.substr(0, kPlyHeader.find("end_header")) + "end_header\v\n0 0 0\n",
         {"vtab.ply", "end_header line"});
  // A file that ends at "end_header" with no line end: after an unknown header line longer
  // than it, Assimp read that line's tail with it, never matched it and looped (fuzzing).
  refuse("ends-at-header.ply",
         kPlyHeader.substr(0, kPlyHeader.find("end_header")) + "c xxxxxxxxx\nc\nend_header",
         {"ends-at-header.ply", "the file ends at end_header"});
  // A second vertex or face element: Assimp sized its arrays by the first and wrote the second
  // past their end (valgrind: invalid writes; fuzzing: ASan's heap checks failed later).
  const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
  const std::string indices = "property list uchar int vertex_indices\n";
  refuse("two-vertex.ply",
         "ply\nformat ascii 1.0\nelement vertex 2\n" + xyz + "element vertex 6\n" + xyz +
             "end_header\n0 0 0\n1 0 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 1\n2 2 2\n",
         {"two-vertex.ply", "header line 7", "a second vertex element"});
  refuse("two-face.ply",
         "ply\nformat ascii 1.0\nelement vertex 3\n" + xyz + "element face 1\n" + indices +
             "element Face 5\n" + indices + "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
         {"two-face.ply", "header line 9", "a second face element"});
  refuse("strips-and-faces.ply",
         "ply\nformat ascii 1.0\nelement vertex 3\n" + xyz + "element tristrips 1\n" + indices +
             "element face 5\n" + indices + "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
         {"strips-and-faces.ply", "header line 9", "a second face element"});
  // Faces cut off by the end of the file after a garbled header line: Assimp's reader
  // returns them empty, called polygons, and its triangulation aborted on an assertion
  // (fuzzing; tests/data/fuzz/mesh-ply/empty-faces-called-polygons.ply).
  refuse("empty-faces.ply",
         "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
         "property float z\nelementrty float y\nproperty float z\nelement face 4\n"
         "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 2 3\n",
         {"empty-faces.ply", "face 0", "a face without vertices"});
  // .gz files that are not gzip, or hold nothing (Assimp said "Invalid parameters passed to
  // ReadFileFromMemory()").
  refuse("plain.stl.gz", "solid x\nendsolid x\n", {"plain.stl.gz", "not a gzip file"});
  refuse("empty.stl.gz",
         std::string("\x1f\x8b\x08\x00\x00\x00\x00\x00\x00\x03\x03\x00"
                     "\x00\x00\x00\x00\x00\x00\x00\x00",
                     20),
         {"empty.stl.gz", "empty after gzip"});
  refuse("cut.stl.gz", "\x1f\x8b\x08\x00\x00\x00", {"cut.stl.gz", "gzip"});
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
  // The good file still loads.
  const std::filesystem::path good = plyFile("good.ply", kPlyHeader + "3 0 1 2\n");
  EXPECT_EQ(importMeshNodes(good).front().mesh.triangles.size(), 1u);
  std::filesystem::remove(good);
}
