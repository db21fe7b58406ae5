#include "cutaway/io/mesh_import.hpp"

#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <zlib.h>

#include <assimp/DefaultIOSystem.h>
#include <assimp/MemoryIOWrapper.h>
#include <algorithm>
#include <assimp/DefaultLogger.hpp>
#include <assimp/Importer.hpp>
#include <assimp/LogStream.hpp>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <new>
#include <regex>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "cutaway/core/contained.hpp"
#include "cutaway/core/error.hpp"
#include "io/ply_reader.hpp"
#include "io/wire_fields.hpp"

namespace cutaway {

namespace {

std::vector<char> readGzip(const std::filesystem::path& file) {
  // zlib passes data without gzip's magic bytes through unchanged: not what a .gz promises.
  unsigned char magic[2] = {0, 0};
  std::ifstream(file, std::ios::binary).read(reinterpret_cast<char*>(magic), 2);
  if (magic[0] != 0x1f || magic[1] != 0x8b) throw Error(file.string(), "", "not a gzip file");
  gzFile gz = gzopen(file.c_str(), "rb");
  if (!gz) throw Error(file.string(), "", "cannot open");
  std::vector<char> data;
  char chunk[1 << 16];
  int n = 0;
  while ((n = gzread(gz, chunk, sizeof chunk)) > 0) data.insert(data.end(), chunk, chunk + n);
  // A stream cut short (or without its 8-byte trailer) ends gzread without an error of its
  // own: zlib only records Z_BUF_ERROR, "unexpected end of file".
  int errnum = Z_OK;
  std::string message = gzerror(gz, &errnum);
  gzclose(gz);
  if (message.starts_with(file.string() + ": "))  // zlib names the file itself
    message.erase(0, file.string().size() + 2);
  if (errnum == Z_BUF_ERROR)
    throw Error(file.string(), "", "truncated gzip stream (" + message + ")");
  if (n < 0 || errnum != Z_OK) throw Error(file.string(), "", "corrupt gzip: " + message);
  if (data.empty()) throw Error(file.string(), "", "empty after gzip decompression");
  return data;
}

glm::mat4 toGlm(const aiMatrix4x4& m) {
  // Assimp matrices are row-major; glm is column-major.
  return glm::transpose(glm::mat4(m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3,
                                  m.c4, m.d1, m.d2, m.d3, m.d4));
}

std::vector<char> readFile(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::vector<char> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in && !in.eof()) throw Error(file.string(), "", "cannot read");
  return data;
}

// Keeps a mesh's normals from its file when each is finite and not zero (normalised), else
// computes them all; whether it computed them.
bool useOrComputeNormals(Mesh& m) {
  bool valid = !m.normals.empty() && m.normals.size() == m.positions.size();
  for (std::size_t i = 0; i < m.normals.size() && valid; ++i) {
    const float len = glm::length(m.normals[i]);
    valid = std::isfinite(len) && len > 1e-6f;
    m.normals[i] /= len;
  }
  if (valid) return false;
  m.normals.clear();
  computeVertexNormals(m);
  return true;
}

// One aiMesh as a cutaway Mesh: triangles only (points and lines were sorted out), normals
// recomputed when missing or invalid. Indices are checked: an importer's output is untrusted.
Mesh convert(const std::filesystem::path& file, const aiMesh& in, bool& normalsComputed) {
  Mesh m;
  m.positions.reserve(in.mNumVertices);
  for (unsigned i = 0; i < in.mNumVertices; ++i)
    m.positions.emplace_back(in.mVertices[i].x, in.mVertices[i].y, in.mVertices[i].z);
  for (unsigned f = 0; f < in.mNumFaces; ++f) {
    const aiFace& face = in.mFaces[f];
    if (face.mNumIndices != 3) continue;
    for (unsigned k = 0; k < 3; ++k)
      if (face.mIndices[k] >= in.mNumVertices)
        throw Error(file.string(), "face " + std::to_string(f),
                    "vertex index " + std::to_string(face.mIndices[k]) + " out of range (" +
                        std::to_string(in.mNumVertices) + " vertices)");
    m.triangles.emplace_back(face.mIndices[0], face.mIndices[1], face.mIndices[2]);
  }
  if (in.HasNormals())
    for (unsigned i = 0; i < in.mNumVertices; ++i)
      m.normals.emplace_back(in.mNormals[i].x, in.mNormals[i].y, in.mNormals[i].z);
  normalsComputed |= useOrComputeNormals(m);
  return m;
}

// The power of two that takes the largest |vertex coordinate| into [1, 2) where it is below 1;
// 0 for any other model.
int joinExponent(const aiScene& scene) {
  float largest = 0.0f;
  for (unsigned i = 0; i < scene.mNumMeshes; ++i) {
    const aiMesh& mesh = *scene.mMeshes[i];
    for (unsigned v = 0; v < mesh.mNumVertices; ++v)
      for (int k = 0; k < 3; ++k)
        if (std::isfinite(mesh.mVertices[v][k]))
          largest = std::max(largest, std::abs(mesh.mVertices[v][k]));
  }
  return largest > 0.0f && largest < 1.0f ? -std::ilogb(largest) : 0;
}

void scaleVertices(const aiScene& scene, int exponent) {  // the meshes are the importer's to change
  if (exponent == 0) return;
  for (unsigned i = 0; i < scene.mNumMeshes; ++i) {
    aiMesh& mesh = *scene.mMeshes[i];
    for (unsigned v = 0; v < mesh.mNumVertices; ++v)
      for (int k = 0; k < 3; ++k) mesh.mVertices[v][k] = std::ldexp(mesh.mVertices[v][k], exponent);
  }
}

// Assimp's name for a glTF node, mesh or material the file leaves unnamed: its place
// ("nodes[74]"; a mesh split by primitive: "meshes[3]-1").
bool isStandIn(const std::string& name) {
  static const std::regex standIn(R"((nodes|meshes|materials)\[\d+\](-\d+)?)");
  return std::regex_match(name, standIn);
}

// A binary glTF's header and chunk table (glTF 2.0 §4.4), checked before Assimp reads it:
// Assimp allocates the lengths they claim (a 330-byte file claiming a 1.2 GB JSON chunk took
// 1.2 GB and five seconds to refuse).
void checkGlbHeader(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  const std::uint64_t size = std::filesystem::file_size(file);
  const auto u32 = [&](std::uint64_t at) {
    unsigned char b[4] = {};
    in.seekg(std::streamoff(at));
    if (at + 4 > size || !in.read(reinterpret_cast<char*>(b), 4))
      throw Error(file.string(), "byte " + std::to_string(at), "the binary glTF ends early");
    return std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 |
           std::uint32_t(b[3]) << 24;
  };
  if (size < 12 || u32(0) != 0x46546c67u)  // "glTF"
    throw Error(file.string(), "", "not a binary glTF file (no \"glTF\" magic)");
  const std::uint32_t version = u32(4), length = u32(8);
  if (length > size)
    throw Error(
        file.string(), "header",
        "claims " + std::to_string(length) + " bytes, the file has " + std::to_string(size));
  // Shorter than its own header and first chunk header (glTF 1.0: the content's header):
  // Assimp then reads the first chunk's claimed length without a bound (a 541-byte file
  // claiming 1 byte took 1.8 GB and 12 s to refuse).
  if (length < 20)
    throw Error(file.string(), "header",
                "claims " + std::to_string(length) + " bytes, less than its 20-byte header");
  if (version != 2) {
    // glTF 1.0's binary: one content block of contentLength bytes after the 20-byte header.
    if (20 + std::uint64_t(u32(12)) > length)
      throw Error(file.string(), "header",
                  "its content claims " + std::to_string(u32(12)) + " bytes beyond the file's " +
                      std::to_string(length));
    return;
  }
  for (std::uint64_t at = 12; at < length;) {
    const std::uint64_t chunk = u32(at);
    if (at + 8 + chunk > length)
      throw Error(
          file.string(), "chunk at byte " + std::to_string(at),
          "claims " + std::to_string(chunk) + " bytes beyond the file's " + std::to_string(length));
    at += 8 + chunk;
  }
}

// The largest finite |coordinate| of the mesh's positions.
float farthest(const Mesh& mesh) {
  float far = 0.0f;
  for (const glm::vec3& p : mesh.positions)
    for (int a = 0; a < 3; ++a)
      if (std::isfinite(p[a])) far = std::max(far, std::abs(p[a]));
  return far;
}

// A triangle's corner that 32-bit floats cannot hold (NaN or infinite in the file, or beyond
// ~3.4e38 once read or placed) is an error, as in the Python module's arrays: the triangle
// would be dropped without a word. Vertices no triangle uses may be anything (a depth
// sensor's mesh keeps NaN for pixels without depth).
// Three numbers as a message shows them: "(1, inf, 0)".
std::string triple(double x, double y, double z) {
  char text[96];
  std::snprintf(text, sizeof text, "(%g, %g, %g)", x, y, z);
  return text;
}

void checkFinite(const std::filesystem::path& file, const std::string& place, const Mesh& mesh) {
  for (const glm::uvec3& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const glm::vec3& p = mesh.positions[t[k]];
      if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) continue;
      throw Error(
          file.string(), place.empty() ? "vertex " + std::to_string(t[k]) : place,
          "a triangle's corner at " + triple(p.x, p.y, p.z) + " is not finite in 32-bit floats");
    }
}

