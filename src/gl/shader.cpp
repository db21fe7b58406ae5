#include "cutaway/gl/shader.hpp"

#include <filesystem>
#include <regex>
#include <set>
#include <sstream>

#include "cutaway/core/error.hpp"
#include "gl/shader_registry.hpp"

namespace cutaway::gl {

namespace {

std::string folderOf(const std::string& name) {
  const auto slash = name.rfind('/');
  return slash == std::string::npos ? std::string() : name.substr(0, slash + 1);
}

std::string resolveInclude(const std::string& includer, const std::string& name,
                           const ProgramDesc& desc) {
  if (auto alias = desc.aliases.find(name); alias != desc.aliases.end()) return alias->second;
  if (desc.sources.count(name)) return name;
  const std::string relative =
      std::filesystem::path(folderOf(includer) + name).lexically_normal().generic_string();
  if (hasShader(relative) || desc.sources.count(relative)) return relative;
  return name;
}

struct Expander {
  const ProgramDesc& desc;
  PreprocessedSource& out;
  std::vector<std::string> stack;

  int fileIndex(const std::string& file) {
    for (std::size_t i = 0; i < out.files.size(); ++i)
      if (out.files[i] == file) return int(i);
    out.files.push_back(file);
    return int(out.files.size() - 1);
  }

  void expand(const std::string& file, const std::string& includedFrom, int includeLine) {
    // A source generated for this program (e.g. the cutter composition) comes first.
    std::string_view text;
    if (const auto generated = desc.sources.find(file); generated != desc.sources.end()) {
      text = generated->second;
    } else if (const auto it = embeddedShaders().find(file); it != embeddedShaders().end()) {
      text = it->second;
    } else {
      if (includedFrom.empty()) throw Error(file, "", "no such shader file");
      throw Error(includedFrom, "line " + std::to_string(includeLine),
                  "#include of unknown shader file \"" + file + "\"");
    }
    for (const auto& f : stack)
      if (f == file)
        throw Error(includedFrom, "line " + std::to_string(includeLine),
                    "recursive #include of \"" + file + "\"");
    stack.push_back(file);
    const int index = fileIndex(file);
    static const std::regex includeRe(R"re(^\s*#\s*include\s+"([^"]+)"\s*$)re");
    static const std::regex versionRe(R"(^\s*#\s*version\b.*$)");
    std::istringstream in{std::string(text)};
    std::string line;
    int number = 0;
    auto emit = [&](const std::string& text, int sourceLine) {
      out.text += text + "\n";
      out.origins.push_back({index, sourceLine});
    };
    while (std::getline(in, line)) {
      ++number;
      std::smatch m;
      if (std::regex_match(line, versionRe)) {
        if (!includedFrom.empty())
          throw Error(file, "line " + std::to_string(number), "#version in an included file");
        emit(line, number);
        for (const auto& [name, value] : desc.defines)
          emit("#define " + name + " " + value, number);
      } else if (std::regex_match(line, m, includeRe)) {
        expand(resolveInclude(file, m[1].str(), desc), file, number);
      } else {
        emit(line, number);
      }
    }
    stack.pop_back();
  }
};

const char* stageName(GLenum stage) {
  switch (stage) {
    case GL_VERTEX_SHADER:
      return "vertex";
    case GL_FRAGMENT_SHADER:
      return "fragment";
    case GL_GEOMETRY_SHADER:
      return "geometry";
    case GL_TESS_CONTROL_SHADER:
      return "tessellation control";
    case GL_TESS_EVALUATION_SHADER:
      return "tessellation evaluation";
    case GL_COMPUTE_SHADER:
      return "compute";
    default:
      return "unknown";
  }
}

}  // namespace

bool hasShader(const std::string& name) {
  return embeddedShaders().count(name) != 0;
}

PreprocessedSource preprocess(const std::string& file, const ProgramDesc& desc) {
  PreprocessedSource out;
  Expander{desc, out, {}}.expand(file, "", 0);
  return out;
}

std::string annotateInfoLog(const std::string& log, const PreprocessedSource& source) {
  static const std::regex prefixRe(R"(^(\d+)(?::(\d+)\(\d+\)|\((\d+)\))\s*:?)");
  std::istringstream in(log);
  std::string line, out;
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_search(line, m, prefixRe)) {
      const std::size_t number = std::stoul(m[2].matched ? m[2].str() : m[3].str());
      if (number >= 1 && number <= source.origins.size()) {
        const auto& origin = source.origins[number - 1];
        line = source.files[std::size_t(origin.file)] + ":" + std::to_string(origin.line) + ":" +
               m.suffix().str();
      } else {
        line = "line " + std::to_string(number) + ":" + m.suffix().str();
      }
    }
    if (!line.empty()) out += (out.empty() ? "" : " | ") + line;
  }
  return out;
}

Program buildProgram(const ProgramDesc& desc) {
  Program program(glCreateProgram());
  std::vector<Shader> shaders;
  std::vector<std::string> allFiles;
  for (const auto& [stage, file] : desc.stages) {
    const PreprocessedSource source = preprocess(file, desc);
    Shader shader(glCreateShader(stage));
    const char* text = source.text.c_str();
    glShaderSource(shader.id(), 1, &text, nullptr);
    glCompileShader(shader.id());
    GLint ok = 0;
    glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
    if (!ok) {
      GLint length = 0;
      glGetShaderiv(shader.id(), GL_INFO_LOG_LENGTH, &length);
      std::string log(std::size_t(std::max(length, 1)), '\0');
      glGetShaderInfoLog(shader.id(), length, nullptr, log.data());
      throw Error(file, std::string(stageName(stage)) + " shader",
                  "compile failed: " + annotateInfoLog(log.c_str(), source));
    }
    glAttachShader(program.id(), shader.id());
    allFiles.push_back(file);
    shaders.push_back(std::move(shader));
  }
  glLinkProgram(program.id());
  GLint ok = 0;
  glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetProgramiv(program.id(), GL_INFO_LOG_LENGTH, &length);
    std::string log(std::size_t(std::max(length, 1)), '\0');
    glGetProgramInfoLog(program.id(), length, nullptr, log.data());
    std::string names;
    for (const auto& f : allFiles) names += (names.empty() ? "" : " + ") + f;
    throw Error(names, "program",
                "link failed: " + annotateInfoLog(log.c_str(), PreprocessedSource{}));
  }
  for (const auto& s : shaders) glDetachShader(program.id(), s.id());
  return program;
}

}  // namespace cutaway::gl
