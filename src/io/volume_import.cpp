#include "cutaway/io/volume_import.hpp"

#include <nifti2_io.h>
#include <zip.h>
#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "core/json_reader.hpp"
#include "cutaway/core/error.hpp"

namespace cutaway {

void Volume::updateRange() {
  bool any = false;
  float lo = 0.0f, hi = 0.0f;
  for (const float v : values) {
    if (!std::isfinite(v)) continue;  // NaN marks missing data; ±inf would swamp any colour map
    if (!any) lo = hi = v, any = true;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  minValue = lo;
  maxValue = hi;
}

namespace {

namespace fs = std::filesystem;

// Where an error is reported: the file and the place inside it.
struct Where {
  std::string file, place;
  [[noreturn]] void fail(const std::string& reason) const { throw Error(file, place, reason); }
  Where at(const std::string& other) const { return {file, other}; }
};

// The voxel types on disk, all converted to float.
struct VoxelType {
  const char* name;
  int bytes;
  char kind;  // 'u', 'i' or 'f'
};
constexpr VoxelType kU8{"u8", 1, 'u'}, kI8{"i8", 1, 'i'}, kU16{"u16", 2, 'u'}, kI16{"i16", 2, 'i'},
    kU32{"u32", 4, 'u'}, kI32{"i32", 4, 'i'}, kF32{"f32", 4, 'f'}, kF64{"f64", 8, 'f'};
constexpr VoxelType kVoxelTypes[] = {kU8, kI8, kU16, kI16, kU32, kI32, kF32, kF64};

const VoxelType* findVoxelType(char kind, int bytes) {
  for (const VoxelType& t : kVoxelTypes)
    if (t.kind == kind && t.bytes == bytes) return &t;
  return nullptr;
}

// value = slope·v + inter (NIfTI's scl_slope and scl_inter); the identity elsewhere.
struct Scaling {
  double slope = 1.0, inter = 0.0;
};

template <typename T>
T load(const unsigned char* p, bool swap) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, p, sizeof(T));
  if (swap) std::reverse(b, b + sizeof(T));
  T v;
  std::memcpy(&v, b, sizeof(T));
  return v;
}

template <typename T>
void convert(const unsigned char* in, std::size_t count, bool swap, Scaling s, float* out) {
  const bool scaled = s.slope != 1.0 || s.inter != 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    const T v = load<T>(in + i * sizeof(T), swap);
    out[i] = scaled ? float(s.slope * double(v) + s.inter) : float(v);
  }
}

void convert(const VoxelType& t, const unsigned char* in, std::size_t count, bool swap, Scaling s,
             float* out) {
  switch (t.kind * 16 + t.bytes) {
    case 'u' * 16 + 1:
      return convert<std::uint8_t>(in, count, swap, s, out);
    case 'i' * 16 + 1:
      return convert<std::int8_t>(in, count, swap, s, out);
    case 'u' * 16 + 2:
      return convert<std::uint16_t>(in, count, swap, s, out);
    case 'i' * 16 + 2:
      return convert<std::int16_t>(in, count, swap, s, out);
    case 'u' * 16 + 4:
      return convert<std::uint32_t>(in, count, swap, s, out);
    case 'i' * 16 + 4:
      return convert<std::int32_t>(in, count, swap, s, out);
    case 'f' * 16 + 4:
      return convert<float>(in, count, swap, s, out);
    case 'f' * 16 + 8:
      return convert<double>(in, count, swap, s, out);
  }
}

constexpr bool kNativeIsBig = std::endian::native == std::endian::big;

std::string dimsText(const std::int64_t d[3]) {
  return std::to_string(d[0]) + "×" + std::to_string(d[1]) + "×" + std::to_string(d[2]);
}

// The voxel count of `d`, refused when a dimension is not positive or the count overflows or
// exceeds the limit: the one check before anything is allocated.
std::size_t checkDims(const std::int64_t d[3], const VolumeLimits& limits, const Where& where) {
  if (d[0] <= 0 || d[1] <= 0 || d[2] <= 0) where.fail("dims must be positive, got " + dimsText(d));
  const std::string limit = " voxels exceed the limit of " + std::to_string(limits.maxVoxels);
  std::size_t count = 1;
  for (int i = 0; i < 3; ++i)
    if (std::uint64_t(d[i]) > std::uint64_t(INT_MAX) ||
        __builtin_mul_overflow(count, std::size_t(d[i]), &count))
      where.fail(dimsText(d) + limit);
  if (count > limits.maxVoxels) where.fail(dimsText(d) + " = " + std::to_string(count) + limit);
  return count;
}

