// Konev18 §§5–7 on the CPU against hand-worked cases (eqs. 4–16, the shaft wedge), the
// network operations (sharp bends, cut intersections, junction shafts, meshes), and the
// rendered frame: the pipes' AOVs, and the §9 interference fix on two crossing pipes; the
// generated benchmark city of Table 1.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "cutaway/cutters/terrain_opening.hpp"
#include "cutaway/geometry/pipe_network.hpp"
#include "cutaway/render/renderer.hpp"
#include "cutaway/scene/benchmark_city.hpp"
#include "cutaway/scene/scene.hpp"
#include "gl_test_context.hpp"
#include "mismatches.hpp"
#include "render_aovs.hpp"
#include "run_command.hpp"

using namespace cutaway;
using test::aov;
using test::renderAovs;

namespace {

const std::string kSource = CUTAWAY_SOURCE_DIR;

void expectVec(const glm::vec3& a, const glm::vec3& b, float eps = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
  EXPECT_NEAR(a.z, b.z, eps);
}

// Signed volume by the divergence theorem: positive for outward-facing closed meshes.
float volume(const Mesh& m) {
  double v = 0;
  for (const auto& t : m.triangles)
    v += glm::dot(m.positions[t.x], glm::cross(m.positions[t.y], m.positions[t.z])) / 6.0;
  return float(v);
}

}  // namespace

TEST(PipeBillboard, UpVectorsFollowEquations4To7) {
  // Along +x seen from (0, 0, 10): v̂_0 = (0, 0, −1), û_0 = v̂_0 × n̂ = (0, −1, 0) (eq. 4); at
  // the far end v̂ = (1, 0, −1)/√2 gives the same direction (eq. 6).
  const auto u = billboardUp({{0, 0, 0}, {10, 0, 0}}, {0, 0, 10});
  expectVec(u[0], {0, -1, 0});
  expectVec(u[1], {0, -1, 0});
  // A right-angle bend seen from above: the middle node uses the mean of (1,0,0) and
  // (0,0,−1) (eq. 5); û = (0,−1,0) × (1,0,−1)/√2 = (1, 0, 1)/√2.
  const auto b = billboardUp({{0, 0, 0}, {1, 0, 0}, {1, 0, -1}}, {1, 10, 0});
  const float h = std::sqrt(0.5f);
  expectVec(b[1], {h, 0, h});
  // Orthographic: the same v̂ at every node.
  const auto o = billboardUpOrthographic({{0, 0, 0}, {0, 0, -5}}, {0, -1, 0});
  expectVec(o[0], {1, 0, 0});  // (0,−1,0) × (0,0,−1)
  expectVec(o[1], {1, 0, 0});
}

TEST(PipeBillboard, FaceAndTubeNormalsFollowEquations8To11) {
  // û = (0, −1, 0) at both ends of a quad along +x: F_a = û × n̂ = (0, 0, 1), towards the eye.
  const glm::vec3 u(0, -1, 0), n(1, 0, 0);
  const glm::vec3 f = billboardFaceNormal(u, u, n);
  expectVec(f, {0, 0, 1});
  // Eq. 11: on the axis N = 0 and N_f = F_a; at the û edge N = û and N_f = (û + F)/|û + F|.
  expectVec(tubeNormal(u, u, 0.5f, 0.0f, f), f);
  const float h = std::sqrt(0.5f);
  expectVec(tubeNormal(u, u, 0.5f, 1.0f, f), {0, -h, h});
  expectVec(tubeNormal(u, u, 0.5f, -1.0f, f), {0, h, h});
  // Twisted ends: F uses the mean of the ends' û.
  expectVec(billboardFaceNormal({0, -1, 0}, {0, 0, -1}, n), glm::normalize(glm::vec3(0, -1, 1)));
}

TEST(PipeProxies, TrianglesFollowEquations12To14) {
  // r_in / r_out = 0.8: d_in = 0.4, d_out = 0.5.
  EXPECT_FLOAT_EQ(proxyTriangleDistance({0.5f, 0.95f}), 0.45f);  // eq. 12
  EXPECT_EQ(proxyTriangle(1, 0.45f, 0.8f, 1.0f), ProxyAction::CutSurface);
  EXPECT_EQ(proxyTriangle(2, 0.45f, 0.8f, 1.0f), ProxyAction::Discard);
  EXPECT_EQ(proxyTriangle(1, 0.3f, 0.8f, 1.0f), ProxyAction::Discard);
  EXPECT_EQ(proxyTriangle(2, 0.3f, 0.8f, 1.0f), ProxyAction::MarkInside);
  for (int pass : {1, 2}) EXPECT_EQ(proxyTriangle(pass, 0.6f, 0.8f, 1.0f), ProxyAction::Discard);
}

TEST(PipeProxies, QuadsFollowEquations15And16) {
  // r_in / r_out = 0.8: each wall is t = 0.1 of the diameter.
  EXPECT_EQ(proxyQuad(1, 0.05f, 0.8f, 1.0f), ProxyAction::CutSurface);
  EXPECT_EQ(proxyQuad(1, 0.95f, 0.8f, 1.0f), ProxyAction::CutSurface);
  EXPECT_EQ(proxyQuad(1, 0.5f, 0.8f, 1.0f), ProxyAction::Discard);
  EXPECT_EQ(proxyQuad(2, 0.5f, 0.8f, 1.0f), ProxyAction::MarkInside);
  EXPECT_EQ(proxyQuad(2, 0.05f, 0.8f, 1.0f), ProxyAction::Discard);
  EXPECT_EQ(proxyQuad(2, 0.89f, 0.8f, 1.0f), ProxyAction::MarkInside);
}

TEST(ShaftWedge, OpensTowardsTheViewerIgnoringHeights) {
  EXPECT_TRUE(shaftWedgeRemoves({1, 0, 0}, {1, 5, 0}, 0.3f));     // facing, seen from above
  EXPECT_FALSE(shaftWedgeRemoves({0, 0, 1}, {1, 5, 0}, 0.3f));    // side: n·v = 0
  EXPECT_FALSE(shaftWedgeRemoves({-1, 0, 0}, {1, 0, 0}, 0.3f));   // back
  EXPECT_TRUE(shaftWedgeRemoves({1, 0, 1}, {1, -3, 0}, 0.3f));    // cos 45° > 0.3
  EXPECT_FALSE(shaftWedgeRemoves({1, 0, 1}, {1, -3, 0}, 0.75f));  // the narrower wedge keeps it
  EXPECT_FALSE(shaftWedgeRemoves({0, 1, 0}, {1, 1, 0}, 0.3f));    // a floor has no radial part
}

TEST(PipeNetworkOps, SharpBendsSplitWithJoints) {
  PipeNetwork net;
  net.pipes.push_back({.nodes = {{0, 0, 0}, {10, 0, 0}, {10, 0, -10}, {11, 0, -20}},
                       .radius = 0.5f,
                       .cut = glm::vec2(5, 15)});
  const auto joints = splitSharpBends(net, 60.0f);
  ASSERT_EQ(joints.size(), 1u);  // the right angle; the 5.7° turn after it stays
  expectVec(joints[0].position, {10, 0, 0});
  ASSERT_EQ(net.pipes.size(), 2u);
  EXPECT_EQ(net.pipes[0].nodes.size(), 2u);
  EXPECT_EQ(net.pipes[1].nodes.size(), 3u);
  ASSERT_TRUE(net.pipes[0].cut && net.pipes[1].cut);
  EXPECT_FLOAT_EQ(net.pipes[0].cut->x, 5.0f);
  EXPECT_FLOAT_EQ(net.pipes[0].cut->y, 10.0f);
  EXPECT_FLOAT_EQ(net.pipes[1].cut->x, 0.0f);
  EXPECT_FLOAT_EQ(net.pipes[1].cut->y, 5.0f);
}

