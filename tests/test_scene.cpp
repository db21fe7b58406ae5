// Tests of the JSON scene format (docs/scene-format.md): malformed files are rejected with the
// file, the JSON pointer and the reason; valid files load with the documented defaults.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "cutaway/core/error.hpp"
#include "cutaway/cutters/adaptive.hpp"
#include "cutaway/fields/cutaway_surface.hpp"
#include "cutaway/render/renderer.hpp"
#include "cutaway/render/techniques.hpp"
#include "cutaway/scene/scene.hpp"
#include "cutaway/styles/blinn_phong.hpp"
#include "cutaway/styles/gooch.hpp"
#include "cutaway/styles/hatching.hpp"
#include "cutaway/styles/toon.hpp"
#include "expect_error.hpp"

// Readable failure messages for glm values (found by argument-dependent lookup).
namespace glm {
inline void PrintTo(const vec3& v, std::ostream* os) {
  *os << "(" << v.x << ", " << v.y << ", " << v.z << ")";
}
}  // namespace glm

using namespace cutaway;

namespace {

const std::filesystem::path kData = CUTAWAY_TEST_DATA;
const std::filesystem::path kMeshes = kData / "meshes";

// Parses `text` as if it were a file in tests/data/meshes, so that "cube.obj" resolves.
Scene parse(const std::string& text) {
  return parseScene(text, "inline.json", kMeshes);
}

glm::vec3 apply(const glm::mat4& m, const glm::vec3& p) {
  return glm::vec3(m * glm::vec4(p, 1.0f));
}

// Tolerance for transformed unit-sized coordinates: a few float ulps of cos/sin(90°).
constexpr float kEps = 1e-5f;

// The scene's options of a cutter, or its defaults when it is off.
template <class O>
const O* optionsOr(const Scene& s) {
  static const O kDefaults{};
  const O* o = s.cutters.find<O>();
  return o ? o : &kDefaults;
}

#define EXPECT_VEC3_NEAR(actual, expected, eps)      \
  do {                                               \
    const glm::vec3 a_ = (actual), e_ = (expected);  \
    EXPECT_NEAR(a_.x, e_.x, eps) << "x of " #actual; \
    EXPECT_NEAR(a_.y, e_.y, eps) << "y of " #actual; \
    EXPECT_NEAR(a_.z, e_.z, eps) << "z of " #actual; \
  } while (0)

// ---------------------------------------------------------------------------------------------
// Malformed scene files: one file per mistake, each with the JSON pointer (or, for syntax
// errors, the line and column) and a substring of the reason that the error must carry.

struct BadScene {
  const char* file;    // under tests/data/bad
  const char* place;   // Error::place(): a JSON pointer, or "line L, column C"
  const char* reason;  // substring of Error::reason()
};

const BadScene kBadScenes[] = {
    // Syntax: the '}' after a trailing comma, 4th line, 51st character.
    {"syntax_error.json", "line 4, column 51", "invalid JSON: syntax error"},
    {"not_an_object.json", "/", "expected an object, got array"},
    // A number beyond double range: "1e999" ends at column 18 of line 2.
    {"number_overflow.json", "line 2, column 18", "invalid JSON: number overflow parsing '1e999'"},
    // Top level.
    {"unknown_top_level_key.json", "/colour", "unknown key \"colour\""},
    {"unknown_key_with_slash.json", "/style~1name",
     "unknown key \"style/name\""},  // RFC 6901 escape
    {"missing_objects.json", "/", "missing required key \"objects\""},
    {"empty_objects.json", "/objects", "a scene needs at least one object, pipe network or volume"},
    {"objects_not_array.json", "/objects", "expected an array, got object"},
    {"version_two.json", "/version", "value 2 is outside [1, 1]"},
    {"resolution_one_number.json", "/resolution", "expected [width, height]"},
    {"resolution_zero.json", "/resolution/0", "value 0 is outside [1, 16384]"},
    {"resolution_not_integer.json", "/resolution/0", "expected an integer, got number"},
    {"samples_three.json", "/samples", "samples must be 1, 2, 4, 8 or 16"},
    {"pixel_error_negative.json", "/pixelError", "value -1 is outside [0, 100]"},
    {"background_missing_bottom.json", "/background", "missing required key \"bottom\""},
    // Objects.
    {"unknown_object_key.json", "/objects/0/material", "unknown key \"material\""},
    {"missing_file_key.json", "/objects/0",
     "needs exactly one of \"file\", \"raster\", \"footprints\" or \"arrays\""},
    {"object_file_and_raster.json", "/objects/0", "needs exactly one of"},
    {"raster_not_found.json", "/objects/0/raster/file", "raster file not found"},
    {"raster_step_zero.json", "/objects/0/raster/step", "outside [1, "},
    {"raster_unknown_key.json", "/objects/0/raster/steps", "unknown key \"steps\""},
    {"raster_with_split.json", "/objects/0/split", "\"split\" needs a mesh \"file\""},
    {"raster_not_an_object.json", "/objects/0/raster", "expected an object, got string"},
    {"footprints_on_unknown.json", "/objects/0/footprints/on", "no object named \"ground\""},
    {"footprints_not_polygons.json", "/objects/0/footprints/file", "not polygons"},
    {"footprints_height_field_missing.json", "/objects/0/footprints/file",
     "no attribute field \"HEIGHT\""},
    {"footprints_height_field_text.json", "/objects/0/footprints/file", "not numbers"},
    {"footprints_height_negative.json", "/objects/0/footprints/height", "outside"},
    {"footprints_without_height.json", "/objects/0/footprints", "missing required key \"height\""},
    {"mesh_not_found.json", "/objects/0/file", "mesh file not found"},
    {"wrong_type_importance.json", "/objects/0/importance", "expected a number, got string"},
    {"importance_out_of_range.json", "/objects/0/importance", "value 1.5 is outside [0, 1]"},
    {"bad_role.json", "/objects/0/role", "unknown value \"focus\""},
    {"color_four_elements.json", "/objects/0/color",
     "expected an array of 3 numbers, got 4 elements"},
    {"color_above_one.json", "/objects/0/color/0", "value 255 is outside [0, 1]"},
    {"bad_split.json", "/objects/0/split", "unknown value \"parts\""},
    {"bad_regex.json", "/objects/0/nodes", "invalid regular expression \"(body\""},
    {"nodes_match_nothing.json", "/objects/0/nodes", "no mesh node of"},
    {"duplicate_names.json", "/objects", "two objects are named \"cube\""},
    {"unknown_object_param.json", "/objects/0/params/glow", "unknown object parameter \"glow\""},
    {"object_param_wrong_type.json", "/objects/0/params/lines",
     "expected true or false, got number"},
    {"override_without_split.json", "/objects/0/overrides", "overrides need \"split\": \"nodes\""},
    {"override_without_match.json", "/objects/0/overrides/0", "missing required key \"match\""},
    {"override_unknown_key.json", "/objects/0/overrides/0/file", "unknown key \"file\""},
    // Transforms.
    {"transform_matrix_and_translate.json", "/objects/0/transform/translate",
     "\"matrix\" excludes"},
    {"transform_singular_matrix.json", "/objects/0/transform/matrix", "the matrix is singular"},
    {"transform_projective_matrix.json", "/objects/0/transform/matrix",
     "the last row must be 0, 0, 0, 1"},
    {"transform_matrix_15.json", "/objects/0/transform/matrix", "expected 16 numbers"},
    {"transform_zero_scale.json", "/objects/0/transform/scale", "scale must not be zero"},
    {"transform_rotate_zero_axis.json", "/objects/0/transform/rotate/axis",
     "must not be the zero vector"},
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
    {"camera_without_eye.json", "/camera",
     "needs \"eye\" and \"target\", a \"path\", or \"fit\": true"},
    {"camera_fov_too_wide.json", "/camera/fov", "value 180 is outside [1, 170]"},
    // Camera paths.
    {"camera_path_eye_equals_target.json", "/camera/path/1/eye", "eye and target coincide"},
    {"camera_path_times_not_increasing.json", "/camera/path/1/time",
     "camera key times must increase"},
    {"camera_path_times_one_float.json", "/camera/path/1/time",
     "camera key times must increase: 1e-300 and 0 are one time in 32-bit floats"},
    {"camera_path_key_without_target.json", "/camera/path/0", "missing required key \"target\""},
    {"camera_path_empty.json", "/camera/path", "expected a non-empty array of camera keys"},
    // Style.
    {"style_unknown_name.json", "/style", "unknown value \"watercolour\""},
    {"style_unknown_line_key.json", "/style/lines/thickness", "unknown key \"thickness\""},
    {"style_line_width.json", "/style/lines/width", "value 20 is outside [0.5, 8]"},
    // Keys that take a bool, a name or an object say so.
    {"style_null.json", "/style", "expected a style's name or an object, got null"},
    {"style_lines_null.json", "/style/lines", "expected true, false or an object, got null"},
    {"adaptive_ghost_lines_number.json", "/cutters/adaptive/ghostLines",
     "expected true, false or an object, got number"},
    {"style_toon_ramp_one_tone.json", "/style/toon/ramp",
     "expected an array of 2 to 16 tones (numbers or colours), got 1 element"},
    {"style_toon_ramp_four_channels.json", "/style/toon/ramp/1",
     "expected an array of 3 numbers, got 4 elements"},
    {"style_toon_ramp_tone_above_one.json", "/style/toon/ramp/1", "value 1.5 is outside [0, 1]"},
    {"style_toon_unknown_key.json", "/style/toon/bands",
     "unknown key \"bands\" (expected one of: highlight, highlightColor, highlightThreshold, "
     "ramp)"},
    {"style_toon_highlight_not_bool.json", "/style/toon/highlight",
     "expected true or false, got string"},
    {"style_hatching_one_tone.json", "/style/hatching/tones", "value 1 is outside [2, 12]"},
    {"style_hatching_zero_scale.json", "/style/hatching/scale", "value 0 is outside [0.001, 10]"},
    {"style_hatching_paper_not_colour.json", "/style/hatching/paper",
     "expected an array of 3 numbers, got string"},
    {"style_hatching_bad_lightness.json", "/style/hatching/lightness",
     "unknown value \"phong\" (expected one of: lambert, gooch)"},
    {"style_hatching_unknown_key.json", "/style/hatching/angle", "unknown key \"angle\""},
    {"style_shadows_size_not_power_of_two.json", "/style/shadows/size", "must be a power of two"},
    {"style_shadows_unknown_key.json", "/style/shadows/softness",
     "unknown key \"softness\" (expected one of: bias, enabled, pcfRadius, size, slopeBias)"},
    {"style_shadows_pcf_radius_9.json", "/style/shadows/pcfRadius", "value 9 is outside [0, 4]"},
    {"style_shadows_string.json", "/style/shadows",
     "expected true, false or an object, got string"},
    {"object_casts_shadow_number.json", "/objects/0/params/castsShadow",
     "expected true or false, got number"},
    // Lights.
    {"light_zero_direction.json", "/lights/0/direction", "must not be the zero vector"},
    {"light_unknown_type.json", "/lights/0/type", "unknown value \"spot\""},
    {"light_point_with_direction.json", "/lights/0/direction", "unknown key \"direction\""},
    {"light_too_many.json", "/lights", "at most 8 lights, got 9"},
    // Cutters: the adaptive cutaway.
    {"cutters_unknown_cutter.json", "/cutters/diepstraten",
     "unknown key \"diepstraten\" (expected one of: adaptive, boxCut, breakaway, clipSurfaces, "
     "cutout, terrainOpening)"},
    // Cutters: Diepstraten03 cutout and breakaway.
    {"cutout_angle_0.json", "/cutters/cutout/angle", "value 0 is outside [1, 180]"},
    {"cutout_jitter_unknown_pattern.json", "/cutters/cutout/jitter/pattern",
     "unknown value \"zigzag\""},
    {"cutout_jitter_image_without_file.json", "/cutters/cutout/jitter",
     "pattern \"image\" needs an \"image\" file"},
    {"cutout_jitter_image_missing.json", "/cutters/cutout/jitter/image", "no such image file"},
    {"cutout_jitter_image_not_png.json", "/cutters/cutout/jitter/image",
     "cannot read PNG: not a PNG file (no PNG signature)"},
    {"cutout_clip_planes_jitter.json", "/cutters/cutout/jitter",
     "the clip-plane method cannot jitter"},
    {"cutout_axial_range_empty.json", "/cutters/cutout/axialRange", "must not be empty"},
    {"cutout_no_exterior.json", "/cutters/cutout", "no object has role \"exterior\""},
    {"breakaway_no_interior.json", "/cutters/breakaway", "no object has role \"interior\""},
    {"breakaway_thickness_above_offset.json", "/cutters/breakaway/wallThickness",
     "must not exceed the offset"},
    // Cutters: Trapp13 clip surfaces.
    {"clip_offset_map_missing.json", "/cutters/clipSurfaces/surfaces/0/offsetMap",
     "no such offset map"},
    {"clip_offset_map_not_png.json", "/cutters/clipSurfaces/surfaces/0/offsetMap",
     "cannot read PNG: not a PNG file (no PNG signature)"},
    {"clip_u_too_long.json", "/cutters/clipSurfaces/surfaces/0/u",
     "its length, 1e+20, lies outside [1e-15, 1e15] scene units"},
    {"clip_uv_not_orthogonal.json", "/cutters/clipSurfaces/surfaces/0/v",
     "u and v must be orthogonal"},
    {"clip_five_surfaces.json", "/cutters/clipSurfaces/surfaces", "expected 1 to 4 entries, got 5"},
    {"clip_offset_pattern_unknown.json", "/cutters/clipSurfaces/surfaces/0/offsetMap/pattern",
     "unknown value \"waves\""},
    {"clip_blend_one_layer.json", "/cutters/clipSurfaces/surfaces/0/offsetMap/layers",
     "expected two offset maps to blend"},
    {"clip_scale_zero.json", "/cutters/clipSurfaces/surfaces/0/scale",
     "repeats (x, y) must be > 0"},
    {"clip_parity_unknown.json", "/cutters/clipSurfaces/parity", "unknown value \"sometimes\""},
    // The geographic frame.
    {"geo_unknown_crs.json", "/geo/crs", "unknown CRS \"EPSG:999999\""},
    {"geo_offset_short.json", "/geo/offset", "expected [easting, northing]"},
    // Konev18 pipe networks.
    {"network_no_pipes.json", "/networks/0/pipes", "non-empty array"},
    {"network_repeated_nodes.json", "/networks/0/pipes/0/lines/0", "at least two distinct nodes"},
    {"network_missing_value.json", "/networks/0/pipes/0/file",
     "feature 1 has no value for \"DIAM\""},
    {"network_value_out_of_range.json", "/networks/0/pipes/0/file",
     "feature 1 has \"DIAM\" = 1e+300 (× scale: 1e+297), outside [0.0001, 1000]"},
    {"network_missing_field.json", "/networks/0/pipes/0/file", "no attribute field \"WIDTH\""},
    {"network_empty_layer.json", "/networks/0/pipes/0/file", "the layer is empty"},
    {"network_shafts_both.json", "/networks/0/shafts", "exactly one of \"file\""},
    {"network_terrain_matches_nothing.json", "/networks/0/terrain", "no object name matches"},
    {"network_wall_too_thick.json", "/networks/0/pipes/0/lines/0",
     "wall thickness 0.5 must be less than the radius 0.5"},
    {"network_shaft_wall_too_thick.json", "/networks/0/shafts/wallThickness",
     "wall thickness must be less than their radius"},
    {"network_duplicate_name.json", "/networks/1/name", "two networks are named \"n\""},
    {"terrain_buildings_match_nothing.json", "/cutters/terrainOpening/buildings",
     "no object name matches \"houses.*\""},
    // Cutters: Konev18 terrain opening.
    {"terrain_no_network.json", "/cutters/terrainOpening", "no network"},
    {"terrain_line_one_node.json", "/cutters/terrainOpening/lines/1",
     "a polyline needs at least two distinct [x, z] nodes"},
    {"terrain_matches_nothing.json", "/cutters/terrainOpening/terrain", "no object name matches"},
    {"terrain_empty_pattern.json", "/cutters/terrainOpening/terrain", "required: a pattern"},
    {"terrain_network_missing.json", "/cutters/terrainOpening/network/0", "no-such.shp"},
    {"object_param_solid_number.json", "/objects/0/params/solid",
     "expected true or false, got number"},
    {"cutters_not_an_object.json", "/cutters", "expected an object, got string"},
    {"adaptive_false.json", "/cutters/adaptive", "use true or an object"},
    {"adaptive_unknown_key.json", "/cutters/adaptive/anlge", "unknown key \"anlge\""},
    {"adaptive_angle_95.json", "/cutters/adaptive/angle", "value 95 is outside [0, 90]"},
    {"adaptive_buffer_size_8.json", "/cutters/adaptive/bufferSize",
     "value 8 is outside [16, 8192]"},
    {"adaptive_buffer_size_not_integer.json", "/cutters/adaptive/bufferSize",
     "expected an integer, got number"},
    {"adaptive_bad_jump_flooding.json", "/cutters/adaptive/jumpFlooding",
     "unknown value \"jfa+3\" (expected one of: jfa, jfa+1, 1+jfa, jfa+2)"},
    {"adaptive_bad_compute.json", "/cutters/adaptive/compute",
     "unknown value \"cuda\" (expected one of: auto, gpu, cpu)"},
    {"adaptive_bad_cut_surfaces.json", "/cutters/adaptive/cutSurfaces", "unknown value \"closed\""},
    {"adaptive_edge_compression_zero.json", "/cutters/adaptive/edgeCompression",
     "value 0 is outside [0.001, 1]"},
    {"adaptive_floor_normal_zero.json", "/cutters/adaptive/floorNormal",
     "must not be the zero vector"},
    {"adaptive_ghost_lines_unknown_key.json", "/cutters/adaptive/ghostLines/width",
     "unknown key \"width\" (expected one of: distance, opacity)"},
    {"adaptive_ghost_opacity_above_one.json", "/cutters/adaptive/ghostLines/opacity",
     "value 1.5 is outside [0, 1]"},
    {"adaptive_contextual_transition_below_angle.json", "/cutters/adaptive/contextual",
     "the transition angle θ₂ (30) must not be below the angle θ₁ (40)"},
    {"adaptive_contextual_negative_overlay.json", "/cutters/adaptive/contextual/overlay",
     "value -1 is outside [0, 1e+30]"},
    {"adaptive_contextual_bad_reduction.json", "/cutters/adaptive/contextual/reduction",
     "unknown value \"translucent\" (expected one of: auto, importance, occlusion)"},
    {"adaptive_contextual_bad_apply.json", "/cutters/adaptive/contextual/apply",
     "unknown value \"transparent\" (expected one of: cut, translucency, edgeHighlights, lines)"},
    {"adaptive_contextual_zero_layers.json", "/cutters/adaptive/contextual/layers",
     "value 0 is outside [1, 64]"},
    {"emphasis_color_above_one.json", "/style/emphasis/color", "value 1.5 is outside [0, 1]"},
    {"object_cutaway_angle_120.json", "/objects/0/params/cutawayAngle",
     "value 120 is outside [0, 90]"},
    // Animation.
    {"animation_times_not_increasing.json", "/objects/0/animation/1/time",
     "keyframe times must increase"},
    {"animation_times_one_float.json", "/objects/0/animation/1/time",
     "keyframe times must increase: 1e+06 and 999999.99 are one time in 32-bit floats"},
    {"animation_keyframe_without_time.json", "/objects/0/animation/1",
     "missing required key \"time\""},
    {"animation_empty.json", "/objects/0/animation", "expected a non-empty array of keyframes"},
    {"animation_negative_time.json", "/objects/0/animation/0/time",
     "value -1 is outside [0, 1000000]"},
    {"animation_keyframe_matrix.json", "/objects/0/animation/0/matrix", "unknown key \"matrix\""},
    {"animation_proxy_zero_scale.json", "/proxies/0/animation/1/scale", "scale must not be zero"},
    // Volumes.
    {"volume_missing_transfer_function.json", "/volumes/0",
     "missing required key \"transferFunction\""},
    {"volume_labels_fractional.json", "/volumes/0/transferFunction/1/value",
     "a label volume's points are whole label values"},
    {"volume_not_a_volume.json", "/volumes/0/file", "unknown volume format (expected"},
    {"volume_name_taken.json", "/volumes/0/name", "the name \"head\" is taken"},
};

void PrintTo(const BadScene& bad, std::ostream* os) {
  *os << bad.file;
}

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

// Issue 16: "scale": 1e30 was accepted and rendered blank (the camera turned NaN). What 32-bit
// floats cannot render is refused, naming the object; far but renderable scenes load.
TEST(SceneErrors, ObjectsBeyondWhatFloatsCanRenderAreRefused) {
  for (const char* transform :
       {R"("scale": 1e30)", R"("scale": 1e16)", R"("translate": [1e20, 0, 0])"}) {
    const std::string json =
        std::string(R"({"objects": [{"name": "far", "file": "cube.obj", "transform": {)") +
        transform + "}}]}";
    test::expectError([&] { (void)parseScene(json, "far.json", kMeshes); },
                      {"far.json", "/objects", "\"far\" reaches", "1e15"});
  }
  EXPECT_NO_THROW((void)parseScene(
      R"({"objects": [{"name": "far", "file": "cube.obj", "transform": {"scale": 1e10}}]})",
      "far.json", kMeshes));
  // A proxy too, at its own entry (it was named as a camera that is not finite).
  test::expectError(
      [&] {
        (void)parseScene(R"({"objects": [{"name": "a", "file": "cube.obj"}], "proxies": [
          {"name": "near", "box": {"min": [0, 0, 0], "max": [1, 1, 1]}},
          {"name": "huge", "box": {"min": [-1e30, -1e30, -1e30], "max": [1e30, 1e30, 1e30]}}]})",
                         "far.json", kMeshes);
      },
      {"far.json", "/proxies/1", "\"huge\" reaches", "1e15"});
}