// Refuses a transform that cannot place voxels: non-finite entries or a singular 3×3 part.
glm::mat4 checkTransform(const glm::dmat4& m, const Where& where) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) where.fail("the voxel-to-world transform is not finite");
  const glm::dmat3 a(m);
  const double scale = glm::length(a[0]) * glm::length(a[1]) * glm::length(a[2]);
  if (!(scale > 0.0) || std::abs(glm::determinant(a)) <= 1e-9 * scale)
    where.fail("the voxel-to-world transform is singular");
  return glm::mat4(m);
}

// A stream of bytes to read voxels from: a file, a gzip file or a zip member.
class Source {
 public:
  virtual ~Source() = default;
  // Reads up to n bytes; fewer only at the end of the data. Throws on read errors.
  virtual std::size_t read(unsigned char* out, std::size_t n) = 0;
};

// Skips `n` bytes of `in` by reading them; returns how many there were.
std::uint64_t skipBytes(Source& in, std::uint64_t n) {
  std::vector<unsigned char> sink(std::size_t(std::min<std::uint64_t>(n, 1 << 16)));
  std::uint64_t done = 0;
  while (done < n) {
    const std::size_t got =
        in.read(sink.data(), std::size_t(std::min<std::uint64_t>(n - done, sink.size())));
    if (got == 0) break;
    done += got;
  }
  return done;
}

class FileSource : public Source {
 public:
  FileSource(const fs::path& file, const Where& where)
      : in_(file, std::ios::binary), where_(where) {
    if (!in_) where.fail("cannot open for reading: " + std::string(std::strerror(errno)));
  }
  std::size_t read(unsigned char* out, std::size_t n) override {
    in_.read(reinterpret_cast<char*>(out), std::streamsize(n));
    if (in_.bad()) where_.fail("read error");
    return std::size_t(in_.gcount());
  }
  void seek(std::uint64_t offset) { in_.seekg(std::streamoff(offset)); }

 private:
  std::ifstream in_;
  Where where_;
};

// Plain files too: zlib reads a file without the gzip magic as it is.
class GzSource : public Source {
 public:
  GzSource(const std::string& file, const Where& where)
      : gz_(gzopen(file.c_str(), "rb")), where_(where) {
    if (!gz_) where.fail("cannot open for reading: " + std::string(std::strerror(errno)));
  }
  ~GzSource() override { gzclose(gz_); }
  gzFile get() const { return gz_; }
  std::size_t read(unsigned char* out, std::size_t n) override {
    std::size_t done = 0;
    while (done < n) {
      const unsigned ask = unsigned(std::min<std::size_t>(n - done, 1u << 30));
      const int got = gzread(gz_, out + done, ask);
      if (got < 0) {
        int code = 0;
        where_.fail("corrupt gzip data: " + std::string(gzerror(gz_, &code)));
      }
      done += std::size_t(got);
      if (unsigned(got) < ask) break;  // the end, or a truncated stream (zlib's Z_BUF_ERROR)
    }
    return done;
  }
  // Skips to `offset` by reading, so a stream too short to reach it reads as truncated.
  std::uint64_t skip(std::uint64_t offset) { return skipBytes(*this, offset); }

 private:
  gzFile gz_;
  Where where_;
};

constexpr std::size_t kChunkBytes = std::size_t(1) << 20;

std::string truncated(std::uint64_t got, std::uint64_t expected) {
  return "truncated: " + std::to_string(got) + " bytes of voxel data, expected " +
         std::to_string(expected);
}

// Reads `count` voxels of type `t` and converts them to float. When the size of the data is
// only claimed (a gzip stream, a zip member), the values grow as the data arrives, so a false
// claim costs no more memory than the data that is really there.
std::vector<float> readVoxels(Source& in, std::size_t count, const VoxelType& t, bool swap,
                              Scaling s, bool sizeKnown, const Where& where) {
  std::vector<float> values;
  const std::size_t chunk = kChunkBytes / std::size_t(t.bytes);
  values.reserve(sizeKnown ? count : std::min(count, chunk));
  std::vector<unsigned char> buffer(std::min(count, chunk) * std::size_t(t.bytes));
  while (values.size() < count) {
    const std::size_t n = std::min(count - values.size(), chunk);
    const std::size_t got = in.read(buffer.data(), n * std::size_t(t.bytes));
    if (got < n * std::size_t(t.bytes))
      where.fail(truncated(values.size() * t.bytes + got, std::uint64_t(count) * t.bytes));
    if (values.size() + n > values.capacity())
      values.reserve(std::min(count, std::max(values.capacity() * 2, values.size() + n)));
    const std::size_t at = values.size();
    values.resize(at + n);
    convert(t, buffer.data(), n, swap, s, values.data() + at);
  }
  return values;
}