// A file without a triangle to draw: where they all collapsed because their corners lie
// where 32-bit floats no longer tell them apart (a node translated by 1e20), or were dropped
// as degenerate (`dropped` of them), it says so rather than "no triangles".
[[noreturn]] void noTriangles(const std::filesystem::path& file, float far, std::size_t dropped) {
  if (far > kMaxSceneReach) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", double(far));
    throw Error(file.string(), "",
                std::string("its triangles lie ") + text +
                    " from the origin, where 32-bit floats cannot tell their corners apart "
                    "(a scene reaches at most 1e15)");
  }
  if (dropped > 0)
    throw Error(
        file.string(), "",
        (dropped == 1 ? std::string("its one triangle has no area")
                      : "none of its " + std::to_string(dropped) + " triangles has an area") +
            " (a repeated corner, or corners in a line, at one point or not finite)");
  throw Error(file.string(), "", "the file contains no triangles");
}

// A UTF-8 byte-order mark, which some editors put before a text file's first line.
constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";

// Text formats whose Assimp readers take a byte-order mark as part of the first line (an OBJ's
// first vertex then goes missing and the faces name the wrong ones): read without it. (Assimp's
// STL reader drops the mark itself.) Binary formats keep every byte.
bool textFormat(const std::string& format) {
  return format == "obj" || format == "off" || format == "gltf";
}

