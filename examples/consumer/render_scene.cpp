// Renders a scene file through the installed library, with options set by their paths as the
// CLI's --set takes them:   render-scene SCENE.json OUT.png [PATH=VALUE ...]
#include <cstdio>
#include <string>

#include <cutaway/core/error.hpp>
#include <cutaway/core/image.hpp>
#include <cutaway/gl/context.hpp>
#include <cutaway/render/renderer.hpp>
#include <cutaway/render/techniques.hpp>

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s SCENE.json OUT.png [PATH=VALUE ...]\n", argv[0]);
    return 2;
  }
  try {
    auto context = cutaway::gl::HeadlessContext::create();
    cutaway::Scene scene = cutaway::loadScene(argv[1]);
    for (int i = 3; i < argc; ++i) {
      const std::string assignment = argv[i];
      const auto equals = assignment.find('=');
      if (equals == std::string::npos) throw cutaway::Error(assignment, "", "expected PATH=VALUE");
      cutaway::setOption(scene, assignment.substr(0, equals), assignment.substr(equals + 1));
    }
    cutaway::Renderer renderer(scene, context->info());
    renderer.render();
    cutaway::writePng(argv[2], renderer.readColor());
  } catch (const cutaway::Error& e) {
    std::fprintf(stderr, "render-scene: %s\n", e.what());
    return 1;
  }
  return 0;
}
