#include "ply_reader.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cutaway/core/error.hpp"

namespace cutaway {
namespace {

enum class Format { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct ScalarType {
  int bytes = 0;  // 0: not a PLY type
  bool integer = false, isSigned = false;
};

ScalarType scalarType(std::string_view name) {
  static const std::pair<std::string_view, ScalarType> kTypes[] = {
      {"char", {1, true, true}},    {"int8", {1, true, true}},     {"uchar", {1, true, false}},
      {"uint8", {1, true, false}},  {"short", {2, true, true}},    {"int16", {2, true, true}},
      {"ushort", {2, true, false}}, {"uint16", {2, true, false}},  {"int", {4, true, true}},
      {"int32", {4, true, true}},   {"uint", {4, true, false}},    {"uint32", {4, true, false}},
      {"float", {4, false, true}},  {"float32", {4, false, true}}, {"double", {8, false, true}},
      {"float64", {8, false, true}}};
  for (const auto& [n, t] : kTypes)
    if (n == name) return t;
  return {};
}

struct Property {
  std::string name;
  ScalarType type;                      // the items' type for a list
  std::optional<ScalarType> countType;  // set for a list
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
  int headerLine = 0;
};

// A number as written in messages: any double, huge or not finite, without undefined casts.
std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.15g", v);
  return text;
}

std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  for (std::size_t at = 0;;) {
    at = line.find_first_not_of(" \t", at);
    if (at == std::string_view::npos) return out;
    const std::size_t end = std::min(line.find_first_of(" \t", at), line.size());
    out.push_back(line.substr(at, end - at));
    at = end;
  }
}

// Reads the data section value by value: ASCII as whitespace-separated words, binary in the
// file's byte order. Errors name the element and instance being read.
class DataReader {
 public:
  DataReader(const std::filesystem::path& file, Format format, const char* data, std::size_t size)
      : file_(file), format_(format), data_(data), size_(size) {}

  const std::string* element = nullptr;
  std::uint64_t instance = 0;
  std::size_t left() const { return size_ - at_; }

  double read(const ScalarType& t) {
    if (format_ == Format::Ascii) return readWord(t);
    if (left() < std::size_t(t.bytes)) fail("the file ends early");
    std::uint64_t raw = 0;
    for (int b = 0; b < t.bytes; ++b) {
      const int shift = 8 * (format_ == Format::BinaryBigEndian ? t.bytes - 1 - b : b);
      raw |= std::uint64_t(static_cast<unsigned char>(data_[at_ + std::size_t(b)])) << shift;
    }
    at_ += std::size_t(t.bytes);
    if (!t.integer) {
      if (t.bytes == 4) {
        float f;
        const auto bits = std::uint32_t(raw);
        std::memcpy(&f, &bits, 4);
        return f;
      }
      double d;
      std::memcpy(&d, &raw, 8);
      return d;
    }
    const int bits = 8 * t.bytes;
    if (t.isSigned && raw >> (bits - 1)) return double(raw) - std::ldexp(1.0, bits);
    return double(raw);
  }

  [[noreturn]] void fail(const std::string& reason) const {
    throw Error(file_.string(), element->substr(0, 40) + " " + std::to_string(instance), reason);
  }

 private:
  double readWord(const ScalarType& t) {
    const auto space = [&](char c) {
      return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
    };
    while (at_ < size_ && space(data_[at_])) ++at_;
    const std::size_t begin = at_;
    while (at_ < size_ && !space(data_[at_])) ++at_;
    if (at_ == begin) fail("the file ends early");
    const std::string_view word(data_ + begin, at_ - begin);
    double value = 0.0;
    // from_chars takes no '+' sign.
    const char* first = word.data() + (word.size() > 1 && word[0] == '+' && word[1] != '-');
    const auto [end, ec] = std::from_chars(first, word.data() + word.size(), value);
    if (ec == std::errc::result_out_of_range)
      fail("the number " + quote(word) + " is out of range");
    if (ec != std::errc() || end != word.data() + word.size())
      fail(quote(word) + " is not a number");
    if (t.integer && value != std::floor(value)) fail(quote(word) + " is not an integer");
    return value;
  }

  const std::filesystem::path& file_;
  Format format_;
  const char* data_;
  std::size_t size_, at_ = 0;
};

}  // namespace

