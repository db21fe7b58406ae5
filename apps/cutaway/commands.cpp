#include "commands.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>

#include "cutaway/core/error.hpp"
#include "cutaway/core/image.hpp"
#include "cutaway/gl/context.hpp"
#include "cutaway/render/aov.hpp"
#include "cutaway/render/renderer.hpp"
#include "cutaway/scene/scene.hpp"

namespace cutaway::cli {

namespace {

void applyOverrides(Scene& scene, const SceneOverrides& o) {
  if (!o.size.empty()) {
    static const std::regex sizeRe(R"((\d{1,5})x(\d{1,5}))");
    std::smatch m;
    if (!std::regex_match(o.size, m, sizeRe))
      throw Error("--size", "", "expected WxH, e.g. 800x600, got \"" + o.size + "\"");
    const int w = std::stoi(m[1]), h = std::stoi(m[2]);
    if (w < 1 || h < 1 || w > 16384 || h > 16384)
      throw Error("--size", "", "width and height must be in [1, 16384]");
    scene.width = w;
    scene.height = h;
  }
  Camera& c = scene.camera;
  if (o.eye) c.eye = *o.eye;
  if (o.target) c.target = *o.target;
  if ((o.eye || o.target) && !o.fit) c.fit = false;
  if (o.fit) c.fit = true;
  if (o.up) c.up = *o.up;
  if (o.fov) c.fovY = *o.fov;
  if (!o.projection.empty())
    c.projection = o.projection == "orthographic" ? Projection::Orthographic : Projection::Perspective;
  if (glm::length(c.eye - c.target) < 1e-9f) throw Error("--eye", "", "eye and target coincide");
  if (glm::length(glm::cross(glm::normalize(c.eye - c.target), glm::normalize(c.up))) < 1e-6f)
    throw Error("--up", "", "up is parallel to the viewing direction");
  if (!o.style.empty()) scene.style.name = o.style;
  if (o.samples) scene.samples = *o.samples;
}

nlohmann::json vec(const glm::vec3& v) { return {v.x, v.y, v.z}; }
nlohmann::json boundsJson(const Bounds& b) { return {{"min", vec(b.min)}, {"max", vec(b.max)}}; }

struct Stats {
  double median, min, max;
};
Stats stats(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  const double median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  return {median, v.front(), v.back()};
}

}  // namespace

int render(const RenderOptions& options) {
  Scene scene = loadScene(options.scene);
  applyOverrides(scene, options.overrides);
  const auto context = gl::HeadlessContext::create();
  Renderer renderer(scene, context->info());
  const Camera camera = scene.resolvedCamera();
  renderer.render(camera);
  writePng(options.output, renderer.readColor());
  std::printf("wrote %s (%dx%d, %s, %s)\n", options.output.c_str(), scene.width, scene.height,
              scene.style.name.c_str(), context->info().renderer.c_str());
  if (!options.aovDir.empty()) {
    writeAovs(options.aovDir, renderer.readAovs(), camera, float(scene.width) / float(scene.height));
    std::printf("wrote AOVs to %s (see aovs.json)\n", options.aovDir.c_str());
  }
  return 0;
}

int info(const std::string& path) {
  const Scene scene = loadScene(path);
  nlohmann::json objects = nlohmann::json::array();
  std::size_t triangles = 0;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& o = scene.objects[i];
    const MeshReport& r = o.mesh->report;
    triangles += o.proxy ? 0 : o.mesh->triangles.size();
    nlohmann::json params = nlohmann::json::object();
    for (const auto& [k, v] : o.params)
      std::visit([&](auto value) { params[k] = value; }, v);
    objects.push_back({{"index", i},
                       {"name", o.name},
                       {"source", o.source},
                       {"group", o.group},
                       {"role", roleName(o.role)},
                       {"importance", o.importance},
                       {"proxy", o.proxy},
                       {"params", params},
                       {"triangles", o.mesh->triangles.size()},
                       {"vertices", o.mesh->positions.size()},
                       {"bounds", boundsJson(o.worldBounds())},
                       {"watertight", r.watertight},
                       {"boundaryEdges", r.boundaryEdges},
                       {"nonManifoldEdges", r.nonManifoldEdges},
                       {"misorientedEdges", r.misorientedEdges},
                       {"droppedDegenerateTriangles", r.droppedDegenerate},
                       {"normalsComputed", r.normalsComputed}});
  }
  const Camera c = scene.resolvedCamera();
  const nlohmann::json out = {
      {"scene", path},
      {"resolution", {scene.width, scene.height}},
      {"style", scene.style.name},
      {"triangles", triangles},
      {"bounds", boundsJson(scene.bounds())},
      {"camera", {{"eye", vec(c.eye)}, {"target", vec(c.target)}, {"near", c.near}, {"far", c.far}}},
      {"objects", objects}};
  std::printf("%s\n", out.dump(2).c_str());
  return 0;
}

int bench(const BenchOptions& options) {
  Scene scene = loadScene(options.scene);
  applyOverrides(scene, options.overrides);
  const auto context = gl::HeadlessContext::create();
  Renderer renderer(scene, context->info());
  const Camera camera = scene.resolvedCamera();
  renderer.render(camera);  // warm-up: shader compilation, first allocation
  glFinish();
  (void)renderer.timings();

  std::map<std::string, std::vector<double>> passTimes;
  std::vector<std::string> passOrder;
  std::vector<double> frameTimes;
  for (int i = 0; i < options.frames; ++i) {
    const auto start = std::chrono::steady_clock::now();
    renderer.render(camera);
    glFinish();
    const auto end = std::chrono::steady_clock::now();
    frameTimes.push_back(std::chrono::duration<double, std::milli>(end - start).count());
    for (const auto& t : renderer.timings()) {
      if (!passTimes.count(t.name)) passOrder.push_back(t.name);
      passTimes[t.name].push_back(t.gpuMs);
    }
  }
  const Stats frame = stats(frameTimes);
  if (options.json) {
    nlohmann::json passes = nlohmann::json::array();
    for (const auto& name : passOrder) {
      const Stats s = stats(passTimes[name]);
      passes.push_back({{"pass", name}, {"gpuMedianMs", s.median}, {"gpuMinMs", s.min}, {"gpuMaxMs", s.max}});
    }
    const nlohmann::json out = {
        {"scene", options.scene},
        {"renderer", context->info().renderer},
        {"resolution", {scene.width, scene.height}},
        {"samples", scene.samples},
        {"frames", options.frames},
        {"passes", passes},
        {"frame", {{"medianMs", frame.median}, {"minMs", frame.min}, {"maxMs", frame.max}}}};
    std::printf("%s\n", out.dump(2).c_str());
    return 0;
  }
  std::printf("%s, %dx%d, %d samples, %d frames on %s\n", options.scene.c_str(), scene.width,
              scene.height, scene.samples, options.frames, context->info().renderer.c_str());
  std::printf("%-24s %10s %10s %10s\n", "pass (GPU ms)", "median", "min", "max");
  for (const auto& name : passOrder) {
    const Stats s = stats(passTimes[name]);
    std::printf("%-24s %10.3f %10.3f %10.3f\n", name.c_str(), s.median, s.min, s.max);
  }
  std::printf("%-24s %10.3f %10.3f %10.3f\n", "frame (wall ms)", frame.median, frame.min, frame.max);
  return 0;
}

}  // namespace cutaway::cli