// …and below: a part under 1e-15 across lost its shading (squared normals underflow near
// 1e-20) with exit 0.
TEST(SceneErrors, ObjectsTooSmallForFloatsToShadeAreRefused) {
  test::expectError(
      [&] {
        (void)parseScene(
            R"({"objects": [{"name": "speck", "file": "cube.obj", "transform": {"scale": 1e-16}}]})",
            "small.json", kMeshes);
      },
      {"small.json", "/objects", "\"speck\" measures", "smaller than 1e-15 (scale it up)"});
  EXPECT_NO_THROW((void)parseScene(
      R"({"objects": [{"name": "speck", "file": "cube.obj", "transform": {"scale": 1e-14}}]})",
      "small.json", kMeshes));
}

// The camera too: an eye 1e20 away was refused as "up is parallel to the viewing direction"
// (the direction's squared length overflowed to a zero vector).
TEST(SceneErrors, ACameraBeyondWhatFloatsCanRenderIsRefused) {
  for (const auto& [given, place] : std::vector<std::pair<std::string, std::string>>{
           {R"("eye": [0, 0, 1e20], "target": [0, 0, 0])", "/camera/eye"},
           {R"("eye": [0, 0, 5], "target": [-1e16, 0, 0])", "/camera/target"},
           {R"("path": [{"time": 0, "eye": [1e30, 0, 0], "target": [0, 0, 0]}])",
            "/camera/path/0/eye"}})
    test::expectError(
        [&camera = given] {
          (void)parseScene(
              R"({"objects": [{"name": "a", "file": "cube.obj"}], "camera": {)" + camera + "}}",
              "far.json", kMeshes);
        },
        {"far.json", place, "32-bit floats cannot render beyond 1e15"});
  EXPECT_NO_THROW((void)parseScene(
      R"({"objects": [{"name": "a", "file": "cube.obj"}],
          "camera": {"eye": [0, 0, 1e15], "target": [0, 0, 0]}})",
      "far.json", kMeshes));
}