// The file's size, or an error saying why there is none.
std::uint64_t fileSize(const fs::path& file, const Where& where) {
  std::error_code ec;
  const std::uint64_t size = fs::file_size(file, ec);
  if (ec) where.fail("cannot read: " + ec.message());
  return size;
}

// Compares the bytes a file holds after its header with what the dims need.
void checkDataSize(std::uint64_t available, std::size_t count, const VoxelType& t,
                   const Where& where) {
  const std::uint64_t expected = std::uint64_t(count) * std::uint64_t(t.bytes);
  if (available < expected) where.fail(truncated(available, expected));
  if (available > expected)
    where.fail(std::to_string(available) + " bytes of voxel data, expected " +
               std::to_string(expected) + ": the dims disagree with the data size");
}

// ---------------------------------------------------------------------------------------------
// NIfTI-1 and NIfTI-2 (single-file .nii, optionally gzip-compressed). The header's bytes are
// read and checked here and handed to libnifti2, which swaps them and derives the qform and
// sform matrices; the voxels are read here too. nifti_image_read would do both but accepts
// only lower- or upper-case suffixes, prints its complaints to stderr, mends dims ≤ 0 to 1 and
// allocates a whole 4-D series.

struct NiftiFree {
  void operator()(nifti_image* p) const { nifti_image_free(p); }
};

const VoxelType* niftiVoxelType(int datatype) {
  static constexpr std::pair<int, const VoxelType*> kTypes[] = {
      {DT_UINT8, &kU8},   {DT_INT8, &kI8},   {DT_UINT16, &kU16},  {DT_INT16, &kI16},
      {DT_UINT32, &kU32}, {DT_INT32, &kI32}, {DT_FLOAT32, &kF32}, {DT_FLOAT64, &kF64}};
  for (const auto& [code, type] : kTypes)
    if (code == datatype) return type;
  return nullptr;
}

glm::dmat4 toGlm(const nifti_dmat44& m) {
  glm::dmat4 out(1.0);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) out[c][r] = m.m[r][c];  // nifti is row-major, glm column-major
  return out;
}

