// Tests of the JSON scene format (docs/scene-format.md): malformed files are rejected with the
// file, the JSON pointer and the reason; valid files load with the documented defaults.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "cutaway/core/error.hpp"
#include "cutaway/scene/scene.hpp"

// Readable failure messages for glm values (found by argument-dependent lookup).
namespace glm {
inline void PrintTo(const vec3& v, std::ostream* os) { *os << "(" << v.x << ", " << v.y << ", " << v.z << ")"; }
}  // namespace glm

using namespace cutaway;

namespace {

const std::filesystem::path kData = CUTAWAY_TEST_DATA;
const std::filesystem::path kMeshes = kData / "meshes";

// Parses `text` as if it were a file in tests/data/meshes, so that "cube.obj" resolves.
Scene parse(const std::string& text) { return parseScene(text, "inline.json", kMeshes); }

glm::vec3 apply(const glm::mat4& m, const glm::vec3& p) { return glm::vec3(m * glm::vec4(p, 1.0f)); }

// Tolerance for transformed unit-sized coordinates: a few float ulps of cos/sin(90°).
constexpr float kEps = 1e-5f;

#define EXPECT_VEC3_NEAR(actual, expected, eps)                                         \
  do {                                                                                  \
    const glm::vec3 a_ = (actual), e_ = (expected);                                     \
    EXPECT_NEAR(a_.x, e_.x, eps) << "x of " #actual;                                    \
    EXPECT_NEAR(a_.y, e_.y, eps) << "y of " #actual;                                    \
    EXPECT_NEAR(a_.z, e_.z, eps) << "z of " #actual;                                    \
  } while (0)

// ---------------------------------------------------------------------------------------------
// Malformed scene files: one file per mistake, each with the JSON pointer (or, for syntax
// errors, the line and column) and a substring of the reason that the error must carry.

struct BadScene {
  const char* file;     // under tests/data/bad
  const char* place;    // Error::place(): a JSON pointer, or "line L, column C"
  const char* reason;   // substring of Error::reason()
};

const BadScene kBadScenes[] = {
    // Syntax: the '}' after a trailing comma, 4th line, 51st character.
    {"syntax_error.json", "line 4, column 51", "invalid JSON: syntax error"},
    {"not_an_object.json", "/", "expected an object, got array"},
    // A number beyond double range: "1e999" ends at column 18 of line 2.
    {"number_overflow.json", "line 2, column 18", "invalid JSON: number overflow parsing '1e999'"},
    // Top level.
    {"unknown_top_level_key.json", "/colour", "unknown key \"colour\""},
    {"unknown_key_with_slash.json", "/style~1name", "unknown key \"style/name\""},  // RFC 6901 escape
    {"missing_objects.json", "/", "missing required key \"objects\""},
    {"empty_objects.json", "/objects", "a scene needs at least one object"},
    {"objects_not_array.json", "/objects", "expected an array, got object"},
    {"version_two.json", "/version", "value 2 is outside [1, 1]"},
    {"resolution_one_number.json", "/resolution", "expected [width, height]"},
    {"resolution_zero.json", "/resolution/0", "value 0 is outside [1, 16384]"},
    {"resolution_not_integer.json", "/resolution/0", "expected an integer, got number"},
    {"samples_three.json", "/samples", "samples must be 1, 2, 4, 8 or 16"},
    {"background_missing_bottom.json", "/background", "missing required key \"bottom\""},
    // Objects.
    {"unknown_object_key.json", "/objects/0/material", "unknown key \"material\""},
    {"missing_file_key.json", "/objects/0", "missing required key \"file\""},
    {"mesh_not_found.json", "/objects/0/file", "mesh file not found"},
    {"wrong_type_importance.json", "/objects/0/importance", "expected a number, got string"},
    {"importance_out_of_range.json", "/objects/0/importance", "value 1.5 is outside [0, 1]"},
    {"bad_role.json", "/objects/0/role", "unknown value \"focus\""},
    {"color_four_elements.json", "/objects/0/color", "expected an array of 3 numbers, got 4 elements"},
    {"color_above_one.json", "/objects/0/color/0", "value 255 is outside [0, 1]"},
    {"bad_split.json", "/objects/0/split", "unknown value \"parts\""},
    {"bad_regex.json", "/objects/0/nodes", "invalid regular expression \"(body\""},
    {"nodes_match_nothing.json", "/objects/0/nodes", "no mesh node of"},
    {"duplicate_names.json", "/objects", "two objects are named \"cube\""},
    {"unknown_object_param.json", "/objects/0/params/glow", "unknown object parameter \"glow\""},
    {"object_param_wrong_type.json", "/objects/0/params/lines", "expected true or false, got number"},
    {"override_without_split.json", "/objects/0/overrides", "overrides need \"split\": \"nodes\""},
    {"override_without_match.json", "/objects/0/overrides/0", "missing required key \"match\""},
    {"override_unknown_key.json", "/objects/0/overrides/0/file", "unknown key \"file\""},
    // Transforms.
    {"transform_matrix_and_translate.json", "/objects/0/transform/translate", "\"matrix\" excludes"},
    {"transform_singular_matrix.json", "/objects/0/transform/matrix", "the matrix is singular"},
    {"transform_projective_matrix.json", "/objects/0/transform/matrix", "the last row must be 0, 0, 0, 1"},
    {"transform_matrix_15.json", "/objects/0/transform/matrix", "expected 16 numbers"},
    {"transform_zero_scale.json", "/objects/0/transform/scale", "scale must not be zero"},
    {"transform_rotate_zero_axis.json", "/objects/0/transform/rotate/axis", "must not be the zero vector"},
    // Proxies.
    {"proxy_box_and_hull.json", "/proxies/0", "exactly one of \"box\" or \"hullOf\""},
    {"proxy_box_min_above_max.json", "/proxies/0/box", "box min must be below max"},
    {"proxy_hull_matches_nothing.json", "/proxies/0/hullOf", "no object name matches"},
    {"proxy_hull_coplanar.json", "/proxies/0/hullOf", "convex hull failed"},
    {"proxy_with_color.json", "/proxies/0/color", "unknown key \"color\""},
    // Camera.
    {"camera_eye_equals_target.json", "/camera/eye", "eye and target coincide"},
    {"camera_up_parallel.json", "/camera/up", "up is parallel to the viewing direction"},
    {"camera_fit_up_parallel.json", "/camera/up", "up is parallel to the viewing direction"},
    {"camera_far_below_near.json", "/camera/far", "far must be greater than near"},
    {"camera_without_eye.json", "/camera", "needs \"eye\" and \"target\", a \"path\", or \"fit\": true"},
    {"camera_fov_too_wide.json", "/camera/fov", "value 180 is outside [1, 170]"},
    // Style.
    {"style_unknown_name.json", "/style", "unknown value \"toon\""},
    {"style_unknown_line_key.json", "/style/lines/thickness", "unknown key \"thickness\""},
    {"style_line_width.json", "/style/lines/width", "value 20 is outside [0.5, 8]"},
    // Lights.
    {"light_zero_direction.json", "/lights/0/direction", "must not be the zero vector"},
    {"light_unknown_type.json", "/lights/0/type", "unknown value \"spot\""},
    {"light_point_with_direction.json", "/lights/0/direction", "unknown key \"direction\""},
    {"light_too_many.json", "/lights", "at most 8 lights, got 9"},
};

void PrintTo(const BadScene& bad, std::ostream* os) { *os << bad.file; }

class SceneBadFile : public ::testing::TestWithParam<BadScene> {};

TEST_P(SceneBadFile, IsRejectedWithFilePointerAndReason) {
  const BadScene& bad = GetParam();
  const std::filesystem::path path = kData / "bad" / bad.file;
  ASSERT_TRUE(std::filesystem::exists(path)) << path;
  try {
    (void)loadScene(path);
    FAIL() << bad.file << " was accepted";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.file(), path.string()) << what;
    EXPECT_EQ(e.place(), bad.place) << what;
    EXPECT_NE(e.reason().find(bad.reason), std::string::npos)
        << "reason \"" << e.reason() << "\" lacks \"" << bad.reason << "\"";
    // The one-line message a user sees: "<file>: <place>: <reason>".
    EXPECT_EQ(what.rfind(path.string() + ": " + bad.place + ": ", 0), 0u) << what;
    EXPECT_NE(what.find(bad.file), std::string::npos) << what;
  }
}