// Directions of any length but zero are taken, normalised in double: a float's squared length
// overflowed past 1e19 (up [1e20, 1e20, 0] refused as parallel to the view) and underflowed
// below 1e-19 (refused as the zero vector).
TEST(SceneLoad, DirectionsOfAnyNonZeroLengthAreNormalised) {
  for (const char* up : {"[1e20, 1e20, 0]", "[1e-20, 1e-20, 0]", "[1e30, 1e30, 0]", "[1, 1, 0]"}) {
    SCOPED_TRACE(up);
    const Scene s = parseScene(R"({"objects": [{"name": "a", "file": "cube.obj"}],
        "camera": {"eye": [3, 3, 3], "target": [0, 0, 0], "up": )" +
                                   std::string(up) + R"(},
        "lights": [{"type": "directional", "direction": )" +
                                   up + "}]}",
                               "up.json", kMeshes);
    for (const glm::vec3& v : {s.camera.up, s.lights.at(0).direction}) {
      EXPECT_NEAR(v.x, std::sqrt(0.5f), 1e-6f);
      EXPECT_NEAR(v.y, std::sqrt(0.5f), 1e-6f);
      EXPECT_EQ(v.z, 0.0f);
    }
  }
  test::expectError(
      [] {
        (void)parseScene(R"({"objects": [{"name": "a", "file": "cube.obj"}],
            "camera": {"eye": [3, 3, 3], "target": [0, 0, 0], "up": [0, 0, 0]}})",
                         "up.json", kMeshes);
      },
      {"up.json", "/camera/up", "must not be the zero vector"});
}

// Issue 16: a NUL inside a file name cut it ("cube.obj\u0000.png" opened cube.obj); no string
// of a scene may hold one.
TEST(SceneErrors, StringsWithANulCharacterAreRefused) {
  test::expectError(
      [] {
        (void)parseScene(R"({"objects": [{"name": "a", "file": "cube.obj\u0000.png"}]})",
                         "nul.json", kMeshes);
      },
      {"nul.json", "/objects/0/file", "NUL character (at 8)"});
  test::expectError(
      [] {
        (void)parseScene(R"({"objects": [{"name": "a\u0000b", "file": "cube.obj"}]})", "nul.json",
                         kMeshes);
      },
      {"/objects/0/name", "NUL"});
}

// std::regex compiles by recursion: a pattern thousands of groups deep, or thousands of terms
// long, would exhaust the stack. Both are refused before compiling, in a scene file and by
// Scene::setImportance, with the pattern cut short in the message.
TEST(SceneErrors, NamePatternsTooDeepOrTooLongAreRefusedBeforeCompiling) {
  const std::string deep = std::string(20000, '(') + "a" + std::string(20000, ')');
  const std::string chained(400000, 'a');
  for (const std::string& pattern : {deep, chained}) {
    const std::string json =
        R"({"objects": [{"name": "a", "file": "cube.obj", "nodes": ")" + pattern + R"("}]})";
    try {
      (void)parseScene(json, "pattern.json", kMeshes);
      FAIL() << "accepted a pattern of " << pattern.size() << " characters";
    } catch (const Error& e) {
      EXPECT_EQ(e.place(), "/objects/0/nodes");
      EXPECT_LT(std::string(e.what()).size(), 200u) << e.what();
    }
    Scene scene =
        parseScene(R"({"objects": [{"name": "a", "file": "cube.obj"}]})", "s.json", kMeshes);
    try {
      scene.setImportance(pattern, 0.5f);
      FAIL() << "accepted a pattern of " << pattern.size() << " characters";
    } catch (const Error& e) {
      EXPECT_LT(std::string(e.what()).size(), 200u) << e.what();
      EXPECT_NE(e.reason().find("regular expression"), std::string::npos) << e.what();
    }
  }
  // At the limits, patterns compile and match.
  Scene scene =
      parseScene(R"({"objects": [{"name": "a", "file": "cube.obj"}]})", "s.json", kMeshes);
  EXPECT_EQ(scene.setImportance(std::string(64, '(') + "a" + std::string(64, ')'), 0.5f), 1u);
  EXPECT_EQ(scene.setImportance("a|" + std::string(1022 - 2, 'b'), 0.5f), 1u);
}

// A backtracking matcher takes exponential time on "(a*)*b" against a's (26 of them ran for
// minutes, a minute-long `--importance` or "hullOf"); the breadth-first one answers at once,
// and refuses back-references, which it cannot match.
TEST(SceneErrors, NamePatternsMatchWithoutBacktracking) {
  const std::string name(1024, 'a');
  Scene scene = parseScene(R"({"objects": [{"name": ")" + name + R"(", "file": "cube.obj"}]})",
                           "s.json", kMeshes);
  try {
    scene.setImportance("(a*)*b", 0.5f);
    FAIL() << "(a*)*b matched";
  } catch (const Error& e) {
    EXPECT_NE(e.reason().find("matches no object"), std::string::npos) << e.what();
  }
  EXPECT_EQ(scene.setImportance("(a*)*", 0.5f), 1u);
  EXPECT_EQ(scene.setImportance("(a|aa)*(b|a)", 0.5f), 1u);
  try {
    scene.setImportance("(a)\\1.*", 0.5f);
    FAIL() << "accepted a back-reference";
  } catch (const Error& e) {
    EXPECT_NE(e.reason().find("back-reference"), std::string::npos) << e.what();
  }
  try {
    (void)parseScene(R"({"objects": [{"name": "a", "file": "cube.obj"}],
                        "proxies": [{"name": "p", "hullOf": "(a)\\1"}]})",
                     "s.json", kMeshes);
    FAIL() << "accepted a back-reference";
  } catch (const Error& e) {
    EXPECT_EQ(e.place(), "/proxies/0/hullOf");
  }
}

// std::regex's backtracking matcher recursed a frame or so per character of the name: a name of
// 16,000 characters overflowed the stack against "(a|b)*". Names are refused beyond 1,024
// characters; at that length every name a pattern can match (objects, groups, proxies, volumes,
// networks) matches the costliest patterns within the limits.
TEST(SceneErrors, NamesTooLongToMatchAreRefused) {
  const std::string longest(1024, 'a'), tooLong(1025, 'a');
  for (const auto& [json, place] : std::vector<std::pair<std::string, std::string>>{
           {R"({"objects": [{"name": "N", "file": "cube.obj"}]})", "/objects/0/name"},
           {R"({"objects": [{"name": "a", "file": "cube.obj", "group": "N"}]})",
            "/objects/0/group"},
           {R"({"objects": [{"name": "a", "file": "cube.obj"}],
                "proxies": [{"name": "N", "hullOf": "a"}]})",
            "/proxies/0/name"}}) {
    const auto with = [&json = json](const std::string& name) {
      std::string s = json;
      s.replace(s.find("\"N\""), 3, "\"" + name + "\"");
      return s;
    };
    try {
      (void)parseScene(with(tooLong), "long.json", kMeshes);
      FAIL() << "accepted " << place << " of 1025 characters";
    } catch (const Error& e) {
      EXPECT_EQ(e.place(), place);
      EXPECT_NE(e.reason().find("1025 characters (at most 1024)"), std::string::npos) << e.what();
    }
    Scene scene = parseScene(with(longest), "long.json", kMeshes);
    for (const std::string& pattern : {".*", "(a|b)*", "((a)|(b))*", "(.*)*"})
      EXPECT_GE(scene.setImportance(pattern, 0.5f), 1u) << place << " " << pattern;
  }
}

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
  // nlohmann's parser ends its input at a NUL byte: what follows one was ignored.
  try {
    (void)parseScene(std::string("{}\n") + '\0' + "not JSON", "nul.json", kMeshes);
    FAIL() << "text after a NUL byte was ignored";
  } catch (const Error& e) {
    EXPECT_EQ(e.place(), "line 2, column 1") << e.what();
    EXPECT_EQ(e.reason(), "invalid JSON: a NUL byte") << e.what();
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
    EXPECT_EQ(e.place(), "/proxies/0/name");
    EXPECT_NE(e.reason().find("the name \"cube\" is taken"), std::string::npos) << e.what();
  }
}