Volume loadNifti(const fs::path& file, const VolumeLimits& limits) {
  const Where header{file.string(), "header"}, data{file.string(), "data"};
  GzSource in(file.string(), header);  // zlib reads an uncompressed .nii as it is

  // sizeof_hdr, 348 (NIfTI-1) or 540 (NIfTI-2), also tells the byte order.
  unsigned char h[540];
  std::size_t got = in.read(h, 4);
  const std::int32_t sizeofHdr = load<std::int32_t>(h, false);
  const std::int32_t swappedSize = load<std::int32_t>(h, true);
  const bool swap = got == 4 && sizeofHdr != 348 && sizeofHdr != 540;
  const std::int32_t hdrSize = swap ? swappedSize : sizeofHdr;
  if (got < 4 || (hdrSize != 348 && hdrSize != 540))
    header.fail("not a NIfTI-1 or NIfTI-2 file (sizeof_hdr is neither 348 nor 540)");
  const bool nifti2 = hdrSize == 540;
  got += in.read(h + 4, std::size_t(hdrSize) - 4);
  if (got < std::size_t(hdrSize))
    header.fail("truncated header: " + std::to_string(got) + " bytes, expected " +
                std::to_string(hdrSize));
  if (nifti2 ? std::memcmp(h + 4, "n+2\0\r\n\032\n", 8) != 0 : std::memcmp(h + 344, "n+1", 4) != 0)
    header.fail(std::string("not a single-file NIfTI-") + (nifti2 ? "2" : "1") + " image (no \"" +
                (nifti2 ? "n+2" : "n+1") + "\" magic)");

  const int datatype = load<std::int16_t>(h + (nifti2 ? 12 : 70), swap);
  const VoxelType* type = niftiVoxelType(datatype);
  if (!type) {
    std::string name = nifti_datatype_to_string(datatype);  // "NIFTI_TYPE_RGB24", "DT_UNKNOWN"
    if (name.starts_with("NIFTI_TYPE_")) name = name.substr(11);
    header.fail("unsupported NIfTI datatype " + std::to_string(datatype) + " (" + name + ")");
  }
  std::int64_t dim[8];
  for (int i = 0; i < 8; ++i)
    dim[i] = nifti2 ? load<std::int64_t>(h + 16 + 8 * i, swap)
                    : load<std::int16_t>(h + 40 + 2 * i, swap);
  if (dim[0] < 1 || dim[0] > 7) header.fail("dim[0] is " + std::to_string(dim[0]) + ", not 1 to 7");
  // Dimensions past dim[0] are 1. A series (dim[4] > 1 and beyond) yields its first volume.
  const std::int64_t d[3] = {dim[1], dim[0] >= 2 ? dim[2] : 1, dim[0] >= 3 ? dim[3] : 1};
  const std::size_t count = checkDims(d, limits, header);
  // vox_offset: where the voxels start, after the header and any extensions.
  const double voxOffset =
      nifti2 ? double(load<std::int64_t>(h + 168, swap)) : double(load<float>(h + 108, swap));
  if (!(voxOffset >= 0.0 && voxOffset < 0x1p62))
    header.fail("invalid vox_offset " + std::to_string(voxOffset));
  const std::uint64_t offset = std::max(std::uint64_t(voxOffset), std::uint64_t(hdrSize));

  nifti_set_debug_level(0);  // libnifti reports on stderr what we report by throwing
  nifti_1_header h1;
  nifti_2_header h2;
  std::memcpy(nifti2 ? static_cast<void*>(&h2) : static_cast<void*>(&h1), h, std::size_t(hdrSize));
  // No file name: libnifti then neither checks the suffix nor looks for the data file.
  const std::unique_ptr<nifti_image, NiftiFree> nim(nifti2 ? nifti_convert_n2hdr2nim(h2, nullptr)
                                                           : nifti_convert_n1hdr2nim(h1, nullptr));
  if (!nim) header.fail("libnifti2 rejects the header");

  Volume v;
  v.dims = glm::ivec3(int(d[0]), int(d[1]), int(d[2]));
  v.voxelType = type->name;
  if (nim->sform_code > 0)
    v.indexToWorld = checkTransform(toGlm(nim->sto_xyz), header.at("header: sform"));
  else if (nim->qform_code > 0)
    v.indexToWorld = checkTransform(toGlm(nim->qto_xyz), header.at("header: qform"));
  else {
    // libnifti mends a zero or non-finite pixdim[1..dim[0]] to 1; a 2-D image may leave its
    // pixdim[3] unset.
    glm::dmat4 m(1.0);
    for (int a = 0; a < 3; ++a)
      if (a < dim[0] || (nim->pixdim[a + 1] != 0.0 && std::isfinite(nim->pixdim[a + 1])))
        m[a][a] = nim->pixdim[a + 1];
    v.indexToWorld = checkTransform(m, header.at("header: pixdim"));
  }

  Scaling s;  // a slope of 0 means "not scaled"
  if (nim->scl_slope != 0.0 && std::isfinite(nim->scl_slope)) {
    s.slope = nim->scl_slope;
    s.inter = std::isfinite(nim->scl_inter) ? nim->scl_inter : 0.0;
  }

  const std::uint64_t expected = std::uint64_t(count) * std::uint64_t(type->bytes);
  // An uncompressed file's size is known: check it before allocating.
  std::uint64_t size = 0;
  const bool sizeKnown = gzdirect(in.get()) == 1;
  if (sizeKnown) {
    size = fileSize(file, data);
    const std::uint64_t available = size > offset ? size - offset : 0;
    if (available < expected) data.fail(truncated(available, expected));
  }
  if (const std::uint64_t skipped = in.skip(offset - std::uint64_t(hdrSize));
      skipped < offset - std::uint64_t(hdrSize))
    data.fail(truncated(0, expected) + " (the file ends before vox_offset " +
              std::to_string(offset) + ")");
  v.values = readVoxels(in, count, *type, swap, s, sizeKnown, data);
  return v;
}

// ---------------------------------------------------------------------------------------------
// NumPy .npy (https://numpy.org/doc/stable/reference/generated/numpy.lib.format.html), alone
// or as a member of an .npz zip archive.

