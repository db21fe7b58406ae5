// Shader preprocessing (#include, #define, #line) and error reporting.
#include <gtest/gtest.h>

#include "cutaway/core/error.hpp"
#include "cutaway/gl/shader.hpp"
#include "cutters/registry.hpp"
#include "gl/shader_registry.hpp"
#include "gl_test_context.hpp"

using namespace cutaway;

TEST(Shader, IncludesResolveRelativelyAndThroughAliases) {
  // Generated sources are included like files: here a composition of two cutter files.
  const gl::ProgramDesc desc{
      .defines = {{"ANSWER", "42"}},
      .aliases = {{"style.glsl", "styles/gooch/gooch.glsl"}},
      .sources = {{"cutters/composition.glsl",
                   "#include \"cutters/fate.glsl\"\n#include \"cutters/cutout/cutout.glsl\"\n"
                   "int cutFragment() { return kKeep; }\n"},
                  {"frame/gbuffer_channels.glsl", "void writeNoChannels() {}\n"}}};
  const gl::PreprocessedSource source = gl::preprocess("kinds/meshes/mesh.frag", desc);
  const std::vector<std::string> expected{"kinds/meshes/mesh.frag",
                                          "frame/frame_uniforms.glsl",
                                          "styles/surface.glsl",
                                          "styles/gooch/gooch.glsl",
                                          "styles/shadows/shadow_lookup.glsl",
                                          "styles/emphasis/emphasis.glsl",
                                          "frame/gbuffer.glsl",
                                          "frame/normal_weight.glsl",
                                          "frame/gbuffer_channels.glsl",
                                          "cutters/composition.glsl",
                                          "cutters/fate.glsl",
                                          "cutters/cutout/cutout.glsl",
                                          "frame/samples.glsl"};
  EXPECT_EQ(source.files, expected);
  // Defines come right after #version, before any other line.
  EXPECT_EQ(source.text.rfind("#version 450 core\n#define ANSWER 42\n", 0), 0u)
      << source.text.substr(0, 80);
  EXPECT_EQ(source.text.find("#include"), std::string::npos);
  // Every output line maps back to its file (embedded or generated) and line.
  std::vector<std::string> lines;
  for (std::size_t start = 0, end; (end = source.text.find('\n', start)) != std::string::npos;
       start = end + 1)
    lines.push_back(source.text.substr(start, end - start));
  ASSERT_EQ(lines.size(), source.origins.size());
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].rfind("#define", 0) == 0) continue;
    const auto& origin = source.origins[i];
    const std::string& file = source.files[std::size_t(origin.file)];
    const std::string raw = desc.sources.count(file)
                                ? desc.sources.at(file)
                                : std::string(gl::embeddedShaders().at(file));
    std::size_t start = 0;
    for (int l = 1; l < origin.line; ++l) start = raw.find('\n', start) + 1;
    EXPECT_EQ(raw.substr(start, raw.find('\n', start) - start), lines[i])
        << "output line " << i + 1;
  }
  EXPECT_EQ(source.files[std::size_t(source.origins[0].file)], "kinds/meshes/mesh.frag");
}

TEST(Shader, UnknownIncludeNamesTheIncludingFileAndLine) {
  const gl::ProgramDesc desc{};  // no alias for "style.glsl"
  try {
    (void)gl::preprocess("kinds/meshes/mesh.frag", desc);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.file(), "kinds/meshes/mesh.frag");
    EXPECT_EQ(e.place(), "line 7");
    EXPECT_NE(e.reason().find("\"style.glsl\""), std::string::npos) << e.what();
  }
}

TEST(Shader, InfoLogPrefixesBecomeFileAndLine) {
  gl::PreprocessedSource source;
  source.files = {"a.frag", "lib/b.glsl"};
  source.origins = {{0, 1}, {0, 2}, {1, 1}, {1, 2}, {0, 4}};
  EXPECT_EQ(gl::annotateInfoLog("0:4(7): error: `x' undeclared\n", source),
            "lib/b.glsl:2: error: `x' undeclared");
  EXPECT_EQ(gl::annotateInfoLog("0(5) : error C1008: undefined variable \"y\"\n", source),
            "a.frag:4: error C1008: undefined variable \"y\"");
  EXPECT_EQ(gl::annotateInfoLog("no prefix here", source), "no prefix here");
}

// A real driver compile error, traced back to the file and line that caused it.
TEST(Shader, CompileErrorNamesFileLineAndLog) {
  test::glContext();
  // Aliasing the style to the uniform block redeclares it: a genuine compile error.
  const gl::ProgramDesc desc{
      .stages = {{GL_VERTEX_SHADER, "frame/mesh.vert"}, {GL_FRAGMENT_SHADER, "kinds/meshes/mesh.frag"}},
      .aliases = {{"style.glsl", "frame/frame_uniforms.glsl"}},
      .sources = {{"cutters/composition.glsl", cutterComposition({})},
                  {"frame/gbuffer_channels.glsl", "void writeNoChannels() {}\n"}}};
  try {
    (void)gl::buildProgram(desc);
    FAIL() << "expected a compile error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.file(), "kinds/meshes/mesh.frag") << what;
    EXPECT_NE(what.find("compile failed"), std::string::npos) << what;
    // kMaxLights is declared on line 2 of the uniform block file; its second inclusion fails.
    EXPECT_NE(what.find("frame/frame_uniforms.glsl:2: error"), std::string::npos) << what;
  }
}
