// cutaway/core/contained.hpp — third-party parsers run on untrusted files in child
// processes, under a memory and a time limit.
//
// Assimp, GDAL and GDCM have bugs this project cannot fix in their Debian packages: a file may
// crash them, make them loop forever or allocate without bound. A contained parser runs in a
// fresh worker process per file, forked by a helper process that the first call starts; its
// result comes back through shared memory, an Error it throws comes back as thrown, and a
// crash, the time limit or the memory limit becomes an Error naming the file. The program is
// never taken down, and nothing is half-read.
//
// A parser is a plain function, registered by name at static initialisation (the helper
// knows the parsers registered before it started); `ContainedReader` does both:
//
//   GisLines importHere(const std::filesystem::path& file, const GisImportOptions& options);
//   const ContainedReader<GisLines, &importHere, GisImportOptions> reader("gis-lines", "GDAL");
//   GisLines lines = reader(file, options);   // throws cutaway::Error
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <glm/glm.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <vector>

namespace cutaway {

struct ContainmentLimits {
  double seconds = 300.0;         // wall-clock time a worker may take
  std::uint64_t memoryBytes = 0;  // memory a worker may allocate beyond what it inherits
};

// The limits file imports run under: CUTAWAY_IMPORT_SECONDS and CUTAWAY_IMPORT_MEMORY_MB when
// set (a bad value is an Error naming the variable), else 300 s and 3/4 of physical memory.
// CUTAWAY_IMPORT_CONTAINED=0 runs importers in the calling process instead (a debugger's way
// in; the limits then do not hold); 1 or unset contains them, any other value is an Error.
ContainmentLimits importLimits();
bool importsContained();

// Starts the helper process now (else the first contained call does). A program calls it
// first thing in main(), before it starts threads (a fork copies the calling thread alone,
// and any lock another one held): the helper is then a copy of a small process, and the
// program does not pay later for pages it shares copy-on-write with the helper.
// Never throws: where the helper cannot start, the first contained call says why.
void startContainedHelper();

// A parser as a worker runs it: its arguments' bytes in, its result's bytes out.
using ContainedParser = std::string (*)(std::string_view arguments);
// Registers `parser` under `id` (false: the id was taken).
bool registerContainedParser(const std::string& id, ContainedParser parser);
// Registers work the helper does once when it starts, so that every worker inherits it
// rather than doing it per file: a library's drivers registered, its symbols bound. A
// warm-up that throws is left undone (each worker then does the work itself).
bool registerContainedWarmUp(void (*warmUp)());

// The bytes a worker handed back, mapped from its shared memory rather than copied.
class ContainedReply {
 public:
  ContainedReply(const char* data, std::size_t size) : data_(data), size_(size) {}
  ContainedReply(ContainedReply&& other) noexcept : data_(other.data_), size_(other.size_) {
    other.data_ = nullptr;
  }
  ContainedReply(const ContainedReply&) = delete;
  ContainedReply& operator=(const ContainedReply&) = delete;
  ContainedReply& operator=(ContainedReply&&) = delete;
  ~ContainedReply();
  std::string_view bytes() const { return {data_ ? data_ : "", data_ ? size_ : 0}; }

 private:
  const char* data_;
  std::size_t size_;
};

// Runs the parser registered as `id` on `arguments` in a worker process and returns its
// result. `file` names the input in errors and `parser` the code that reads it ("the mesh
// importer"). Throws the cutaway::Error that the parser threw, or an Error "FILE: PARSER
// crashed on this file (…)", "…took longer than N s", "…needed more than N MB of memory".
// Calls from several threads take turns.
ContainedReply runContained(const std::string& file, const std::string& parser,
                            const std::string& id, const std::string& arguments,
                            const ContainmentLimits& limits);

// The bytes a contained parser hands back, and what they are read back into. Numbers, enums
// and glm vectors and matrices are written as their bytes (the child is the same program);
// strings, vectors, arrays and optionals with their sizes; any other type through a function
// found by argument-dependent lookup that names its members to an archive, once for both ways:
//
//   template <class Archive> void wireFields(Archive& a, GisCrs& c) { a(c.name, c.wkt); }
namespace wire {
template <class T>
struct IsGlm : std::false_type {};
template <glm::length_t L, class T, glm::qualifier Q>
struct IsGlm<glm::vec<L, T, Q>> : std::true_type {};
template <glm::length_t C, glm::length_t R, class T, glm::qualifier Q>
struct IsGlm<glm::mat<C, R, T, Q>> : std::true_type {};
template <class T>
constexpr bool kAsBytes = std::is_arithmetic_v<T> || std::is_enum_v<T> || IsGlm<T>::value;
template <class T>
struct IsVector : std::false_type {};
template <class T, class A>
struct IsVector<std::vector<T, A>> : std::true_type {};
template <class T>
struct IsOptional : std::false_type {};
template <class T>
struct IsOptional<std::optional<T>> : std::true_type {};
template <class T>
struct IsArray : std::false_type {};
template <class T, std::size_t N>
struct IsArray<std::array<T, N>> : std::true_type {};
}  // namespace wire

class ByteWriter {
 public:
  template <class... T>
  void operator()(const T&... values) {
    (put(values), ...);
  }
  std::string bytes;

