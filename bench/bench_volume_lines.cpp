// Burns11 Fig. 2.8–2.9 on a real volume. Fig. 2.8: over a camera orbit with a changing
// isovalue, the fraction of the brute-force contour segments that each seeding strategy finds
// per frame, and its cost against brute force (wall time and cells read); every strategy
// starts from a brute-force first frame, as in the paper. Fig. 2.9: a still view, random
// probes alone from nothing, the found part growing over frames.
//   previous  the previous frame's cells as seeds (§2.4.1.3)
//   random    eq. 2.5 probes from random cells only (§2.4.1.4)
//   both      previous cells, probes from them and random probes
//
//   cmake --build --preset release --target cutaway-bench-volume-lines
//   build/release/bench/cutaway-bench-volume-lines [scene.json] [--frames N] [--probes K]
//       [--iso LO HI] [--svg plot.svg] [--csv table.csv]
// Defaults: examples/ct-stent-boundaries.json's CT, 60 frames over a quarter orbit, the
// isovalue swinging over [200, 400] HU, K = n random probes per frame (n³ ≈ the voxel count).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "cutaway/core/error.hpp"
#include "cutaway/scene/scene.hpp"
#include "cutaway/styles/volume_lines.hpp"

namespace {

using Clock = std::chrono::steady_clock;

struct Strategy {
  Strategy(const char* n, cutaway::VolumeLineSeeding s, std::uint64_t randomSeed)
      : name(n), seeding(s), tracker(randomSeed) {}
  const char* name;
  cutaway::VolumeLineSeeding seeding;
  cutaway::VolumeLineTracker tracker;
  double found = 0, seconds = 0, cells = 0;
  std::vector<double> perFrame;
};

double secondsSince(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// A line chart of the fraction found per frame, one polyline per strategy.
void writeSvg(const std::string& path, const std::vector<Strategy>& strategies, int frames) {
  const double w = 640, h = 320, left = 50, bottom = 30, top = 20, right = 120;
  const auto x = [&](int f) { return left + (w - left - right) * f / std::max(1, frames - 1); };
  const auto y = [&](double v) { return top + (h - top - bottom) * (1.0 - v); };
  std::ofstream out(path);
  out << "<svg xmlns='http://www.w3.org/2000/svg' width='" << w << "' height='" << h
      << "' font-family='sans-serif' font-size='11'>\n<rect width='100%' height='100%' fill='white'/>\n";
  for (int i = 0; i <= 4; ++i) {
    const double v = i / 4.0;
    out << "<line x1='" << left << "' x2='" << w - right << "' y1='" << y(v) << "' y2='" << y(v)
        << "' stroke='#ddd'/><text x='" << left - 6 << "' y='" << y(v) + 4
        << "' text-anchor='end'>" << int(v * 100) << "%</text>\n";
  }
  out << "<text x='" << (left + w - right) / 2 << "' y='" << h - 6
      << "' text-anchor='middle'>frame</text>\n";
  const char* colours[] = {"#1f5fbf", "#c0307a", "#208040"};
  for (std::size_t s = 0; s < strategies.size(); ++s) {
    out << "<polyline fill='none' stroke='" << colours[s % 3] << "' stroke-width='1.5' points='";
    for (std::size_t f = 0; f < strategies[s].perFrame.size(); ++f)
      out << x(int(f) + 1) << "," << y(strategies[s].perFrame[f]) << " ";
    out << "'/>\n<text x='" << w - right + 8 << "' y='" << top + 16 * (s + 1) << "' fill='"
        << colours[s % 3] << "'>" << strategies[s].name << "</text>\n";
  }
  out << "</svg>\n";
}

int run(int argc, char** argv) {
  std::string scenePath = CUTAWAY_SOURCE_DIR "/examples/ct-stent-boundaries.json", svg, csv;
  int frames = 60, probes = -1;
  float isoLo = 200.0f, isoHi = 400.0f;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto next = [&]() -> std::string {
      if (i + 1 >= argc) throw cutaway::Error(a + " needs a value");
      return argv[++i];
    };
    if (a == "--frames") frames = std::stoi(next());
    else if (a == "--probes") probes = std::stoi(next());
    else if (a == "--iso") isoLo = std::stof(next()), isoHi = std::stof(next());
    else if (a == "--svg") svg = next();
    else if (a == "--csv") csv = next();
    else scenePath = a;
  }
  const cutaway::Scene scene = cutaway::loadScene(scenePath);
  if (scene.volumes.empty()) throw cutaway::Error(scenePath + ": the scene has no volume");
  const cutaway::SceneVolume& sv = scene.volumes[0];
  const cutaway::Volume& volume = *sv.volume;
  if (probes < 0) probes = int(std::cbrt(double(volume.voxelCount())));
  const cutaway::Camera camera = scene.resolvedCamera();

  std::vector<Strategy> strategies;
  strategies.emplace_back("previous", cutaway::VolumeLineSeeding{.previousCells = true}, 1);
  strategies.emplace_back(
      "random", cutaway::VolumeLineSeeding{.previousCells = false, .randomProbes = probes}, 2);
  strategies.emplace_back(
      "both",
      cutaway::VolumeLineSeeding{
          .previousCells = true, .probesFromPrevious = probes / 4, .randomProbes = probes},
      3);
  std::ofstream table;
  if (!csv.empty()) {
    table.open(csv);
    table << "frame,isovalue,bruteSegments,bruteSeconds";
    for (const auto& s : strategies) table << "," << s.name << "Found," << s.name << "Seconds";
    table << "\n";
  }
  std::printf("%s: %dx%dx%d voxels, %d frames, %d random probes per frame\n", scenePath.c_str(),
              volume.dims.x, volume.dims.y, volume.dims.z, frames, probes);
  double bruteSeconds = 0, bruteCells = 0, bruteSegments = 0;
  for (int frame = 0; frame < frames; ++frame) {
    const float t = float(frame) / float(std::max(1, frames - 1));
    // A quarter orbit about the target's vertical, the isovalue swinging once over its range.
    const glm::mat4 turn =
        glm::rotate(glm::mat4(1.0f), t * glm::half_pi<float>(), camera.up);
    cutaway::Camera c = camera;
    c.eye = camera.target + glm::vec3(turn * glm::vec4(camera.eye - camera.target, 0.0f));
    const float iso = isoLo + (isoHi - isoLo) * 0.5f * (1.0f - std::cos(t * 2.0f * glm::pi<float>()));
    const cutaway::VolumeLineField field(volume, sv.indexToWorld(), cutaway::VolumeLineView::of(c),
                                         {.isoValue = iso});
    auto start = Clock::now();
    const cutaway::VolumeLineSet brute = cutaway::extractVolumeLinesBruteForce(field);
    const double bs = secondsSince(start);
    if (table.is_open()) table << frame << "," << iso << "," << brute.segmentCount() << "," << bs;
    for (Strategy& s : strategies) {
      start = Clock::now();
      const cutaway::VolumeLineSet set = s.tracker.extract(field, s.seeding);
      const double seconds = secondsSince(start);
      const double fraction = brute.segmentCount()
                                  ? double(brute.countFoundIn(set)) / double(brute.segmentCount())
                                  : 1.0;
      if (table.is_open()) table << "," << fraction << "," << seconds;
      if (frame == 0) continue;  // brute force for every strategy
      s.perFrame.push_back(fraction);
      s.found += fraction, s.seconds += seconds, s.cells += double(set.cellsExamined);
    }
    if (table.is_open()) table << "\n";
    if (frame == 0) continue;
    bruteSeconds += bs, bruteCells += double(brute.cellsExamined);
    bruteSegments += double(brute.segmentCount());
  }
  const double n = std::max(1, frames - 1);
  std::printf("brute force: %.0f segments per frame, %.1f ms per frame\n", bruteSegments / n,
              1e3 * bruteSeconds / n);
  std::printf("%-9s %12s %12s %14s %14s %14s\n", "strategy", "found mean", "found min",
              "ms per frame", "time / brute", "cells / brute");
  for (const Strategy& s : strategies) {
    double lowest = 1.0;
    for (double f : s.perFrame) lowest = std::min(lowest, f);
    std::printf("%-9s %11.1f%% %11.1f%% %14.2f %13.1f%% %13.2f%%\n", s.name, 100 * s.found / n,
                100 * lowest, 1e3 * s.seconds / n, 100 * s.seconds / bruteSeconds,
                100 * s.cells / bruteCells);
  }
  if (!svg.empty()) writeSvg(svg, strategies, frames - 1);

  // Fig. 2.9: a still view and threshold, no brute-force start; random probes alone (k·n per
  // frame), the cells found kept as the next frame's seeds, so the found part grows.
  const cutaway::VolumeLineField still(volume, sv.indexToWorld(),
                                       cutaway::VolumeLineView::of(camera), {.isoValue = isoLo});
  const cutaway::VolumeLineSet reference = cutaway::extractVolumeLinesBruteForce(still);
  std::printf("\nstill view, isovalue %g: %zu segments; found after frame", double(isoLo),
              reference.segmentCount());
  const int stills[] = {1, 2, 5, 10, 20};
  for (int f : stills) std::printf(" %6d", f);
  std::printf("\n");
  for (int k : {1, 4, 16}) {
    cutaway::VolumeLineTracker tracker(7);
    std::printf("%5d·n probes per frame                 ", k);
    for (int frame = 1; frame <= 20; ++frame) {
      const cutaway::VolumeLineSet set =
          tracker.extract(still, {.randomProbes = k * probes, .bruteForceFirstFrame = false});
      if (std::find(std::begin(stills), std::end(stills), frame) == std::end(stills)) continue;
      std::printf(" %5.1f%%", 100.0 * double(reference.countFoundIn(set)) /
                                  double(std::max<std::size_t>(1, reference.segmentCount())));
    }
    std::printf("\n");
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cutaway-bench-volume-lines: %s\n", e.what());
    return 1;
  }
}
