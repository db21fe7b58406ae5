#include "cutaway/scene/benchmark_city.hpp"

#include "cutaway/cutters/terrain_opening.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "cutaway/core/noise.hpp"

namespace cutaway {

namespace {

// Konev18 §8.3, Table 1.
constexpr int kPipes = 1190, kShafts = 1156;
constexpr double kTerrainTriangles = 2.9e6;
constexpr float kSide = 2000.0f;  // metres at scale 1

float terrainHeight(float x, float z, std::uint32_t seed) {
  float h = 0.0f, amplitude = 12.0f, frequency = 1.0f / 600.0f;
  for (int octave = 0; octave < 4; ++octave, amplitude *= 0.5f, frequency *= 2.0f)
    h += amplitude * valueNoise(x * frequency, z * frequency, seed + std::uint32_t(octave));
  return h;
}

SceneObject generatedObject(std::string name, glm::vec3 color, std::shared_ptr<Mesh> mesh) {
  SceneObject o;
  o.name = std::move(name);
  o.source = "generated";
  o.material.color = color;
  o.mesh = std::move(mesh);
  return o;
}

}  // namespace

Scene benchmarkCity(const BenchmarkCityOptions& options) {
  const int scale = std::max(options.scale, 1);
  const float side = kSide * std::sqrt(float(scale));
  std::mt19937 random(options.seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);

  Scene scene;
  scene.file = "benchmark-city";
  scene.width = 1280, scene.height = 960;
  scene.style.name = "blinn-phong";
  scene.style.lines.reset();
  scene.backgroundTop = {0.93f, 0.96f, 1.0f};
  scene.lights.push_back(Light{});

  // The terrain: an n × n grid of two triangles per cell.
  const int n = int(std::lround(std::sqrt(kTerrainTriangles * scale / 2.0)));
  auto terrain = std::make_shared<Mesh>();
  terrain->positions.reserve(std::size_t(n + 1) * std::size_t(n + 1));
  terrain->normals.reserve(terrain->positions.capacity());
  const float cell = side / float(n);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const float x = float(i) * cell, z = -float(j) * cell;
      terrain->positions.emplace_back(x, terrainHeight(x, z, options.seed), z);
      const float e = 0.5f * cell;
      const glm::vec3 g(
          terrainHeight(x + e, z, options.seed) - terrainHeight(x - e, z, options.seed), 0.0f,
          terrainHeight(x, z + e, options.seed) - terrainHeight(x, z - e, options.seed));
      terrain->normals.push_back(glm::normalize(glm::vec3(-g.x, 2.0f * e, -g.z)));
    }
  // Two triangles per cell, implied by the grid: z decreases with j, so the corners
  // (i, j) → (i+1, j) → (i, j+1) turn counter-clockwise seen from +y, and front faces up.
  terrain->grid = GridLayout{n + 1, n + 1, {{{0, 1, 2}, {1, 3, 2}}}};
  scene.objects.push_back(generatedObject("terrain", {0.62f, 0.72f, 0.5f}, terrain));
  // What the openings show below the pipes: one quad of soil under the whole city (two
  // triangles; the terrain row's count stays the paper's).
  float lowest = 1e30f;
  for (const glm::vec3& p : terrain->positions) lowest = std::min(lowest, p.y);
  auto soil = std::make_shared<Mesh>();
  const float y = lowest - 8.0f;
  soil->positions = {{0, y, 0}, {side, y, 0}, {side, y, -side}, {0, y, -side}};
  soil->normals.assign(4, glm::vec3(0, 1, 0));
  soil->triangles = {{0, 1, 2}, {0, 2, 3}};
  scene.objects.push_back(generatedObject("subsurface", {0.45f, 0.4f, 0.36f}, soil));

  // Streets on a jittered grid; each pipe walks 2–6 segments along them (4.6 nodes on average).
  PipeNetwork net;
  net.name = "sewers";
  const int blocks = int(std::sqrt(float(kPipes * scale)) * 1.2f);
  const float block = side / float(blocks + 1);
  const auto junction = [&](int i, int j) {
    const float jx = latticeValue(i, j, options.seed + 11) - 0.5f;
    const float jz = latticeValue(i, j, options.seed + 12) - 0.5f;
    return glm::vec2((float(i) + 0.5f + 0.3f * jx) * block, -(float(j) + 0.5f + 0.3f * jz) * block);
  };
  const int dx[4] = {1, 0, -1, 0}, dz[4] = {0, 1, 0, -1};
  for (int p = 0; p < kPipes * scale; ++p) {
    int i = int(unit(random) * float(blocks)), j = int(unit(random) * float(blocks));
    const int nodes = 3 + int(unit(random) * 4.0f) + (p % 10 == 0 ? 1 : 0);  // 3–6, +1 every 10th
    const float depth = 2.0f + 2.0f * unit(random);
    int dir = int(unit(random) * 4.0f) % 4;
    Pipe pipe;
    pipe.radius = 0.3f + 0.4f * unit(random);
    pipe.wallThickness = 0.15f * pipe.radius;
    pipe.waterLevel = unit(random) * 2.0f * pipe.innerRadius();
    for (int k = 0; k < nodes; ++k) {
      const glm::vec2 q = junction(i, j);
      pipe.nodes.emplace_back(q.x, terrainHeight(q.x, q.y, options.seed) - depth, q.y);
      // Straight on, or turn left or right; never back.
      const float r = unit(random);
      dir = r < 0.6f ? dir : r < 0.8f ? (dir + 1) % 4 : (dir + 3) % 4;
      if (i + dx[dir] < 0 || i + dx[dir] > blocks || j + dz[dir] < 0 || j + dz[dir] > blocks)
        dir = (dir + 2) % 4;
      i += dx[dir], j += dz[dir];
    }
    pipe.cut = glm::vec2(0.3f, 0.7f) * pipe.length();
    net.pipes.push_back(std::move(pipe));
  }
  for (int s = 0; s < kShafts * scale; ++s) {
    const Pipe& p = net.pipes[std::size_t(s)];
    Shaft shaft;
    shaft.radius = p.radius + 0.4f;
    shaft.wallThickness = 0.15f;
    shaft.bottom = p.nodes.front() - glm::vec3(0.0f, p.radius, 0.0f);
    shaft.top = terrainHeight(shaft.bottom.x, shaft.bottom.z, options.seed);
    shaft.waterLevel = 0.5f * unit(random);
    net.shafts.push_back(shaft);
  }
  resolveCutIntersections(net, 0.0f);
  trimAtShafts(net);
  for (const bool inner : {false, true}) scene.objects.push_back(shaftObject(net, 0, inner));
  scene.networks.push_back(std::move(net));

  TerrainOpeningOptions opening;
  opening.terrain = "terrain";
  opening.resolution = 4096;
  for (const Pipe& p : scene.networks[0].pipes) {
    std::vector<glm::vec2> xz;
    for (const glm::vec3& q : p.nodes) xz.emplace_back(q.x, q.z);
    opening.lines.push_back(std::move(xz));
  }
  opening.cameraDistance = false;  // Fig. 15b: the whole network seen at once
  opening.w = 0.01f, opening.s = 1.0f;
  scene.cutters.enable<TerrainOpeningOptions>() = opening;

  // The whole network in view (Konev18 §8.3), from the south-west and above.
  scene.camera.eye = {-0.25f * side, 0.7f * side, 0.35f * side};
  scene.camera.target = {0.5f * side, 0.0f, -0.5f * side};
  scene.camera.fovY = 45.0f;
  scene.camera.near = 1.0f;
  scene.camera.far = 3.0f * side;
  return scene;
}

}  // namespace cutaway