// The header is a Python dict literal: strings, True/False, integers and tuples suffice.
struct PyValue {
  enum Kind { kString, kBool, kInt, kTuple, kNone } kind = kNone;
  std::string text;  // the string, or the literal as written
  std::int64_t integer = 0;
  bool boolean = false;
  std::vector<PyValue> items;
};

class PyParser {
 public:
  PyParser(const std::string& s, const Where& where) : s_(s), where_(where) {}

  std::vector<std::pair<std::string, PyValue>> dict() {
    std::vector<std::pair<std::string, PyValue>> out;
    expect('{');
    while (!peek('}')) {
      const PyValue key = value(0);
      if (key.kind != PyValue::kString) fail("expected a string key");
      expect(':');
      out.emplace_back(key.text, value(0));
      if (!peek('}')) expect(',');
    }
    expect('}');
    return out;
  }

 private:
  [[noreturn]] void fail(const std::string& what) {
    where_.fail(what + " at character " + std::to_string(i_) + " of the header dict");
  }
  void space() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  bool peek(char c) {
    space();
    return i_ < s_.size() && s_[i_] == c;
  }
  void expect(char c) {
    if (!peek(c)) fail(std::string("expected '") + c + "'");
    ++i_;
  }
  bool word(const char* w) {
    space();
    if (s_.compare(i_, std::strlen(w), w) != 0) return false;
    i_ += std::strlen(w);
    return true;
  }
  PyValue value(int depth) {
    if (depth > 8) fail("nested too deeply");
    PyValue v;
    space();
    const std::size_t start = i_;
    if (peek('\'') || peek('"')) {
      const char quote = s_[i_++];
      v.kind = PyValue::kString;
      while (i_ < s_.size() && s_[i_] != quote) v.text += s_[i_++];
      if (i_ == s_.size()) fail("unterminated string");
      ++i_;
    } else if (peek('(') || peek('[')) {
      const char close = s_[i_++] == '(' ? ')' : ']';
      v.kind = PyValue::kTuple;
      while (!peek(close)) {
        v.items.push_back(value(depth + 1));
        if (!peek(close)) expect(',');
      }
      ++i_;
    } else if (word("True") || word("False")) {
      v.kind = PyValue::kBool;
      v.boolean = s_[start] == 'T';
    } else if (word("None")) {
      v.kind = PyValue::kNone;
    } else {
      const bool negative = peek('-');
      if (negative) ++i_;
      if (i_ >= s_.size() || !std::isdigit(static_cast<unsigned char>(s_[i_])))
        fail("unexpected character");
      v.kind = PyValue::kInt;
      while (i_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[i_])))
        if (__builtin_mul_overflow(v.integer, 10, &v.integer) ||
            __builtin_add_overflow(v.integer, s_[i_++] - '0', &v.integer))
          fail("integer too large");
      if (i_ < s_.size() && (s_[i_] == 'L' || s_[i_] == 'l')) ++i_;  // Python 2's long
      if (negative) v.integer = -v.integer;
    }
    v.text = v.kind == PyValue::kString ? v.text : s_.substr(start, i_ - start);
    return v;
  }

  const std::string& s_;
  Where where_;
  std::size_t i_ = 0;
};

// Headers of real arrays take ~100 bytes; NumPy itself refuses more than 10 000 by default.
constexpr std::uint64_t kMaxNpyHeader = 1 << 20;

