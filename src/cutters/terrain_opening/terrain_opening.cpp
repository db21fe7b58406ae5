#include "cutters/terrain_opening/terrain_opening.hpp"

#include <regex>

#include "cutaway/core/error.hpp"

namespace cutaway {

TerrainOpening::TerrainOpening(const Scene& scene, const TerrainOpeningOptions& options,
                               Frame& frame)
    : options_(options),
      frame_(frame),
      terrain_(scene.objects.size(), false),
      cutBuildings_(scene.objects.size(), false) {
  const std::regex terrain(options.terrain);
  const std::regex buildings(options.buildings.empty() ? "$^" : options.buildings);
  Bounds bounds;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& o = scene.objects[i];
    if (o.proxy) continue;
    if (std::regex_match(o.name, terrain)) {
      terrain_[i] = true;
      bounds.extend(o.worldBounds());
    } else if (options.cutBuildings && std::regex_match(o.name, buildings)) {
      cutBuildings_[i] = true;
    }
  }
  // No terrain object (a viewer's scene that just turned the cutter on): nothing to open.
  if (bounds.empty()) bounds.extend(glm::vec3(0.0f)), bounds.extend(glm::vec3(1.0f));
  field_ = terrainField(options, bounds);
  const int n = field_.resolution;
  texture_ = gl::Texture::create2D(GL_R32F, n, n);
  glTextureSubImage2D(texture_.id(), 0, 0, 0, n, n, GL_RED, GL_FLOAT, field_.distance.data());
  frame.declare("terrainThreshold",
                {.format = GL_RG32F,
                 .meaning = "Konev18 eq. 1 at the last terrain fragment of the pixel: x = camera "
                            "distance d_c (scene units), y = threshold t, z = 0",
                 .aovChannels = 3});
  frame.declare("terrainClass", {.format = GL_R32UI,
                                 .meaning = "Konev18 eqs. 2-3 over the pixel's terrain fragments: "
                                            "0 none, 1 terrain drawn, 2 artificial thickness, 3 "
                                            "a fragment discarded (the largest seen)"});
}

void TerrainOpening::prepare(GLuint program) const {
  const float zero[4] = {0, 0, 0, 0};
  const GLuint none = 0;
  glClearTexImage(frame_.texture("terrainThreshold").id(), 0, GL_RG, GL_FLOAT, zero);
  glClearTexImage(frame_.texture("terrainClass").id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &none);
  glBindTextureUnit(23, texture_.id());
  glBindImageTexture(2, frame_.texture("terrainThreshold").id(), 0, GL_FALSE, 0, GL_WRITE_ONLY,
                     GL_RG32F);
  glBindImageTexture(3, frame_.texture("terrainClass").id(), 0, GL_FALSE, 0, GL_READ_WRITE,
                     GL_R32UI);
  // Locations of terrain_opening.glsl.
  glProgramUniform4f(program, 50, field_.min.x, field_.min.y, 1.0f / field_.size.x,
                     1.0f / field_.size.y);
  glProgramUniform4f(program, 51, options_.w, options_.s, options_.cameraDistance ? 1.0f : 0.0f,
                     float(field_.resolution));
}

Aov TerrainOpening::fieldAov() const {
  const int n = field_.resolution;
  FloatImage image(n, n, 1);
  image.data = field_.distance;
  image.flipVertically();  // rows of increasing z stored first; AOVs run top to bottom
  return {"terrainDistance",
          "D_p (Konev18 §4): distance from texel to the closest pipe, min(texels, 255) / 255, "
          "over the terrain's x (columns) and z (rows, decreasing downwards) extent",
          std::move(image)};
}

}  // namespace cutaway