Mesh readPly(const std::filesystem::path& file, const char* data, std::size_t size) {
  const auto fail = [&](int line, const std::string& reason) {
    throw Error(file.string(), line ? "header line " + std::to_string(line) : "", reason);
  };
  // The header, line by line up to "end_header".
  std::optional<Format> format;
  std::vector<Element> elements;
  std::size_t at = 0;
  bool ended = false;
  // Lines end at \n, \r\n or \r (the format's own description says carriage returns).
  for (int number = 1; at < size && !ended; ++number) {
    const std::size_t length =
        std::min(std::string_view(data + at, size - at).find_first_of("\r\n"), size - at);
    const std::string_view line(data + at, length);
    at += length;
    if (at < size && data[at] == '\r') ++at;
    if (at < size && data[at] == '\n') ++at;
    if (number == 1) {
      if (line != "ply") fail(0, "not a PLY file (no \"ply\" line)");
      continue;
    }
    const auto w = words(line);
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    const std::string keyword(w[0].substr(0, 40));
    if (keyword == "format") {
      if (w.size() != 3 || (w[2] != "1.0" && w[2] != "1"))
        fail(number,
             "a format line is \"format ascii|binary_little_endian|binary_big_endian 1.0\"");
      if (w[1] == "ascii")
        format = Format::Ascii;
      else if (w[1] == "binary_little_endian")
        format = Format::BinaryLittleEndian;
      else if (w[1] == "binary_big_endian")
        format = Format::BinaryBigEndian;
      else
        fail(number, "unknown format \"" + std::string(w[1].substr(0, 40)) + "\"");
    } else if (keyword == "element") {
      std::uint64_t count = 0;
      const auto [end, ec] = w.size() == 3
                                 ? std::from_chars(w[2].data(), w[2].data() + w[2].size(), count)
                                 : std::from_chars_result{nullptr, std::errc::invalid_argument};
      if (ec != std::errc() || end != w[2].data() + w[2].size())
        fail(number, "an element line is \"element NAME COUNT\", COUNT a whole number");
      // Each instance takes at least a byte: a larger count is a lie (or a truncated file).
      if (count > size)
        fail(number, "claims " + std::to_string(count) + " " + std::string(w[1].substr(0, 40)) +
                         " elements in a file of " + std::to_string(size) + " bytes");
      for (const Element& e : elements)
        if (e.name == w[1]) fail(number, "a second " + quote(e.name) + " element");
      elements.push_back({std::string(w[1]), count, {}, number});
    } else if (keyword == "property") {
      if (elements.empty()) fail(number, "a property before any element");
      Property p;
      if (w.size() == 5 && w[1] == "list") {
        p.countType = scalarType(w[2]);
        p.type = scalarType(w[3]);
        p.name = w[4];
        if (!p.countType->integer)
          fail(number, "a list's count needs an integer type, not \"" +
                           std::string(w[2].substr(0, 40)) + "\"");
      } else if (w.size() == 3) {
        p.type = scalarType(w[1]);
        p.name = w[2];
      } else {
        fail(number,
             "a property line is \"property TYPE NAME\" or \"property list COUNTTYPE "
             "TYPE NAME\"");
      }
      if (p.type.bytes == 0)
        fail(number, "unknown property type in \"" + std::string(line.substr(0, 80)) + "\"");
      elements.back().properties.push_back(std::move(p));
    } else if (keyword == "end_header" && w.size() == 1) {
      ended = true;
    } else {
      fail(number, "unknown header keyword " + quote(keyword));
    }
  }
  if (!ended) fail(0, "the PLY header has no end_header line (truncated?)");
  if (!format) fail(0, "the PLY header has no format line");

  const Element* vertex = nullptr;
  for (const Element& e : elements)
    if (e.name == "vertex") vertex = &e;
  if (!vertex) fail(0, "no vertex element");
  const auto find = [](const Element& e, std::string_view name) {
    for (std::size_t i = 0; i < e.properties.size(); ++i)
      if (e.properties[i].name == name && !e.properties[i].countType) return int(i);
    return -1;
  };
  const std::array<int, 6> slots{find(*vertex, "x"),  find(*vertex, "y"),  find(*vertex, "z"),
                                 find(*vertex, "nx"), find(*vertex, "ny"), find(*vertex, "nz")};
  if (slots[0] < 0 || slots[1] < 0 || slots[2] < 0)
    fail(vertex->headerLine, "the vertex element has no x, y and z properties");
  const bool normals = slots[3] >= 0 && slots[4] >= 0 && slots[5] >= 0;

  // The face or strip element's list of vertex indices; -1 for other elements.
  const auto vertexIndices = [](const Element& e) {
    for (std::size_t i = 0; i < e.properties.size(); ++i)
      if ((e.name == "face" || e.name == "tristrips") && e.properties[i].countType &&
          (e.properties[i].name == "vertex_indices" || e.properties[i].name == "vertex_index"))
        return int(i);
    return -1;
  };
  for (const Element& e : elements)
    if (const int i = vertexIndices(e); i >= 0 && !e.properties[std::size_t(i)].type.integer)
      fail(e.headerLine, "the " + e.name + " element's vertex indices need an integer type");

  Mesh mesh;
  DataReader in(file, *format, data + at, size - at);
  const std::uint64_t vertices = vertex->count;
  std::vector<std::uint32_t> polygon;
  for (const Element& e : elements) {
    const bool isVertex = &e == vertex, isFace = e.name == "face", isStrip = e.name == "tristrips";
    const int indices = vertexIndices(e);
    if (isVertex) {
      // No more than the bytes left can hold: a vertex takes its properties' bytes in binary,
      // and a character and a separator per property in ASCII.
      std::uint64_t least = 0;
      for (const Property& p : e.properties)
        least += *format == Format::Ascii
                     ? 2
                     : std::uint64_t((p.countType ? *p.countType : p.type).bytes);
      mesh.positions.reserve(std::size_t(
          std::min<std::uint64_t>(e.count, in.left() / std::max<std::uint64_t>(least, 1) + 1)));
      if (normals) mesh.normals.reserve(mesh.positions.capacity());
    }
    if (e.properties.empty()) continue;  // instances of nothing: no bytes to read
    std::array<double, 6> v{};
    for (std::uint64_t n = 0; n < e.count; ++n) {
      in.element = &e.name, in.instance = n;
      for (std::size_t i = 0; i < e.properties.size(); ++i) {
        const Property& p = e.properties[i];
        if (!p.countType) {
          const double value = in.read(p.type);
          for (int k = 0; k < 6 && isVertex; ++k)
            if (slots[std::size_t(k)] == int(i)) v[std::size_t(k)] = value;
          continue;
        }
        const double count = in.read(*p.countType);
        const double least = *format == Format::Ascii ? 1.0 : double(p.type.bytes);
        if (count < 0 || count * least > double(in.left()))
          in.fail("the file ends early: a list of " + number(count) + " values in the " +
                  std::to_string(in.left()) + " bytes left");
        if (int(i) != indices) {
          for (double k = 0; k < count; ++k) in.read(p.type);
          continue;
        }
        polygon.clear();
        for (double k = 0; k < count; ++k) {
          const double index = in.read(p.type);
          if (isStrip && index == -1.0) {
            polygon.push_back(UINT32_MAX);  // a restart
            continue;
          }
          if (index < 0 || index >= double(vertices))
            in.fail("vertex index " + number(index) + " out of range (" + std::to_string(vertices) +
                    " vertices)");
          polygon.push_back(std::uint32_t(index));
        }
        if (isFace) {
          for (std::size_t k = 2; k < polygon.size(); ++k)
            mesh.triangles.emplace_back(polygon[0], polygon[k - 1], polygon[k]);
        } else {
          // A strip's k-th triangle (k counted from its last restart) alternates its winding.
          std::size_t start = 0;
          for (std::size_t k = 0; k < polygon.size(); ++k) {
            if (polygon[k] == UINT32_MAX) {
              start = k + 1;
              continue;
            }
            if (k < start + 2) continue;
            const std::uint32_t a = polygon[k - 2], b = polygon[k - 1], c = polygon[k];
            if ((k - start) % 2 == 0)
              mesh.triangles.emplace_back(a, b, c);
            else
              mesh.triangles.emplace_back(b, a, c);
          }
        }
      }
      if (isVertex) {
        mesh.positions.emplace_back(float(v[0]), float(v[1]), float(v[2]));
        if (normals) mesh.normals.emplace_back(float(v[3]), float(v[4]), float(v[5]));
      }
    }
  }
  return mesh;
}

}  // namespace cutaway
