// cutaway/core/contained.hpp — a third-party parser run on an untrusted file in a child
// process, under a memory and a time limit.
//
// Assimp and GDAL have bugs this project cannot fix in their Debian packages: a file may
// crash them, make them loop forever or allocate without bound. `runContained` forks, runs
// `work` in the child and returns the bytes it produced; an Error it throws comes back as
// thrown, and a crash, the time limit or the memory limit becomes an Error naming the file.
// The caller (not the library) is never taken down, and nothing is half-read.
//
//   const std::string bytes = cutaway::runContained("engine.glb", "the mesh importer",
//                                                   [&] { return serialize(parse(file)); });
#pragma once

#include <cstdint>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace cutaway {

struct ContainmentLimits {
  double seconds = 300.0;         // wall-clock time the child may take
  std::uint64_t memoryBytes = 0;  // memory the child may allocate beyond what it inherits
};

// The limits file imports run under: CUTAWAY_IMPORT_SECONDS and CUTAWAY_IMPORT_MEMORY_MB when
// set (a bad value is an Error naming the variable), else 300 s and 3/4 of physical memory.
// CUTAWAY_IMPORT_CONTAINED=0 runs importers in the calling process instead (a debugger's way
// in; the limits then do not hold).
ContainmentLimits importLimits();
bool importsContained();

// The bytes a child handed back, mapped from its shared memory rather than copied.
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
  std::string_view bytes() const { return {data_ ? data_ + 1 : "", data_ ? size_ - 1 : 0}; }

 private:
  const char* data_;  // the whole mapping: a kind byte, then the bytes
  std::size_t size_;
};

// Runs `work` in a child process and returns what it returned. `file` names the input in
// errors and `parser` the code that reads it ("the mesh importer"). Throws the cutaway::Error
// that `work` threw, or an Error "FILE: PARSER crashed on this file (…)", "…took longer than
// N s", "…needed more than N MB of memory".
ContainedReply runContained(const std::string& file, const std::string& parser,
                            const std::function<std::string()>& work,
                            const ContainmentLimits& limits);

// The bytes a contained parser hands back: values, arrays and strings, read in the order
// they were written.
class ByteWriter {
 public:
  template <class T>
  void value(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  template <class T>
  void array(const std::vector<T>& v) {
    value(std::uint64_t(v.size()));
    bytes.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  void string(const std::string& s) {
    value(std::uint64_t(s.size()));
    bytes += s;
  }
  std::string bytes;
};

class ByteReader {
 public:
  explicit ByteReader(std::string_view bytes) : bytes_(bytes) {}
  template <class T>
  T value() {
    static_assert(std::is_trivially_copyable_v<T>);
    T v;
    std::memcpy(&v, take(sizeof v), sizeof v);
    return v;
  }
  template <class T>
  std::vector<T> array() {
    const auto n = value<std::uint64_t>();
    if (n > (bytes_.size() - at_) / sizeof(T)) throw std::length_error("a reply cut short");
    std::vector<T> v(n);
    std::memcpy(v.data(), take(n * sizeof(T)), n * sizeof(T));
    return v;
  }
  std::string string() {
    const auto n = value<std::uint64_t>();
    return std::string(take(n), n);
  }

 private:
  const char* take(std::uint64_t n) {
    if (n > bytes_.size() - at_) throw std::length_error("a reply cut short");
    at_ += n;
    return bytes_.data() + at_ - n;
  }
  std::string_view bytes_;
  std::size_t at_ = 0;
};

}  // namespace cutaway
