// cutaway/gl/shader.hpp — GLSL programs from the shader files embedded at build time.
//
// Shader files live beside the code that uses them (src/styles/gooch/gooch.glsl, …) and are
// named by their path relative to src/. A source may `#include "name"`: the name is looked up
// relative to the including file's folder, then from src/, then in the program's aliases
// (which is how a geometry shader picks the active style: alias "style.glsl" to
// "styles/gooch/gooch.glsl"), or among the program's generated sources (text made at run time,
// such as the composition of the active cutters, under a file name of its own). Variants are
// made by `#define`s injected after `#version`.
// Compile and link errors throw cutaway::Error naming the file and line, with the info log.
//
//   cutaway::gl::ProgramDesc desc{
//       .stages = {{GL_VERTEX_SHADER, "kinds/meshes/mesh.vert"}, {GL_FRAGMENT_SHADER,
//       "kinds/meshes/mesh.frag"}}, .defines = {{"LINES", "1"}}, .aliases = {{"style.glsl",
//       "styles/gooch/gooch.glsl"}}};
//   cutaway::gl::Program program = cutaway::gl::buildProgram(desc);
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "cutaway/gl/objects.hpp"

namespace cutaway::gl {

struct ProgramDesc {
  std::vector<std::pair<GLenum, std::string>> stages;  // stage, shader file name
  std::map<std::string, std::string> defines;
  std::map<std::string, std::string> aliases;
  std::map<std::string, std::string> sources;  // generated files: name → GLSL text
};

// The source of one stage after #include expansion and #define injection. `origins[i]` is
// where line i + 1 of `text` came from: an index into `files` and a line in that file.
// (No `#line` directives: drivers disagree on honouring their source-string numbers.)
struct PreprocessedSource {
  std::string text;
  std::vector<std::string> files;
  struct Origin {
    int file, line;
  };
  std::vector<Origin> origins;
};
PreprocessedSource preprocess(const std::string& file, const ProgramDesc& desc);

// Rewrites driver info-log prefixes ("0:12(3): error" from Mesa, "0(12) : error" from
// NVIDIA) as "file:line: error", mapping the line back through `source.origins`.
std::string annotateInfoLog(const std::string& log, const PreprocessedSource& source);

Program buildProgram(const ProgramDesc& desc);

// Whether a file of that name was embedded.
bool hasShader(const std::string& name);

}  // namespace cutaway::gl