// ---------------------------------------------------------------------------------------------
// Valid scenes.

TEST(SceneLoad, PipeNetworksAloneMakeAScene) {
  const Scene s = parse(R"({"networks": [{"name": "n", "wallThickness": 0.1,
      "pipes": [{"lines": [[[0, 0, 0], [4, 0, 0]]], "radius": 0.5}]}]})");
  EXPECT_TRUE(s.objects.empty());
  ASSERT_EQ(s.networks.size(), 1u);
  // The camera fits the network: its bounds are the pipe's, radius included.
  EXPECT_NEAR(s.bounds().max.x, 4.5f, 1e-5f);
  EXPECT_NEAR(s.bounds().min.y, -0.5f, 1e-5f);
}

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
  EXPECT_TRUE(s.camera.path.empty());
  // No cutter, no motion.
  EXPECT_FALSE((s.cutters.find<AdaptiveCutawayOptions>() != nullptr));
  EXPECT_EQ(s.duration(), 0.0f);

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
  EXPECT_TRUE(o.animation.empty());
  EXPECT_EQ(o.transformAt(5.0f), o.transform);
  EXPECT_FLOAT_EQ(o.material.specular, 0.25f);
  EXPECT_FLOAT_EQ(o.material.shininess, 32.0f);
  ASSERT_TRUE(o.mesh);
  EXPECT_EQ(o.mesh->triangles.size(), 12u);
  EXPECT_EQ(s.find("cube"), &o);
  EXPECT_EQ(s.find("nothing"), nullptr);
}

// "fit" frames a scene the same way at any size (a 1e-3 floor on the radius framed a 1e-8
// cube as a few pixels).
TEST(SceneLoad, FitFramesAScaleFreeView) {
  const auto fitted = [](const std::string& scale) {
    const Scene scene =
        parseScene(R"({"objects": [{"name": "a", "file": "cube.obj", "transform": {"scale": )" +
                       scale + R"(}}]})",
                   "fit.json", kMeshes);
    const Camera c = scene.resolvedCamera();
    const Bounds b = scene.bounds();
    return std::tuple{glm::length(c.eye - b.center()) / b.radius(), c.near / b.radius(),
                      c.far / b.radius()};
  };
  const auto [distance, near, far] = fitted("1");
  for (const char* scale : {"1e-4", "1e-8"}) {
    const auto [d, n, f] = fitted(scale);
    EXPECT_NEAR(d, distance, 1e-3f * distance) << scale;
    EXPECT_NEAR(n, near, 1e-3f * distance) << scale;
    EXPECT_NEAR(f, far, 1e-3f * distance) << scale;
  }
}

// A fitted camera whose eye and target coincide looks along the documented default direction
// (1, 0.8, 1.4); without fit they are refused.
TEST(SceneLoad, AFittedCameraWhoseEyeIsItsTargetTakesTheDefaultDirection) {
  const auto scene = [](const std::string& camera) {
    return parseScene(
        R"({"objects": [{"name": "a", "file": "cube.obj"}], "camera": )" + camera + "}", "fit.json",
        kMeshes);
  };
  const Camera c =
      scene(R"({"fit": true, "eye": [1, 1, 1], "target": [1, 1, 1]})").resolvedCamera();
  const glm::vec3 along = glm::normalize(c.eye - c.target);
  EXPECT_NEAR(glm::distance(along, glm::normalize(glm::vec3(1.0f, 0.8f, 1.4f))), 0.0f, 1e-6f);
  test::expectError([&] { scene(R"({"eye": [1, 1, 1], "target": [1, 1, 1]})"); },
                    {"fit.json", "/camera/eye", "eye and target coincide"});
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
  EXPECT_EQ(s.style.get<GoochStyle>().cool, glm::vec3(0, 0, 0.4f));
  EXPECT_EQ(s.style.get<GoochStyle>().warm, glm::vec3(0.4f, 0.4f, 0));
  EXPECT_FLOAT_EQ(s.style.get<GoochStyle>().alpha, 0.1f);
  EXPECT_FLOAT_EQ(s.style.get<GoochStyle>().beta, 0.7f);
  EXPECT_FLOAT_EQ(s.style.get<BlinnPhongStyle>().ambient, 0.3f);

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
  EXPECT_TRUE(s.objects[1].mesh->report.watertight);                      // two closed parts
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
  EXPECT_EQ(roi->role, Role::Interest);    // proxy default
  EXPECT_FLOAT_EQ(roi->importance, 1.0f);  // proxy default
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
// "cutters": {"adaptive": …}: the adaptive cutaway's options (Burns08; Burns11 ch. 4–6).

// Every field of `o` equals the documented default (docs/scene-format.md, cutters.adaptive).
void expectAdaptiveDefaults(const AdaptiveCutawayOptions& o, const std::string& label) {
  SCOPED_TRACE(label);
  EXPECT_FLOAT_EQ(o.angle, 45.0f);
  EXPECT_EQ(o.bufferSize, 512);
  EXPECT_TRUE(o.perspectiveCompensation);
  EXPECT_TRUE(o.edgeCompression);
  EXPECT_FLOAT_EQ(o.edgeRegion, 0.1f);
  EXPECT_FALSE(o.directionalConstraint);
  EXPECT_EQ(o.floorNormal, glm::vec3(0, 1, 0));
  EXPECT_EQ(o.variant, fields::JumpFloodingVariant::jfaPlus1);
  EXPECT_STREQ(fields::variantName(o.variant), "jfa+1");
  EXPECT_EQ(o.compute, AdaptiveCutawayOptions::Compute::Auto);
  EXPECT_EQ(o.cutSurfaces, AdaptiveCutawayOptions::CutSurfaces::All);
  EXPECT_FALSE(o.cutSurfaceColor.has_value());
  EXPECT_TRUE(o.outlines);
  EXPECT_EQ(o.outlineColor, glm::vec3(0.0f));
  EXPECT_FALSE(o.ghostLines);
  EXPECT_EQ(GhostLineOptions{}.distance, 0.0f);
  EXPECT_FLOAT_EQ(GhostLineOptions{}.opacity, 0.4f);
}

TEST(SceneAdaptive, TrueAndAnEmptyObjectGiveTheDefaults) {
  const Scene on = parse(R"({"objects": [{"name": "cube", "file": "cube.obj"}],
                             "cutters": {"adaptive": true}})");
  ASSERT_TRUE((on.cutters.find<AdaptiveCutawayOptions>() != nullptr));
  expectAdaptiveDefaults(*on.cutters.find<AdaptiveCutawayOptions>(), "adaptive: true");
  const Scene empty = parse(R"({"objects": [{"name": "cube", "file": "cube.obj"}],
                                "cutters": {"adaptive": {}}})");
  ASSERT_TRUE((empty.cutters.find<AdaptiveCutawayOptions>() != nullptr));
  expectAdaptiveDefaults(*empty.cutters.find<AdaptiveCutawayOptions>(), "adaptive: {}");
  // The parser's defaults are the struct's.
  expectAdaptiveDefaults(AdaptiveCutawayOptions{}, "AdaptiveCutawayOptions{}");
  // "cutters": {} names no cutter: none runs.
  const Scene none = parse(R"({"objects": [{"name": "cube", "file": "cube.obj"}], "cutters": {}})");
  EXPECT_FALSE((none.cutters.find<AdaptiveCutawayOptions>() != nullptr));
}

TEST(SceneAdaptive, EveryKeyIsRead) {
  const Scene s = parse(R"({"objects": [{"name": "cube", "file": "cube.obj"}],
    "cutters": {"adaptive": {
      "angle": 30, "bufferSize": 256, "perspectiveCompensation": false, "edgeCompression": 0.25,
      "floorNormal": [0, 0, 2], "directionalConstraint": true, "jumpFlooding": "jfa+2",
      "compute": "cpu", "cutSurfaces": "watertight", "cutSurfaceColor": [0.9, 0.1, 0.1],
      "outlines": false, "outlineColor": [0.2, 0.3, 0.4],
      "ghostLines": {"distance": 0.5, "opacity": 0.7}}}})");
  ASSERT_TRUE((s.cutters.find<AdaptiveCutawayOptions>() != nullptr));
  const AdaptiveCutawayOptions& o = *s.cutters.find<AdaptiveCutawayOptions>();
  EXPECT_FLOAT_EQ(o.angle, 30.0f);
  EXPECT_EQ(o.bufferSize, 256);
  EXPECT_FALSE(o.perspectiveCompensation);
  EXPECT_TRUE(o.edgeCompression);  // a number sets r and keeps compression on
  EXPECT_FLOAT_EQ(o.edgeRegion, 0.25f);
  EXPECT_TRUE(o.directionalConstraint);
  EXPECT_VEC3_NEAR(o.floorNormal, glm::vec3(0, 0, 1), 1e-6f);  // normalised
  EXPECT_EQ(o.variant, fields::JumpFloodingVariant::jfaPlus2);
  EXPECT_EQ(o.compute, AdaptiveCutawayOptions::Compute::Cpu);
  EXPECT_EQ(o.cutSurfaces, AdaptiveCutawayOptions::CutSurfaces::Watertight);
  ASSERT_TRUE(o.cutSurfaceColor.has_value());
  EXPECT_EQ(*o.cutSurfaceColor, glm::vec3(0.9f, 0.1f, 0.1f));
  EXPECT_FALSE(o.outlines);
  EXPECT_EQ(o.outlineColor, glm::vec3(0.2f, 0.3f, 0.4f));
  ASSERT_TRUE(o.ghostLines);
  EXPECT_FLOAT_EQ(o.ghostLines->distance, 0.5f);
  EXPECT_FLOAT_EQ(o.ghostLines->opacity, 0.7f);
}