// Reads one .npy stream of `size` bytes (`sizeKnown` when the size is a file's, not a claim).
Volume readNpy(Source& in, std::uint64_t size, bool sizeKnown, const VolumeLimits& limits,
               const Where& header, const Where& data) {
  unsigned char prefix[12];
  if (in.read(prefix, 10) < 10 || std::memcmp(prefix, "\x93NUMPY", 6) != 0)
    header.fail("not a NumPy .npy file (no \\x93NUMPY magic)");
  const int major = prefix[6];
  if (major < 1 || major > 3)
    header.fail("unsupported .npy format version " + std::to_string(major) + "." +
                std::to_string(prefix[7]));
  std::uint64_t headerLength = prefix[8] | (prefix[9] << 8);
  std::uint64_t headerEnd = 10;
  if (major >= 2) {
    if (in.read(prefix + 10, 2) < 2) header.fail("truncated header");
    headerLength |= std::uint64_t(prefix[10]) << 16 | std::uint64_t(prefix[11]) << 24;
    headerEnd = 12;
  }
  if (headerLength > kMaxNpyHeader || headerEnd + headerLength > size)
    header.fail("header length " + std::to_string(headerLength) + " exceeds the " +
                (headerLength > kMaxNpyHeader ? "limit of " + std::to_string(kMaxNpyHeader)
                                              : "data size " + std::to_string(size)));
  std::string text(std::size_t(headerLength), '\0');
  if (in.read(reinterpret_cast<unsigned char*>(text.data()), text.size()) < text.size())
    header.fail("truncated header");
  headerEnd += headerLength;

  std::string descr;
  bool fortran = false, haveDescr = false, haveOrder = false, haveShape = false;
  std::vector<PyValue> shape;
  for (const auto& [key, value] : PyParser(text, header).dict()) {
    if (key == "descr") {
      if (value.kind != PyValue::kString) header.fail("unsupported dtype " + value.text);
      descr = value.text, haveDescr = true;
    } else if (key == "fortran_order") {
      if (value.kind != PyValue::kBool) header.fail("fortran_order is not True or False");
      fortran = value.boolean, haveOrder = true;
    } else if (key == "shape") {
      if (value.kind != PyValue::kTuple) header.fail("shape is not a tuple");
      shape = value.items, haveShape = true;
    } else {
      header.fail("unknown key '" + key + "' in the header dict");
    }
  }
  if (!haveDescr || !haveOrder || !haveShape)
    header.fail("the header dict lacks " + std::string(!haveDescr   ? "'descr'"
                                                       : !haveOrder ? "'fortran_order'"
                                                                    : "'shape'"));

  // '<' little-endian, '>' big-endian, '|' not applicable (one byte), '=' native.
  const VoxelType* type = nullptr;
  if (descr.size() == 3 && std::string("<>|=").find(descr[0]) != std::string::npos &&
      std::isdigit(static_cast<unsigned char>(descr[2])))
    type = findVoxelType(descr[1], descr[2] - '0');
  if (!type || (descr[0] == '|' && type->bytes > 1))
    header.fail("unsupported dtype '" + descr +
                "' (expected one of |u1 |i1 <u2 <i2 <u4 <i4 <f4 <f8, or > for big-endian)");
  const bool big = descr[0] == '>' || (descr[0] == '=' && kNativeIsBig);

  if (shape.size() != 3)
    header.fail("shape has " + std::to_string(shape.size()) + " dimensions, expected 3");
  std::int64_t d[3];
  for (int i = 0; i < 3; ++i) {
    if (shape[std::size_t(i)].kind != PyValue::kInt)
      header.fail("shape is not a tuple of integers");
    // C order: the last axis varies fastest, so it becomes i; Fortran order: the first.
    d[i] = shape[std::size_t(fortran ? i : 2 - i)].integer;
  }
  const std::size_t count = checkDims(d, limits, header);
  checkDataSize(size - headerEnd, count, *type, data);

  Volume v;
  v.dims = glm::ivec3(int(d[0]), int(d[1]), int(d[2]));
  v.voxelType = type->name;
  v.values = readVoxels(in, count, *type, big != kNativeIsBig, {}, sizeKnown, data);
  return v;
}

Volume loadNpy(const fs::path& file, const VolumeLimits& limits) {
  const Where header{file.string(), "header"}, data{file.string(), "data"};
  const std::uint64_t size = fileSize(file, header);
  FileSource in(file, header);
  return readNpy(in, size, true, limits, header, data);
}

struct ZipClose {
  void operator()(zip_t* z) const { zip_discard(z); }  // read-only: nothing to write back
};
struct ZipFileClose {
  void operator()(zip_file_t* f) const { zip_fclose(f); }
};

class ZipSource : public Source {
 public:
  ZipSource(zip_file_t* f, const Where& where) : f_(f), where_(where) {}
  std::size_t read(unsigned char* out, std::size_t n) override {
    std::size_t done = 0;
    while (done < n) {
      const zip_int64_t got = zip_fread(f_, out + done, n - done);
      if (got < 0) where_.fail("corrupt zip member: " + std::string(zip_file_strerror(f_)));
      if (got == 0) break;
      done += std::size_t(got);
    }
    return done;
  }

 private:
  zip_file_t* f_;
  Where where_;
};