INSTANTIATE_TEST_SUITE_P(Files, SceneBadFile, ::testing::ValuesIn(kBadScenes),
                         [](const ::testing::TestParamInfo<BadScene>& param) {
                           std::string name = param.param.file;
                           name = name.substr(0, name.find('.'));
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

TEST(SceneBadFile, EveryFileInTheFolderIsInTheTable) {
  std::size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kData / "bad")) {
    ++files;
    bool listed = false;
    for (const auto& bad : kBadScenes) listed |= entry.path().filename() == bad.file;
    EXPECT_TRUE(listed) << entry.path() << " has no expectation";
  }
  EXPECT_EQ(files, std::size(kBadScenes));
  EXPECT_GE(files, 20u);
}

// ---------------------------------------------------------------------------------------------
// Errors that need no file of their own.

TEST(SceneErrors, MissingSceneFile) {
  const std::filesystem::path path = kData / "bad" / "no_such_scene.json";
  try {
    (void)loadScene(path);
    FAIL() << "a missing scene file was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.file(), path.string());
    EXPECT_EQ(e.reason(), "cannot open scene file");
  }
}

TEST(SceneErrors, ParseSceneNamesTheDisplayNameAndCountsLines) {
  try {
    (void)parseScene("{\n  \"objects\": [\n    {\"name\": \"a\" \"file\": \"cube.obj\"}\n  ]\n}",
                     "shown-name.json", kMeshes);
    FAIL() << "invalid JSON was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.file(), "shown-name.json");
    // A missing comma before "file" (columns 18–23 of line 3): the place is the last
    // character of the token that could not be parsed, as nlohmann::json reports it.
    EXPECT_EQ(e.place(), "line 3, column 23") << e.what();
    EXPECT_NE(e.reason().find("invalid JSON"), std::string::npos) << e.what();
  }
  try {
    (void)parseScene("", "empty.json", kMeshes);
    FAIL() << "empty text was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.place(), "line 1, column 1") << e.what();
  }
}

