// Timings of the terrains' level of detail (cutaway/geometry/grid_lod.hpp) on Konev18's
// generated city: building the chunks' errors once per terrain, and what a frame whose view
// changed pays before it draws (the levels, then the stitched triangles), for the whole city
// in view (the benchmark's camera) and for a walk-through eye 20 m above the ground.
//
//   cmake --build --preset release --target cutaway-bench-terrain-lod
//   build/release/bench/cutaway-bench-terrain-lod
#include <benchmark/benchmark.h>

#include <map>

#include <glm/gtc/matrix_transform.hpp>

#include "cutaway/geometry/grid_lod.hpp"
#include "cutaway/scene/benchmark_city.hpp"

namespace {

const cutaway::Scene& city(int scale) {
  static std::map<int, cutaway::Scene> cities;
  auto it = cities.find(scale);
  if (it == cities.end())
    it = cities.emplace(scale, cutaway::benchmarkCity({.scale = scale})).first;
  return it->second;
}

const cutaway::Mesh& cityTerrain(int scale) {
  return *city(scale).objects[0].mesh;
}

// 1920 × 1200 from the city's own camera, or 20 m over its middle looking across it.
cutaway::GridLod::View cityView(int scale, bool walkThrough) {
  const cutaway::Camera& camera = city(scale).camera;
  const cutaway::Bounds b = cityTerrain(scale).bounds();
  cutaway::GridLod::View view;
  view.eye = walkThrough ? glm::vec3(b.center().x, b.max.y + 20.0f, b.center().z) : camera.eye;
  const glm::vec3 target = walkThrough ? glm::vec3(b.max.x, b.max.y, b.min.z) : camera.target;
  view.projection = glm::perspective(glm::radians(camera.fovY), 1.6f, 1.0f, 1e5f);
  view.viewProjection = view.projection * glm::lookAt(view.eye, target, glm::vec3(0, 1, 0));
  view.viewportHeight = 1200.0f;
  view.pixelError = 0.5f;
  return view;
}

void build(benchmark::State& state) {
  const cutaway::Mesh& terrain = cityTerrain(int(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(cutaway::GridLod::build(terrain));
  state.counters["nodes"] = double(terrain.positions.size());
}
BENCHMARK(build)->ArgName("scale")->Arg(1)->Arg(10)->Unit(benchmark::kMillisecond);

void selectAndStitch(benchmark::State& state) {
  const int scale = int(state.range(0));
  const auto lod = cutaway::GridLod::build(cityTerrain(scale));
  const cutaway::GridLod::View view = cityView(scale, state.range(1) != 0);
  std::size_t triangles = 0;
  for (auto _ : state) {
    const std::vector<std::uint8_t> levels = lod->select(view);
    triangles = lod->triangles(levels).size();
    benchmark::DoNotOptimize(triangles);
  }
  state.counters["triangles"] = double(triangles);
}
BENCHMARK(selectAndStitch)
    ->ArgNames({"scale", "walkThrough"})
    ->ArgsProduct({{1, 10}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