// A zig-zag of 20,000 right angles splits into 19,999 two-node pieces, each holding its own
// nodes only (each once held room for all of them: 5 GB for a 330 KB scene file).
TEST(PipeNetworkOps, AZigZagSplitsIntoPiecesThatHoldTheirOwnNodes) {
  PipeNetwork net;
  Pipe zigzag{.radius = 0.1f};
  for (int i = 0; i < 20000; ++i) zigzag.nodes.push_back({float(i / 2 + i % 2), 0, float(i / 2)});
  net.pipes.push_back(zigzag);
  EXPECT_EQ(splitSharpBends(net, 60.0f).size(), 19998u);
  ASSERT_EQ(net.pipes.size(), 19999u);
  std::size_t held = 0;
  for (const Pipe& p : net.pipes) EXPECT_EQ(p.nodes.size(), 2u), held += p.nodes.capacity();
  EXPECT_LE(held, 2u * 2u * net.pipes.size());
}

TEST(PipeNetworkOps, CrossingCutsKeepTheLargerPipe) {
  PipeNetwork net;
  net.pipes.push_back(
      {.nodes = {{0, -2, 0}, {20, -2, 0}}, .radius = 0.5f, .cut = glm::vec2(2, 18)});
  net.pipes.push_back(
      {.nodes = {{10, -2.5f, 10}, {10, -2.5f, -10}}, .radius = 0.3f, .cut = glm::vec2(1, 19)});
  net.pipes.push_back(
      {.nodes = {{0, -2, 50}, {20, -2, 50}}, .radius = 0.3f, .cut = glm::vec2(2, 18)});
  EXPECT_EQ(resolveCutIntersections(net, 0.2f), 1);
  EXPECT_EQ(*net.pipes[0].cut, glm::vec2(2, 18));  // the larger keeps its cut
  EXPECT_EQ(*net.pipes[2].cut, glm::vec2(2, 18));  // far away: untouched
  // The smaller's stretch now stops 0.5 + 0.3 + 0.2 before the crossing at arc length 10.
  ASSERT_TRUE(net.pipes[1].cut);
  EXPECT_FLOAT_EQ(net.pipes[1].cut->x, 1.0f);
  EXPECT_NEAR(net.pipes[1].cut->y, 9.0f, 1e-4f);
}

TEST(PipeNetworkOps, ShaftsAtJunctionsReachTheGround) {
  PipeNetwork net;
  for (const glm::vec3& end : {glm::vec3(-10, -3, 0), glm::vec3(10, -3, 0), glm::vec3(0, -3, -10)})
    net.pipes.push_back({.nodes = {{0, -2.5f, 0}, end}, .radius = 0.4f});
  const auto ground = [](glm::vec2 xz) { return 1.0f + 0.1f * xz.x; };
  addJunctionShafts(net, {.radius = 0.7f, .wallThickness = 0.1f, .ends = false}, ground);
  ASSERT_EQ(net.shafts.size(), 1u);
  const Shaft& s = net.shafts[0];
  expectVec(s.bottom, {0, -2.9f, 0});  // under the lowest pipe: −2.5 − 0.4
  EXPECT_FLOAT_EQ(s.top, 1.0f);
  EXPECT_FLOAT_EQ(s.radius, 0.7f);
  net.shafts.clear();
  addJunctionShafts(net, {.ends = true}, ground);
  EXPECT_EQ(net.shafts.size(), 4u);  // and at the three open ends
}

TEST(PipeNetworkOps, PipesOpenIntoTheShaftsTheyReach) {
  PipeNetwork net;
  net.pipes.push_back({.nodes = {{0, -2, 0}, {5, -2, 0}}, .radius = 0.3f, .cut = glm::vec2(0.5f, 3.0f)});
  net.pipes.push_back({.nodes = {{-5, -2, 0}, {-2, -2, 0}, {0, -2, 0}}, .radius = 0.3f});
  net.pipes.push_back({.nodes = {{0, -2, -5}, {0, -2, 0}, {0, -2, 5}}, .radius = 0.3f});  // through
  net.pipes.push_back({.nodes = {{0.1f, -2, 0}, {0.3f, -2, 0}}, .radius = 0.1f});  // wholly inside
  net.shafts.push_back({.bottom = {0, -2.5f, 0}, .top = 0, .radius = 1.0f, .wallThickness = 0.1f});
  EXPECT_EQ(trimAtShafts(net), 2);
  // Ends on the inner wall (radius 0.9); the cut keeps its place along the pipe.
  expectVec(net.pipes[0].nodes.front(), {0.9f, -2, 0});
  ASSERT_TRUE(net.pipes[0].cut);
  EXPECT_NEAR(net.pipes[0].cut->x, 0.0f, 1e-5f);
  EXPECT_NEAR(net.pipes[0].cut->y, 2.1f, 1e-5f);
  ASSERT_EQ(net.pipes[1].nodes.size(), 3u);
  expectVec(net.pipes[1].nodes.back(), {-0.9f, -2, 0});
  EXPECT_EQ(net.pipes[2].nodes.size(), 3u);
  expectVec(net.pipes[3].nodes.front(), {0.1f, -2, 0});
  // A shaft elsewhere in height leaves the ends alone.
  net.pipes[0].nodes.front() = {0, -2, 0};
  net.shafts[0].bottom.y = -10, net.shafts[0].top = -5;
  EXPECT_EQ(trimAtShafts(net), 0);
}

TEST(PipeNetworkOps, MeshesAreClosedAndOutward) {
  PipeNetwork net;
  net.pipes.push_back({.nodes = {{0, 0, 0}, {10, 0, 0}, {14, 0, -3}}, .radius = 0.5f});
  Mesh pipes = pipeMesh(net, 24);
  analyzeTopology(pipes);
  EXPECT_TRUE(pipes.report.watertight);
  const float r = 0.5f, length = 15.0f;
  EXPECT_NEAR(volume(pipes), glm::pi<float>() * r * r * length, 0.08f * length);
  Mesh joint = jointMesh({{{1, 2, 3}, 2.0f}}, 24, 48);
  analyzeTopology(joint);
  EXPECT_TRUE(joint.report.watertight);
  EXPECT_NEAR(volume(joint), 4.0f / 3.0f * glm::pi<float>() * 8.0f, 0.8f);
  // Shafts: both cylinders with outward normals (§7), the inner one with the floor.
  net.shafts.push_back({.bottom = {0, -3, 0}, .top = 0.0f, .radius = 1.0f, .wallThickness = 0.2f});
  const Mesh outer = shaftMesh(net, false, 16), inner = shaftMesh(net, true, 16);
  for (std::size_t i = 0; i < outer.positions.size(); ++i)
    EXPECT_GT(
        glm::dot(outer.normals[i], outer.positions[i] - glm::vec3(0, outer.positions[i].y, 0)),
        0.0f);
  EXPECT_NEAR(glm::length(glm::vec2(inner.positions[0].x, inner.positions[0].z)), 0.8f, 1e-5f);
}