TEST(SceneErrors, MeshPathInTheReasonIsResolvedAgainstTheBaseDirectory) {
  try {
    (void)parseScene(R"({"objects": [{"name": "a", "file": "missing.obj"}]})", "x.json", kMeshes);
    FAIL() << "a missing mesh was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.place(), "/objects/0/file");
    EXPECT_NE(e.reason().find((kMeshes / "missing.obj").string()), std::string::npos) << e.what();
  }
}

TEST(SceneErrors, ProxyNameClashesWithAnObject) {
  try {
    (void)parse(R"({"objects": [{"name": "cube", "file": "cube.obj"}],
                    "proxies": [{"name": "cube", "hullOf": "cube"}]})");
    FAIL() << "a proxy with an object's name was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.place(), "/objects");
    EXPECT_NE(e.reason().find("two objects are named \"cube\""), std::string::npos) << e.what();
  }
}

// ---------------------------------------------------------------------------------------------
// Valid scenes.

TEST(SceneLoad, MinimalSceneGetsTheDefaults) {
  const Scene s = parse(R"({"objects": [{"name": "cube", "file": "cube.obj"}]})");
  EXPECT_EQ(s.file, "inline.json");
  EXPECT_EQ(s.width, 800);
  EXPECT_EQ(s.height, 600);
  EXPECT_EQ(s.samples, 4);
  EXPECT_EQ(s.backgroundTop, glm::vec3(1.0f));
  EXPECT_EQ(s.backgroundBottom, glm::vec3(1.0f));
  EXPECT_EQ(s.style.name, "gooch");
  ASSERT_TRUE(s.style.lines.has_value());
  EXPECT_TRUE(s.style.lines->silhouettes);
  EXPECT_TRUE(s.style.lines->creases);
  EXPECT_FLOAT_EQ(s.style.lines->creaseAngle, 45.0f);
  // One default light: directional, in camera space.
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].type, Light::Type::Directional);
  EXPECT_TRUE(s.lights[0].cameraSpace);
  EXPECT_FLOAT_EQ(s.lights[0].intensity, 1.0f);
  // No camera: fit the scene, looking down −z from +z.
  EXPECT_TRUE(s.camera.fit);
  EXPECT_EQ(s.camera.projection, Projection::Perspective);
  EXPECT_FLOAT_EQ(s.camera.fovY, 40.0f);
  EXPECT_EQ(s.camera.near, 0.0f);
  EXPECT_EQ(s.camera.far, 0.0f);

  ASSERT_EQ(s.objects.size(), 1u);
  const SceneObject& o = s.objects[0];
  EXPECT_EQ(o.name, "cube");
  EXPECT_EQ(o.source, (kMeshes / "cube.obj").string());
  EXPECT_EQ(o.role, Role::Context);
  EXPECT_FLOAT_EQ(o.importance, 0.5f);
  EXPECT_EQ(o.group, "");
  EXPECT_FALSE(o.proxy);
  EXPECT_TRUE(o.params.empty());
  EXPECT_EQ(o.transform, glm::mat4(1.0f));
  EXPECT_FLOAT_EQ(o.material.specular, 0.25f);
  EXPECT_FLOAT_EQ(o.material.shininess, 32.0f);
  ASSERT_TRUE(o.mesh);
  EXPECT_EQ(o.mesh->triangles.size(), 12u);
  EXPECT_EQ(s.find("cube"), &o);
  EXPECT_EQ(s.find("nothing"), nullptr);
}

