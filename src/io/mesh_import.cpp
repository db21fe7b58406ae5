#include "cutaway/io/mesh_import.hpp"

#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <zlib.h>

#include <assimp/MemoryIOWrapper.h>
#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <sstream>

#include "cutaway/core/contained.hpp"
#include "cutaway/core/error.hpp"
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
  int errnum = 0;
  const std::string message = n < 0 ? gzerror(gz, &errnum) : "";
  gzclose(gz);
  if (n < 0) throw Error(file.string(), "", "corrupt gzip: " + message);
  if (data.empty()) throw Error(file.string(), "", "empty after gzip decompression");
  return data;
}

glm::mat4 toGlm(const aiMatrix4x4& m) {
  // Assimp matrices are row-major; glm is column-major.
  return glm::transpose(glm::mat4(m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3,
                                  m.c4, m.d1, m.d2, m.d3, m.d4));
}

// The layout a PLY header declares, as far as the list counts in its data need it.
struct PlyProperty {
  int bytes = 0;       // a scalar's size, or a list's items'
  int countBytes = 0;  // a list's count's size; 0 for a scalar
  bool signedCount = false;
};
struct PlyElement {
  std::string name;
  double count = 0;
  std::vector<PlyProperty> properties;
  bool closed = false;  // past a property of a type Assimp does not know
};