// The files a model names (an OBJ's mtllib, a glTF's buffers) are read only where they are
// regular files: a FIFO would block the reader, a device feed it without end. The model's own
// file, in a text format, is read without a byte-order mark.
class RegularFilesOnly : public Assimp::DefaultIOSystem {
 public:
  explicit RegularFilesOnly(std::filesystem::path model) : model_(std::move(model)) {}
  bool Exists(const char* file) const override {  // Assimp's own opens the file to see
    std::error_code ec;
    return std::filesystem::is_regular_file(file, ec);
  }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) return nullptr;
    if (!model_.empty() && std::filesystem::equivalent(file, model_, ec)) {
      // Read whole only when it starts with the mark.
      char head[kByteOrderMark.size()];
      std::ifstream in(model_, std::ios::binary);
      in.read(head, sizeof head);
      if (std::string_view(head, std::size_t(in.gcount())) == kByteOrderMark) {
        const std::vector<char> data = readFile(model_);
        const std::size_t size = data.size() - std::min(data.size(), kByteOrderMark.size());
        auto* text = new std::uint8_t[size];
        std::memcpy(text, data.data() + (data.size() - size), size);
        return new Assimp::MemoryIOStream(text, size, true);  // the stream owns the copy
      }
    }
    return DefaultIOSystem::Open(file, mode);
  }

 private:
  std::filesystem::path model_;  // empty: none read without its mark
};