TEST(SceneLoad, EveryKeyIsRead) {
  const Scene s = parse(R"({
    "version": 1,
    "resolution": [320, 200],
    "samples": 8,
    "background": {"top": [0.1, 0.2, 0.3], "bottom": [0.4, 0.5, 0.6]},
    "style": {"name": "blinn-phong",
              "lines": {"silhouettes": false, "creases": true, "creaseAngle": 30,
                        "depthThreshold": 0.05, "width": 2, "color": [0.2, 0.2, 0.2]},
              "gooch": {"cool": [0, 0, 0.4], "warm": [0.4, 0.4, 0], "alpha": 0.1, "beta": 0.7},
              "blinnPhong": {"ambient": 0.3}},
    "lights": [{"type": "point", "position": [1, 2, 3], "color": [1, 0.5, 0.25],
                "intensity": 2.5, "space": "world"},
               {"type": "directional", "direction": [0, -2, 0]}],
    "camera": {"projection": "orthographic", "eye": [0, 0, 10], "target": [0, 0, 0],
               "up": [0, 3, 0], "fov": 50, "height": 4, "near": 0.5, "far": 20},
    "objects": [{"name": "cube", "file": "cube.obj", "role": "interest", "importance": 0.9,
                 "group": "parts", "params": {"lines": false}, "color": [0.1, 0.2, 0.3],
                 "specular": 0.6, "shininess": 64}]
  })");
  EXPECT_EQ(s.width, 320);
  EXPECT_EQ(s.height, 200);
  EXPECT_EQ(s.samples, 8);
  EXPECT_EQ(s.backgroundTop, glm::vec3(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(s.backgroundBottom, glm::vec3(0.4f, 0.5f, 0.6f));
  EXPECT_EQ(s.style.name, "blinn-phong");
  ASSERT_TRUE(s.style.lines.has_value());
  EXPECT_FALSE(s.style.lines->silhouettes);
  EXPECT_TRUE(s.style.lines->creases);
  EXPECT_FLOAT_EQ(s.style.lines->creaseAngle, 30.0f);
  EXPECT_FLOAT_EQ(s.style.lines->depthThreshold, 0.05f);
  EXPECT_FLOAT_EQ(s.style.lines->width, 2.0f);
  EXPECT_EQ(s.style.lines->color, glm::vec3(0.2f));
  EXPECT_EQ(s.style.gooch.cool, glm::vec3(0, 0, 0.4f));
  EXPECT_EQ(s.style.gooch.warm, glm::vec3(0.4f, 0.4f, 0));
  EXPECT_FLOAT_EQ(s.style.gooch.alpha, 0.1f);
  EXPECT_FLOAT_EQ(s.style.gooch.beta, 0.7f);
  EXPECT_FLOAT_EQ(s.style.blinnPhong.ambient, 0.3f);

  ASSERT_EQ(s.lights.size(), 2u);
  EXPECT_EQ(s.lights[0].type, Light::Type::Point);
  EXPECT_EQ(s.lights[0].position, glm::vec3(1, 2, 3));
  EXPECT_EQ(s.lights[0].color, glm::vec3(1, 0.5f, 0.25f));
  EXPECT_FLOAT_EQ(s.lights[0].intensity, 2.5f);
  EXPECT_FALSE(s.lights[0].cameraSpace);
  EXPECT_EQ(s.lights[1].type, Light::Type::Directional);
  EXPECT_VEC3_NEAR(s.lights[1].direction, glm::vec3(0, -1, 0), kEps);  // normalised
  EXPECT_TRUE(s.lights[1].cameraSpace);

  EXPECT_EQ(s.camera.projection, Projection::Orthographic);
  EXPECT_FALSE(s.camera.fit);
  EXPECT_EQ(s.camera.eye, glm::vec3(0, 0, 10));
  EXPECT_EQ(s.camera.target, glm::vec3(0));
  EXPECT_VEC3_NEAR(s.camera.up, glm::vec3(0, 1, 0), kEps);  // normalised
  EXPECT_FLOAT_EQ(s.camera.fovY, 50.0f);
  EXPECT_FLOAT_EQ(s.camera.height, 4.0f);
  EXPECT_FLOAT_EQ(s.camera.near, 0.5f);
  EXPECT_FLOAT_EQ(s.camera.far, 20.0f);
  const Camera resolved = s.resolvedCamera();  // explicit planes stay as given
  EXPECT_FLOAT_EQ(resolved.near, 0.5f);
  EXPECT_FLOAT_EQ(resolved.far, 20.0f);
  EXPECT_EQ(resolved.eye, s.camera.eye);

  ASSERT_EQ(s.objects.size(), 1u);
  const SceneObject& o = s.objects[0];
  EXPECT_EQ(o.role, Role::Interest);
  EXPECT_FLOAT_EQ(o.importance, 0.9f);
  EXPECT_EQ(o.group, "parts");
  ASSERT_EQ(o.params.count("lines"), 1u);
  EXPECT_EQ(std::get<bool>(o.params.at("lines")), false);
  EXPECT_EQ(o.material.color, glm::vec3(0.1f, 0.2f, 0.3f));
  EXPECT_FLOAT_EQ(o.material.specular, 0.6f);
  EXPECT_FLOAT_EQ(o.material.shininess, 64.0f);
}

TEST(SceneLoad, ShortForms) {
  // style as a string, lines: false, background as one colour, no lights at all.
  const Scene s = parse(R"({"style": "blinn-phong", "background": [0.5, 0.5, 0.5], "lights": [],
                            "objects": [{"name": "cube", "file": "cube.obj"}]})");
  EXPECT_EQ(s.style.name, "blinn-phong");
  EXPECT_TRUE(s.style.lines.has_value());
  EXPECT_EQ(s.backgroundTop, glm::vec3(0.5f));
  EXPECT_EQ(s.backgroundBottom, glm::vec3(0.5f));
  EXPECT_TRUE(s.lights.empty());
  const Scene noLines = parse(R"({"style": {"lines": false},
                                  "objects": [{"name": "cube", "file": "cube.obj"}]})");
  EXPECT_EQ(noLines.style.name, "gooch");
  EXPECT_FALSE(noLines.style.lines.has_value());
}