TEST(BenchmarkCity, HasTable1sSizesAndAGroundFacingUp) {
  const Scene city = benchmarkCity({});
  ASSERT_EQ(city.networks.size(), 1u);
  const PipeNetwork& net = city.networks[0];
  EXPECT_EQ(net.pipes.size(), 1190u);
  EXPECT_EQ(net.shafts.size(), 1156u);
  std::size_t nodes = 0;
  for (const Pipe& p : net.pipes) nodes += p.nodes.size();
  EXPECT_NEAR(double(nodes) / double(net.pipes.size()), 4.6, 0.1);
  const Mesh& ground = *city.find("terrain")->mesh;
  // A grid whose triangles are implied, not stored.
  ASSERT_TRUE(ground.impliedTriangles());
  EXPECT_NEAR(double(ground.triangleCount()), 2.9e6, 0.01 * 2.9e6);
  // Every triangle is a front face seen from above, as its vertex normals say.
  std::size_t downward = 0;
  for (std::size_t i = 0; i < ground.triangleCount(); ++i) {
    const glm::uvec3 t = ground.triangle(i);
    const glm::vec3 a = ground.positions[t.x], b = ground.positions[t.y], c = ground.positions[t.z];
    const glm::vec3 face = glm::cross(b - a, c - a);
    downward += face.y <= 0.0f || glm::dot(face, ground.normals[t.x]) <= 0.0f;
  }
  EXPECT_EQ(downward, 0u);
  // The shafts reach from their pipe up to the ground; the opening follows every pipe.
  for (const Shaft& s : net.shafts) ASSERT_GT(s.top, s.bottom.y);
  ASSERT_TRUE(city.cutters.find<TerrainOpeningOptions>());
  EXPECT_EQ(city.cutters.find<TerrainOpeningOptions>()->lines.size(), net.pipes.size());
}

TEST(PipeRendering, StreetShowsEveryPipeClass) {
  const Scene scene = loadScene(kSource + "/examples/pipes-street.json");
  const auto aovs = renderAovs(scene);
  const FloatImage &stencil = aov(aovs, "pipeStencil"), &cls = aov(aovs, "pipeClass");
  int stencilCounts[4] = {0, 0, 0, 0}, classCounts[5] = {0, 0, 0, 0, 0};
  for (int y = 0; y < cls.height; ++y)
    for (int x = 0; x < cls.width; ++x) {
      const float s = stencil.at(x, y)[0];
      ASSERT_TRUE(s == 0.0f || s == 1.0f || s == 2.0f || s == 4.0f) << s;
      ++stencilCounts[std::min(int(s), 3)];
      ++classCounts[int(std::lround(cls.at(x, y)[0] * 4.0f))];
    }
  EXPECT_GT(stencilCounts[1], 100);  // proxy pass 2: insides
  EXPECT_GT(stencilCounts[2], 50);   // proxy pass 1: cut surfaces
  for (int c = 1; c <= 4; ++c) EXPECT_GT(classCounts[c], 30) << "class " << c;
}

TEST(PipeRendering, CrossingPipeOverAnOpeningStaysOutside) {
  // Konev18 §9: B is cut open under A; A (uncut) passes over B's inside area. Every pixel of
  // A's billboard must be A's outside, not B's inside.
  const std::string text = R"({"resolution": [200, 150], "samples": 1,
    "style": {"name": "blinn-phong", "lines": false},
    "camera": {"eye": [0, 12, 6], "target": [0, -2, 0], "fov": 40},
    "objects": [{"name": "floor", "file": ")" +
                           kSource + R"(/examples/data/tile.obj",
                 "transform": {"translate": [-20, -6, 20], "scale": [40, 1, 40]}}],
    "networks": [{"name": "n", "wallThickness": 0.1,
      "pipes": [{"lines": [[[-10, -1, 0], [10, -1, 0]]], "radius": 0.4},
                {"lines": [[[0, -3, -10], [0, -3, 10]]], "radius": 1.0}]}]})";
  Scene scene = parseScene(text, "crossing.json", kSource);
  scene.networks[0].pipes[1].cut = glm::vec2(2, 18);
  const auto aovs = renderAovs(scene);
  const FloatImage &cls = aov(aovs, "pipeClass"), &pos = aov(aovs, "position"),
                   &stencil = aov(aovs, "pipeStencil");
  int onA = 0, overOpening = 0;
  for (int y = 0; y < cls.height; ++y)
    for (int x = 0; x < cls.width; ++x) {
      const glm::vec3 p = glm::make_vec3(pos.at(x, y));
      if (cls.at(x, y)[0] < 0.1f || std::abs(p.y + 1.0f) > 0.45f || std::abs(p.z) > 0.45f) continue;
      ++onA;
      overOpening += stencil.at(x, y)[0] == 1.0f;
      EXPECT_NEAR(cls.at(x, y)[0], 0.25f, 0.01f) << x << "," << y;  // an 8-bit class
    }
  EXPECT_GT(onA, 200);
  EXPECT_GT(overOpening, 20);  // the case exists: A crosses B's marked inside
}

TEST(PipeRendering, RadiusScaleAppliesWithoutANewRenderer) {
  // Konev18 §5: the billboards are built from the node buffer every frame, so a radius scale
  // set between two frames of one renderer widens the pipe on screen. Looking straight down
  // with an orthographic camera 20 units high on 200 rows, a pipe of radius r·scale along x
  // covers 2·r·scale·10 rows.
  const std::string text = R"({"resolution": [200, 200], "samples": 1,
    "style": {"name": "blinn-phong", "lines": false},
    "camera": {"projection": "orthographic", "eye": [0, 10, 0.001], "target": [0, 0, 0],
               "up": [0, 0, -1], "height": 20, "fit": false, "near": 1, "far": 30},
    "networks": [{"name": "n", "wallThickness": 0.05,
                  "pipes": [{"lines": [[[-20, 0, 0], [20, 0, 0]]], "radius": 0.5}]}]})";
  Scene scene = parseScene(text, "radius.json", kSource);
  Renderer renderer(scene, test::glContext().info());
  const auto rowsCovered = [&] {
    renderer.render();
    const auto aovs = renderer.readAovs();
    const FloatImage& cls = aov(aovs, "pipeClass");
    int rows = 0;
    for (int y = 0; y < cls.height; ++y) rows += cls.at(cls.width / 2, y)[0] > 0.1f;
    return rows;
  };
  EXPECT_NEAR(rowsCovered(), 10, 1);
  scene.networks[0].radiusScale = 2.5f;
  EXPECT_NEAR(rowsCovered(), 25, 1);
}