TEST(SceneAdaptive, ShortFormsAndInteractions) {
  const auto adaptive = [](const std::string& body) {
    const Scene s =
        parse(R"({"objects": [{"name": "cube", "file": "cube.obj"}], "cutters": {"adaptive": )" +
              body + "}}");
    EXPECT_TRUE((s.cutters.find<AdaptiveCutawayOptions>() != nullptr)) << body;
    return (*optionsOr<AdaptiveCutawayOptions>(s));
  };
  // edgeCompression: false turns eq. 5.8 off and leaves r alone.
  const AdaptiveCutawayOptions noEdge = adaptive(R"({"edgeCompression": false})");
  EXPECT_FALSE(noEdge.edgeCompression);
  EXPECT_FLOAT_EQ(noEdge.edgeRegion, 0.1f);
  EXPECT_TRUE(adaptive(R"({"edgeCompression": true})").edgeCompression);
  EXPECT_FLOAT_EQ(adaptive(R"({"edgeCompression": 1})").edgeRegion, 1.0f);
  // floorNormal alone enables the directional constraint; an explicit false wins whatever
  // the order of the keys; directionalConstraint alone uses the default floor normal +y.
  const AdaptiveCutawayOptions floor = adaptive(R"({"floorNormal": [0, 0, -3]})");
  EXPECT_TRUE(floor.directionalConstraint);
  EXPECT_VEC3_NEAR(floor.floorNormal, glm::vec3(0, 0, -1), 1e-6f);
  for (const char* body : {R"({"floorNormal": [0, 0, 1], "directionalConstraint": false})",
                           R"({"directionalConstraint": false, "floorNormal": [0, 0, 1]})"}) {
    const AdaptiveCutawayOptions off = adaptive(body);
    EXPECT_FALSE(off.directionalConstraint) << body;
    EXPECT_VEC3_NEAR(off.floorNormal, glm::vec3(0, 0, 1), 1e-6f);
  }
  const AdaptiveCutawayOptions plain = adaptive(R"({"directionalConstraint": true})");
  EXPECT_TRUE(plain.directionalConstraint);
  EXPECT_EQ(plain.floorNormal, glm::vec3(0, 1, 0));
  // ghostLines: true, or an object (even an empty one), turns them on with the defaults for
  // what it leaves out; false keeps them off.
  for (const char* body : {R"({"ghostLines": true})", R"({"ghostLines": {}})"}) {
    const AdaptiveCutawayOptions g = adaptive(body);
    ASSERT_TRUE(g.ghostLines) << body;
    EXPECT_EQ(g.ghostLines->distance, 0.0f) << body;  // 0: 5% of the scene radius, chosen by the renderer
    EXPECT_FLOAT_EQ(g.ghostLines->opacity, 0.4f) << body;
  }
  EXPECT_FLOAT_EQ(adaptive(R"({"ghostLines": {"opacity": 1}})").ghostLines->distance, 0.0f);
  EXPECT_FALSE(adaptive(R"({"ghostLines": false})").ghostLines);
  // Range ends are allowed.
  EXPECT_FLOAT_EQ(adaptive(R"({"angle": 0})").angle, 0.0f);
  EXPECT_FLOAT_EQ(adaptive(R"({"angle": 90})").angle, 90.0f);
  EXPECT_EQ(adaptive(R"({"bufferSize": 16})").bufferSize, 16);
  EXPECT_EQ(adaptive(R"({"bufferSize": 8192})").bufferSize, 8192);
  EXPECT_FLOAT_EQ(adaptive(R"({"edgeCompression": 0.001})").edgeRegion, 0.001f);
}

TEST(SceneAdaptive, EnumeratedValues) {
  const auto adaptive = [](const std::string& key, const std::string& value) {
    const Scene s =
        parse(R"({"objects": [{"name": "cube", "file": "cube.obj"}], "cutters": {"adaptive": {")" +
              key + "\": \"" + value + "\"}}}");
    return (*optionsOr<AdaptiveCutawayOptions>(s));
  };
  using V = fields::JumpFloodingVariant;
  const std::pair<const char*, V> variants[] = {
      {"jfa", V::jfa}, {"jfa+1", V::jfaPlus1}, {"1+jfa", V::onePlusJfa}, {"jfa+2", V::jfaPlus2}};
  for (const auto& [name, variant] : variants) {
    EXPECT_EQ(adaptive("jumpFlooding", name).variant, variant) << name;
    EXPECT_STREQ(fields::variantName(variant), name);
  }
  using C = AdaptiveCutawayOptions::Compute;
  EXPECT_EQ(adaptive("compute", "auto").compute, C::Auto);
  EXPECT_EQ(adaptive("compute", "gpu").compute, C::Gpu);
  EXPECT_EQ(adaptive("compute", "cpu").compute, C::Cpu);
  using S = AdaptiveCutawayOptions::CutSurfaces;
  EXPECT_EQ(adaptive("cutSurfaces", "all").cutSurfaces, S::All);
  EXPECT_EQ(adaptive("cutSurfaces", "unmarked").cutSurfaces, S::Unmarked);
  EXPECT_EQ(adaptive("cutSurfaces", "watertight").cutSurfaces, S::Watertight);
  EXPECT_EQ(adaptive("cutSurfaces", "none").cutSurfaces, S::None);
}

TEST(SceneAdaptive, CutawayAngleIsAPerObjectNumber) {
  const Scene s = parse(R"({
    "objects": [{"name": "parts", "file": "two_parts.obj", "split": "nodes", "role": "interest",
                 "params": {"cutawayAngle": 20},
                 "overrides": [{"match": "pin", "params": {"cutawayAngle": 60}}]}],
    "proxies": [{"name": "roi", "box": {"min": [0, 0, 0], "max": [1, 1, 1]},
                 "params": {"cutawayAngle": 90}}],
    "cutters": {"adaptive": {"angle": 35}}})");
  ASSERT_TRUE(s.find("parts/body") && s.find("parts/pin") && s.find("roi"));
  EXPECT_EQ(std::get<double>(s.find("parts/body")->params.at("cutawayAngle")), 20.0);
  EXPECT_EQ(std::get<double>(s.find("parts/pin")->params.at("cutawayAngle")), 60.0);
  EXPECT_EQ(std::get<double>(s.find("roi")->params.at("cutawayAngle")), 90.0);
  // Declared among the object parameters, with its range.
  const auto& specs = objectParameterSpecs();
  const auto spec = std::find_if(specs.begin(), specs.end(),
                                 [](const ObjectParamSpec& p) { return p.name == "cutawayAngle"; });
  ASSERT_NE(spec, specs.end());
  EXPECT_EQ(spec->type, ObjectParamSpec::Type::Number);
  EXPECT_EQ(spec->min, 0.0);
  EXPECT_EQ(spec->max, 90.0);
}

// ---------------------------------------------------------------------------------------------
// "animation": keyframes K(t) on top of the static transform, world = K(t) · transform.

TEST(SceneAnimation, TransformAtKeyframesBetweenThemAndPastTheEnds) {
  // Static transform: uniform scale 2. Keyframes at t = 1 (identity) and t = 3 (translate
  // (4,0,0), 90° about z, scale 3).
  const Scene s = parse(R"({"objects": [{"name": "cube", "file": "cube.obj",
      "transform": {"scale": 2},
      "animation": [{"time": 1},
                    {"time": 3, "translate": [4, 0, 0], "rotate": {"axis": [0, 0, 1], "degrees": 90},
                     "scale": 3}]}]})");
  const SceneObject& o = s.objects[0];
  ASSERT_EQ(o.animation.size(), 2u);
  EXPECT_EQ(o.animation[0].time, 1.0f);
  EXPECT_EQ(o.animation[1].time, 3.0f);
  EXPECT_EQ(o.animation[0].trs.matrix(),
            glm::mat4(1.0f));  // a keyframe without TRS keys is identity
  EXPECT_VEC3_NEAR(apply(o.transform, {1, 0, 0}), glm::vec3(2, 0, 0),
                   kEps);  // static part unchanged

  // At the keyframes: K(1) = I, so (1,0,0) → S2 (2,0,0). K(3): (2,0,0) → S3 (6,0,0) →
  // Rz(90°) (0,6,0) → T (4,6,0). (transform · K would give (8,12,0) instead.)
  EXPECT_VEC3_NEAR(apply(o.transformAt(1.0f), {1, 0, 0}), glm::vec3(2, 0, 0), kEps);
  EXPECT_VEC3_NEAR(apply(o.transformAt(3.0f), {1, 0, 0}), glm::vec3(4, 6, 0), kEps);
  // Held before the first keyframe and after the last.
  EXPECT_EQ(o.transformAt(0.0f), o.transformAt(1.0f));
  EXPECT_EQ(o.transformAt(100.0f), o.transformAt(3.0f));

  // Halfway (t = 2): translation (2,0,0), scale 2, rotation 45°: (1,0,0) → S2 (2,0,0) →
  // S2 (4,0,0) → Rz(45°) (2√2, 2√2, 0) → T (2 + 2√2, 2√2, 0).
  const float r2 = std::sqrt(2.0f);
  EXPECT_VEC3_NEAR(apply(o.transformAt(2.0f), {1, 0, 0}), glm::vec3(2 + 2 * r2, 2 * r2, 0), 1e-4f);
  EXPECT_VEC3_NEAR(apply(o.transformAt(2.0f), {0, 0, 0}), glm::vec3(2, 0, 0),
                   1e-5f);  // translation only

  // A quarter of the way (t = 1.5): slerp turns by exactly 22.5° at constant speed (nlerp of
  // the quaternions would give 21.6°, a lerp of matrices would also shrink the vertex).
  // Translation (1,0,0) and scale 1.5 are linear: (1,0,0) → S2 → S1.5 (3,0,0) → Rz(22.5°) → +T.
  const glm::vec3 v = apply(o.transformAt(1.5f), {1, 0, 0}) - glm::vec3(1, 0, 0);
  EXPECT_NEAR(glm::degrees(std::atan2(v.y, v.x)), 22.5f, 1e-3f);
  EXPECT_NEAR(glm::length(v), 3.0f, 1e-5f);
  EXPECT_NEAR(v.z, 0.0f, 1e-6f);
}