TEST(SceneLoad, RelativePathsResolveAgainstTheSceneFolderAndGzipIsRead) {
  const Scene s = parseScene(R"({"objects": [
      {"name": "relative", "file": "../meshes/tetra.obj"},
      {"name": "compressed", "file": "tetra.stl.gz"}]})",
                             "scene.json", kMeshes);
  ASSERT_EQ(s.objects.size(), 2u);
  EXPECT_EQ(s.objects[0].source, (kMeshes / "../meshes/tetra.obj").string());
  EXPECT_EQ(s.objects[0].mesh->triangles.size(), 4u);
  EXPECT_EQ(s.objects[1].mesh->triangles.size(), 4u);
  EXPECT_TRUE(s.objects[1].mesh->report.watertight);
  EXPECT_EQ(s.objects[1].mesh->bounds().max, glm::vec3(1.0f));
}

TEST(SceneLoad, TransformIsTranslateRotateScale) {
  // p' = T · R · S · p: scale first, then rotate, then translate.
  const Scene s = parse(R"({"objects": [{"name": "cube", "file": "cube.obj",
      "transform": {"translate": [1, 2, 3], "rotate": [0, 0, 90], "scale": [2, 1, 1]}}]})");
  const glm::mat4& m = s.objects[0].transform;
  // (1,0,0) → S (2,0,0) → Rz(90°) (0,2,0) → T (1,4,3).
  EXPECT_VEC3_NEAR(apply(m, {1, 0, 0}), glm::vec3(1, 4, 3), kEps);
  // (0,1,0) → S (0,1,0) → Rz(90°) (−1,0,0) → T (0,2,3).
  EXPECT_VEC3_NEAR(apply(m, {0, 1, 0}), glm::vec3(0, 2, 3), kEps);
  // World bounds follow the transform: x ∈ [0, 1], y ∈ [2, 4], z ∈ [3, 4].
  const Bounds b = s.objects[0].worldBounds();
  EXPECT_VEC3_NEAR(b.min, glm::vec3(0, 2, 3), kEps);
  EXPECT_VEC3_NEAR(b.max, glm::vec3(1, 4, 4), kEps);
}

TEST(SceneLoad, EulerAnglesRotateAboutXThenYThenZ) {
  // R = Rz · Ry · Rx. (0,1,0) → Rx(90°) (0,0,1) → Ry(90°) (1,0,0) → Rz(0) (1,0,0).
  // The other order (Ry first) would give (0,0,1).
  const Scene s = parse(R"({"objects": [{"name": "cube", "file": "cube.obj",
      "transform": {"rotate": [90, 90, 0]}}]})");
  EXPECT_VEC3_NEAR(apply(s.objects[0].transform, {0, 1, 0}), glm::vec3(1, 0, 0), kEps);
  // (1,0,0) → Rx (1,0,0) → Ry(90°) (0,0,−1).
  EXPECT_VEC3_NEAR(apply(s.objects[0].transform, {1, 0, 0}), glm::vec3(0, 0, -1), kEps);
}