TEST(PipeRendering, BillboardsCoverWhatTheMeshedPipesCover) {
  // Eqs. 4–7 on the GPU against the tessellated tubes of the same network: a pipe with two
  // bends (one joined by the twisted quads, one split with a joint) seen in perspective
  // covers the same pixels either way, up to the rim pixels (a billboard is 2r wide across the
  // view ray; the tube's silhouette is narrower by r²/d, under a pixel here) and the meshed
  // pipe's rounded ends (6% of the pixels when this was written).
  const std::string text = R"({"resolution": [240, 180], "samples": 1,
    "style": {"name": "blinn-phong", "lines": false},
    "camera": {"eye": [2, 9, 12], "target": [2, 0, -1], "fov": 45},
    "networks": [{"name": "n", "wallThickness": 0.1, "maxBend": 60,
                  "pipes": [{"lines": [[[-6, 0, 0], [0, 0, 0], [4, 0, -3], [4, 1, -8]]],
                             "radius": 0.5}]}]})";
  const auto coverage = [&](const char* mode) {
    std::string scene = text;
    scene.replace(scene.find("\"name\": \"n\""), 11,
                  std::string("\"name\": \"n\", \"mode\": \"") + mode + "\"");
    const auto aovs = renderAovs(parseScene(scene, "cover.json", kSource));
    const FloatImage& id = aov(aovs, "objectId");
    std::vector<bool> covered;
    for (float v : id.data) covered.push_back(v >= 0.0f);
    return covered;
  };
  const std::vector<bool> billboards = coverage("billboards"), mesh = coverage("mesh");
  int both = 0, either = 0;
  for (std::size_t i = 0; i < mesh.size(); ++i)
    both += billboards[i] && mesh[i], either += billboards[i] || mesh[i];
  EXPECT_GT(both, 2000);
  EXPECT_GT(double(both) / either, 0.93) << both << " of " << either;
}

// Eqs. 8–11 on the GPU: a straight pipe seen orthographically (û the same at both nodes, so
// the quad is a flat rectangle and `across` is the position's offset along û over r), cut
// open over its middle: each outside pixel's normal is tubeNormal (N_f = (N + F_a)/|N + F_a|),
// each inside pixel's the inverted mean (F_a − N)/|F_a − N| (§6), against the positions the
// same frame dumped; and Fig. 11's discard of the upper half along the cut.
TEST(PipeRendering, BillboardNormalsFollowEquations8To11) {
  const glm::vec3 p0(-4, 0, 0), p1(4, 0, 0), eye(1, 3, 8);
  const float r = 0.5f;
  const Scene scene = parseScene(R"({"resolution": [200, 150], "samples": 1,
    "style": {"name": "blinn-phong", "lines": false},
    "camera": {"projection": "orthographic", "height": 5, "eye": [1, 3, 8], "target": [0, 0, 0]},
    "networks": [{"name": "n", "wallThickness": 0.1, "cut": {"from": 0.3, "to": 0.7},
                  "pipes": [{"lines": [[[-4, 0, 0], [4, 0, 0]]], "radius": 0.5}]}]})",
                                 "normals.json", kSource);
  const auto aovs = renderAovs(scene);
  const FloatImage &cls = aov(aovs, "pipeClass"), &position = aov(aovs, "position"),
                   &normal = aov(aovs, "normal");
  const glm::vec3 n = glm::normalize(p1 - p0);
  const glm::vec3 u = billboardUpOrthographic({p0, p1}, glm::vec3(0) - eye)[0];
  const glm::vec3 face = billboardFaceNormal(u, u, n);
  int outside = 0, inside = 0, wrong = 0, upperOutside = 0, lowerOutside = 0, upperInside = 0;
  double worst = 0.0;
  for (int y = 0; y < cls.height; ++y)
    for (int x = 0; x < cls.width; ++x) {
      const long c = std::lround(cls.at(x, y)[0] * 4.0f);  // 8-bit quarters
      if (c != 1 && c != 2) continue;                      // the outside and the inner wall
      const glm::vec3 p = glm::make_vec3(position.at(x, y));
      const float along = glm::dot(p - p0, n) / glm::length(p1 - p0);
      const float across = glm::dot(p - p0, u) / r;
      if (along < 0.02f || along > 0.98f || std::abs(across) > 0.98f) continue;  // rims
      const glm::vec3 expected =
          c == 1 ? tubeNormal(u, u, along, across, face) : glm::normalize(face - across * u);
      const double error = glm::length(glm::make_vec3(normal.at(x, y)) - expected);
      worst = std::max(worst, error);
      wrong += error > 2e-3;
      (c == 1 ? outside : inside) += 1;
      // Fig. 11: along the cut the billboard's upper half (above the axis, +y) is discarded,
      // so the outside shows only below the axis there and the inside above it.
      if (along > 0.33f && along < 0.67f) {
        const bool upper = glm::dot(p - glm::mix(p0, p1, along), glm::vec3(0, 1, 0)) > 1e-3f;
        if (c == 1) upper ? ++upperOutside : ++lowerOutside;
        if (c == 2 && upper) ++upperInside;
      }
    }
  EXPECT_GT(outside, 1000);
  EXPECT_GT(inside, 200);
  EXPECT_EQ(wrong, 0) << "worst " << worst;  // the normal AOV holds half floats
  EXPECT_EQ(upperOutside, 0);
  EXPECT_GT(lowerOutside, 100);
  EXPECT_GT(upperInside, 100);
}

// §6.4: the water in an opened pipe is a plane at its level over the pipe's floor, within the
// bore's chord there, coloured by the fill ratio (depth over the inner diameter) between the
// low and high colours and shaded by the style with an upward normal. Each water pixel
// against those formulas: a pipe of inner radius 0.4 holding 0.3 of water (level 0.1 below
// the axis, fill 0.375), Blinn-Phong with one light (the pipes' specular 0.35, shininess 24).
TEST(PipeRendering, WaterLiesAtItsLevelInItsFillColour) {
  const glm::vec3 low(0.8f, 0.9f, 1.0f), high(0.0f, 0.2f, 0.6f);
  const float innerR = 0.4f, depth = 0.3f, level = depth - innerR;
  const Scene scene = parseScene(R"({"resolution": [200, 150], "samples": 1,
    "style": {"name": "blinn-phong", "lines": false, "blinnPhong": {"ambient": 0.1}},
    "lights": [{"type": "directional", "direction": [-0.2, -1, -0.4], "space": "world"}],
    "camera": {"projection": "orthographic", "height": 4, "eye": [1, 6, 6], "target": [0, 0, 0]},
    "networks": [{"name": "n", "wallThickness": 0.1, "waterLevel": 0.3,
                  "waterColors": [[0.8, 0.9, 1.0], [0.0, 0.2, 0.6]], "cut": {"from": 0.3, "to": 0.7},
                  "pipes": [{"lines": [[[-4, 0, 0], [4, 0, 0]]], "radius": 0.5}]}]})",
                                 "water.json", kSource);
  Renderer renderer(scene, test::glContext().info());
  renderer.render();
  const auto aovs = renderer.readAovs();
  const Rgba8Image color = renderer.readColor();
  const FloatImage &cls = aov(aovs, "pipeClass"), &position = aov(aovs, "position");
  const glm::vec3 kd = glm::mix(low, high, depth / (2.0f * innerR));
  const glm::vec3 l = -glm::normalize(glm::vec3(-0.2f, -1.0f, -0.4f)), n(0, 1, 0);
  const glm::vec3 v = glm::normalize(scene.resolvedCamera().eye);  // orthographic: −forward
  const float specular = std::pow(std::max(glm::dot(n, glm::normalize(l + v)), 0.0f), 24.0f);
  const glm::vec3 expected = glm::clamp(
      0.1f * kd + kd * std::max(glm::dot(n, l), 0.0f) + glm::vec3(0.35f * specular), 0.0f, 1.0f);
  const float halfChord = std::sqrt(innerR * innerR - level * level);
  int water = 0, offPlane = 0, outsideBore = 0;
  double worst = 0.0;
  const auto isWater = [&](int x, int y) { return std::lround(cls.at(x, y)[0] * 4.0f) == 4; };
  for (int y = 1; y + 1 < cls.height; ++y)
    for (int x = 1; x + 1 < cls.width; ++x) {
      if (!isWater(x, y)) continue;
      ++water;
      const glm::vec3 p = glm::make_vec3(position.at(x, y));
      offPlane += std::abs(p.y - level) > 1e-4f;
      outsideBore += std::abs(p.z) > halfChord + 1e-4f;
      if (!isWater(x + 1, y) || !isWater(x - 1, y) || !isWater(x, y + 1) || !isWater(x, y - 1))
        continue;  // its rim blends with the wall
      for (int k = 0; k < 3; ++k)
        worst = std::max(worst, std::abs(color.at(x, y)[k] - 255.0 * expected[k]));
    }
  EXPECT_GT(water, 500);
  EXPECT_EQ(offPlane, 0);
  EXPECT_EQ(outsideBore, 0);
  EXPECT_LE(worst, 1.0) << "expected " << expected.r * 255 << ", " << expected.g * 255 << ", "
                        << expected.b * 255;
}