Volume loadNpz(const fs::path& file, const VolumeLimits& limits) {
  const Where archive{file.string(), ""};
  int code = 0;
  const std::unique_ptr<zip_t, ZipClose> z(zip_open(file.c_str(), ZIP_RDONLY, &code));
  if (!z) {
    zip_error_t error;
    zip_error_init_with_code(&error, code);
    const std::string reason = zip_error_strerror(&error);
    zip_error_fini(&error);
    archive.fail("not a readable .npz (zip) archive: " + reason);
  }
  // np.savez names its arrays arr_0.npy, arr_1.npy, … or by keyword: take the first.
  const zip_int64_t entries = zip_get_num_entries(z.get(), 0);
  zip_int64_t index = -1;
  std::string member;
  for (zip_int64_t i = 0; i < entries && index < 0; ++i) {
    const char* name = zip_get_name(z.get(), zip_uint64_t(i), 0);
    if (name && std::string(name).ends_with(".npy")) index = i, member = name;
  }
  if (index < 0) archive.fail("the archive holds no .npy member");

  const Where where{file.string(), member};
  zip_stat_t st;
  zip_stat_init(&st);
  if (zip_stat_index(z.get(), zip_uint64_t(index), 0, &st) != 0 || !(st.valid & ZIP_STAT_SIZE))
    where.fail("cannot read the member's size: " + std::string(zip_strerror(z.get())));
  const std::unique_ptr<zip_file_t, ZipFileClose> f(
      zip_fopen_index(z.get(), zip_uint64_t(index), 0));
  if (!f) where.fail("cannot open the member: " + std::string(zip_strerror(z.get())));
  ZipSource in(f.get(), where);
  // The member's size is the archive's claim, checked only as the data is inflated.
  Volume v = readNpy(in, st.size, false, limits, where, where);
  // libzip checks the CRC when it reaches the member's end: read on to it.
  unsigned char extra;
  if (in.read(&extra, 1) != 0)
    where.fail("corrupt zip member: more data than the archive's directory says");
  return v;
}

// ---------------------------------------------------------------------------------------------
// VolPack density files (.den): a header of shorts in the writer's byte order, then one byte
// per voxel, x fastest. See libvolpack1-dev's examples/denfile.c.

Volume loadDen(const fs::path& file, const VolumeLimits& limits) {
  const Where header{file.string(), "header"}, data{file.string(), "data"};
  const std::uint64_t size = fileSize(file, header);
  FileSource in(file, header);
  constexpr std::size_t kHeaderBytes = 2 + 27 * 2 + 2 + 4;
  unsigned char h[kHeaderBytes];
  if (in.read(h, kHeaderBytes) < kHeaderBytes)
    header.fail("truncated header: " + std::to_string(size) + " bytes, expected at least " +
                std::to_string(kHeaderBytes));
  // map_version is 1; written on a machine of the other byte order it reads as 0x0100.
  bool swap = false;
  if (load<std::int16_t>(h, false) == 0x0100)
    swap = true;
  else if (load<std::int16_t>(h, false) != 1)
    header.fail("not a VolPack density file (map_version is neither 1 nor 0x0100)");
  const auto shortAt = [&](int index) { return load<std::int16_t>(h + 2 + 2 * index, swap); };
  // orig_min/max/len, extr_min/max/len, map_min/max/len: three shorts each.
  const std::int64_t d[3] = {shortAt(24), shortAt(25), shortAt(26)};
  const std::int64_t mapLength = load<std::int32_t>(h + 58, swap);
  const std::size_t count = checkDims(d, limits, header);
  if (mapLength != std::int64_t(count))
    header.fail("inconsistent header: map_length " + std::to_string(mapLength) + " is not " +
                dimsText(d));
  checkDataSize(size - kHeaderBytes, count, kU8, data);

  Volume v;
  v.dims = glm::ivec3(int(d[0]), int(d[1]), int(d[2]));
  v.voxelType = kU8.name;
  v.values = readVoxels(in, count, kU8, false, {}, true, data);
  return v;
}

// ---------------------------------------------------------------------------------------------
// Raw voxels described by a JSON header.

std::int64_t jsonInteger(const json_reader::Context& ctx, const json_reader::json& j,
                         const std::string& ptr) {
  if (!j.is_number_integer()) ctx.fail(ptr, "expected an integer, got " + json_reader::typeName(j));
  if (j.is_number_unsigned() && j.get<std::uint64_t>() > std::uint64_t(INT64_MAX))
    ctx.fail(ptr, "integer too large");
  return j.get<std::int64_t>();
}