// Assimp's warnings on this thread while it lives: some readers drop what they cannot read (a
// glTF face naming a vertex past the end) and say so only in the log.
class AssimpWarnings {
 public:
  AssimpWarnings() {
    static const bool attached = [] {
      // A host program's own logger stays; the stream joins it (which then owns it).
      if (Assimp::DefaultLogger::isNullLogger())
        Assimp::DefaultLogger::create("", Assimp::Logger::NORMAL, 0);  // no default streams
      Assimp::DefaultLogger::get()->attachStream(new Stream, Assimp::Logger::Warn);
      return true;
    }();
    (void)attached;
    current_ = &messages_;
  }
  ~AssimpWarnings() { current_ = nullptr; }
  AssimpWarnings(const AssimpWarnings&) = delete;
  AssimpWarnings& operator=(const AssimpWarnings&) = delete;
  const std::vector<std::string>& messages() const { return messages_; }

 private:
  struct Stream : Assimp::LogStream {
    void write(const char* message) override {
      if (!current_) return;
      std::string text = message;
      // "Warn,  T0: Some faces …\n" → "Some faces …"
      if (const auto colon = text.find(": "); colon != std::string::npos) text.erase(0, colon + 2);
      while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
      current_->push_back(std::move(text));
    }
  };
  static thread_local std::vector<std::string>* current_;
  std::vector<std::string> messages_;
};
thread_local std::vector<std::string>* AssimpWarnings::current_ = nullptr;