// A GIS field mapped to radius and water level, end to end: a GeoJSON layer of two pipes
// whose DIAM and LEVEL fields (millimetres, scale 0.001) give radii 0.5 and 0.4 and water
// depths 0.3 and 0.12; every water pixel of each opened pipe lies on its own level, inside
// its own bore's chord (§6.4).
TEST(PipeRendering, RadiusAndWaterLevelFromGisFieldsShowInTheFrame) {
  const std::filesystem::path layer = test::scratchPath("pipes", "levels.geojson");
  std::ofstream(layer) << R"({"type": "FeatureCollection", "features": [
     {"type": "Feature", "properties": {"DIAM": 1000, "LEVEL": 300},
      "geometry": {"type": "LineString", "coordinates": [[-4, 0], [4, 0]]}},
     {"type": "Feature", "properties": {"DIAM": 800, "LEVEL": 120},
      "geometry": {"type": "LineString", "coordinates": [[-4, 3], [4, 3]]}}]})";
  const Scene scene = parseScene(R"({"resolution": [240, 180], "samples": 1,
    "style": {"name": "blinn-phong", "lines": false},
    "camera": {"projection": "orthographic", "height": 7, "eye": [1, 8, 6], "target": [0, -2, 0]},
    "networks": [{"name": "n", "wallThickness": 0.1, "cut": {"from": 0.3, "to": 0.7},
                  "radius": {"field": "DIAM", "scale": 0.0005},
                  "waterLevel": {"field": "LEVEL", "scale": 0.001},
                  "pipes": [{"file": ")" +
                                     layer.string() + R"("}]}]})",
                                 "levels.json", kSource);
  const auto& pipes = scene.networks.at(0).pipes;
  ASSERT_EQ(pipes.size(), 2u);
  const auto aovs = renderAovs(scene);
  const FloatImage &cls = aov(aovs, "pipeClass"), &position = aov(aovs, "position");
  // Each feature's values from its fields: DIAM × 0.0005 and LEVEL × 0.001.
  struct Feature {
    float radius, water;
  };
  const Feature fields[2] = {{1000 * 0.0005f, 300 * 0.001f}, {800 * 0.0005f, 120 * 0.001f}};
  for (const Pipe& pipe : pipes) {
    ASSERT_TRUE(pipe.featureId == 0 || pipe.featureId == 1) << pipe.featureId;
    const Feature& f = fields[pipe.featureId];
    EXPECT_NEAR(pipe.radius, f.radius, 1e-6f);
    EXPECT_NEAR(pipe.waterLevel, f.water, 1e-6f);
    // The axis at the feature's line, 3 apart; its height the network's own.
    const glm::vec3 axis = pipe.nodes.front();
    const float innerR = f.radius - 0.1f, level = axis.y - innerR + f.water;
    const float halfChord = std::sqrt(innerR * innerR - (level - axis.y) * (level - axis.y));
    int water = 0;
    test::Mismatches offPlane, outsideBore;  // heights; distances from the axis
    for (int y = 0; y < cls.height; ++y)
      for (int x = 0; x < cls.width; ++x) {
        const glm::vec3 p = glm::make_vec3(position.at(x, y));
        if (std::lround(cls.at(x, y)[0] * 4.0f) != 4 || std::abs(p.z - axis.z) > 1.0f) continue;
        ++water;
        if (std::abs(p.y - level) > 1e-4f) offPlane.add(x, y, level, p.y);
        if (std::abs(p.z - axis.z) > halfChord + 1e-4f)
          outsideBore.add(x, y, halfChord, std::abs(p.z - axis.z));
      }
    std::printf("feature %lld: %d water pixels, level %.3f\n",
                static_cast<long long>(pipe.featureId), water, level);
    EXPECT_GT(water, 200) << pipe.featureId;
    EXPECT_EQ(offPlane.count(), 0) << pipe.featureId << ": " << offPlane;
    EXPECT_EQ(outsideBore.count(), 0) << pipe.featureId << ": " << outsideBore;
  }
}

TEST(PipeRendering, BillboardsCastTheOutlineOfTubesAndTroughs) {
  // The shadow map from the key light: a pipe along x, cut open over its middle half, against
  // the same pipe closed. From straight above an opened stretch (the lower half-tube) casts
  // the full width, so both maps hold as many texels; from the side (across the pipe) it casts
  // half the height, so the cut pipe's map holds 1 − ½·½ = 3/4 of the closed one's.
  const auto texels = [&](const char* direction, bool cut) {
    const std::string text = std::string(R"({"resolution": [64, 64], "samples": 1,
      "style": {"name": "blinn-phong", "lines": false, "shadows": {"size": 1024}},
      "lights": [{"type": "directional", "direction": )") +
                             direction + R"(, "space": "world"}],
      "camera": {"eye": [0, 5, 12], "target": [0, 0, 0], "fov": 45},
      "networks": [{"name": "n", "wallThickness": 0.1,)" +
                             (cut ? R"("cut": {"from": 0.25, "to": 0.75},)" : "") + R"(
                    "pipes": [{"lines": [[[-5, 0, 0], [5, 0, 0]]], "radius": 0.5}]}]})";
    const auto aovs = renderAovs(parseScene(text, "shadow.json", kSource));
    int n = 0;
    for (float v : aov(aovs, "shadowMap").data) n += v > 0.0f;
    return double(n);
  };
  EXPECT_NEAR(texels("[0.001, -1, 0]", true) / texels("[0.001, -1, 0]", false), 1.0, 0.02);
  EXPECT_NEAR(texels("[0, -0.001, -1]", true) / texels("[0, -0.001, -1]", false), 0.75, 0.03);
}