TEST(SceneAnimation, RotationTakesTheShorterArcAndEulerKeysWork) {
  // Keys 270° apart about z: slerp goes the short way (−90°), so halfway is −45°.
  const Scene s = parse(R"({"objects": [{"name": "cube", "file": "cube.obj",
      "animation": [{"time": 0, "rotate": [0, 0, 0]}, {"time": 1, "rotate": [0, 0, 270]}]}]})");
  const float h = std::sqrt(0.5f);
  EXPECT_VEC3_NEAR(apply(s.objects[0].transformAt(0.5f), {1, 0, 0}), glm::vec3(h, -h, 0), 1e-5f);
  EXPECT_VEC3_NEAR(apply(s.objects[0].transformAt(1.0f), {1, 0, 0}), glm::vec3(0, -1, 0), 1e-5f);
}

TEST(SceneAnimation, ProxiesAndSplitNodesAreAnimatedAndBoundsCoverTheMotion) {
  const Scene s = parse(R"({
    "objects": [{"name": "parts", "file": "two_parts.obj", "split": "nodes",
                 "animation": [{"time": 0}, {"time": 2, "translate": [0, 10, 0]}]}],
    "proxies": [{"name": "roi", "box": {"min": [0, 0, 0], "max": [1, 1, 1]},
                 "transform": {"translate": [5, 0, 0]},
                 "animation": [{"time": 0.5, "scale": [1, 1, 1]}, {"time": 4, "scale": [3, 1, 1]}]}]})");
  // Every node of a split file gets the object's animation.
  for (const char* name : {"parts/body", "parts/pin"}) {
    const SceneObject* o = s.find(name);
    ASSERT_TRUE(o) << name;
    ASSERT_EQ(o->animation.size(), 2u) << name;
    EXPECT_VEC3_NEAR(apply(o->transformAt(1.0f), {0, 0, 0}), glm::vec3(0, 5, 0), 1e-5f);
  }
  // The proxy: K(t) · T(5,0,0); scale along x is linear, 2 at t = 2.25.
  const SceneObject* roi = s.find("roi");
  ASSERT_TRUE(roi);
  EXPECT_VEC3_NEAR(apply(roi->transformAt(2.25f), {1, 0, 0}), glm::vec3(12, 0, 0), 1e-4f);
  // Bounds span the whole motion (the still bounds are x ∈ [0, 4], y, z ∈ [0, 1]).
  const Bounds b = s.bounds();
  EXPECT_VEC3_NEAR(b.min, glm::vec3(0, 0, 0), kEps);
  EXPECT_VEC3_NEAR(b.max, glm::vec3(4, 11, 1), kEps);
  EXPECT_FLOAT_EQ(s.duration(), 4.0f);  // the proxy's last keyframe counts
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
  struct Case {
    int w, h;
    const char* projection;
    glm::vec3 eye;
    float fov;
  };
  const Case cases[] = {
      {800, 600, "perspective", {1, 0.8f, 1.4f}, 40}, {600, 800, "perspective", {0, 0, 1}, 40},
      {1600, 400, "perspective", {-2, 1, -0.5f}, 25}, {400, 1600, "perspective", {0.1f, -3, 1}, 90},
      {800, 600, "orthographic", {1, 1, 1}, 40},      {300, 900, "orthographic", {-1, 0.2f, 0}, 40},
  };
  for (const auto& k : cases) {
    char text[1024];
    std::snprintf(text, sizeof text, scene, k.w, k.h, k.projection, k.eye.x, k.eye.y, k.eye.z,
                  k.fov);
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

// Views that 32-bit floats cannot draw are named, and nothing near them is.
TEST(SceneCamera, ViewsThatFloatsCannotDrawAreNamed) {
  const auto why = [](const char* camera, const char* transform = "{}") {
    return parse(std::string(R"({"objects": [{"name": "cube", "file": "cube.obj", "transform": )") +
                 transform + R"(}], "camera": )" + camera + "}")
        .resolvedCamera()
        .unresolvable(4.0f / 3.0f);
  };
  EXPECT_EQ(why(R"({"eye": [0.5, 0.5, 30], "target": [0.5, 0.5, 0.5]})"), "");
  EXPECT_EQ(why(R"({"fit": true})"), "");
  // Projected coordinates: 5e6 from the origin, the eye 50 away (100 float steps) still draws.
  EXPECT_EQ(why(R"({"eye": [5e6, 30, 5000040], "target": [5e6, 0, 5e6]})",
                R"({"translate": [5e6, 0, 5e6]})"),
            "");
  // The scene 1e14 away: its depth range is one float.
  EXPECT_NE(why(R"({"eye": [1e14, 0, 0], "target": [0, 0, 0]})").find("depth range"),
            std::string::npos);
  // Eye and target one float step apart at 1e14.
  EXPECT_NE(why(R"({"eye": [1e14, 0, 0], "target": [99999990000000, 0, 0]})",
                R"({"translate": [1e14, 0, 0]})")
                .find("eye and target are 8.39e+06 apart at 1e+14"),
            std::string::npos);
  // A view 1e-30 across (a scene file's parts are refused below 1e-15): lookAt's squares
  // underflow.
  Camera tiny;
  tiny.eye = {0.0f, 0.0f, 3e-30f};
  tiny.near = 1e-30f, tiny.far = 5e-30f;
  EXPECT_NE(tiny.unresolvable(1.0f).find("not finite"), std::string::npos)
      << tiny.unresolvable(1.0f);
}

// The adaptive cutaway keeps its cut in window depths: a perspective range deeper than they
// resolve (far / near > 1e4) is named where the cutter is on, and drawn where it is not (an
// orthographic view's window depth is linear: any range).
TEST(SceneCamera, ARangeDeeperThanTheAdaptiveCutResolvesIsNamed) {
  Scene s = parse(R"({"objects": [{"name": "cube", "file": "cube.obj"}],
    "camera": {"eye": [0.5, 0.5, 30], "target": [0.5, 0.5, 0.5], "near": 1e-4, "far": 40}})");
  EXPECT_EQ(deepestDepthRange(s), 0.0f);
  s.cutters.enable<AdaptiveCutawayOptions>();
  EXPECT_EQ(deepestDepthRange(s), 1e4f);
  Camera c = s.resolvedCamera();
  EXPECT_EQ(c.unresolvable(1.0f), "");
  EXPECT_NE(c.unresolvable(1.0f, deepestDepthRange(s))
                .find("far / near 4e+05) is deeper than the adaptive cutaway resolves"),
            std::string::npos)
      << c.unresolvable(1.0f, deepestDepthRange(s));
  c.near = 4e-3f;  // far / near 1e4
  EXPECT_EQ(c.unresolvable(1.0f, deepestDepthRange(s)), "");
  c.near = 1e-4f;
  c.projection = Projection::Orthographic;
  EXPECT_EQ(c.unresolvable(1.0f, deepestDepthRange(s)), "");
}

// Whatever the cutters, a perspective range deeper than the depth buffer's floats resolve
// (far / near > 1e6) is named: at 1e8 every surface rounded to the cleared far depth and the
// picture was blank with exit 0. Its least near, 1e-15, is taken as written.
TEST(SceneCamera, ARangeDeeperThanTheDepthBufferResolvesIsNamed) {
  const std::string objects = R"({"objects": [{"name": "cube", "file": "cube.obj"}],)";
  Camera c = parse(objects + R"("camera": {"eye": [0.5, 0.5, 3], "target": [0.5, 0.5, 0.5],
    "near": 4e-8, "far": 4}})")
                 .resolvedCamera();
  EXPECT_NE(c.unresolvable(1.0f).find("far / near 1e+08) is deeper than a 32-bit depth buffer "
                                      "resolves (1e+06): give a larger near"),
            std::string::npos)
      << c.unresolvable(1.0f);
  c.near = 5e-6f;  // far / near 8e5
  EXPECT_EQ(c.unresolvable(1.0f), "");
  c.near = 4e-8f;
  c.projection = Projection::Orthographic;
  EXPECT_EQ(c.unresolvable(1.0f), "");
  const Scene least = parse(objects + R"("camera": {"fit": true, "near": 1e-15, "height": 1e-15,
    "projection": "orthographic"}})");
  EXPECT_EQ(least.camera.near, 1e-15f);
  EXPECT_EQ(least.camera.height, 1e-15f);
}

// A given far plane nearer than the derived near is kept; the near plane yields to it.
TEST(SceneCamera, AGivenFarNearerThanTheSceneIsKept) {
  for (const char* projection : {"perspective", "orthographic"}) {
    const Scene s = parse(std::string(R"({"objects": [{"name": "cube", "file": "cube.obj"}],
      "camera": {"eye": [0.5, 0.5, 30], "target": [0.5, 0.5, 0.5], "far": 2, "projection": ")") +
                          projection + R"("}})");
    const Camera c = s.resolvedCamera();
    EXPECT_EQ(c.far, 2.0f) << projection;
    EXPECT_LT(c.near, c.far) << projection;
    if (std::string(projection) == "perspective") EXPECT_GT(c.near, 0.0f);
  }
  // A given near beyond the scene keeps its value; the derived far moves past it.
  const Scene s = parse(R"({"objects": [{"name": "cube", "file": "cube.obj"}],
                            "camera": {"eye": [0.5, 0.5, 30], "target": [0.5, 0.5, 0.5], "near": 50}})");
  const Camera c = s.resolvedCamera();
  EXPECT_EQ(c.near, 50.0f);
  EXPECT_GT(c.far, c.near);
}

