// Would a CPU ray caster beat llvmpipe's fragment shader for volumes (as the CPU jump flooding
// beats its fragment passes)? The scene's first volume, uncut and unshaded, at 512²: the GPU's
// `volumes` pass (GL_TIME_ELAPSED) against the CPU reference caster (kinds/volume_ray_cast:
// the same rays, samples and transfer function, emission only) on 1 and on every hardware
// thread, rows split among them.
//
//   cmake --build --preset release --target cutaway-bench-volume-rays
//   build/release/bench/cutaway-bench-volume-rays [scene.json]   (default mri-head-box-cut)
#include <benchmark/benchmark.h>

#include <algorithm>
#include <thread>
#include <vector>

#include "cutaway/gl/context.hpp"
#include "cutaway/kinds/volume_ray_cast.hpp"
#include "cutaway/render/renderer.hpp"
#include "cutaway/scene/scene.hpp"

namespace {

constexpr int kSize = 512;
std::string gScenePath = CUTAWAY_SOURCE_DIR "/examples/mri-head-box-cut.json";

// The scene's first volume alone: no cutters, no meshes, no shading, no jitter.
const cutaway::Scene& volumeScene() {
  static const cutaway::Scene scene = [] {
    cutaway::Scene s = cutaway::loadScene(gScenePath);
    s.camera = s.resolvedCamera();
    s.camera.fit = false;
    s.cutters = {};
    s.objects.clear();
    s.volumes.resize(1);
    s.volumes[0].shading = false;
    s.width = s.height = kSize;
    s.samples = 1;
    return s;
  }();
  return scene;
}

void cpuRays(benchmark::State& state) {
  const cutaway::Scene& s = volumeScene();
  const cutaway::Camera c = s.resolvedCamera();
  const glm::mat4 view = c.view(), projection = c.projectionMatrix(1.0f);
  const int threads = int(state.range(0));
  double opacity = 0.0;
  for (auto _ : state) {
    std::vector<double> sums(threads, 0.0);
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
      pool.emplace_back([&, t] {
        for (int y = t; y < kSize; y += threads)
          for (int x = 0; x < kSize; ++x)
            sums[t] += cutaway::castVolumeRay(s.volumes[0], view, projection, {kSize, kSize},
                                              {x, y})
                           .opacity;
      });
    for (std::thread& p : pool) p.join();
    for (double v : sums) opacity += v;
  }
  benchmark::DoNotOptimize(opacity);
}

void gpuRays(benchmark::State& state) {
  static auto context = cutaway::gl::HeadlessContext::create();
  cutaway::Renderer renderer(volumeScene(), context->info());
  renderer.render();  // warm-up: programs, uploads
  for (auto _ : state) {
    renderer.render();
    double ms = 0.0;
    for (const cutaway::PassTiming& t : renderer.timings())
      if (t.name == "volumes") ms = t.gpuMs;
    state.SetIterationTime(ms / 1000.0);
  }
}

}  // namespace

BENCHMARK(cpuRays)->Arg(1)->Arg(int(std::max(2u, std::thread::hardware_concurrency())))
    ->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);
BENCHMARK(gpuRays)->Unit(benchmark::kMillisecond)->UseManualTime()->Iterations(5);

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (argc > 1) gScenePath = argv[1];
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
}