TEST(PipeRendering, OpenedPipesAreLitInsideAndShadowTheGround) {
  // Light from above: the inside and the water of the cut stretch look as without shadows
  // (the light falls into the trough), while the floor under the pipe darkens. (The inside of
  // the closed tube beyond, seen through an end triangle's bore, lies in its own shadow.)
  const auto render = [&](bool shadows) {
    const std::string text = std::string(R"({"resolution": [240, 150], "samples": 1,
      "style": {"name": "blinn-phong", "lines": false, "shadows": )") +
                             (shadows ? "true" : "false") + R"(},
      "lights": [{"type": "directional", "direction": [-0.2, -1, -0.3], "space": "world"}],
      "camera": {"eye": [0, 8, 10], "target": [0, 0, 0], "fov": 45},
      "objects": [{"name": "floor", "file": ")" +
                             kSource + R"(/examples/data/tile.obj",
                   "transform": {"translate": [-10, 0, 10], "scale": [20, 1, 20]}}],
      "networks": [{"name": "n", "wallThickness": 0.1, "waterLevel": 0.3,
                    "cut": {"from": 0.3, "to": 0.7},
                    "pipes": [{"lines": [[[-6, 1.5, 0], [6, 1.5, 0]]], "radius": 0.6}]}]})";
    Scene scene = parseScene(text, "lit.json", kSource);
    Renderer renderer(scene, test::glContext().info());
    renderer.render();
    return std::pair{renderer.readColor(), renderer.readAovs()};
  };
  const auto [plain, plainAovs] = render(false);
  const auto [shadowed, aovs] = render(true);
  const FloatImage &cls = aov(aovs, "pipeClass"), &id = aov(aovs, "objectId"),
                   &position = aov(aovs, "position");
  double insideDifference = 0;
  int inside = 0, darkFloor = 0;
  for (int y = 0; y < cls.height; ++y)
    for (int x = 0; x < cls.width; ++x) {
      const auto* a = plain.at(x, y);
      const auto* b = shadowed.at(x, y);
      const float c = cls.at(x, y)[0];
      const bool cutStretch = std::abs(position.at(x, y)[0]) < 2.3f;  // the cut: |x| < 2.4
      if (((c > 0.4f && c < 0.6f) || c > 0.9f) && cutStretch) {       // inside or water
        ++inside;
        for (int k = 0; k < 3; ++k) insideDifference += std::abs(int(a[k]) - int(b[k]));
      } else if (id.at(x, y)[0] == 0.0f && b[1] < 0.7 * a[1]) {
        ++darkFloor;
      }
    }
  ASSERT_GT(inside, 200);
  EXPECT_LT(insideDifference / (3.0 * inside), 4.0) << "mean channel difference inside";
  EXPECT_GT(darkFloor, 500);
}

// Konev18 §7 on the GPU against the rule written here: a junction shaft seen from above and to
// the side, rendered whole (shaftOpening 1 removes nothing) and opened (0.3). Every outer-wall
// front-face pixel of the whole frame whose normal and view, heights ignored, meet at n̂·v̂ > 0.3 is
// gone from the opened frame and every other one stays (pixels within 0.02 of the
// coefficient may go either way); every cut-surface pixel of the opened shaft has the wedge's
// side plane for its normal: horizontal, perpendicular to the radius from the shaft's axis
// through its position, turned towards the viewer.
TEST(PipeRendering, TheShaftWedgeRemovesWhereNormalAndViewMeet) {
  const auto scene = [&](double opening) {
    return parseScene(
        R"({"resolution": [320, 240], "samples": 1,
      "style": {"name": "blinn-phong", "lines": false},
      "camera": {"eye": [4, 5, 7], "target": [0, -1.5, 0], "fov": 40},
      "networks": [{"name": "n", "radius": 0.3, "wallThickness": 0.05, "depth": 2,
        "shaftOpening": )" +
            std::to_string(opening) +
            R"(, "pipes": [{"lines": [[[-6, 0], [0, 0]], [[0, 0], [6, 1]], [[0, 0], [0, -6]]]}],
        "shafts": {"generate": "junctions", "radius": 1.0, "wallThickness": 0.15}}]})",
        "shaft.json", kSource);
  };
  const Scene whole = scene(1.0), opened = scene(0.3);
  ASSERT_EQ(opened.networks.at(0).shafts.size(), 1u);
  const Shaft shaft = opened.networks[0].shafts[0];
  float outerId = -1.0f, innerId = -1.0f;
  for (std::size_t i = 0; i < opened.objects.size(); ++i) {
    if (opened.objects[i].networkPart == NetworkPart::ShaftOuter) outerId = float(i);
    if (opened.objects[i].networkPart == NetworkPart::ShaftInner) innerId = float(i);
  }
  ASSERT_GE(outerId, 0.0f);
  ASSERT_GE(innerId, 0.0f);
  const glm::vec3 eye = opened.resolvedCamera().eye;
  const auto a = renderAovs(whole), b = renderAovs(opened);
  const FloatImage &wholeId = aov(a, "objectId"), &wholePos = aov(a, "position"),
                   &wholeNormal = aov(a, "normal"), &id = aov(b, "objectId"),
                   &pos = aov(b, "position"), &normal = aov(b, "normal"), &cut = aov(b, "cutMask");
  int removed = 0, kept = 0, cutPixels = 0;
  test::Mismatches wrong, wrongCut;  // 1 removed, 0 kept; 1 a side wall, 0 not
  for (int y = 0; y < id.height; ++y)
    for (int x = 0; x < id.width; ++x) {
      if (wholeId.at(x, y)[0] == outerId) {
        const glm::vec3 p = glm::make_vec3(wholePos.at(x, y)),
                        n = glm::make_vec3(wholeNormal.at(x, y));
        const glm::vec2 nh(n.x, n.z), vh(eye.x - p.x, eye.z - p.z);
        // Front faces only: their normal is the radius (the outer wall's back faces, seen
        // between the cylinders from above, are cut surfaces in both frames).
        const glm::vec2 radius(p.x - shaft.bottom.x, p.z - shaft.bottom.z);
        if (glm::length(nh) > 1e-3f &&
            glm::dot(glm::normalize(nh), glm::normalize(radius)) > 0.9f &&
            std::abs(glm::dot(glm::normalize(nh), glm::normalize(vh)) - 0.3f) > 0.02f) {
          const bool gone = shaftWedgeRemoves(n, eye - p, 0.3f);
          const bool same =
              id.at(x, y)[0] == outerId && glm::length(glm::make_vec3(pos.at(x, y)) - p) < 1e-4f;
          gone ? ++removed : ++kept;
          if (gone == same) wrong.add(x, y, gone, !same);
        }
      }
      const float k = id.at(x, y)[0];
      if (cut.at(x, y)[0] != 1.0f || (k != outerId && k != innerId)) continue;
      ++cutPixels;
      const glm::vec3 p = glm::make_vec3(pos.at(x, y)), n = glm::make_vec3(normal.at(x, y));
      const glm::vec2 radial =
          glm::normalize(glm::vec2(p.x - shaft.bottom.x, p.z - shaft.bottom.z));
      const bool side = std::abs(n.y) < 1e-3f &&
                        std::abs(glm::dot(glm::vec2(n.x, n.z), radial)) < 0.09f &&
                        glm::dot(glm::vec2(n.x, n.z), glm::vec2(eye.x - p.x, eye.z - p.z)) >= 0.0f;
      if (!side) wrongCut.add(x, y, 1.0, 0.0);
    }
  EXPECT_GT(removed, 100);
  EXPECT_GT(kept, 100);
  EXPECT_EQ(wrong.count(), 0) << "of " << removed + kept << ": " << wrong;
  EXPECT_GT(cutPixels, 30);
  // The cylinders' normals are interpolated between facets: within 5° of the true radius.
  EXPECT_EQ(wrongCut.count(), 0) << "of " << cutPixels << ": " << wrongCut;
}