TEST(SceneLoad, AxisAngleRotationUniformScaleAndRowMajorMatrix) {
  const Scene s = parse(R"({"objects": [
      {"name": "a", "file": "cube.obj", "transform": {"rotate": {"axis": [0, 0, 2], "degrees": 90}}},
      {"name": "b", "file": "cube.obj", "transform": {"scale": 3}},
      {"name": "c", "file": "cube.obj", "transform": {"matrix": [1, 0, 0, 5,
                                                                0, 2, 0, 6,
                                                                0, 0, 1, 7,
                                                                0, 0, 0, 1]}},
      {"name": "d", "file": "cube.obj", "transform": {"scale": 0.0001}},
      {"name": "e", "file": "cube.obj", "transform": {"matrix": [0.0001, 0, 0, 0,
                                                                0, 0.0001, 0, 0,
                                                                0, 0, 0.0001, 0,
                                                                0, 0, 0, 1]}}]})");
  EXPECT_VEC3_NEAR(apply(s.objects[0].transform, {1, 0, 0}), glm::vec3(0, 1, 0), kEps);
  EXPECT_VEC3_NEAR(apply(s.objects[1].transform, {1, 1, 1}), glm::vec3(3, 3, 3), kEps);
  // Written row by row: the last column is the translation.
  EXPECT_VEC3_NEAR(apply(s.objects[2].transform, {0, 0, 0}), glm::vec3(5, 6, 7), kEps);
  EXPECT_VEC3_NEAR(apply(s.objects[2].transform, {0, 1, 0}), glm::vec3(5, 8, 7), kEps);
  // Small but regular scales are not "zero" or "singular".
  EXPECT_VEC3_NEAR(apply(s.objects[3].transform, {1, 1, 1}), glm::vec3(1e-4f), 1e-9f);
  EXPECT_VEC3_NEAR(apply(s.objects[4].transform, {1, 1, 1}), glm::vec3(1e-4f), 1e-9f);
}

TEST(SceneLoad, SplitNodesNamesObjectsAfterTheNodesAndAppliesOverridesToMatchesOnly) {
  const Scene s = parse(R"({"objects": [{"name": "parts", "file": "two_parts.obj",
      "split": "nodes", "role": "context", "importance": 0.3,
      "overrides": [
        {"match": ".*", "importance": 0.2},
        {"match": "pin", "role": "interest", "importance": 0.9, "group": "pins",
         "color": [0, 1, 0], "params": {"lines": false}, "specular": 0.8, "shininess": 8}
      ]}]})");
  ASSERT_EQ(s.objects.size(), 2u);
  const SceneObject* body = s.find("parts/body");
  const SceneObject* pin = s.find("parts/pin");
  ASSERT_TRUE(body && pin);
  EXPECT_EQ(body->source, (kMeshes / "two_parts.obj").string() + "#body");
  EXPECT_EQ(pin->source, (kMeshes / "two_parts.obj").string() + "#pin");
  EXPECT_EQ(body->mesh->triangles.size(), 12u);
  EXPECT_EQ(pin->mesh->triangles.size(), 4u);

  EXPECT_EQ(body->role, Role::Context);
  EXPECT_FLOAT_EQ(body->importance, 0.2f);  // first override only
  EXPECT_EQ(body->group, "");
  EXPECT_TRUE(body->params.empty());
  EXPECT_VEC3_NEAR(body->material.color, glm::vec3(0.5f), 1e-6f);  // two_parts.mtl "grey"
  EXPECT_FLOAT_EQ(body->material.specular, 0.25f);

  EXPECT_EQ(pin->role, Role::Interest);
  EXPECT_FLOAT_EQ(pin->importance, 0.9f);  // later overrides win
  EXPECT_EQ(pin->group, "pins");
  EXPECT_EQ(std::get<bool>(pin->params.at("lines")), false);
  EXPECT_EQ(pin->material.color, glm::vec3(0, 1, 0));
  EXPECT_FLOAT_EQ(pin->material.specular, 0.8f);
  EXPECT_FLOAT_EQ(pin->material.shininess, 8.0f);
}

TEST(SceneLoad, NodeFilterAndMergedFile) {
  const Scene s = parse(R"({"objects": [
      {"name": "only", "file": "two_parts.obj", "split": "nodes", "nodes": "p.n"},
      {"name": "merged", "file": "two_parts.obj"},
      {"name": "merged-pin", "file": "two_parts.obj", "split": "file", "nodes": "pin"},
      {"name": "coloured", "file": "two_parts.obj", "color": [0.2, 0.4, 0.6]}]})");
  ASSERT_EQ(s.objects.size(), 4u);
  EXPECT_EQ(s.objects[0].name, "only/pin");  // full match: "p.n" matches "pin" only
  EXPECT_EQ(s.objects[1].name, "merged");
  EXPECT_EQ(s.objects[1].source, (kMeshes / "two_parts.obj").string());
  EXPECT_EQ(s.objects[1].mesh->triangles.size(), 16u);
  EXPECT_TRUE(s.objects[1].mesh->report.watertight);  // two closed parts
  EXPECT_VEC3_NEAR(s.objects[1].material.color, glm::vec3(0.5f), 1e-6f);  // first node's colour
  EXPECT_EQ(s.objects[2].mesh->triangles.size(), 4u);
  EXPECT_VEC3_NEAR(s.objects[2].material.color, glm::vec3(0.8f, 0.1f, 0.1f), 1e-6f);
  EXPECT_EQ(s.objects[3].material.color, glm::vec3(0.2f, 0.4f, 0.6f));
}