Volume loadRawJson(const fs::path& file, const VolumeLimits& limits) {
  using json_reader::json;
  const json_reader::Context ctx{file.string(), file.parent_path(), {}};
  std::ifstream stream(file);
  if (!stream) ctx.fail("", "cannot open for reading: " + std::string(std::strerror(errno)));
  json root;
  try {
    root = json::parse(stream);
  } catch (const json::exception& e) {
    std::string reason = e.what();
    if (const auto p = reason.find("] "); p != std::string::npos) reason = reason.substr(p + 2);
    throw Error(file.string(), "", "invalid JSON: " + reason);
  }

  json_reader::ObjectReader r(ctx, root, "");
  const std::string raw = json_reader::string(ctx, r.require("file"), "/file");
  const json& dimsJson = r.require("dims");
  const std::string typeName = json_reader::oneOf(
      ctx, r.require("type"), "/type", {"u8", "i8", "u16", "i16", "u32", "i32", "f32", "f64"});
  glm::dvec3 spacing(1.0), origin(0.0);
  if (const json* j = r.take("spacing")) spacing = json_reader::vec3(ctx, *j, "/spacing");
  if (const json* j = r.take("origin")) origin = json_reader::vec3(ctx, *j, "/origin");
  bool big = false;
  if (const json* j = r.take("endianness"))
    big = json_reader::oneOf(ctx, *j, "/endianness", {"little", "big"}) == "big";
  std::int64_t headerBytes = 0;
  if (const json* j = r.take("headerBytes")) {
    headerBytes = jsonInteger(ctx, *j, "/headerBytes");
    if (headerBytes < 0) ctx.fail("/headerBytes", "must not be negative");
  }
  r.finish();

  if (!dimsJson.is_array() || dimsJson.size() != 3)
    ctx.fail("/dims", "expected an array of 3 integers");
  std::int64_t d[3];
  for (std::size_t i = 0; i < 3; ++i)
    d[i] = jsonInteger(ctx, dimsJson[i], "/dims/" + std::to_string(i));
  const std::size_t count = checkDims(d, limits, {file.string(), "/dims"});
  const VoxelType* type = nullptr;
  for (const VoxelType& t : kVoxelTypes)
    if (typeName == t.name) type = &t;

  Volume v;
  v.dims = glm::ivec3(int(d[0]), int(d[1]), int(d[2]));
  v.voxelType = type->name;
  // Voxel (i, j, k) at origin + spacing·(i, j, k); a zero spacing is singular.
  glm::dmat4 m(1.0);
  for (int a = 0; a < 3; ++a) m[a][a] = spacing[a], m[3][a] = origin[a];
  v.indexToWorld = checkTransform(m, {file.string(), "/spacing"});

  const fs::path rawPath = file.parent_path() / raw;
  const Where where{file.string(), "/file"};
  const Where data{file.string(), "/file: " + rawPath.string()};
  std::error_code ec;
  if (!fs::is_regular_file(rawPath, ec)) where.fail("raw file not found: " + rawPath.string());
  const std::uint64_t size = fileSize(rawPath, data);
  if (std::uint64_t(headerBytes) > size)
    ctx.fail("/headerBytes", "headerBytes " + std::to_string(headerBytes) +
                                 " exceeds the raw file's size of " + std::to_string(size));
  checkDataSize(size - std::uint64_t(headerBytes), count, *type, data);
  FileSource in(rawPath, data);
  in.seek(std::uint64_t(headerBytes));
  v.values = readVoxels(in, count, *type, big != kNativeIsBig, {}, true, data);
  return v;
}

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

Volume importVolume(const std::filesystem::path& file) {
  return importVolume(file, {});
}

Volume importVolume(const std::filesystem::path& file, const VolumeLimits& limits) {
  std::string name = file.filename().string();
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  Volume (*reader)(const fs::path&, const VolumeLimits&) = nullptr;
  if (endsWith(name, ".nii") || endsWith(name, ".nii.gz"))
    reader = loadNifti;
  else if (endsWith(name, ".npy"))
    reader = loadNpy;
  else if (endsWith(name, ".npz"))
    reader = loadNpz;
  else if (endsWith(name, ".den"))
    reader = loadDen;
  else if (endsWith(name, ".json"))
    reader = loadRawJson;
  else
    throw Error(file.string(), "",
                "unknown volume format (expected .nii, .nii.gz, .npy, .npz, .den or .json)");
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) throw Error(file.string(), "", "volume file not found");
  Volume v = reader(file, limits);
  v.updateRange();
  return v;
}

}  // namespace cutaway