// Konev18 §7: the cut surface colour goes on the outer cylinder's back faces and the inner
// cylinder's front faces (the wall's thickness seen through the wedge), and nowhere else on
// the shaft. Rendered with two cut colours, the shaft pixels that change are exactly those
// whose surface (position AOV) faces away from the eye on the outer cylinder or towards it on
// the inner one, the facing from the cylinder's radius there; pixels whose radius is within
// 5° of edge-on may go either way (the rim's top and the floor are not cylinders).
TEST(PipeRendering, TheShaftsCutColourIsOnOuterBackAndInnerFrontFaces) {
  const auto render = [&](const char* cutColor) {
    const Scene scene = parseScene(
        std::string(R"({"resolution": [320, 240], "samples": 1,
      "style": {"name": "blinn-phong", "lines": false},
      "camera": {"eye": [4, 5, 7], "target": [0, -1.5, 0], "fov": 40},
      "networks": [{"name": "n", "radius": 0.3, "wallThickness": 0.05, "depth": 2,
        "shaftOpening": 0.3, "cutColor": )") +
            cutColor +
            R"(, "pipes": [{"lines": [[[-6, 0], [0, 0]], [[0, 0], [6, 1]], [[0, 0], [0, -6]]]}],
        "shafts": {"generate": "junctions", "radius": 1.0, "wallThickness": 0.15}}]})",
        "shaft.json", kSource);
    Renderer renderer(scene, test::glContext().info());
    renderer.render();
    return std::tuple{scene, renderer.readColor(), renderer.readAovs()};
  };
  const auto [scene, red, aovs] = render("[1, 0, 0]");
  const auto [unused, blue, unusedAovs] = render("[0, 0, 1]");
  const Shaft shaft = scene.networks.at(0).shafts.at(0);
  float outerId = -1.0f, innerId = -1.0f;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    if (scene.objects[i].networkPart == NetworkPart::ShaftOuter) outerId = float(i);
    if (scene.objects[i].networkPart == NetworkPart::ShaftInner) innerId = float(i);
  }
  const glm::vec3 eye = scene.resolvedCamera().eye;
  const FloatImage &id = aov(aovs, "objectId"), &pos = aov(aovs, "position");
  int cut = 0, plain = 0;
  test::Mismatches wrong;  // 1 recoloured, 0 not
  for (int y = 0; y < id.height; ++y)
    for (int x = 0; x < id.width; ++x) {
      const float k = id.at(x, y)[0];
      if (k != outerId && k != innerId) continue;
      const glm::vec3 p = glm::make_vec3(pos.at(x, y));
      const glm::vec2 radial(p.x - shaft.bottom.x, p.z - shaft.bottom.z);
      // On its cylinder: not the rim's top, not the floor (part of the inner object).
      const float r = k == outerId ? shaft.radius : shaft.innerRadius();
      if (p.y > shaft.top - 0.02f || p.y < shaft.bottom.y + 0.02f ||
          std::abs(glm::length(radial) - r) > 0.02f)
        continue;
      const glm::vec2 radius = glm::normalize(radial);
      const float facing = glm::dot(radius, glm::normalize(glm::vec2(eye.x - p.x, eye.z - p.z)));
      if (std::abs(facing) < std::sin(glm::radians(5.0f))) continue;
      const bool expected = k == outerId ? facing < 0.0f : facing > 0.0f;
      const auto* a = red.at(x, y);
      const auto* b = blue.at(x, y);
      const bool changed = a[0] != b[0] || a[2] != b[2];
      expected ? ++cut : ++plain;
      if (changed != expected) wrong.add(x, y, expected, changed);
    }
  EXPECT_GT(cut, 100);
  EXPECT_GT(plain, 1000);
  EXPECT_EQ(wrong.count(), 0) << "of " << cut + plain << ": " << wrong;
}

// Konev18 Fig. 10: an end triangle of a cut stretch seen from behind resets its area to the
// pipe's outside (stencil 4), so the closed tube's end covers the disc there. A straight pipe
// cut open over its middle, seen orthographically from beyond one end of the cut: every
// stencil-4 pixel's ray meets one of the two end discs (radius r_out, perpendicular to the
// pipe at the cut's ends) and shows the outside; the disc seen from behind shows the outside
// wherever no cut surface lies in front (stencil 2), reset or covered by the closed tube in
// front of it; the disc seen from the front is never reset.
TEST(PipeRendering, AnEndTriangleSeenFromBehindShowsTheOutside) {
  const float r = 0.5f, ends[2] = {-1.6f, 1.6f};  // the cut from 0.3 to 0.7 of x ∈ [−4, 4]
  const Scene scene = parseScene(R"({"resolution": [200, 150], "samples": 1,
    "style": {"name": "blinn-phong", "lines": false},
    "camera": {"projection": "orthographic", "height": 4, "eye": [7, 2.5, 3], "target": [0, 0, 0]},
    "networks": [{"name": "n", "wallThickness": 0.1, "cut": {"from": 0.3, "to": 0.7},
                  "pipes": [{"lines": [[[-4, 0, 0], [4, 0, 0]]], "radius": 0.5}]}]})",
                                 "ends.json", kSource);
  const auto aovs = renderAovs(scene);
  const FloatImage &stencil = aov(aovs, "pipeStencil"), &cls = aov(aovs, "pipeClass");
  const Camera camera = scene.resolvedCamera();
  const float aspect = float(scene.width) / float(scene.height);
  const glm::mat4 inverse = glm::inverse(camera.projectionMatrix(aspect) * camera.view());
  const glm::vec3 forward = glm::normalize(camera.target - camera.eye);
  // How far from end k's disc centre the pixel's ray crosses the disc's plane.
  const auto offset = [&](int x, int y, int k) {
    const glm::vec2 ndc((x + 0.5f) / float(stencil.width) * 2.0f - 1.0f,
                        1.0f - (y + 0.5f) / float(stencil.height) * 2.0f);  // rows top down
    const glm::vec4 h = inverse * glm::vec4(ndc, -1.0f, 1.0f);
    const glm::vec3 origin = glm::vec3(h) / h.w;
    const float t = (ends[k] - origin.x) / forward.x;
    return glm::length(origin + t * forward - glm::vec3(ends[k], 0.0f, 0.0f));
  };
  int reset = 0, stray = 0, notOutside = 0, disc[2] = {0, 0}, outside[2] = {0, 0},
      resetIn[2] = {0, 0};
  for (int y = 0; y < stencil.height; ++y)
    for (int x = 0; x < stencil.width; ++x) {
      const float s = stencil.at(x, y)[0];
      if (s == 4.0f) {
        ++reset;
        stray += offset(x, y, 0) > r + 0.03f && offset(x, y, 1) > r + 0.03f;
        notOutside += std::lround(cls.at(x, y)[0] * 4.0f) != 1;
      }
      for (int k = 0; k < 2; ++k)
        if (offset(x, y, k) < r - 0.03f && s != 2.0f)
          ++disc[k], resetIn[k] += s == 4.0f,
              outside[k] += std::lround(cls.at(x, y)[0] * 4.0f) == 1;
    }
  EXPECT_GT(reset, 100);
  EXPECT_EQ(stray, 0);
  EXPECT_EQ(notOutside, 0);
  // The end nearer the eye (x = 1.6) is seen from behind: its disc, less the cut surfaces in
  // front, shows the outside; the far end's is seen from the front and is not reset.
  EXPECT_GT(resetIn[1], 100);
  EXPECT_EQ(outside[1], disc[1]);
  EXPECT_EQ(resetIn[0], 0) << "of " << disc[0];
}