TEST(SceneLoad, HullProxyIsWatertightAndInWorldSpace) {
  const Scene s = parse(R"({
    "objects": [{"name": "parts", "file": "two_parts.obj", "split": "nodes",
                 "transform": {"translate": [0, 10, 0]}}],
    "proxies": [{"name": "roi", "hullOf": "parts/.*", "group": "focus", "role": "interior",
                 "importance": 0.7, "params": {"lines": true}}]})");
  const SceneObject* roi = s.find("roi");
  ASSERT_TRUE(roi);
  EXPECT_TRUE(roi->proxy);
  EXPECT_EQ(roi->source, "proxy");
  EXPECT_EQ(roi->role, Role::Interior);
  EXPECT_FLOAT_EQ(roi->importance, 0.7f);
  EXPECT_EQ(roi->group, "focus");
  EXPECT_EQ(roi->transform, glm::mat4(1.0f));
  EXPECT_TRUE(roi->mesh->report.watertight);
  EXPECT_EQ(roi->mesh->report.boundaryEdges, 0u);
  // Hull of the unit cube and the tetrahedron at x ∈ [3, 4], lifted by 10 in y.
  const Bounds b = roi->worldBounds();
  EXPECT_VEC3_NEAR(b.min, glm::vec3(0, 10, 0), kEps);
  EXPECT_VEC3_NEAR(b.max, glm::vec3(4, 11, 1), kEps);
  // Every hull triangle faces away from the centroid of the hull's vertices.
  glm::vec3 centroid(0.0f);
  for (const auto& p : roi->mesh->positions) centroid += p;
  centroid /= float(roi->mesh->positions.size());
  for (const auto& t : roi->mesh->triangles) {
    const auto& p = roi->mesh->positions;
    const glm::vec3 n = glm::cross(p[t.y] - p[t.x], p[t.z] - p[t.x]);
    EXPECT_GT(glm::dot(n, (p[t.x] + p[t.y] + p[t.z]) / 3.0f - centroid), 0.0f);
  }
  // Proxies are invisible: they do not count in the scene bounds.
  EXPECT_VEC3_NEAR(s.bounds().min, glm::vec3(0, 10, 0), kEps);
}

TEST(SceneLoad, BoxProxyHasTwelveTrianglesAndDefaults) {
  const Scene s = parse(R"({
    "objects": [{"name": "cube", "file": "cube.obj"}],
    "proxies": [{"name": "roi", "box": {"min": [-1, -2, -3], "max": [1, 2, 3]},
                 "transform": {"translate": [10, 0, 0]}}]})");
  const SceneObject* roi = s.find("roi");
  ASSERT_TRUE(roi);
  EXPECT_TRUE(roi->proxy);
  EXPECT_EQ(roi->role, Role::Interest);       // proxy default
  EXPECT_FLOAT_EQ(roi->importance, 1.0f);     // proxy default
  EXPECT_EQ(roi->mesh->triangles.size(), 12u);
  EXPECT_TRUE(roi->mesh->report.watertight);
  EXPECT_EQ(roi->mesh->bounds().min, glm::vec3(-1, -2, -3));
  EXPECT_EQ(roi->mesh->bounds().max, glm::vec3(1, 2, 3));
  EXPECT_VEC3_NEAR(roi->worldBounds().min, glm::vec3(9, -2, -3), kEps);
  EXPECT_VEC3_NEAR(s.bounds().max, glm::vec3(1, 1, 1), kEps);  // the proxy is not visible
}

TEST(SceneLoad, WatertightnessReports) {
  const Scene s = parse(R"({"objects": [{"name": "cube", "file": "cube.obj"},
                                        {"name": "tetra", "file": "tetra.obj"},
                                        {"name": "open", "file": "open_cube.obj"}]})");
  const MeshReport& cube = s.find("cube")->mesh->report;
  EXPECT_TRUE(cube.watertight);
  EXPECT_EQ(cube.boundaryEdges, 0u);
  EXPECT_EQ(cube.nonManifoldEdges, 0u);
  EXPECT_EQ(cube.misorientedEdges, 0u);
  EXPECT_TRUE(s.find("tetra")->mesh->report.watertight);
  const MeshReport& open = s.find("open")->mesh->report;
  EXPECT_FALSE(open.watertight);
  EXPECT_EQ(open.boundaryEdges, 4u);  // the rim of the missing face
  EXPECT_EQ(open.nonManifoldEdges, 0u);
  EXPECT_EQ(open.misorientedEdges, 0u);
}

// ---------------------------------------------------------------------------------------------
// resolvedCamera(): "fit" frames the scene, and derived near/far planes enclose it.