 private:
  void raw(const void* p, std::size_t n) { bytes.append(static_cast<const char*>(p), n); }
  template <class T>
  void put(const T& v) {
    if constexpr (wire::kAsBytes<T>) {
      raw(&v, sizeof v);
    } else if constexpr (std::is_same_v<T, std::string>) {
      put(std::uint64_t(v.size()));
      raw(v.data(), v.size());
    } else if constexpr (std::is_same_v<T, std::filesystem::path>) {
      put(v.string());
    } else if constexpr (wire::IsVector<T>::value) {
      put(std::uint64_t(v.size()));
      if constexpr (wire::kAsBytes<typename T::value_type>) {
        if (!v.empty()) raw(v.data(), v.size() * sizeof(typename T::value_type));
      } else
        for (const auto& e : v) put(e);
    } else if constexpr (wire::IsArray<T>::value) {
      for (const auto& e : v) put(e);
    } else if constexpr (wire::IsOptional<T>::value) {
      put(v.has_value());
      if (v) put(*v);
    } else {
      wireFields(*this, const_cast<T&>(v));  // only read
    }
  }
};

class ByteReader {
 public:
  explicit ByteReader(std::string_view bytes) : bytes_(bytes) {}
  template <class... T>
  void operator()(T&... values) {
    (get(values), ...);
  }
  // Reads one T.
  template <class T>
  T read() {
    T v{};
    get(v);
    return v;
  }

 private:
  const char* take(std::uint64_t n) {
    if (n > bytes_.size() - at_) throw std::length_error("a contained parser's reply cut short");
    at_ += n;
    return bytes_.data() + at_ - n;
  }
  std::uint64_t count(std::size_t elementSize) {
    const auto n = read<std::uint64_t>();
    if (elementSize && n > (bytes_.size() - at_) / elementSize)
      throw std::length_error("a contained parser's reply cut short");
    return n;
  }
  template <class T>
  void get(T& v) {
    if constexpr (wire::kAsBytes<T>) {
      std::memcpy(&v, take(sizeof v), sizeof v);
    } else if constexpr (std::is_same_v<T, std::string>) {
      const auto n = count(1);
      v.assign(take(n), n);
    } else if constexpr (std::is_same_v<T, std::filesystem::path>) {
      v = read<std::string>();
    } else if constexpr (wire::IsVector<T>::value) {
      using E = typename T::value_type;
      v.resize(count(wire::kAsBytes<E> ? sizeof(E) : 0));
      if constexpr (wire::kAsBytes<E>) {
        if (!v.empty()) std::memcpy(v.data(), take(v.size() * sizeof(E)), v.size() * sizeof(E));
      } else
        for (auto& e : v) get(e);
    } else if constexpr (wire::IsArray<T>::value) {
      for (auto& e : v) get(e);
    } else if constexpr (wire::IsOptional<T>::value) {
      if (read<bool>())
        get(v.emplace());
      else
        v.reset();
    } else {
      wireFields(*this, v);
    }
  }
  std::string_view bytes_;
  std::size_t at_ = 0;
};

// `Read(file, arguments...)` as a contained parser named `id`: called, it runs in a worker
// under importLimits() (in this process when CUTAWAY_IMPORT_CONTAINED=0). Define one as a
// namespace-scope object, so that it registers before the helper starts.
template <class Result, auto Read, class... Arguments>
class ContainedReader {
 public:
  ContainedReader(const char* id, const char* parser) : id_(id), parser_(parser) {
    registerContainedParser(id, &work);
  }
  Result operator()(const std::filesystem::path& file, const Arguments&... arguments) const {
    if (!importsContained()) return Read(file, arguments...);
    ByteWriter w;
    w(file, arguments...);
    const ContainedReply reply = runContained(file.string(), parser_, id_, w.bytes, importLimits());
    return ByteReader(reply.bytes()).read<Result>();
  }

 private:
  static std::string work(std::string_view bytes) {
    std::tuple<std::filesystem::path, Arguments...> arguments;
    ByteReader r(bytes);
    std::apply([&](auto&... a) { r(a...); }, arguments);
    ByteWriter w;
    w(std::apply(Read, arguments));
    return std::move(w.bytes);
  }
  const char* id_;
  const char* parser_;
};

}  // namespace cutaway