// The size of a PLY type; `integer`: of an integer type only (a list's count).
int plyTypeBytes(const std::string& type, bool integer = false) {
  static const std::pair<const char*, int> kTypes[] = {
      {"char", 1},  {"uchar", 1},   {"int8", 1},   {"uint8", 1},  {"short", 2}, {"ushort", 2},
      {"int16", 2}, {"uint16", 2},  {"int", 4},    {"uint", 4},   {"int32", 4}, {"uint32", 4},
      {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
  for (const auto& [name, bytes] : kTypes)
    if (type == name) return integer && (type[0] == 'f' || type[0] == 'd') ? 0 : bytes;
  return 0;
}

// Lines as Assimp's IOStreamBuffer::getNextLine cuts them: a line ends at \n, \r, \0 or \f, and
// a call that starts on such a character first skips past the next \n (so \r\n is one break).
// Past the end there is no next line (Assimp then parses its last line again).
class PlyLines {
 public:
  PlyLines(const char* data, std::size_t size, std::size_t at = 0)
      : data_(data), size_(size), at_(at) {}
  bool next(std::size_t& begin, std::size_t& end) {
    if (at_ < size_ && isEnd(data_[at_])) {
      while (at_ < size_ && data_[at_] != '\n') ++at_;
      ++at_;
    }
    if (at_ >= size_) return false;
    begin = at_;
    while (at_ < size_ && !isEnd(data_[at_])) ++at_;
    end = at_++;
    return true;
  }
  std::size_t at() const { return std::min(at_, size_); }

 private:
  static bool isEnd(char c) { return c == '\n' || c == '\r' || c == '\0' || c == '\f'; }
  const char* data_;
  std::size_t size_, at_;
};

// Assimp allocates what each list in the data claims before reading it ("9999…3" indices in
// an ASCII face: 34 GB; fuzzing). In ASCII a list item takes at least a byte, in binary its
// type's size, so a list longer than the bytes left is a lie. Walks the elements the header
// declared, laid out as Assimp takes them, until the data ends.
void checkPlyLists(const std::filesystem::path& file, const char* data, std::size_t size,
                   std::size_t at, const std::string& format,
                   const std::vector<PlyElement>& elements) {
  const bool ascii = format == "ascii", big = format == "binary_big_endian";
  if (!ascii && !big && format != "binary_little_endian") return;
  auto refuse = [&](const PlyElement& e, double instance, double count) {
    char claimed[32];
    std::snprintf(claimed, sizeof claimed, "%.15g", count);
    throw Error(file.string(), e.name.substr(0, 40) + " " + std::to_string(std::uint64_t(instance)),
                "a list of " + std::string(claimed) + " values in the " +
                    std::to_string(size - at) + " bytes left");
  };
  // ASCII: one instance per line, as Assimp reads them; `token` moves past the line's next word.
  // Assimp parses the lists of the elements it knows; it skips the others' lines. Its number
  // parser stops inside an integer beyond 64 bits and takes the rest of the digits for the
  // next word (a vertex's 24-digit x made its list count 333…; fuzzing): such numbers are
  // refused.
  std::size_t begin = 0, lineBegin = 0, lineEnd = 0;
  const PlyElement* element = nullptr;
  double instance = 0;
  auto token = [&] {
    while (at < lineEnd && std::isspace(static_cast<unsigned char>(data[at]))) ++at;
    begin = at;
    while (at < lineEnd && !std::isspace(static_cast<unsigned char>(data[at]))) ++at;
    std::size_t digits = begin + (at > begin && (data[begin] == '-' || data[begin] == '+'));
    while (digits < at && std::isdigit(static_cast<unsigned char>(data[digits]))) ++digits;
    if (digits - begin > 20)
      throw Error(file.string(),
                  element->name.substr(0, 40) + " " + std::to_string(std::uint64_t(instance)),
                  "a number of " + std::to_string(digits - begin) + " digits, beyond 64 bits");
    return at > begin;
  };
  PlyLines lines(data, size, at);
  bool read = false;
  for (const PlyElement& e : elements) {
    std::string kind = e.name;
    for (char& c : kind) c = char(std::tolower(static_cast<unsigned char>(c)));
    const bool parsed = kind == "vertex" || kind == "face" || kind == "tristrips" ||
                        kind == "edge" || kind == "material" || kind == "texturefile";
    element = &e;
    for (double i = 0; i < e.count; ++i) {
      instance = i;
      bool stale = false;
      if (ascii) {
        stale = !lines.next(lineBegin, lineEnd);
        if (stale && !read) return;
        read = true;
        at = lineBegin;
        if (!parsed) {
          if (stale) break;
          continue;
        }
      }
      for (const PlyProperty& p : e.properties) {
        if (p.countBytes == 0) {  // a scalar
          if (!ascii) {
            if (size - at < std::size_t(p.bytes)) return;  // the data ends
            at += std::size_t(p.bytes);
          } else if (!token()) {
            break;
          }
          continue;
        }
        double count = 0;
        if (ascii) {
          if (!token()) break;
          count = std::strtod(
              std::string(data + begin, std::min<std::size_t>(at - begin, 400)).c_str(), nullptr);
        } else {
          if (size - at < std::size_t(p.countBytes)) return;
          std::uint32_t raw = 0;
          for (int b = 0; b < p.countBytes; ++b)
            raw |= std::uint32_t(static_cast<unsigned char>(data[at + std::size_t(b)]))
                   << (8 * (big ? p.countBytes - 1 - b : b));
          at += std::size_t(p.countBytes);
          count = raw;
          if (p.signedCount && raw >> (8 * p.countBytes - 1))
            count = double(raw) - std::ldexp(1.0, 8 * p.countBytes);
        }
        if (!(count >= 0) || count * (ascii ? 1 : p.bytes) > double(size - at)) refuse(e, i, count);
        if (ascii) {
          for (double k = 0; k < count && token(); ++k) {
          }
        } else {
          at += std::size_t(count) * std::size_t(p.bytes);
        }
      }
      if (stale) break;  // the later instances parse the same line again
    }
  }
}

// A PLY file's header, checked before Assimp reads it: Assimp's reader loops forever on a header
// without an "end_header" line and allocates what an element count claims. Each element takes
// at least one byte of the file, so a count beyond its size is a lie. "element" is compared
// without case, as a header Assimp still parses ("elemeNt", found by fuzzing) must be checked;
// "end_header" with it, as Assimp reads nothing else as the header's end. Assimp 5.2 sizes
// its vertex and face arrays by the first element of each kind and writes a later one's into
// them past their end (heap overflows under valgrind; a corrupted heap when fuzzing): one
// vertex element and one face or tristrips element at most. Then the data's lists.
void checkPlyHeader(const std::filesystem::path& file, const char* data, std::size_t size) {
  const std::string head(data, std::min<std::size_t>(size, 1 << 16));
  if (head.rfind("ply", 0) != 0) throw Error(file.string(), "", "not a PLY file (no \"ply\" line)");
  const auto lower = [](std::string w) {
    for (char& c : w) c = char(std::tolower(static_cast<unsigned char>(c)));
    return w;
  };
  PlyLines lines(head.data(), head.size());
  std::string format;
  std::vector<PlyElement> elements;
  bool vertices = false, faces = false;
  std::size_t lineBegin = 0, lineEnd = 0;
  for (int number = 1; lines.next(lineBegin, lineEnd); ++number) {
    const std::string text = head.substr(lineBegin, lineEnd - lineBegin);
    std::istringstream words(text);
    std::string keyword, name, countText;
    if (!(words >> keyword)) continue;
    // Assimp ends the header only at "end_header" as written, between spaces and tabs alone
    // ("end_headEr" and "end_header\v" made it read on and loop at the end of the file;
    // fuzzing), but takes "elemeNt" for an element.
    const std::size_t first = text.find_first_not_of(" \t"), last = text.find_last_not_of(" \t");
    if (first != std::string::npos && text.substr(first, last - first + 1) == "end_header") {
      // Assimp reads a last line without a line end over the line before it: after some
      // unknown header lines it never matched "end_header" and looped (fuzzing).
      if (lineEnd >= size)
        throw Error(file.string(), "header line " + std::to_string(number),
                    "the file ends at end_header, with no line end and no data (truncated?)");
      checkPlyLists(file, data, size, lines.at(), format, elements);
      return;
    }
    if (lower(keyword) == "format") words >> format;
    // A property of a type Assimp does not know ends its element's properties, as Assimp
    // skips that line and takes the element's layout to end there.
    if (lower(keyword) == "property" && !elements.empty() && !elements.back().closed) {
      std::string type, countType, itemType;
      words >> type;
      PlyProperty p;
      if (lower(type) == "list" && words >> countType >> itemType) {
        p.countBytes = plyTypeBytes(countType, true);
        p.signedCount = countType.find('u') == std::string::npos;
        p.bytes = p.countBytes ? plyTypeBytes(itemType) : 0;
      } else {
        p.bytes = plyTypeBytes(type);
      }
      if (p.bytes == 0)
        elements.back().closed = true;
      else
        elements.back().properties.push_back(p);
    }
    if (lower(keyword) != "element") continue;
    // The count as written: its value may be beyond every integer type (fuzzing).
    char* end = nullptr;
    const double count = words >> name >> countText ? std::strtod(countText.c_str(), &end) : -1.0;
    if (countText.empty() || *end != '\0' || !(count >= 0.0))
      throw Error(file.string(), "header line " + std::to_string(number),
                  "an element needs a name and a count");
    if (count > double(size))
      throw Error(file.string(), "header line " + std::to_string(number),
                  "claims " + countText.substr(0, 40) + " " + name.substr(0, 40) +
                      " elements in a file of " + std::to_string(size) + " bytes");
    // Assimp's parser does not move past a name it does not know, and reads that element's
    // count from the name's first digits ("666…face 8": 2³² − 1 faces, 68 GB; fuzzing).
    double counted = count;
    if (name != "vertex" && name != "face" && name != "tristrips" && name != "edge" &&
        name != "material" && name != "TextureFile") {
      const std::size_t digits = name.find_first_not_of("0123456789");
      counted = std::strtod(name.substr(0, std::min<std::size_t>(digits, 400)).c_str(), nullptr);
      if (counted > double(size))
        throw Error(file.string(), "header line " + std::to_string(number),
                    "an element named \"" + name.substr(0, 40) +
                        "\", whose count Assimp reads from its name's digits");
    }
    elements.push_back({name, counted, {}});
    const std::string kind = lower(name);
    bool& seen = kind == "vertex" ? vertices : faces;
    if (kind == "vertex" || kind == "face" || kind == "tristrips") {
      if (seen)
        throw Error(file.string(), "header line " + std::to_string(number),
                    "a second " + std::string(kind == "vertex" ? "vertex" : "face") +
                        " element (one of each is read)");
      seen = true;
    }
  }
  throw Error(file.string(), "header", "the PLY header has no end_header line (truncated?)");
}

std::vector<char> readFile(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::vector<char> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in && !in.eof()) throw Error(file.string(), "", "cannot read");
  return data;
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
  bool valid = in.HasNormals();
  if (valid) {
    m.normals.reserve(in.mNumVertices);
    for (unsigned i = 0; i < in.mNumVertices && valid; ++i) {
      const glm::vec3 n(in.mNormals[i].x, in.mNormals[i].y, in.mNormals[i].z);
      const float len = glm::length(n);
      valid = std::isfinite(len) && len > 1e-6f;
      m.normals.push_back(valid ? n / len : n);
    }
  }
  if (!valid) {
    computeVertexNormals(m);
    normalsComputed = true;
  }
  return m;
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

// The import itself, in whichever process runs it.
std::vector<ImportedNode> importHere(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw Error(file.string(), "", "mesh file not found");
  Assimp::Importer importer;
  // Points and lines carry no surface: drop them rather than fail.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                              aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  // Validation first: the later steps index vertices the file claims without checking. They
  // run once the primitive types are corrected (below).
  const unsigned flags = aiProcess_ValidateDataStructure;
  const aiScene* scene = nullptr;
  const bool gzip = file.extension() == ".gz";
  // "room.stl.gz" → "stl"
  std::string format = (gzip ? file.stem().extension() : file.extension()).string();
  if (!format.empty()) format.erase(0, 1);
  std::transform(format.begin(), format.end(), format.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  if (gzip || format == "ply") {
    const std::vector<char> data = gzip ? readGzip(file) : readFile(file);
    if (format == "ply") checkPlyHeader(file, data.data(), data.size());
    scene = importer.ReadFileFromMemory(data.data(), data.size(), flags, format.c_str());
  } else {
    if (format == "glb") checkGlbHeader(file);
    scene = importer.ReadFile(file.string(), flags);
  }
  if (scene && scene->mRootNode) {
    // A reader may return faces without vertices and claim primitive types its faces do not
    // have (a truncated PLY: empty faces, called polygons), and Assimp's triangulation then
    // aborts on an assertion (found by fuzzing), which its validation lets through: empty
    // faces are refused, and the types set from the faces before the steps that trust them.
    for (unsigned i = 0; i < scene->mNumMeshes; ++i) {
      aiMesh& mesh = *scene->mMeshes[i];
      unsigned types = 0;
      for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
        const unsigned n = mesh.mFaces[f].mNumIndices;
        if (n == 0)
          throw Error(file.string(), "mesh " + std::to_string(i) + ", face " + std::to_string(f),
                      "a face without vertices (truncated or corrupt file?)");
        types |= n == 1   ? aiPrimitiveType_POINT
                 : n == 2 ? aiPrimitiveType_LINE
                 : n == 3 ? aiPrimitiveType_TRIANGLE
                          : aiPrimitiveType_POLYGON;
      }
      mesh.mPrimitiveTypes = types;
    }
    scene = importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_SortByPType |
                                         aiProcess_JoinIdenticalVertices);
  }
  if (!scene || !scene->mRootNode) {
    // A file read from memory goes by Assimp's stand-in name: give the user's back.
    std::string reason = importer.GetErrorString();
    const std::string standIn = std::string(AI_MEMORYIO_MAGIC_FILENAME) + "." + format;
    for (std::size_t at; (at = reason.find(standIn)) != std::string::npos;)
      reason.replace(at, standIn.size(), file.filename().string());
    throw Error(file.string(), "", "cannot import mesh: " + reason);
  }

  std::vector<ImportedNode> nodes;
  std::map<std::string, int> nameCount;
  auto visit = [&](auto&& self, const aiNode* node, const glm::mat4& parent) -> void {
    const glm::mat4 transform = parent * toGlm(node->mTransformation);
    if (node->mNumMeshes > 0) {
      ImportedNode out;
      std::string name = node->mName.C_Str();
      if (name.empty() || isStandIn(name)) {
        const aiMesh* first = scene->mMeshes[node->mMeshes[0]];
        const std::string candidates[] = {
            first->mName.C_Str(), node->mParent ? node->mParent->mName.C_Str() : "",
            first->mMaterialIndex < scene->mNumMaterials
                ? scene->mMaterials[first->mMaterialIndex]->GetName().C_Str()
                : ""};
        for (const std::string& c : candidates)
          if (!c.empty() && !isStandIn(c) && c != AI_DEFAULT_MATERIAL_NAME) {
            out.id = name;
            name = c;
            break;
          }
        if (name.empty()) name = "node";
      }
      const int seen = nameCount[name]++;
      out.name = seen ? name + "#" + std::to_string(seen + 1) : name;
      bool normalsComputed = false;
      for (unsigned i = 0; i < node->mNumMeshes; ++i) {
        const aiMesh* mesh = scene->mMeshes[node->mMeshes[i]];
        if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
        out.mesh.append(convert(file, *mesh, normalsComputed), transform);
        if (!out.color && mesh->mMaterialIndex < scene->mNumMaterials) {
          aiColor4D c;
          const aiMaterial* material = scene->mMaterials[mesh->mMaterialIndex];
          // Assimp invents "DefaultMaterial" for files without materials: not the file's colour.
          if (material->GetName() == aiString(AI_DEFAULT_MATERIAL_NAME)) continue;
          if (material->Get(AI_MATKEY_BASE_COLOR, c) == AI_SUCCESS ||
              material->Get(AI_MATKEY_COLOR_DIFFUSE, c) == AI_SUCCESS)
            out.color = glm::clamp(glm::vec3(c.r, c.g, c.b), 0.0f, 1.0f);
        }
      }
      out.mesh.report.normalsComputed = normalsComputed;
      out.mesh.report.droppedDegenerate = dropDegenerateTriangles(out.mesh);
      if (!out.mesh.triangles.empty()) {
        analyzeTopology(out.mesh);
        nodes.push_back(std::move(out));
      }
    }
    for (unsigned i = 0; i < node->mNumChildren; ++i) self(self, node->mChildren[i], transform);
  };
  visit(visit, scene->mRootNode, glm::mat4(1.0f));
  if (nodes.empty()) throw Error(file.string(), "", "the file contains no triangles");
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