// The bounds' corners inside the view volume (clip-space |x|, |y|, |z| ≤ w), and the bounding
// sphere between the near and far planes; returns the largest |NDC x|, |NDC y| of a corner.
float checkFramed(const Scene& s, const Camera& c, const std::string& label) {
  const Bounds b = s.bounds();
  const float aspect = float(s.width) / float(s.height);
  const glm::mat4 viewProjection = c.projectionMatrix(aspect) * c.view();
  float extent = 0.0f;
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 corner{(i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y,
                           (i & 4) ? b.max.z : b.min.z};
    const glm::vec4 clip = viewProjection * glm::vec4(corner, 1.0f);
    EXPECT_GT(clip.w, 0.0f) << label << ": corner " << i << " behind the eye";
    const glm::vec3 ndc = glm::vec3(clip) / clip.w;
    EXPECT_LE(std::abs(ndc.x), 1.0f) << label << ": corner " << i << " left/right of the view";
    EXPECT_LE(std::abs(ndc.y), 1.0f) << label << ": corner " << i << " above/below the view";
    EXPECT_LE(std::abs(ndc.z), 1.0f) << label << ": corner " << i << " outside near/far";
    extent = std::max({extent, std::abs(ndc.x), std::abs(ndc.y)});
  }
  const glm::vec3 forward = glm::normalize(c.target - c.eye);
  const float centerDepth = glm::dot(b.center() - c.eye, forward);
  EXPECT_GT(c.near, 0.0f) << label;
  EXPECT_LE(c.near, centerDepth - b.radius()) << label << ": near cuts the bounding sphere";
  EXPECT_GE(c.far, centerDepth + b.radius()) << label << ": far cuts the bounding sphere";
  return extent;
}

TEST(SceneCamera, FitFramesTheWholeSceneFromAnyDirection) {
  const char* scene = R"({"resolution": [%d, %d], "objects": [
      {"name": "cube", "file": "cube.obj", "transform": {"scale": [4, 1, 2]}},
      {"name": "tetra", "file": "tetra.obj", "transform": {"translate": [-3, 5, 1]}}],
      "camera": {"fit": true, "projection": "%s", "eye": [%g, %g, %g], "target": [0, 0, 0],
                 "fov": %g}})";
  struct Case { int w, h; const char* projection; glm::vec3 eye; float fov; };
  const Case cases[] = {
      {800, 600, "perspective", {1, 0.8f, 1.4f}, 40}, {600, 800, "perspective", {0, 0, 1}, 40},
      {1600, 400, "perspective", {-2, 1, -0.5f}, 25}, {400, 1600, "perspective", {0.1f, -3, 1}, 90},
      {800, 600, "orthographic", {1, 1, 1}, 40},      {300, 900, "orthographic", {-1, 0.2f, 0}, 40},
  };
  for (const auto& k : cases) {
    char text[1024];
    std::snprintf(text, sizeof text, scene, k.w, k.h, k.projection, k.eye.x, k.eye.y, k.eye.z, k.fov);
    const std::string label = std::string(k.projection) + " " + std::to_string(k.w) + "x" +
                              std::to_string(k.h) + " from (" + std::to_string(k.eye.x) + ", " +
                              std::to_string(k.eye.y) + ", " + std::to_string(k.eye.z) + ")";
    const Scene s = parse(text);
    const Camera c = s.resolvedCamera();
    // Aimed at the centre of the bounds, from the direction eye − target of the file.
    EXPECT_VEC3_NEAR(c.target, s.bounds().center(), 1e-4f);
    EXPECT_VEC3_NEAR(glm::normalize(c.eye - c.target), glm::normalize(k.eye), 1e-4f);
    const float extent = checkFramed(s, c, label);
    // …and fills the view: some corner reaches at least half-way to the border.
    EXPECT_GE(extent, 0.5f) << label;
  }
}

TEST(SceneCamera, DefaultCameraFitsLookingDownMinusZ) {
  const Scene s = parse(R"({"objects": [{"name": "cube", "file": "cube.obj"}]})");
  const Camera c = s.resolvedCamera();
  EXPECT_VEC3_NEAR(c.target, glm::vec3(0.5f), 1e-5f);
  EXPECT_NEAR(c.eye.x, 0.5f, 1e-5f);
  EXPECT_NEAR(c.eye.y, 0.5f, 1e-5f);
  EXPECT_GT(c.eye.z, 1.0f);
  checkFramed(s, c, "default camera");
}

TEST(SceneCamera, DerivedPlanesEncloseTheSceneWithoutFit) {
  const Scene s = parse(R"({"objects": [{"name": "cube", "file": "cube.obj"}],
                            "camera": {"eye": [0.5, 0.5, 30], "target": [0.5, 0.5, 0.5], "fov": 10}})");
  EXPECT_FALSE(s.camera.fit);
  const Camera c = s.resolvedCamera();
  EXPECT_EQ(c.eye, s.camera.eye);
  EXPECT_EQ(c.target, s.camera.target);
  EXPECT_LT(c.near, c.far);
  checkFramed(s, c, "explicit camera");
}

}  // namespace