// Konev18 eqs. 12–14 on the GPU against the pipe's own geometry: the end triangle at the
// cut's start, seen from the front (from above the opened stretch, so that nothing else lies
// over it), holds the upper half of the pipe's cross-section. Where a pixel's ray meets that
// plane at ρ from the axis (above it), pass 1 draws the cut surface for r_in < ρ < r_out
// (eq. 13: stencil 2, pipe class "cut"), pass 2 marks the inside for ρ < r_in (eq. 14:
// stencil 1), and the triangle's corners beyond r_out are discarded by both (stencil 0).
// Through the bore the closed tube beyond the triangle shows its inside (pipe class 0.5).
// Pixels within 1.5 pixels of a border may go either way.
TEST(PipeRendering, TheEndTriangleMarksWallAndBoreByTheirDistanceFromTheAxis) {
  const float rOut = 0.5f, rIn = 0.4f, start = -1.6f;  // the cut from 0.3 of x ∈ [−4, 4]
  const Scene scene = parseScene(R"({"resolution": [240, 240], "samples": 1,
    "style": {"name": "blinn-phong", "lines": false},
    "camera": {"projection": "orthographic", "height": 1.6, "eye": [3, 2, 0],
               "target": [-1.6, 0, 0]},
    "networks": [{"name": "n", "wallThickness": 0.1, "cut": {"from": 0.3, "to": 0.7},
                  "pipes": [{"lines": [[[-4, 0, 0], [4, 0, 0]]], "radius": 0.5}]}]})",
                                 "end.json", kSource);
  const auto aovs = renderAovs(scene);
  const FloatImage &stencil = aov(aovs, "pipeStencil"), &cls = aov(aovs, "pipeClass");
  const Camera camera = scene.resolvedCamera();
  const glm::mat4 inverse = glm::inverse(camera.projectionMatrix(1.0f) * camera.view());
  const glm::vec3 forward = glm::normalize(camera.target - camera.eye);
  const float pixel = 1.6f / float(stencil.height), margin = 1.5f * pixel;
  int wall = 0, bore = 0, corners = 0, notCut = 0, notInside = 0;
  test::Mismatches wrong;  // stencil values
  for (int y = 0; y < stencil.height; ++y)
    for (int x = 0; x < stencil.width; ++x) {
      const glm::vec2 ndc((x + 0.5f) / float(stencil.width) * 2.0f - 1.0f,
                          1.0f - (y + 0.5f) / float(stencil.height) * 2.0f);  // rows top down
      const glm::vec4 h = inverse * glm::vec4(ndc, -1.0f, 1.0f);
      const glm::vec3 origin = glm::vec3(h) / h.w;
      const glm::vec3 p = origin + (start - origin.x) / forward.x * forward;  // on x = start
      const float rho = std::hypot(p.y, p.z);
      // Within the triangle (apex √2·r_out above the axis, base ±√2·r_out), above the axis.
      if (p.y < margin || p.y + std::abs(p.z) > std::sqrt(2.0f) * rOut - margin) continue;
      if (std::abs(rho - rIn) < margin || std::abs(rho - rOut) < margin) continue;
      const float expected = rho < rIn ? 1.0f : rho < rOut ? 2.0f : 0.0f;
      wall += expected == 2.0f, bore += expected == 1.0f, corners += expected == 0.0f;
      const float s = stencil.at(x, y)[0];
      if (s != expected) wrong.add(x, y, expected, s);
      if (expected == 2.0f) notCut += std::abs(cls.at(x, y)[0] - 0.75f) > 0.01f;
      if (expected == 1.0f) notInside += std::abs(cls.at(x, y)[0] - 0.5f) > 0.01f;
    }
  EXPECT_GT(wall, 300);
  EXPECT_GT(bore, 3000);
  EXPECT_GT(corners, 300);
  EXPECT_EQ(wrong.count(), 0) << "of " << wall + bore + corners << ": " << wrong;
  EXPECT_EQ(notCut, 0) << "of " << wall;
  EXPECT_EQ(notInside, 0) << "of " << bore;
}

// Konev18 eqs. 15–16 on the GPU against the pipe's own geometry: the horizontal proxy quad
// along a cut spans the full diameter, so seen from straight above (orthographic) proxy pass
// 1 marks the two walls, r_in < |z| < r_out, as cut surface (stencil 2) and pass 2 the bore,
// |z| < r_in, as inside (stencil 1), over the cut's middle; the end triangles are edge-on.
// Pixels within 1.5 pixels of a band's border may go either way.
TEST(PipeRendering, TheCutQuadMarksWallsAndBoreFromAbove) {
  const float rOut = 0.5f, rIn = 0.4f;
  const Scene scene = parseScene(R"({"resolution": [200, 200], "samples": 1,
    "style": {"name": "blinn-phong", "lines": false},
    "camera": {"projection": "orthographic", "height": 2, "eye": [0, 10, 0], "target": [0, 0, 0],
               "up": [0, 0, -1]},
    "networks": [{"name": "n", "wallThickness": 0.1, "cut": {"from": 0.2, "to": 0.8},
                  "pipes": [{"lines": [[[-4, 0, 0], [4, 0, 0]]], "radius": 0.5}]}]})",
                                 "quad.json", kSource);
  const auto aovs = renderAovs(scene);
  const FloatImage& stencil = aov(aovs, "pipeStencil");
  const float pixel = 2.0f / float(stencil.height);  // scene units per pixel
  int walls = 0, bore = 0;
  test::Mismatches wrong;  // stencil values
  for (int y = 0; y < stencil.height; ++y)
    for (int x = 0; x < stencil.width; ++x) {
      // Up is −z: row 0 (the top) at z = −1; columns from x = −1.
      const float wx = -1.0f + (x + 0.5f) * pixel, z = std::abs(-1.0f + (y + 0.5f) * pixel);
      if (std::abs(wx) > 0.9f) continue;
      const float margin = 1.5f * pixel;
      if (std::abs(z - rIn) < margin || std::abs(z - rOut) < margin) continue;
      const float expected = z < rIn ? 1.0f : z < rOut ? 2.0f : 0.0f;
      walls += expected == 2.0f, bore += expected == 1.0f;
      if (stencil.at(x, y)[0] != expected) wrong.add(x, y, expected, stencil.at(x, y)[0]);
    }
  EXPECT_GT(walls, 1000);
  EXPECT_GT(bore, 5000);
  EXPECT_EQ(wrong.count(), 0) << wrong;
}