// The derived depth range holds the proxies of interest, which the adaptive cutter draws;
// fitting frames only the visible objects.
TEST(SceneCamera, TheDerivedDepthRangeHoldsTheProxies) {
  const char* objects = R"({"objects": [{"name": "cube", "file": "cube.obj"}], )";
  const char* camera = R"("camera": {"eye": [0.5, 0.5, 30], "target": [0.5, 0.5, 0.5]})";
  const Camera alone = parse(std::string(objects) + camera + "}").resolvedCamera();
  const Scene s =
      parse(std::string(objects) +
            R"("proxies": [{"name": "room", "box": {"min": [0, 0, -40], "max": [1, 1, 1]}}], )" +
            camera + "}");
  const Camera c = s.resolvedCamera();
  EXPECT_GE(c.far, 30.0f + 40.0f) << "the proxy's far end";
  EXPECT_LE(c.near, 29.0f);
  EXPECT_GT(c.near, 0.0f);
  EXPECT_GT(c.far, alone.far);
  Scene fitted = s;
  fitted.camera.fit = true;
  EXPECT_EQ(fitted.resolvedCamera().target, glm::vec3(0.5f)) << "fit frames the cube alone";
  // A proxy of another role has no effect: far away, it leaves the planes alone (it once
  // moved the near plane past the cube: a blank picture).
  const Camera context =
      parse(
          std::string(objects) +
          R"("proxies": [{"name": "far", "role": "context", "box": {"min": [1e6, 1e6, 1e6], "max": [1.1e6, 1.1e6, 1.1e6]}}], )" +
          camera + "}")
          .resolvedCamera();
  EXPECT_EQ(context.near, alone.near);
  EXPECT_EQ(context.far, alone.far);
}

// ---------------------------------------------------------------------------------------------
// Camera paths and the scene's duration.

TEST(SceneCamera, PathIsInterpolatedLinearlyAndHeldAtTheEnds) {
  const Scene s = parse(R"({"objects": [{"name": "cube", "file": "cube.obj"}],
    "camera": {"fov": 30, "path": [
      {"time": 1, "eye": [0, 0, 10], "target": [0, 0, 0]},
      {"time": 3, "eye": [10, 0, 0], "target": [2, 0, 0]},
      {"time": 4, "eye": [10, 0, 10], "target": [2, 0, 0]}]}})");
  ASSERT_EQ(s.camera.path.size(), 3u);
  EXPECT_FALSE(s.camera.fit);
  // No eye/target of its own: the static camera takes the first key's.
  EXPECT_EQ(s.camera.eye, glm::vec3(0, 0, 10));
  EXPECT_EQ(s.camera.target, glm::vec3(0, 0, 0));
  struct Expect {
    float time;
    glm::vec3 eye, target;
  };
  const Expect expected[] = {
      {0.0f, {0, 0, 10}, {0, 0, 0}},  // before the first key: held
      {1.0f, {0, 0, 10}, {0, 0, 0}},  // at a key
      {2.0f, {5, 0, 5}, {1, 0, 0}},   // halfway between keys 0 and 1
      {2.5f, {7.5f, 0, 2.5f}, {1.5f, 0, 0}}, {3.0f, {10, 0, 0}, {2, 0, 0}},
      {3.5f, {10, 0, 5}, {2, 0, 0}},         {4.0f, {10, 0, 10}, {2, 0, 0}},
      {50.0f, {10, 0, 10}, {2, 0, 0}},  // after the last key: held
  };
  const Bounds b = s.bounds();
  for (const auto& e : expected) {
    const Camera c = s.resolvedCamera(e.time);
    const std::string label = "t = " + std::to_string(e.time);
    SCOPED_TRACE(label);
    EXPECT_VEC3_NEAR(c.eye, e.eye, 1e-5f);
    EXPECT_VEC3_NEAR(c.target, e.target, 1e-5f);
    EXPECT_FLOAT_EQ(c.fovY, 30.0f) << label;
    EXPECT_EQ(c.up, glm::vec3(0, 1, 0)) << label;
    // Near and far are derived again at every instant, around the scene's bounding sphere.
    const float d = glm::length(b.center() - c.eye);
    EXPECT_GT(c.near, 0.0f) << label;
    EXPECT_NEAR(c.near, d - 1.05f * b.radius(), 1e-4f) << label;
    EXPECT_NEAR(c.far, d + 1.05f * b.radius(), 1e-4f) << label;
  }
  // resolvedCamera() is the camera at t = 0.
  EXPECT_EQ(s.resolvedCamera().eye, s.resolvedCamera(0.0f).eye);
  EXPECT_FLOAT_EQ(s.duration(), 4.0f);
}

TEST(SceneCamera, PathOverridesEyeTargetAndFit) {
  const Scene s = parse(R"({"objects": [{"name": "cube", "file": "cube.obj"}],
    "camera": {"fit": true, "eye": [3, 3, 3], "target": [1, 1, 1],
               "path": [{"time": 2, "eye": [0, 1, 8], "target": [0, 1, 0]}]}})");
  EXPECT_TRUE(s.camera.fit);  // kept as written…
  EXPECT_EQ(s.camera.eye, glm::vec3(3, 3, 3));
  for (float t : {0.0f, 2.0f, 9.0f}) {  // …but the single path key decides
    const Camera c = s.resolvedCamera(t);
    EXPECT_FALSE(c.fit);
    EXPECT_EQ(c.eye, glm::vec3(0, 1, 8));
    EXPECT_EQ(c.target, glm::vec3(0, 1, 0));
  }
  EXPECT_FLOAT_EQ(s.duration(), 2.0f);
}

TEST(SceneCamera, DurationIsTheLastKeyOfAnyObjectOrTheCameraPath) {
  const std::string cube = R"({"name": "cube", "file": "cube.obj"})";
  EXPECT_EQ(parse(R"({"objects": [)" + cube + "]}").duration(), 0.0f);
  // A single keyframe at t = 0 moves nothing and lasts nothing.
  EXPECT_EQ(parse(R"({"objects": [{"name": "cube", "file": "cube.obj",
                                   "animation": [{"time": 0, "translate": [1, 0, 0]}]}]})")
                .duration(),
            0.0f);
  EXPECT_FLOAT_EQ(parse(R"({"objects": [)" + cube + R"(],
      "camera": {"path": [{"time": 0.5, "eye": [0, 0, 5], "target": [0, 0, 0]},
                          {"time": 2.5, "eye": [5, 0, 5], "target": [0, 0, 0]}]}})")
                      .duration(),
                  2.5f);
  EXPECT_FLOAT_EQ(parse(R"({"objects": [)" + cube + R"(,
      {"name": "moving", "file": "tetra.obj", "animation": [{"time": 1}, {"time": 7, "translate": [0, 1, 0]}]}],
      "camera": {"path": [{"time": 0, "eye": [0, 0, 5], "target": [0, 0, 0]},
                          {"time": 4, "eye": [5, 0, 5], "target": [0, 0, 0]}]}})")
                      .duration(),
                  7.0f);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Toon, hatching and shadows (src/styles/toon, hatching, shadows).

TEST(SceneStyle, ToonHatchingAndShadowDefaults) {
  const Scene s = parse(R"({"objects": [{"name": "cube", "file": "cube.obj"}]})");
  ASSERT_EQ(s.style.get<ToonStyle>().ramp.size(), 3u);
  EXPECT_VEC3_NEAR(s.style.get<ToonStyle>().ramp[0], glm::vec3(0.45f), kEps);
  EXPECT_VEC3_NEAR(s.style.get<ToonStyle>().ramp[2], glm::vec3(1.0f), kEps);
  EXPECT_TRUE(s.style.get<ToonStyle>().highlight);
  EXPECT_FLOAT_EQ(s.style.get<ToonStyle>().highlightThreshold, 0.5f);
  EXPECT_EQ(s.style.get<HatchingStyle>().tones, 6);
  EXPECT_FLOAT_EQ(s.style.get<HatchingStyle>().tint, 0.35f);
  EXPECT_FLOAT_EQ(s.style.get<HatchingStyle>().scale, 0.4f);
  EXPECT_EQ(s.style.get<HatchingStyle>().lightness, HatchingStyle::Lightness::Lambert);
  EXPECT_FALSE(s.style.shadows.enabled);
  EXPECT_EQ(s.style.shadows.size, 2048);
  EXPECT_EQ(s.style.shadows.pcfRadius, 1);
  EXPECT_EQ(styleNames(), (std::vector<std::string>{"gooch", "blinn-phong", "toon", "hatching"}));
}

TEST(SceneStyle, EveryToonHatchingAndShadowKeyIsRead) {
  const Scene s = parse(R"({"style": {"name": "toon",
      "toon": {"ramp": [0.1, [0.2, 0.3, 0.4], 0.7, 1], "highlight": false,
               "highlightThreshold": 0.8, "highlightColor": [1, 1, 0.5]},
      "hatching": {"tones": 8, "paper": [1, 1, 0.9], "ink": [0, 0, 0.2], "tint": 0.5,
                   "scale": 0.25, "seed": 42, "lightness": "gooch"},
      "shadows": {"size": 1024, "bias": 0.001, "slopeBias": 3, "pcfRadius": 2}},
      "objects": [{"name": "cube", "file": "cube.obj", "params": {"castsShadow": false}}]})");
  EXPECT_EQ(s.style.name, "toon");
  const ToonStyle& t = s.style.get<ToonStyle>();
  ASSERT_EQ(t.ramp.size(), 4u);
  EXPECT_VEC3_NEAR(t.ramp[0], glm::vec3(0.1f), kEps);  // a number is a grey tone
  EXPECT_VEC3_NEAR(t.ramp[1], glm::vec3(0.2f, 0.3f, 0.4f), kEps);
  EXPECT_VEC3_NEAR(t.ramp[3], glm::vec3(1.0f), kEps);
  EXPECT_FALSE(t.highlight);
  EXPECT_FLOAT_EQ(t.highlightThreshold, 0.8f);
  EXPECT_VEC3_NEAR(t.highlightColor, glm::vec3(1, 1, 0.5f), kEps);
  const HatchingStyle& h = s.style.get<HatchingStyle>();
  EXPECT_EQ(h.tones, 8);
  EXPECT_VEC3_NEAR(h.paper, glm::vec3(1, 1, 0.9f), kEps);
  EXPECT_VEC3_NEAR(h.ink, glm::vec3(0, 0, 0.2f), kEps);
  EXPECT_FLOAT_EQ(h.tint, 0.5f);
  EXPECT_FLOAT_EQ(h.scale, 0.25f);
  EXPECT_EQ(h.seed, 42u);
  EXPECT_EQ(h.lightness, HatchingStyle::Lightness::Gooch);
  const ShadowStyle& sh = s.style.shadows;
  EXPECT_TRUE(sh.enabled);  // an object turns them on
  EXPECT_EQ(sh.size, 1024);
  EXPECT_FLOAT_EQ(sh.bias, 0.001f);
  EXPECT_FLOAT_EQ(sh.slopeBias, 3.0f);
  EXPECT_EQ(sh.pcfRadius, 2);
  EXPECT_EQ(std::get<bool>(s.objects[0].params.at("castsShadow")), false);
}