// The import itself, in whichever process runs it.
std::vector<ImportedNode> importHere(const std::filesystem::path& file) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(file, ec);
  if (!std::filesystem::is_regular_file(status))
    throw Error(file.string(), "",
                std::filesystem::exists(status) ? "mesh file is not a regular file"
                : ec && ec != std::errc::no_such_file_or_directory
                    ? "mesh file cannot be read: " + ec.message()  // a loop of links
                    : "mesh file not found");
  const bool gzip = file.extension() == ".gz";
  // "room.stl.gz" → "stl"
  std::string format = (gzip ? file.stem().extension() : file.extension()).string();
  if (!format.empty()) format.erase(0, 1);
  std::transform(format.begin(), format.end(), format.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  if (format == "ply") {
    const std::vector<char> data = gzip ? readGzip(file) : readFile(file);
    ImportedNode node;
    // "bunny.ply.gz" → "bunny"
    node.name = (gzip ? file.stem().stem() : file.stem()).string();
    node.mesh = readPly(file, data.data(), data.size());
    checkFinite(file, "", node.mesh);
    node.mesh.report.normalsComputed = useOrComputeNormals(node.mesh);
    node.mesh.report.droppedDegenerate = dropDegenerateTriangles(node.mesh);
    if (node.mesh.triangles.empty())
      noTriangles(file, farthest(node.mesh), node.mesh.report.droppedDegenerate);
    analyzeTopology(node.mesh);
    orientOutward(node.mesh);
    return {std::move(node)};
  }
  Assimp::Importer importer;
  importer.SetIOHandler(new RegularFilesOnly(textFormat(format) ? file : ""));  // owned by it
  // Points and lines carry no surface: drop them rather than fail.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                              aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const AssimpWarnings warnings;
  const aiScene* scene = nullptr;
  if (gzip) {
    std::vector<char> data = readGzip(file);
    if (textFormat(format) &&
        std::string_view(data.data(), data.size()).starts_with(kByteOrderMark))
      data.erase(data.begin(), data.begin() + std::ptrdiff_t(kByteOrderMark.size()));
    scene = importer.ReadFileFromMemory(data.data(), data.size(), 0, format.c_str());
  } else {
    if (format == "glb") checkGlbHeader(file);
    scene = importer.ReadFile(file.string(), 0);
  }
  if (scene && scene->mRootNode) {
    // A reader may return faces without vertices and claim primitive types its faces do not
    // have (a truncated PLY: empty faces, called polygons; an OBJ face of one or two
    // vertices, called a triangle), which Assimp's validation refuses in its own words and its
    // triangulation aborts on (found by fuzzing): empty faces are refused, and the types set
    // from the faces before validation and the steps that trust them.
    for (unsigned i = 0; i < scene->mNumMeshes; ++i) {
      const std::string place = "mesh " + std::to_string(i);
      if (!scene->mMeshes || !scene->mMeshes[i])
        throw Error(file.string(), place, "missing (corrupt file?)");
      aiMesh& mesh = *scene->mMeshes[i];
      if (mesh.mNumFaces > 0 && !mesh.mFaces)
        throw Error(file.string(), place, "faces missing (corrupt file?)");
      unsigned types = 0;
      for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
        const unsigned n = mesh.mFaces[f].mNumIndices;
        if (n == 0)
          throw Error(file.string(), place + ", face " + std::to_string(f),
                      "a face without vertices (truncated or corrupt file?)");
        types |= n == 1   ? aiPrimitiveType_POINT
                 : n == 2 ? aiPrimitiveType_LINE
                 : n == 3 ? aiPrimitiveType_TRIANGLE
                          : aiPrimitiveType_POLYGON;
      }
      mesh.mPrimitiveTypes = types;
    }
    // Validation before the steps that index vertices the file claims without checking.
    scene = importer.ApplyPostProcessing(aiProcess_ValidateDataStructure);
    if (scene) {
      // Faces' corners checked before the join, which may merge a NaN corner into another (a
      // lone triangle then said "no area"); points and lines are dropped whatever they hold.
      for (unsigned i = 0; i < scene->mNumMeshes; ++i) {
        const aiMesh& mesh = *scene->mMeshes[i];
        for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
          const aiFace& face = mesh.mFaces[f];
          if (face.mNumIndices < 3) continue;
          for (unsigned k = 0; k < face.mNumIndices; ++k) {
            const aiVector3D& p = mesh.mVertices[face.mIndices[k]];
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
              throw Error(
                  file.string(), "mesh " + std::to_string(i) + ", face " + std::to_string(f),
                  "a corner at " + triple(p.x, p.y, p.z) + " is not finite in 32-bit floats");
          }
        }
      }
      // Assimp joins vertices less than 1e-5 apart, in absolute units: a model 1e-6 across
      // lost corners. Where every coordinate is below 1, the vertices are scaled by a power of
      // two (exactly) for the join, so that it joins within 1e-5 of the largest, and back.
      const int exponent = joinExponent(*scene);
      scaleVertices(*scene, exponent);
      scene = importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_SortByPType |
                                           aiProcess_JoinIdenticalVertices);
      if (scene) scaleVertices(*scene, -exponent);
    }
  }
  // A reader that drops what it cannot read says so only in its log.
  for (const std::string& warning : warnings.messages())
    if (warning.find("out-of-range indices") != std::string::npos)  // glTF 2
      throw Error(file.string(), "",
                  "faces name vertices past the end of their mesh (corrupt file?)");
  if (!scene || !scene->mRootNode) {
    // A file read from memory goes by Assimp's stand-in name: give the user's back.
    std::string reason = importer.GetErrorString();
    // Assimp turns a failed allocation into its error text: the worker reports it as such
    // (the memory limit, CUTAWAY_IMPORT_MEMORY_MB, named).
    if (reason.find("std::bad_alloc") != std::string::npos) throw std::bad_alloc();
    const std::string standIn = std::string(AI_MEMORYIO_MAGIC_FILENAME) + "." + format;
    for (std::size_t at; (at = reason.find(standIn)) != std::string::npos;)
      reason.replace(at, standIn.size(), file.filename().string());
    throw Error(file.string(), "", "cannot import mesh: " + reason);
  }

  std::vector<ImportedNode> nodes;
  std::map<std::string, int> nameCount;
  std::set<std::string> taken;
  float far = 0.0f;         // of the nodes left without triangles, for noTriangles
  std::size_t dropped = 0;  // degenerate triangles of every node
  auto visit = [&](auto&& self, const aiNode* node, const glm::mat4& parent) -> void {
    const glm::mat4 transform = parent * toGlm(node->mTransformation);
    if (node->mNumMeshes > 0) {
      ImportedNode out;
      std::string name = node->mName.C_Str();
      if (name.empty() || isStandIn(name)) {
        const aiMesh* first = scene->mMeshes[node->mMeshes[0]];
        const std::string candidates[] = {
            first->mName.C_Str(),
            // Assimp's glTF reader joins a scene's top-level nodes under a root it names "ROOT".
            node->mParent && !(node->mParent == scene->mRootNode &&
                               std::string_view(node->mParent->mName.C_Str()) == "ROOT")
                ? node->mParent->mName.C_Str()
                : "",
            first->mMaterialIndex < scene->mNumMaterials
                ? scene->mMaterials[first->mMaterialIndex]->GetName().C_Str()
                : ""};
        std::string named = "node";
        for (const std::string& c : candidates)
          if (!c.empty() && !isStandIn(c) && c != AI_DEFAULT_MATERIAL_NAME) {
            named = c;
            break;
          }
        out.id = name;
        name = named;
      }
      // Repeated names take "#2", "#3", …, skipping those the file's own nodes hold ("a",
      // "a#2", "a" gave two "a#2").
      out.name = name;
      for (int k = nameCount[name]++; taken.count(out.name);)
        out.name = name + "#" + std::to_string(++k);
      taken.insert(out.name);
      bool normalsComputed = false;
      for (unsigned i = 0; i < node->mNumMeshes; ++i) {
        const aiMesh* mesh = scene->mMeshes[node->mMeshes[i]];
        if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
        Mesh converted = convert(file, *mesh, normalsComputed);
        // As the file gives them: the node's transform would mix a lone infinity into NaNs.
        checkFinite(file, "node \"" + out.name + "\"", converted);
        out.mesh.append(converted, transform);
        if (!out.color && mesh->mMaterialIndex < scene->mNumMaterials) {
          aiColor4D c;
          const aiMaterial* material = scene->mMaterials[mesh->mMaterialIndex];
          // Assimp invents "DefaultMaterial" for files without materials: not the file's colour.
          if (material->GetName() == aiString(AI_DEFAULT_MATERIAL_NAME)) continue;
          if (material->Get(AI_MATKEY_BASE_COLOR, c) == AI_SUCCESS ||
              material->Get(AI_MATKEY_COLOR_DIFFUSE, c) == AI_SUCCESS) {
            // Beyond [0, 1] (an OBJ's Kd 5, a glTF factor of 50) clamped, as a display would;
            // not a number refused, with its material.
            if (!std::isfinite(c.r) || !std::isfinite(c.g) || !std::isfinite(c.b)) {
              throw Error(file.string(), "material " + quote(material->GetName().C_Str()),
                          "its colour " + triple(c.r, c.g, c.b) + " is not finite");
            }
            out.color = glm::clamp(glm::vec3(c.r, c.g, c.b), 0.0f, 1.0f);
          }
        }
      }
      checkFinite(file, "node \"" + out.name + "\"", out.mesh);
      out.mesh.report.normalsComputed = normalsComputed;
      out.mesh.report.droppedDegenerate = dropDegenerateTriangles(out.mesh);
      dropped += out.mesh.report.droppedDegenerate;
      if (!out.mesh.triangles.empty()) {
        analyzeTopology(out.mesh);
        orientOutward(out.mesh);
        nodes.push_back(std::move(out));
      } else {
        far = std::max(far, farthest(out.mesh));  // only a file without triangles asks
      }
    }
    for (unsigned i = 0; i < node->mNumChildren; ++i) self(self, node->mChildren[i], transform);
  };
  visit(visit, scene->mRootNode, glm::mat4(1.0f));
  if (nodes.empty()) noTriangles(file, far, dropped);
  return nodes;
}

}  // namespace

template <class Archive>
void wireFields(Archive& a, ImportedNode& n) {
  a(n.name, n.id, n.mesh, n.color);
}

// Assimp's importers are made once by the helper the workers are forked from.
const bool kImportersWarm = registerContainedWarmUp([] { Assimp::Importer importer; });
const ContainedReader<std::vector<ImportedNode>, &importHere> containedImport("mesh",
                                                                              "the mesh importer");

std::vector<ImportedNode> importMeshNodes(const std::filesystem::path& file) {
  return containedImport(file);
}

}  // namespace cutaway
