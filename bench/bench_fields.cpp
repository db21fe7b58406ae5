// Timings of the CPU cutaway-surface algorithms (src/fields) on a synthetic seed image shaped
// like a real one: a few discs and rectangles (rear hulls of objects of interest, Burns08
// §5.1) covering 17% of the buffer, with tilted depths and per-object slopes.
//
//   cmake --build --preset release --target cutaway-bench-fields
//   build/release/bench/cutaway-bench-fields
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>

#include "cutaway/fields/cutaway_surface.hpp"

namespace fields = cutaway::fields;

namespace {

// View-plane units as makeSeedImage() gives them for a 45° vertical field of view
// (P₁₁ = 1/tan 22.5°) and a square buffer of n pixels.
fields::SeedImage syntheticSeeds(int n, bool directional) {
  const float unit = 2.0f / float(n) * std::tan(std::numbers::pi_v<float> / 8.0f);
  fields::SeedImage seeds(n, n, unit, unit);
  struct Shape {
    float cx, cy, rx, ry;  // centre and half sizes, as fractions of the image
    bool disc;
    float z, tilt, slope;  // NDC depth at the centre, depth change across it, m_E
  };
  const Shape shapes[] = {{0.30f, 0.35f, 0.14f, 0.14f, true, 0.90f, 0.020f, 1.2f},
                          {0.68f, 0.62f, 0.10f, 0.10f, true, 0.95f, -0.010f, 0.8f},
                          {0.55f, 0.25f, 0.07f, 0.07f, true, 0.97f, 0.005f, 2.0f},
                          {0.25f, 0.75f, 0.12f, 0.06f, false, 0.93f, 0.010f, 1.0f},
                          {0.75f, 0.30f, 0.05f, 0.15f, false, 0.96f, -0.020f, 1.5f}};
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const float u = (float(x) + 0.5f) / float(n), v = (float(y) + 0.5f) / float(n);
      for (const Shape& s : shapes) {
        const float a = (u - s.cx) / s.rx, b = (v - s.cy) / s.ry;
        if (s.disc ? a * a + b * b > 1.0f : std::abs(a) > 1.0f || std::abs(b) > 1.0f) continue;
        // The directional constraint narrows the cone towards a floor seen from above
        // (Burns11 eq. 6.2): m_F > m_E, f pointing down the screen, slightly turned.
        const float fx = directional ? 0.2f * a : 0.0f, fy = directional ? -1.0f : 0.0f;
        const float norm = std::hypot(fx, fy);
        seeds.set(x, y, s.z + s.tilt * a, s.slope, directional ? 3.0f * s.slope : s.slope,
                  directional ? fx / norm : 0.0f, directional ? fy / norm : 0.0f);
        break;
      }
    }
  return seeds;
}

void jumpFlooding(benchmark::State& state) {
  const fields::SeedImage seeds = syntheticSeeds(int(state.range(0)), state.range(2) != 0);
  for (auto _ : state)
    benchmark::DoNotOptimize(
        fields::jumpFlooding(seeds, -1.0f, fields::JumpFloodingVariant::jfa, int(state.range(1))));
}
BENCHMARK(jumpFlooding)
    ->ArgNames({"n", "threads", "directional"})
    ->ArgsProduct({{512, 1024}, {1, 2}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The adaptive cutter's default variant (src/cutters/adaptive: jfa+1).
void jumpFloodingPlus1(benchmark::State& state) {
  const fields::SeedImage seeds = syntheticSeeds(int(state.range(0)), state.range(1) != 0);
  for (auto _ : state)
    benchmark::DoNotOptimize(
        fields::jumpFlooding(seeds, -1.0f, fields::JumpFloodingVariant::jfaPlus1, 2));
}
BENCHMARK(jumpFloodingPlus1)
    ->ArgNames({"n", "directional"})
    ->ArgsProduct({{1024}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The portable kernel that machines without AVX2 + FMA run, for comparison.
void jumpFloodingScalar(benchmark::State& state) {
  const fields::SeedImage seeds = syntheticSeeds(int(state.range(0)), state.range(1) != 0);
  for (auto _ : state)
    benchmark::DoNotOptimize(fields::jumpFlooding(seeds, -1.0f, fields::JumpFloodingVariant::jfa, 1,
                                                  fields::JumpFloodingKernel::scalar));
}
BENCHMARK(jumpFloodingScalar)
    ->ArgNames({"n", "directional"})
    ->ArgsProduct({{512}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

void chamfer(benchmark::State& state) {
  const fields::SeedImage seeds = syntheticSeeds(int(state.range(0)), false);
  const auto kernel =
      state.range(1) == 3 ? fields::ChamferKernel::k3x3 : fields::ChamferKernel::k5x5;
  for (auto _ : state) benchmark::DoNotOptimize(fields::chamfer(seeds, -1.0f, kernel));
}
BENCHMARK(chamfer)
    ->ArgNames({"n", "kernel"})
    ->ArgsProduct({{512}, {3, 5}})
    ->Unit(benchmark::kMillisecond);

void bruteForce(benchmark::State& state) {
  const fields::SeedImage seeds = syntheticSeeds(int(state.range(0)), state.range(1) != 0);
  for (auto _ : state) benchmark::DoNotOptimize(fields::bruteForce(seeds, -1.0f));
}
BENCHMARK(bruteForce)
    ->ArgNames({"n", "directional"})
    ->ArgsProduct({{128}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