TEST(SceneStyle, ShadowShortFormsAndNames) {
  EXPECT_TRUE(
      parse(R"({"style": {"shadows": true}, "objects": [{"name": "c", "file": "cube.obj"}]})")
          .style.shadows.enabled);
  EXPECT_FALSE(
      parse(R"({"style": {"shadows": false}, "objects": [{"name": "c", "file": "cube.obj"}]})")
          .style.shadows.enabled);
  EXPECT_FALSE(parse(R"({"style": {"shadows": {"enabled": false, "size": 512}},
                         "objects": [{"name": "c", "file": "cube.obj"}]})")
                   .style.shadows.enabled);
  EXPECT_EQ(
      parse(R"({"style": "hatching", "objects": [{"name": "c", "file": "cube.obj"}]})").style.name,
      "hatching");
}

namespace {

// A 2×2×2 volume of ones, as the Python module gives volumes in memory.
std::shared_ptr<Volume> oneVolume() {
  auto volume = std::make_shared<Volume>();
  volume->dims = {2, 2, 2};
  volume->values.assign(8, 1.0f);
  return volume;
}

}  // namespace

// Meshes and volumes given in memory (the Python module's arrays) by "arrays": KEY.
TEST(SceneArrays, EntriesTakeTheirMeshAndVolumeByKey) {
  SceneArrays arrays;
  auto mesh = std::make_shared<Mesh>();
  mesh->positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh->triangles = {{0, 1, 2}};
  arrays.meshes["tri"] = mesh;
  const auto volume = oneVolume();
  arrays.volumes["v"] = volume;
  const Scene s = parseScene(
      R"({"objects": [{"name": "a", "arrays": "tri", "role": "interest"}],
          "volumes": [{"name": "b", "arrays": "v", "transferFunction": [{"value": 1, "opacity": 0.5}]}]})",
      "<dict>", kMeshes, arrays);
  ASSERT_EQ(s.objects.size(), 1u);
  EXPECT_EQ(s.objects[0].mesh, mesh);
  EXPECT_EQ(s.objects[0].role, Role::Interest);
  EXPECT_EQ(s.objects[0].source, "arrays tri");
  ASSERT_EQ(s.volumes.size(), 1u);
  EXPECT_EQ(s.volumes[0].volume, volume);

  test::expectError(
      [&] { parseScene(R"({"objects": [{"name": "a", "arrays": "x"}]})", "s.json", kMeshes); },
      {"s.json: /objects/0/arrays: no arrays named \"x\" were given"});
  test::expectError(
      [&] {
        parseScene(R"({"objects": [{"name": "a", "arrays": "tri", "file": "cube.obj"}]})", "s.json",
                   kMeshes, arrays);
      },
      {"/objects/0: an object needs exactly one of"});
  test::expectError(
      [&] {
        parseScene(R"({"volumes": [{"name": "b", "arrays": "v", "file": "x.nii",
                                    "transferFunction": [{"value": 1, "opacity": 0.5}]}]})",
                   "s.json", kMeshes, arrays);
      },
      {"/volumes/0: a volume needs one of \"file\" or \"arrays\", not both"});
}

TEST(SceneArrays, AppendVolumeChecksTheEntryAndLeavesTheSceneOnError) {
  SceneArrays arrays;
  const auto volume = oneVolume();
  arrays.volumes["v"] = volume;
  Scene s = parseScene(R"({"objects": [{"name": "cube", "file": "cube.obj"}]})", "s", kMeshes);
  test::expectError(
      [&] {
        appendVolume(
            s,
            R"({"name": "cube", "arrays": "v", "transferFunction": [{"value": 1, "opacity": 0.5}]})",
            "add_volume", kMeshes, arrays);
      },
      {"add_volume: /volumes/0/name: the name \"cube\" is taken"});
  test::expectError(
      [&] {
        appendVolume(s, R"({"name": "w", "arrays": "v", "transferFunction": [{"value": 1,
                        "opacity": 2}]})",
                     "add_volume", kMeshes, arrays);
      },
      {"add_volume: /transferFunction/0/opacity"});
  EXPECT_TRUE(s.volumes.empty());
  appendVolume(
      s, R"({"name": "w", "arrays": "v", "transferFunction": [{"value": 1, "opacity": 0.5}]})",
      "add_volume", kMeshes, arrays);
  ASSERT_EQ(s.volumes.size(), 1u);
  EXPECT_EQ(s.volumes[0].name, "w");
}

TEST(SceneRoles, SetRoleGivesObjectsByNameOrGroupAndVolumesByName) {
  SceneArrays arrays;
  const auto volume = oneVolume();
  arrays.volumes["v"] = volume;
  Scene s = parseScene(
      R"({"objects": [{"name": "a", "file": "cube.obj"},
                      {"name": "b", "file": "cube.obj", "group": "walls"},
                      {"name": "c", "file": "cube.obj"}],
          "proxies": [{"name": "room", "hullOf": "a"}],
          "volumes": [{"name": "wall scan", "arrays": "v",
                       "transferFunction": [{"value": 1, "opacity": 0.5}]}]})",
      "s", kMeshes, arrays);
  EXPECT_EQ(s.setRole("walls|a", Role::Exterior), 2u);
  EXPECT_EQ(s.setRole("wall scan", Role::Interest), 1u);
  EXPECT_EQ(s.objects[0].role, Role::Exterior);
  EXPECT_EQ(s.objects[1].role, Role::Exterior);
  EXPECT_EQ(s.objects[2].role, Role::Context);
  EXPECT_EQ(s.volumes[0].role, Role::Interest);
  EXPECT_EQ(s.find("room")->role, Role::Interest);  // a proxy keeps its role
  test::expectError([&] { s.setRole("room", Role::Context); },
                    {"room: matches no object's name or group, nor a volume"});
  test::expectError([&] { s.setRole("(", Role::Context); }, {"("});
}

// Issue 17: a glTF node the file leaves unnamed (Assimp calls it by its place, "nodes[74]")
// takes its mesh's name, and the place stays matchable as its alias, so scenes written for
// the places keep working: 2CylinderEngine.glb names none of its 67 mesh nodes.
TEST(SceneNames, UnnamedGltfNodesTakeTheirMeshNamesAndKeepTheirPlaceAsAnAlias) {
  const std::string engine =
      "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
  Scene s = parseScene(R"({"objects": [{"name": "engine", "file": ")" + engine +
                           R"(", "split": "nodes",
      "overrides": [{"match": "nodes\\[(2|5)\\]", "role": "interest", "group": "pistons"}]}]})",
                       "engine.json", kMeshes);
  ASSERT_EQ(s.objects.size(), 67u);
  std::vector<std::string> pistons;
  for (const SceneObject& o : s.objects) {
    EXPECT_EQ(o.name.find("nodes["), std::string::npos) << o.name;
    EXPECT_EQ(o.alias.rfind("engine/nodes[", 0), 0u) << o.alias;
    if (o.group == "pistons") pistons.push_back(o.name + " = " + o.alias);
  }
  std::sort(pistons.begin(), pistons.end());
  EXPECT_EQ(pistons,
            (std::vector<std::string>{"engine/Piston_123-844_0_Parts_1-0 = engine/nodes[5]",
                                      "engine/Piston_123-844_0_Parts_1-0#2 = engine/nodes[2]"}));
  // Name patterns elsewhere take either name.
  s.setRole("engine/nodes\\[9\\]", Role::Interest);
  s.setImportance("engine/rod_.*", 0.9f);
  int rods = 0;
  for (const SceneObject& o : s.objects) {
    EXPECT_EQ(o.role == Role::Interest, o.group == "pistons" || o.alias == "engine/nodes[9]");
    rods += o.importance == 0.9f;
  }
  EXPECT_EQ(rods, 2);
}

// An unnamed glTF node takes its mesh's name, else its parent's, else its material's, and
// keeps its place as the alias (tests/data/meshes/unnamed-nodes.gltf: node 1 under the named
// "assembly", node 2 with the mesh "bolt", node 5 under "assembly" with the material "brass"
// (the parent first), node 3 at the top with "brass", node 4 with nothing named: "node").
// The root Assimp puts over a scene's top-level nodes ("ROOT")
// is no name of the file's.
TEST(SceneNames, UnnamedGltfNodesTakeTheirMeshParentOrMaterialName) {
  const Scene s =
      parseScene(R"({"objects": [{"name": "a", "file": "unnamed-nodes.gltf", "split": "nodes"}]})",
                 "names.json", kMeshes);
  std::vector<std::string> names;
  for (const SceneObject& o : s.objects) names.push_back(o.name + " = " + o.alias);
  EXPECT_EQ(names, (std::vector<std::string>{"a/assembly = a/nodes[1]", "a/bolt = a/nodes[2]",
                                             "a/assembly#2 = a/nodes[5]", "a/brass = a/nodes[3]",
                                             "a/node = a/nodes[4]"}));
}

// A reload while the last scene is held (the viewer's way) imports no mesh file again; a file
// that changed is imported anew, and one no scene holds any more is let go.
TEST(SceneMeshes, AFileAScenesStillHoldsIsNotImportedAgain) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) /
                                    ("cutaway-reload-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::filesystem::copy_file(std::string(CUTAWAY_SOURCE_DIR) + "/examples/data/hollow-box.obj",
                             dir / "box.obj", std::filesystem::copy_options::overwrite_existing);
  // Split by nodes, objects share the file's meshes (an unsplit object is a merged copy).
  const std::string text = R"({"objects": [{"name": "box", "file": "box.obj", "split": "nodes"},
                                {"name": "again", "file": "box.obj", "split": "nodes"}]})";
  const auto load = [&] { return parseScene(text, "reload.json", dir); };
  const Scene first = load();
  const Mesh* mesh = first.objects[0].mesh.get();
  EXPECT_EQ(first.objects[1].mesh.get(), mesh);  // one import per scene
  const Scene second = load();
  EXPECT_EQ(second.objects[0].mesh.get(), mesh);
  // Changed on disk: imported again, and what it holds is the new file.
  std::ofstream(dir / "box.obj", std::ios::app) << "v 9 9 9\nv 9 9 10\nv 9 10 9\nf 17 18 19\n";
  const Scene third = load();
  EXPECT_NE(third.objects[0].mesh.get(), mesh);
  EXPECT_EQ(third.objects[0].mesh->triangles.size(), mesh->triangles.size() + 1);
  std::filesystem::remove_all(dir);
}
