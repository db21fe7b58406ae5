#include "cutaway/io/volume_import.hpp"

#include <nifti2_io.h>
#include <zip.h>
#include <zlib.h>

#include <gdcmByteValue.h>
#include <gdcmDataSet.h>
#include <gdcmDictEntry.h>
#include <gdcmDicts.h>
#include <gdcmGlobal.h>
#include <gdcmImage.h>
#include <gdcmImageReader.h>
#include <gdcmPixelFormat.h>
#include <gdcmReader.h>
#include <gdcmTrace.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "core/json_reader.hpp"
#include "cutaway/core/contained.hpp"
#include "cutaway/core/error.hpp"
#include "cutaway/geometry/mesh.hpp"
#include "io/wire_fields.hpp"

namespace cutaway {

bool Volume::updateRange() {
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
  return any;
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

// Refuses a transform that cannot place voxels: non-finite entries, entries beyond a scene's
// reach (1e300's squares overflowed into "singular"), or a singular 3×3 part.
glm::mat4 checkTransform(const glm::dmat4& m, const Where& where) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) {
      if (!std::isfinite(m[c][r])) where.fail("the voxel-to-world transform is not finite");
      if (std::abs(m[c][r]) > double(kMaxSceneReach)) {
        char text[32];
        std::snprintf(text, sizeof text, "%.3g", std::abs(m[c][r]));
        where.fail(std::string("the voxel-to-world transform has an entry of magnitude ") + text +
                   ", beyond the 1e15 a scene may reach");
      }
    }
  const glm::dmat3 a(m);
  const double scale = glm::length(a[0]) * glm::length(a[1]) * glm::length(a[2]);
  if (!(scale > 0.0) || std::abs(glm::determinant(a)) <= 1e-9 * scale)
    where.fail("the voxel-to-world transform is singular");
  return glm::mat4(m);
}

// Scanner data are placed in RAS+ millimetres, NIfTI's world (+x to the patient's right, +y
// anterior, +z superior). DICOM and ITK's MetaImage are LPS+ (+x left, +y posterior), as NRRD's
// left-… spaces are: those axes turn round, so volumes and meshes from any of these formats
// line up in one scene.
glm::dmat4 toRas(glm::dmat4 m, bool flipX, bool flipY) {
  for (int c = 0; c < 4; ++c) {
    if (flipX) m[c].x = -m[c].x;
    if (flipY) m[c].y = -m[c].y;
  }
  return m;
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
      : gz_(gzopen(file.c_str(), "rb")), where_(where), file_(file) {
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
        std::string reason = gzerror(gz_, &code);
        if (reason.starts_with(file_ + ": ")) reason.erase(0, file_.size() + 2);  // named already
        where_.fail("corrupt gzip data: " + reason);
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
  std::string file_;  // zlib's messages start with it
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
  // In a single file the voxels follow the header. 0 is "unset" (as NiBabel reads it): right
  // after the header and its 4-byte extension flag.
  if (voxOffset > 0.0 && voxOffset < double(hdrSize)) {
    char text[32];
    std::snprintf(text, sizeof text, "%.10g", voxOffset);
    header.fail(std::string("vox_offset ") + text + " lies inside the " + std::to_string(hdrSize) +
                "-byte header");
  }
  const std::uint64_t offset =
      voxOffset == 0.0 ? std::uint64_t(hdrSize) + 4 : std::uint64_t(voxOffset);

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
  std::ifstream stream(file, std::ios::binary);
  if (!stream) ctx.fail("", "cannot open for reading: " + std::string(std::strerror(errno)));
  std::stringstream text;
  text << stream.rdbuf();
  const json root = json_reader::parse(ctx, text.str());

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
  // Voxel (i, j, k) at origin + spacing·(i, j, k); a zero spacing is singular. The origin is
  // checked apart so that an error names it; checkTransform names the spacing.
  for (int a = 0; a < 3; ++a)
    if (std::abs(origin[a]) > double(kMaxSceneReach)) {
      char text[32];
      std::snprintf(text, sizeof text, "%.3g", std::abs(origin[a]));
      ctx.fail("/origin/" + std::to_string(a),
               std::string("magnitude ") + text + " is beyond the 1e15 a scene may reach");
    }
  glm::dmat4 m(1.0);
  for (int a = 0; a < 3; ++a) m[a][a] = spacing[a], m[3][a] = origin[a];
  v.indexToWorld = checkTransform(m, {file.string(), "/spacing"});

  const fs::path rawPath = file.parent_path() / raw;
  const Where where{file.string(), "/file"};
  const Where data{file.string(), "/file: " + rawPath.string()};
  std::error_code ec;
  if (!fs::is_regular_file(rawPath, ec))
    where.fail(
        (fs::exists(rawPath, ec) ? "raw file is not a regular file: " : "raw file not found: ") +
        rawPath.string());
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

// ---------------------------------------------------------------------------------------------
// Text headers: MetaImage, NRRD and VTK files begin with lines of text.

// Real headers take a few hundred bytes; a binary file under one of their suffixes stops here.
constexpr std::uint64_t kMaxTextHeader = 1 << 20;

bool isSpace(char c) {
  return std::isspace(static_cast<unsigned char>(c)) != 0;
}

std::string trim(std::string_view s) {
  while (!s.empty() && isSpace(s.front())) s.remove_prefix(1);
  while (!s.empty() && isSpace(s.back())) s.remove_suffix(1);
  return std::string(s);
}

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string upper(std::string s) {
  for (char& c : s) c = char(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

std::vector<std::string> words(std::string_view s) {
  std::vector<std::string> out;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && isSpace(s[i])) ++i;
    const std::size_t start = i;
    while (i < s.size() && !isSpace(s[i])) ++i;
    if (i > start) out.emplace_back(s.substr(start, i - start));
  }
  return out;
}

// A value quoted for an error message, cut short if long, bytes other than printable ASCII as
// \xNN (it may come from a binary file).
std::string inQuotes(std::string_view s) {
  std::string out = "\"";
  for (const char c : s.substr(0, 60)) {
    if (c >= ' ' && c <= '~') {
      out += c;
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", unsigned(static_cast<unsigned char>(c)));
      out += hex;
    }
  }
  return out + (s.size() > 60 ? "…\"" : "\"");
}

// A length in mm for an error message: "2.5", not "2.500000".
std::string mm(double v) {
  char s[32];
  std::snprintf(s, sizeof s, "%g mm", v);
  return s;
}

// A number as C writes it ("1.5", "-2e3", "+4", "nan"), whatever the locale.
std::optional<double> toNumber(std::string_view s) {
  if (s.starts_with('+') && !s.starts_with("+-")) s.remove_prefix(1);  // from_chars: '-' only
  double v = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
  return v;
}

std::optional<std::int64_t> toInteger(std::string_view s) {
  if (s.starts_with('+') && !s.starts_with("+-")) s.remove_prefix(1);
  std::int64_t v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
  return v;
}

// `text` as exactly `n` finite numbers, else an error naming `what`.
std::vector<double> numberList(const std::string& text, std::size_t n, const std::string& what,
                               const Where& where) {
  const std::vector<std::string> w = words(text);
  std::vector<double> out;
  for (const std::string& s : w)
    if (const std::optional<double> v = toNumber(s); v && std::isfinite(*v)) out.push_back(*v);
  if (w.size() != n || out.size() != n)
    where.fail((what.empty() ? "" : what + ": ") + "expected " + std::to_string(n) +
               (n == 1 ? " finite number" : " finite numbers") + ", got " + inQuotes(text));
  return out;
}

std::vector<std::int64_t> integerList(const std::string& text, std::size_t n,
                                      const std::string& what, const Where& where) {
  const std::vector<std::string> w = words(text);
  std::vector<std::int64_t> out;
  for (const std::string& s : w)
    if (const std::optional<std::int64_t> v = toInteger(s)) out.push_back(*v);
  if (w.size() != n || out.size() != n)
    where.fail(what + ": expected " + std::to_string(n) + (n == 1 ? " integer" : " integers") +
               ", got " + inQuotes(text));
  return out;
}

std::int64_t integer(const std::string& text, const std::string& what, const Where& where) {
  return integerList(text, 1, what, where)[0];
}

// The lines of a header, each without its "\n" or "\r\n", counted from 1; where the next line
// (or attached data) starts.
class HeaderLines {
 public:
  HeaderLines(const fs::path& file, const Where& where)
      : in_(file, std::ios::binary), where_(where) {
    if (!in_) where.fail("cannot open for reading: " + std::string(std::strerror(errno)));
  }
  // False at the end of the file.
  bool next(std::string& line) {
    line.clear();
    int c = in_.get();
    if (c == EOF) {
      if (in_.bad()) where_.fail("read error");
      return false;
    }
    ++number_;
    for (; c != EOF && c != '\n'; c = in_.get()) {
      if (++offset_ > kMaxTextHeader)
        where_.fail("no end of the header in its first " + std::to_string(kMaxTextHeader) +
                    " bytes: not a header, or a broken one");
      line += char(c);
    }
    if (c == '\n') ++offset_;
    if (in_.bad()) where_.fail("read error");
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return true;
  }
  int number() const { return number_; }
  std::uint64_t offset() const { return offset_; }
  // The line just read, as a place for errors.
  Where here() const { return where_.at("line " + std::to_string(number_)); }

 private:
  std::ifstream in_;
  Where where_;
  int number_ = 0;
  std::uint64_t offset_ = 0;
};

// ---------------------------------------------------------------------------------------------
// Voxels stored raw, deflated (zlib or gzip) or as text, where a header says.

enum class Encoding { kRaw, kDeflate, kAscii };

struct DataLayout {
  fs::path file;
  std::uint64_t offset = 0;  // where the data, or the lines to skip, start
  std::int64_t lineSkip = 0;
  // Bytes skipped in the file after those lines; −1: the data are the file's last bytes (the
  // voxels' size when raw, compressedSize when deflated).
  std::int64_t byteSkip = 0;
  std::int64_t inflatedSkip = 0;  // bytes skipped once inflated (NRRD's byte skip with gzip)
  std::optional<std::uint64_t> compressedSize;
  Encoding encoding = Encoding::kRaw;
  bool big = false;
  bool exact = true;  // more data than the dims need is an error
};

// A zlib or a gzip stream (told apart by its header) inflated from at most `limit` bytes of
// `in`.
class InflateSource : public Source {
 public:
  InflateSource(Source& in, std::uint64_t limit, const Where& where)
      : in_(in), left_(limit), where_(where), buffer_(1 << 16) {
    if (inflateInit2(&z_, 15 + 32) != Z_OK) where.fail("zlib cannot start inflating");
  }
  ~InflateSource() override { inflateEnd(&z_); }
  std::size_t read(unsigned char* out, std::size_t n) override {
    std::size_t done = 0;
    while (done < n && !ended_) {
      if (z_.avail_in == 0 && left_ > 0) {
        const std::size_t got =
            in_.read(buffer_.data(), std::size_t(std::min<std::uint64_t>(left_, buffer_.size())));
        left_ = got == 0 ? 0 : left_ - got;
        z_.next_in = buffer_.data();
        z_.avail_in = uInt(got);
      }
      const uInt ask = uInt(std::min<std::size_t>(n - done, 1u << 30));
      z_.next_out = out + done;
      z_.avail_out = ask;
      const int rc = inflate(&z_, Z_NO_FLUSH);
      done += ask - z_.avail_out;
      if (rc == Z_STREAM_END)
        ended_ = true;
      else if (rc == Z_BUF_ERROR)
        break;  // no input left: a truncated stream, told by the caller from the count
      else if (rc != Z_OK)
        where_.fail("corrupt compressed data: " + std::string(z_.msg ? z_.msg : "zlib error"));
    }
    return done;
  }

 private:
  Source& in_;
  std::uint64_t left_;
  Where where_;
  std::vector<unsigned char> buffer_;
  z_stream z_{};
  bool ended_ = false;
};

// The value range of an integer voxel type, for numbers read as text.
bool holds(const VoxelType& t, double v) {
  if (t.kind == 'f') return true;
  const double bits = t.bytes * 8;
  const double lo = t.kind == 'u' ? 0.0 : -std::exp2(bits - 1);
  const double hi = (t.kind == 'u' ? std::exp2(bits) : std::exp2(bits - 1)) - 1.0;
  return v == std::floor(v) && v >= lo && v <= hi;
}

// `count` whitespace-separated numbers; an integer type takes the integers it can hold.
std::vector<float> readAsciiVoxels(Source& in, std::size_t count, const VoxelType& t,
                                   const Where& where) {
  std::vector<float> values;
  values.reserve(std::min(count, kChunkBytes / sizeof(float)));  // grows as values arrive
  std::vector<unsigned char> buffer(1 << 16);
  std::size_t have = 0, at = 0;
  const auto next = [&]() -> int {
    if (at == have) {
      have = in.read(buffer.data(), buffer.size()), at = 0;
      if (have == 0) return EOF;
    }
    return buffer[at++];
  };
  std::string token;
  while (values.size() < count) {
    token.clear();
    int c = next();
    while (c != EOF && isSpace(char(c))) c = next();
    for (; c != EOF && !isSpace(char(c)); c = next()) {
      if (token.size() == 64) where.fail("value " + std::to_string(values.size()) + " is too long");
      token += char(c);
    }
    if (token.empty())
      where.fail("truncated: " + std::to_string(values.size()) + " values, expected " +
                 std::to_string(count));
    const std::optional<double> v = toNumber(token);
    if (!v)
      where.fail("value " + std::to_string(values.size()) + ", " + inQuotes(token) +
                 ", is not a number");
    if (!holds(t, *v))
      where.fail("value " + std::to_string(values.size()) + ", " + inQuotes(token) +
                 ", does not fit " + t.name);
    values.push_back(float(*v));
  }
  return values;
}

std::vector<float> readData(const DataLayout& d, std::size_t count, const VoxelType& t,
                            const Where& data) {
  std::error_code ec;
  if (!fs::is_regular_file(d.file, ec))
    data.fail(fs::exists(d.file, ec) ? "data file is not a regular file" : "data file not found");
  const std::uint64_t size = fileSize(d.file, data);
  const std::uint64_t expected = std::uint64_t(count) * std::uint64_t(t.bytes);
  if (d.offset > size) data.fail(truncated(0, expected));
  std::uint64_t start = d.offset;
  if (d.lineSkip > 0) {
    std::ifstream lines(d.file, std::ios::binary);
    lines.seekg(std::streamoff(start));
    for (std::int64_t i = 0; i < d.lineSkip; ++i)
      if (!lines.ignore(std::numeric_limits<std::streamsize>::max(), '\n') || lines.eof())
        data.fail("the file ends within the " + std::to_string(d.lineSkip) + " lines to skip");
    start = std::uint64_t(lines.tellg());
  }
  FileSource in(d.file, data);
  const std::uint64_t left = size - start;
  const bool swap = d.big != kNativeIsBig;

  if (d.encoding == Encoding::kRaw) {
    std::uint64_t available = left;
    if (d.byteSkip == -1) {
      if (available < expected) data.fail(truncated(available, expected));
      start = size - expected, available = expected;
    } else {
      if (std::uint64_t(d.byteSkip) > left)
        data.fail("truncated: the file ends within the " + std::to_string(d.byteSkip) +
                  " bytes to skip");
      start += std::uint64_t(d.byteSkip), available -= std::uint64_t(d.byteSkip);
    }
    if (d.exact)
      checkDataSize(available, count, t, data);
    else if (available < expected)
      data.fail(truncated(available, expected));
    in.seek(start);
    return readVoxels(in, count, t, swap, {}, true, data);
  }

  if (d.byteSkip == -1) {
    if (!d.compressedSize) data.fail("data at the file's end need a compressed size");
    if (*d.compressedSize > left) data.fail(truncated(left, *d.compressedSize) + " (compressed)");
    start = size - *d.compressedSize;
  } else {
    if (std::uint64_t(d.byteSkip) > left)
      data.fail("truncated: the file ends within the " + std::to_string(d.byteSkip) +
                " bytes to skip");
    start += std::uint64_t(d.byteSkip);
  }
  in.seek(start);
  if (d.encoding == Encoding::kAscii) return readAsciiVoxels(in, count, t, data);

  std::uint64_t limit = size - start;
  if (d.compressedSize) {
    if (*d.compressedSize > limit)
      data.fail("truncated: " + std::to_string(limit) + " bytes of compressed data, expected " +
                std::to_string(*d.compressedSize));
    limit = *d.compressedSize;
  }
  InflateSource z(in, limit, data);
  if (const std::uint64_t skip = std::uint64_t(d.inflatedSkip); skipBytes(z, skip) < skip)
    data.fail(truncated(0, expected) + " (the inflated data end within the " +
              std::to_string(skip) + " bytes to skip)");
  std::vector<float> values = readVoxels(z, count, t, swap, {}, false, data);
  unsigned char extra;
  if (d.exact && z.read(&extra, 1) != 0)
    data.fail("more inflated voxel data than the " + std::to_string(expected) +
              " bytes expected: the dims disagree with the data size");
  return values;
}

// The file a header names, beside the header unless the path is absolute; patterns and lists
// of files (several slices' files) are not read.
fs::path dataFile(const fs::path& header, const std::string& name, const Where& where,
                  const std::string& what) {
  if (name.empty()) where.fail(what + " is empty");
  const std::vector<std::string> w = words(name);
  if (upper(w[0]) == "LIST" || name.find('%') != std::string::npos)
    where.fail(what + " " + inQuotes(name) +
               ": lists and patterns of data files are not read, only a single file");
  return header.parent_path() / name;
}

// ---------------------------------------------------------------------------------------------
// MetaImage (.mha, .mhd): "Key = Value" lines, the last of them ElementDataFile, then the
// voxels (ElementDataFile = LOCAL) or the voxels' file's name. See ITK's MetaIO (metaImage.cxx)
// and itk::MetaImageIO.

// A voxel type as a text header spells it.
struct TypeName {
  const char* name;
  const VoxelType* type;
};
constexpr TypeName kMetaTypes[] = {
    {"MET_UCHAR", &kU8}, {"MET_CHAR", &kI8}, {"MET_USHORT", &kU16}, {"MET_SHORT", &kI16},
    {"MET_UINT", &kU32}, {"MET_INT", &kI32}, {"MET_FLOAT", &kF32},  {"MET_DOUBLE", &kF64}};

Volume loadMetaImage(const fs::path& file, const VolumeLimits& limits) {
  const Where header{file.string(), "header"}, data{file.string(), "data"};
  struct Field {
    std::string key, value;  // the key as written
    Where where;
  };
  std::map<std::string, Field> fields;  // by lower-case key; a repeated key's last value
  HeaderLines lines(file, header);
  std::string line;
  bool ended = false;
  while (!ended && lines.next(line)) {
    const std::string text = trim(line);
    if (text.empty()) continue;
    const std::size_t eq = text.find('=');
    if (eq == std::string::npos)
      lines.here().fail("expected \"Key = Value\", got " + inQuotes(text));
    const std::string key = trim(text.substr(0, eq));
    fields[lower(key)] = {key, trim(text.substr(eq + 1)), lines.here()};
    ended = lower(key) == "elementdatafile";
  }
  if (!ended) header.fail("no ElementDataFile line: not a MetaImage header, or a cut one");

  // The first of `keys` present (MetaIO's synonyms, in order of precedence).
  const auto get = [&](std::initializer_list<const char*> keys) -> const Field* {
    for (const char* k : keys)
      if (const auto it = fields.find(lower(k)); it != fields.end()) return &it->second;
    return nullptr;
  };
  const auto require = [&](const char* key) -> const Field& {
    const Field* f = get({key});
    if (!f) header.fail("no " + std::string(key) + " line");
    return *f;
  };
  const auto boolean = [&](std::initializer_list<const char*> keys, bool otherwise) {
    const Field* f = get(keys);
    if (!f) return otherwise;
    const std::string v = lower(f->value);
    if (v != "true" && v != "false" && v != "1" && v != "0")
      f->where.fail(f->key + ": expected True or False, got " + inQuotes(f->value));
    return v == "true" || v == "1";
  };

  if (const Field* f = get({"ObjectType"}); f && lower(f->value) != "image")
    f->where.fail("ObjectType is " + inQuotes(f->value) + ": only Image is read");
  const Field& nDims = require("NDims");
  if (const std::int64_t n = integer(nDims.value, "NDims", nDims.where); n != 3)
    nDims.where.fail("NDims is " + std::to_string(n) + ": only 3-D images are read");
  const Field& dimSize = require("DimSize");
  const std::vector<std::int64_t> d = integerList(dimSize.value, 3, "DimSize", dimSize.where);
  const std::size_t count = checkDims(d.data(), limits, dimSize.where);
  if (const Field* f = get({"ElementNumberOfChannels"}))
    if (const std::int64_t n = integer(f->value, f->key, f->where); n != 1)
      f->where.fail("ElementNumberOfChannels is " + std::to_string(n) +
                    ": only single-channel (scalar) images are read");
  const Field& elementType = require("ElementType");
  const VoxelType* type = nullptr;
  for (const auto& [name, t] : kMetaTypes)
    if (upper(elementType.value) == name) type = t;
  if (!type)
    elementType.where.fail("unsupported ElementType " + inQuotes(elementType.value) +
                           " (expected MET_UCHAR, MET_CHAR, MET_USHORT, MET_SHORT, MET_UINT, "
                           "MET_INT, MET_FLOAT or MET_DOUBLE)");

  // World = Offset + TransformMatrix·diag(ElementSpacing)·(i, j, k): ITK's MetaImageIO reads
  // TransformMatrix's numbers 3a, 3a + 1, 3a + 2 as the direction of index axis a (a column of
  // itk::Image's direction matrix) and writes them so. Offset is voxel (0, 0, 0)'s centre.
  glm::dmat4 m(1.0);
  const Field* spacing = get({"ElementSpacing", "ElementSize"});
  const Field* offset = get({"Offset", "Position", "Origin"});
  const Field* matrix = get({"TransformMatrix", "Rotation", "Orientation"});
  const std::vector<double> s = spacing
                                    ? numberList(spacing->value, 3, spacing->key, spacing->where)
                                    : std::vector<double>{1, 1, 1};
  if (matrix) {
    const std::vector<double> t = numberList(matrix->value, 9, matrix->key, matrix->where);
    for (int a = 0; a < 3; ++a)
      for (int r = 0; r < 3; ++r) m[a][r] = t[std::size_t(3 * a + r)];
  }
  for (int a = 0; a < 3; ++a) m[a] *= s[std::size_t(a)];
  if (offset) {
    const std::vector<double> o = numberList(offset->value, 3, offset->key, offset->where);
    m[3] = glm::dvec4(o[0], o[1], o[2], 1.0);
  }

  DataLayout layout;
  const Field& elementDataFile = *get({"ElementDataFile"});
  if (upper(elementDataFile.value) == "LOCAL") {
    layout.file = file;
    layout.offset = lines.offset();
  } else {
    layout.file = dataFile(file, elementDataFile.value, elementDataFile.where, "ElementDataFile");
  }
  layout.big = boolean({"BinaryDataByteOrderMSB", "ElementByteOrderMSB"}, false);
  const bool binary = boolean({"BinaryData"}, true);  // MetaImage files are binary in practice
  const bool compressed = boolean({"CompressedData"}, false);
  if (!binary && compressed)
    get({"CompressedData"})->where.fail("CompressedData = True with BinaryData = False");
  layout.encoding = !binary ? Encoding::kAscii : compressed ? Encoding::kDeflate : Encoding::kRaw;
  if (const Field* f = get({"CompressedDataSize"}); f && compressed) {
    const std::int64_t n = integer(f->value, f->key, f->where);
    if (n < 0) f->where.fail("CompressedDataSize must not be negative");
    if (n > 0) layout.compressedSize = std::uint64_t(n);  // 0: unknown, to the file's end
  }
  if (const Field* f = get({"HeaderSize"})) {
    layout.byteSkip = integer(f->value, f->key, f->where);
    if (layout.byteSkip < -1) f->where.fail("HeaderSize must be −1 (data at the end) or more");
    if (layout.byteSkip == -1 && (!binary || (compressed && !layout.compressedSize)))
      f->where.fail("HeaderSize = −1 needs binary, uncompressed data or a CompressedDataSize");
  }

  Volume v;
  v.dims = glm::ivec3(int(d[0]), int(d[1]), int(d[2]));
  v.voxelType = type->name;
  // A zero spacing is the likelier culprit of a singular transform.
  const bool zero = std::find(s.begin(), s.end(), 0.0) != s.end();
  const Field* culprit = spacing && (zero || !matrix) ? spacing : matrix;
  v.indexToWorld = checkTransform(
      toRas(m, true, true),
      culprit ? culprit->where.at(culprit->where.place + ": " + culprit->key) : header);
  v.values = readData(layout, count, *type,
                      layout.file == file ? data : data.at("data: " + layout.file.string()));
  return v;
}

// ---------------------------------------------------------------------------------------------
// NRRD (.nrrd with the data attached after a blank line, .nhdr naming a data file), after
// http://teem.sourceforge.net/nrrd/format.html: the fields that place and decode a 3-D
// volume; a 4-D one whose first axis has one sample (a "vector" of one value) reads as 3-D.

struct NrrdTypeName {
  const char* name;
  const VoxelType* type;  // nullptr: a type of the spec that is not read
};
constexpr NrrdTypeName kNrrdTypes[] = {
    {"signed char", &kI8},
    {"int8", &kI8},
    {"int8_t", &kI8},
    {"uchar", &kU8},
    {"unsigned char", &kU8},
    {"uint8", &kU8},
    {"uint8_t", &kU8},
    {"short", &kI16},
    {"short int", &kI16},
    {"signed short", &kI16},
    {"signed short int", &kI16},
    {"int16", &kI16},
    {"int16_t", &kI16},
    {"ushort", &kU16},
    {"unsigned short", &kU16},
    {"unsigned short int", &kU16},
    {"uint16", &kU16},
    {"uint16_t", &kU16},
    {"int", &kI32},
    {"signed int", &kI32},
    {"int32", &kI32},
    {"int32_t", &kI32},
    {"uint", &kU32},
    {"unsigned int", &kU32},
    {"uint32", &kU32},
    {"uint32_t", &kU32},
    {"float", &kF32},
    {"double", &kF64},
    {"longlong", nullptr},
    {"long long", nullptr},
    {"long long int", nullptr},
    {"signed long long", nullptr},
    {"signed long long int", nullptr},
    {"int64", nullptr},
    {"int64_t", nullptr},
    {"ulonglong", nullptr},
    {"unsigned long long", nullptr},
    {"unsigned long long int", nullptr},
    {"uint64", nullptr},
    {"uint64_t", nullptr},
    {"block", nullptr},
};

// The fields read, and those that do not change the voxels or their placement (the spec's
// alternative spellings without spaces included: names are compared without spaces).
constexpr const char* kNrrdFields[] = {
    "dimension", "type",           "sizes",           "encoding",    "endian",
    "space",     "spacedimension", "spacedirections", "spaceorigin", "spacings",
    "byteskip",  "lineskip",       "datafile"};
constexpr const char* kNrrdIgnoredFields[] = {
    "content", "number",     "blocksize", "min",         "max",         "oldmin",
    "oldmax",  "axismins",   "axismaxs",  "centers",     "centerings",  "labels",
    "units",   "spaceunits", "kinds",     "thicknesses", "sampleunits", "measurementframe"};

// The spaces of the spec, all 3-D but those with time.
constexpr const char* kNrrdSpaces[] = {"right-anterior-superior",
                                       "ras",
                                       "left-anterior-superior",
                                       "las",
                                       "left-posterior-superior",
                                       "lps",
                                       "scanner-xyz",
                                       "3d-right-handed",
                                       "3d-left-handed"};
constexpr const char* kNrrdTimeSpaces[] = {"right-anterior-superior-time",
                                           "rast",
                                           "left-anterior-superior-time",
                                           "last",
                                           "left-posterior-superior-time",
                                           "lpst",
                                           "scanner-xyz-time",
                                           "3d-right-handed-time",
                                           "3d-left-handed-time"};

// "(x,y,z)" vectors or "none", `n` of them.
std::vector<std::optional<glm::dvec3>> nrrdVectors(const std::string& text, std::size_t n,
                                                   const std::string& what, const Where& where) {
  const auto bad = [&] {
    where.fail(what + ": expected " + std::to_string(n) +
               (n == 1 ? " vector" : " vectors (or none)") + " of 3 finite numbers, got " +
               inQuotes(text));
  };
  std::vector<std::optional<glm::dvec3>> out;
  std::size_t i = 0;
  for (;;) {
    while (i < text.size() && isSpace(text[i])) ++i;
    if (i == text.size()) break;
    if (text.compare(i, 4, "none") == 0) {
      out.emplace_back(), i += 4;
      continue;
    }
    const std::size_t close = text.find(')', i);
    if (text[i] != '(' || close == std::string::npos) bad();
    std::string inner = text.substr(i + 1, close - i - 1);
    std::replace(inner.begin(), inner.end(), ',', ' ');
    const std::vector<std::string> w = words(inner);
    glm::dvec3 v(0.0);
    for (std::size_t a = 0; a < w.size() && a < 3; ++a) {
      const std::optional<double> x = toNumber(w[a]);
      if (!x || !std::isfinite(*x)) bad();
      v[int(a)] = *x;
    }
    if (w.size() != 3 || std::count(text.begin() + std::ptrdiff_t(i),
                                    text.begin() + std::ptrdiff_t(close), ',') != 2)
      bad();
    out.emplace_back(v), i = close + 1;
  }
  if (out.size() != n) bad();
  return out;
}

Volume loadNrrd(const fs::path& file, const VolumeLimits& limits) {
  const Where header{file.string(), "header"}, data{file.string(), "data"};
  HeaderLines lines(file, header);
  std::string line;
  if (!lines.next(line) || line.size() != 8 || !line.starts_with("NRRD000") || line[7] < '1' ||
      line[7] > '5')
    header.fail("not a NRRD file (no NRRD0001 to NRRD0005 magic line)");
  struct Field {
    std::string name, value;
    Where where;
  };
  std::map<std::string, Field> fields;  // by name without spaces
  bool blank = false;
  while (!blank && lines.next(line)) {
    if (trim(line).empty()) {
      blank = true;  // the end of the header; attached data follow
      continue;
    }
    if (line[0] == '#') continue;
    const std::size_t colon = line.find(": "), pair = line.find(":=");
    if (pair != std::string::npos && (colon == std::string::npos || pair < colon))
      continue;  // a key/value pair: free-form annotation
    std::string name, value;
    if (colon != std::string::npos)
      name = line.substr(0, colon), value = trim(line.substr(colon + 2));
    else if (line.back() == ':')
      name = line.substr(0, line.size() - 1);
    else
      lines.here().fail("expected \"field: description\", got " + inQuotes(line));
    std::string key = lower(name);
    key.erase(std::remove_if(key.begin(), key.end(), isSpace), key.end());
    const auto known = [&](const auto& list) {
      return std::any_of(std::begin(list), std::end(list), [&](const char* k) { return key == k; });
    };
    if (known(kNrrdIgnoredFields)) continue;
    if (!known(kNrrdFields)) lines.here().fail("unknown field " + inQuotes(name));
    if (fields.count(key)) lines.here().fail("field " + inQuotes(name) + " given twice");
    fields[key] = {name, value, lines.here()};
  }
  const auto get = [&](const char* key) -> const Field* {
    const auto it = fields.find(key);
    return it == fields.end() ? nullptr : &it->second;
  };
  const auto require = [&](const char* key, const char* name) -> const Field& {
    const Field* f = get(key);
    if (!f) header.fail(std::string("no \"") + name + "\" field");
    return *f;
  };

  const Field& dimension = require("dimension", "dimension");
  const std::int64_t dim = integer(dimension.value, "dimension", dimension.where);
  if (dim != 3 && dim != 4)
    dimension.where.fail("dimension is " + std::to_string(dim) +
                         ": only 3-D volumes (or 4-D with a first axis of size 1) are read");
  const std::size_t axes = std::size_t(dim), first = axes - 3;  // the first spatial axis
  const Field& sizes = require("sizes", "sizes");
  const std::vector<std::int64_t> size = integerList(sizes.value, axes, "sizes", sizes.where);
  if (dim == 4 && size[0] != 1)
    sizes.where.fail("a 4-D volume whose first axis has " + std::to_string(size[0]) +
                     " samples: only a first axis of size 1 is read");
  const std::size_t count = checkDims(size.data() + first, limits, sizes.where);

  const Field& typeField = require("type", "type");
  const std::string typeName = lower(trim(typeField.value));
  const NrrdTypeName* type = nullptr;
  for (const NrrdTypeName& t : kNrrdTypes)
    if (words(typeName) == words(t.name)) type = &t;
  if (!type) typeField.where.fail("unknown type " + inQuotes(typeField.value));
  if (!type->type) typeField.where.fail("unsupported type " + inQuotes(typeField.value));

  DataLayout layout;
  const Field& encoding = require("encoding", "encoding");
  const std::string enc = lower(encoding.value);
  if (enc == "raw")
    layout.encoding = Encoding::kRaw;
  else if (enc == "gzip" || enc == "gz")
    layout.encoding = Encoding::kDeflate;
  else if (enc == "ascii" || enc == "text" || enc == "txt")
    layout.encoding = Encoding::kAscii;
  else if (enc == "hex" || enc == "bzip2" || enc == "bz2" || enc == "zrl")
    encoding.where.fail("unsupported encoding " + inQuotes(encoding.value) +
                        " (raw, gzip and ascii are read)");
  else
    encoding.where.fail("unknown encoding " + inQuotes(encoding.value));
  if (const Field* f = get("endian")) {
    const std::string e = lower(f->value);
    if (e != "little" && e != "big")
      f->where.fail("endian: expected little or big, got " + inQuotes(f->value));
    layout.big = e == "big";
  } else if (type->type->bytes > 1 && layout.encoding != Encoding::kAscii) {
    header.fail("no \"endian\" field, needed for " + std::string(type->name) + " data");
  }

  // RAS and scanner coordinates are kept; LPS and LAS turn round (toRas).
  bool space = false, left = false, posterior = false;
  if (const Field* f = get("space")) {
    const std::string s = lower(f->value);
    left =
        s == "lps" || s == "left-posterior-superior" || s == "las" || s == "left-anterior-superior";
    posterior = s == "lps" || s == "left-posterior-superior";
    const auto in = [&](const auto& list) {
      return std::any_of(std::begin(list), std::end(list), [&](const char* k) { return s == k; });
    };
    if (in(kNrrdTimeSpaces))
      f->where.fail("space " + inQuotes(f->value) + " has time as a 4th axis: not read");
    if (!in(kNrrdSpaces)) f->where.fail("unknown space " + inQuotes(f->value));
    space = true;
  }
  if (const Field* f = get("spacedimension")) {
    if (const std::int64_t n = integer(f->value, f->name, f->where); n != 3)
      f->where.fail("space dimension is " + std::to_string(n) + ": only 3 is read");
    space = true;
  }

  glm::dmat4 m(1.0);
  Where placement = header;
  if (const Field* f = get("spacedirections")) {
    if (!space) f->where.fail("space directions without a \"space\" or \"space dimension\" field");
    const auto directions = nrrdVectors(f->value, axes, f->name, f->where);
    for (std::size_t a = 0; a < 3; ++a) {
      if (!directions[first + a])
        f->where.fail("axis " + std::to_string(first + a) + " of the volume has no direction");
      m[int(a)] = glm::dvec4(*directions[first + a], 0.0);
    }
    placement = f->where;
  } else if (const Field* f = get("spacings")) {
    const std::vector<std::string> w = words(f->value);
    if (w.size() != axes)
      f->where.fail("spacings: expected " + std::to_string(axes) + " numbers, got " +
                    inQuotes(f->value));
    for (std::size_t a = 0; a < 3; ++a) {
      const std::optional<double> x = toNumber(w[first + a]);
      if (!x || !std::isfinite(*x))
        f->where.fail("spacings: axis " + std::to_string(first + a) +
                      " needs a finite spacing, got " + inQuotes(w[first + a]));
      m[int(a)][int(a)] = *x;
    }
    placement = f->where;
  }
  if (const Field* f = get("spaceorigin")) {
    if (!space) f->where.fail("space origin without a \"space\" or \"space dimension\" field");
    m[3] = glm::dvec4(*nrrdVectors(f->value, 1, f->name, f->where)[0], 1.0);
  }

  if (const Field* f = get("lineskip")) {
    layout.lineSkip = integer(f->value, f->name, f->where);
    if (layout.lineSkip < 0) f->where.fail("line skip must not be negative");
  }
  if (const Field* f = get("byteskip")) {
    const std::int64_t skip = integer(f->value, f->name, f->where);
    if (skip < -1) f->where.fail("byte skip must be −1 (data at the end) or more");
    if (skip == -1 && layout.encoding != Encoding::kRaw)
      f->where.fail("byte skip −1 needs raw encoding");
    (layout.encoding == Encoding::kDeflate ? layout.inflatedSkip : layout.byteSkip) = skip;
  }
  if (const Field* f = get("datafile")) {
    layout.file = dataFile(file, f->value, f->where, f->name);
  } else {
    if (!blank) header.fail("no \"data file\" field and no blank line before attached data");
    layout.file = file;
    layout.offset = lines.offset();
  }

  Volume v;
  v.dims = glm::ivec3(int(size[first]), int(size[first + 1]), int(size[first + 2]));
  v.voxelType = type->type->name;
  v.indexToWorld = checkTransform(toRas(m, left, posterior), placement);
  v.values = readData(layout, count, *type->type,
                      layout.file == file ? data : data.at("data: " + layout.file.string()));
  return v;
}

// ---------------------------------------------------------------------------------------------
// VTK legacy files (.vtk) holding STRUCTURED_POINTS: the first point data array, which must
// be SCALARS of one component. BINARY data are big-endian.

constexpr TypeName kVtkTypes[] = {
    {"unsigned_char", &kU8}, {"char", &kI8}, {"unsigned_short", &kU16}, {"short", &kI16},
    {"unsigned_int", &kU32}, {"int", &kI32}, {"float", &kF32},          {"double", &kF64}};

Volume loadVtk(const fs::path& file, const VolumeLimits& limits) {
  const Where header{file.string(), "header"}, data{file.string(), "data"};
  HeaderLines lines(file, header);
  std::string line;
  if (!lines.next(line) || !line.starts_with("# vtk DataFile Version"))
    header.fail("not a VTK legacy file (no \"# vtk DataFile Version\" line)");
  if (!lines.next(line)) header.fail("truncated header: no title line");
  if (!lines.next(line)) header.fail("truncated header: no ASCII or BINARY line");
  const std::string format = upper(trim(line));
  if (format != "ASCII" && format != "BINARY")
    lines.here().fail("expected ASCII or BINARY, got " + inQuotes(line));

  std::vector<std::string> w;  // the next line's words, blank lines skipped
  const auto next = [&](const char* expected) {
    do
      if (!lines.next(line)) header.fail(std::string("truncated header: no ") + expected);
    while ((w = words(line)).empty());
    w[0] = upper(w[0]);
  };
  const auto arguments = [&](std::size_t n) {
    if (w.size() != n + 1)
      lines.here().fail(w[0] + ": expected " + std::to_string(n) + (n == 1 ? " value" : " values") +
                        ", got " + inQuotes(line));
    // The words after the keyword, split as words() splits (a carriage return counts: fuzzing).
    const std::string t = trim(line);
    std::size_t end = 0;
    while (end < t.size() && !isSpace(t[end])) ++end;
    return trim(std::string_view(t).substr(end));
  };

  next("DATASET");
  if (w[0] != "DATASET") lines.here().fail("expected DATASET, got " + inQuotes(line));
  const std::string dataset = upper(arguments(1));
  if (dataset != "STRUCTURED_POINTS")
    lines.here().fail("DATASET " + dataset + " is not read, only STRUCTURED_POINTS");
  std::optional<std::vector<std::int64_t>> dims;
  std::vector<double> spacing{1, 1, 1}, origin{0, 0, 0};
  Where placement = header;
  for (next("POINT_DATA"); w[0] != "POINT_DATA"; next("POINT_DATA")) {
    if (w[0] == "DIMENSIONS") {
      dims = integerList(arguments(3), 3, "DIMENSIONS", lines.here());
    } else if (w[0] == "SPACING" || w[0] == "ASPECT_RATIO") {
      spacing = numberList(arguments(3), 3, w[0], lines.here());
      placement = lines.here();
    } else if (w[0] == "ORIGIN") {
      origin = numberList(arguments(3), 3, "ORIGIN", lines.here());
    } else {
      lines.here().fail("unexpected " + inQuotes(w[0]) +
                        " (expected DIMENSIONS, SPACING, ORIGIN or POINT_DATA)");
    }
  }
  const Where pointData = lines.here();
  const std::int64_t points = integer(arguments(1), "POINT_DATA", pointData);
  if (!dims) header.fail("no DIMENSIONS line");
  const std::size_t count = checkDims(dims->data(), limits, header.at("DIMENSIONS"));
  if (points < 0 || std::uint64_t(points) != count)
    pointData.fail("POINT_DATA " + std::to_string(points) + " disagrees with DIMENSIONS " +
                   dimsText(dims->data()) + " = " + std::to_string(count));

  next("SCALARS");
  if (w[0] != "SCALARS")
    lines.here().fail("the first point data are " + inQuotes(w[0]) + ": only SCALARS are read");
  if (w.size() != 3 && w.size() != 4)
    lines.here().fail("SCALARS: expected a name, a type and an optional number of components");
  if (w.size() == 4 && w[3] != "1")
    lines.here().fail("SCALARS of " + w[3] + " components: only 1 is read");
  const VoxelType* type = nullptr;
  for (const auto& [name, t] : kVtkTypes)
    if (lower(w[2]) == name) type = t;
  if (!type)
    lines.here().fail("unsupported SCALARS type " + inQuotes(w[2]) +
                      " (expected unsigned_char, char, unsigned_short, short, unsigned_int, int, "
                      "float or double)");
  next("LOOKUP_TABLE");
  if (w[0] != "LOOKUP_TABLE" || w.size() != 2)
    lines.here().fail("expected \"LOOKUP_TABLE name\" after SCALARS, got " + inQuotes(line));

  DataLayout layout;
  layout.file = file;
  layout.offset = lines.offset();
  layout.encoding = format == "ASCII" ? Encoding::kAscii : Encoding::kRaw;
  layout.big = true;
  layout.exact = false;  // other arrays may follow, and VTK ends binary data with a newline

  Volume v;
  v.dims = glm::ivec3(int((*dims)[0]), int((*dims)[1]), int((*dims)[2]));
  v.voxelType = type->name;
  glm::dmat4 m(1.0);
  for (int a = 0; a < 3; ++a) m[a][a] = spacing[std::size_t(a)], m[3][a] = origin[std::size_t(a)];
  v.indexToWorld = checkTransform(m, placement);
  v.values = readData(layout, count, *type, data);
  return v;
}

// ---------------------------------------------------------------------------------------------
// DICOM series: a folder of single-frame images, read through GDCM.

std::string tagText(std::uint16_t group, std::uint16_t element) {
  char s[16];
  std::snprintf(s, sizeof s, "(%04X,%04X)", group, element);
  return s;
}

// GDCM allocates an element's claimed length before reading its value: a 1 KB file claiming
// 4 GB gets 4 GB. So the element structure is walked here first, each defined length checked
// against the bytes left in its file, item or sequence. (Part 5, §7: elements, sequences and
// items of defined or undefined length; encapsulated pixel data as fragments.)
class DicomWalker {
 public:
  DicomWalker(const fs::path& file, std::uint64_t size, const Where& where)
      : in_(file, std::ios::binary), size_(size), where_(where) {
    if (!in_) where.fail("cannot open for reading: " + std::string(std::strerror(errno)));
  }

  // The pixel data's length, when native (not encapsulated): GDCM, given less than the image
  // needs, pads it or asserts.
  std::optional<std::uint64_t> nativePixelData;
  bool encapsulated = false;

  // The file meta information (explicit VR little-endian) from byte 132, then the data set as
  // its transfer syntax says.
  void walk() {
    pos_ = 132;
    in_.seekg(std::streamoff(pos_));
    std::string syntax;
    std::uint64_t metaEnd = 0;
    while (pos_ + 4 <= size_ && peekGroup() == 0x0002) {
      const Element e = element(true, false);
      if (e.length == kUndefined) where_.fail("file meta information of undefined length");
      if (e.tag == 0x00020000u && e.length == 4) {
        const std::uint32_t groupLength = number(4, false);
        metaEnd = pos_ + groupLength;
      } else if (e.tag == 0x00020010u && e.length <= 64) {
        syntax.assign(e.length, '\0');
        read(syntax.data(), e.length);
        while (!syntax.empty() && (syntax.back() == '\0' || syntax.back() == ' '))
          syntax.pop_back();
      } else {
        skip(e.length, size_);
      }
    }
    // GDCM asserts on a file that ends within or right after its meta information.
    if (metaEnd > size_ || pos_ >= size_)
      where_.fail("truncated DICOM file: it ends within or right after its meta information");
    if (syntax == "1.2.840.10008.1.2.1.99")
      where_.fail("deflated data sets (transfer syntax " + syntax + ") are not read");
    explicit_ = syntax != "1.2.840.10008.1.2";
    big_ = syntax == "1.2.840.10008.1.2.2";
    elements(size_, false, 0);
  }

 private:
  static constexpr std::uint32_t kUndefined = 0xFFFFFFFFu;
  static constexpr std::uint32_t kItem = 0xFFFEE000u, kItemEnd = 0xFFFEE00Du,
                                 kSequenceEnd = 0xFFFEE0DDu, kPixelData = 0x7FE00010u,
                                 kRecognitionCode = 0x00080010u;
  struct Element {
    std::uint32_t tag, length;
    bool sequence;  // SQ, or UN / implicit of undefined length: items follow
  };

  void read(char* out, std::uint64_t n) {
    if (n > size_ - pos_ || !in_.read(out, std::streamsize(n)))
      where_.fail("truncated DICOM element at byte " + std::to_string(pos_));
    pos_ += n;
  }
  std::uint32_t number(int bytes, bool big) {
    unsigned char b[4];
    read(reinterpret_cast<char*>(b), std::uint64_t(bytes));
    std::uint32_t v = 0;
    for (int i = 0; i < bytes; ++i) v |= std::uint32_t(b[big ? bytes - 1 - i : i]) << (8 * i);
    return v;
  }
  std::uint16_t peekGroup() {
    unsigned char b[2];
    if (!in_.read(reinterpret_cast<char*>(b), 2)) where_.fail("read error");
    in_.seekg(std::streamoff(pos_));
    return std::uint16_t(big_ ? b[0] << 8 | b[1] : b[1] << 8 | b[0]);
  }
  // Fails unless `n` bytes are left before `end`.
  void bound(std::uint64_t n, std::uint64_t end) {
    if (n > end - pos_)
      where_.fail("DICOM element at byte " + std::to_string(pos_) + " claims " + std::to_string(n) +
                  " bytes, more than the " + std::to_string(end - pos_) + " left");
  }
  void skip(std::uint64_t n, std::uint64_t end) {
    bound(n, end);
    pos_ += n;
    in_.seekg(std::streamoff(pos_));
  }
  Element element(bool explicitVR, bool big) {
    const std::uint32_t group = number(2, big), elem = number(2, big);
    Element e{group << 16 | elem, 0, false};
    if (group == 0xFFFE) {  // items and delimiters: no VR, whatever the syntax
      e.length = number(4, big);
      return e;
    }
    if (!explicitVR) {
      e.length = number(4, big);
      e.sequence = e.length == kUndefined && e.tag != kPixelData;
      return e;
    }
    char vr[2];
    read(vr, 2);
    const std::string v(vr, 2);
    // GDCM asserts (aborts, in Debian's build) on a VR it does not know.
    static const char* const kVRs[] = {"AE", "AS", "AT", "CS", "DA", "DS", "DT", "FL", "FD",
                                       "IS", "LO", "LT", "OB", "OD", "OF", "OL", "OV", "OW",
                                       "PN", "SH", "SL", "SQ", "SS", "ST", "SV", "TM", "UC",
                                       "UI", "UL", "UN", "UR", "US", "UT", "UV"};
    if (std::none_of(std::begin(kVRs), std::end(kVRs), [&](const char* k) { return v == k; }))
      where_.fail("invalid VR " + inQuotes(v) + " at byte " + std::to_string(pos_ - 2));
    // And on a public tag of a VR its dictionary does not allow, when it reads the tag.
    if (group % 2 == 0 && v != "UN") {
      const gdcm::Tag tag{std::uint16_t(group), std::uint16_t(elem)};
      const gdcm::VR dictionary = gdcm::Global::GetInstance().GetDicts().GetDictEntry(tag).GetVR();
      if (dictionary != gdcm::VR::INVALID && dictionary != gdcm::VR::UN &&
          !dictionary.Compatible(gdcm::VR(gdcm::VR::GetVRType(v.c_str()))))
        where_.fail(tagText(std::uint16_t(group), std::uint16_t(elem)) + " has the VR " + v +
                    ", not the dictionary's " + gdcm::VR::GetVRString(dictionary));
    }
    static const char* const kLong[] = {"OB", "OD", "OF", "OL", "OV", "OW", "SQ",
                                        "SV", "UC", "UN", "UR", "UT", "UV"};
    if (std::any_of(std::begin(kLong), std::end(kLong), [&](const char* k) { return v == k; })) {
      number(2, big);
      e.length = number(4, big);
    } else {
      e.length = number(2, big);
    }
    e.sequence = v == "SQ" || (v == "UN" && e.length == kUndefined);
    return e;
  }
  // Elements until `end`, or until an item's end when `inItem` and of undefined length.
  void elements(std::uint64_t end, bool inItem, int depth) {
    if (depth > 32) where_.fail("DICOM sequences nested too deeply");
    while (pos_ < end) {
      const Element e = element(explicit_, big_);
      if (e.tag == kItemEnd && inItem) return;
      if (e.tag == kItem || e.tag == kItemEnd || e.tag == kSequenceEnd)
        where_.fail("misplaced DICOM item or delimiter at byte " + std::to_string(pos_ - 8));
      if (e.tag == kPixelData && depth == 0) {
        encapsulated = e.length == kUndefined;
        if (!encapsulated) nativePixelData = e.length;
      }
      // GDCM reads a Recognition Code as text and asserts (aborts) unless it is ACR-NEMA's.
      if (e.tag == kRecognitionCode && depth == 0 && e.length != 0) {
        if (e.sequence || e.length == kUndefined)
          where_.fail("(0008,0010) RecognitionCode is not a text value");
        bound(e.length, end);
        std::string code(std::min<std::uint32_t>(e.length, 8), '\0');
        read(code.data(), code.size());
        if (code.rfind("ACR-NEMA", 0) != 0 && code.rfind("ACRNEMA", 0) != 0)
          where_.fail("(0008,0010) RecognitionCode " + inQuotes(code) +
                      " is not ACR-NEMA's (\"ACR-NEMA\" or \"ACRNEMA\")");
        skip(e.length - code.size(), end);
        continue;
      }
      if (e.length == kUndefined) {
        if (e.sequence)
          items(end, depth + 1, false);
        else
          fragments(end);
      } else if (bound(e.length, end); e.sequence || (!explicit_ && startsWithItem(e.length))) {
        items(pos_ + e.length, depth + 1, true);
      } else {
        skip(e.length, end);
      }
    }
    if (inItem) where_.fail("a DICOM item without its end");
  }
  bool startsWithItem(std::uint32_t length) {
    if (length < 8) return false;
    const std::uint64_t at = pos_;
    const bool item = number(4, big_) == (big_ ? 0xFFFEE000u : 0xE000FFFEu);
    pos_ = at;
    in_.seekg(std::streamoff(pos_));
    return item;
  }
  // The items of a sequence, up to its delimiter, or to `end` when `defined`.
  void items(std::uint64_t end, int depth, bool defined) {
    if (depth > 32) where_.fail("DICOM sequences nested too deeply");
    while (!defined || pos_ < end) {
      const Element e = element(false, big_);
      if (e.tag == kSequenceEnd && !defined) return;
      if (e.tag != kItem) where_.fail("expected a DICOM item at byte " + std::to_string(pos_ - 8));
      if (e.length == kUndefined) {
        elements(end, true, depth + 1);
      } else {
        bound(e.length, end);
        elements(pos_ + e.length, false, depth + 1);
      }
    }
  }
  // Encapsulated pixel data: an offset table and fragments, each an item of defined length.
  void fragments(std::uint64_t end) {
    for (;;) {
      const Element e = element(false, big_);
      if (e.tag == kSequenceEnd) return;
      if (e.tag != kItem || e.length == kUndefined)
        where_.fail("expected a pixel data fragment at byte " + std::to_string(pos_ - 8));
      skip(e.length, end);
    }
  }

  std::ifstream in_;
  std::uint64_t size_, pos_ = 0;
  Where where_;
  bool explicit_ = true, big_ = false;
};

// Part 10 files begin with a 128-byte preamble and "DICM".
bool isDicomFile(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  char b[132];
  return in.read(b, 132) && std::memcmp(b + 128, "DICM", 4) == 0;
}

struct DicomSlice {
  std::string file, series;
  std::int64_t rows = 0, columns = 0;
  glm::dvec3 row{0.0}, column{0.0};  // ImageOrientationPatient: along a row, down a column
  glm::dvec3 position{0.0};          // ImagePositionPatient: the first pixel's centre
  glm::dvec2 pixelSpacing{0.0};      // PixelSpacing: between rows, between columns
  Scaling scaling;
  double along = 0.0;  // the position along the slice normal
};

// A DICOM tag, its name and where its value is bad.
struct DicomTag {
  std::uint16_t group, element;
  const char* name;
  Where at(const std::string& file) const { return {file, tagText(group, element) + " " + name}; }
};
constexpr DicomTag kSeriesUid{0x0020, 0x000E, "SeriesInstanceUID"},
    kPosition{0x0020, 0x0032, "ImagePositionPatient"},
    kOrientation{0x0020, 0x0037, "ImageOrientationPatient"},
    kSamples{0x0028, 0x0002, "SamplesPerPixel"}, kFrames{0x0028, 0x0008, "NumberOfFrames"},
    kRows{0x0028, 0x0010, "Rows"}, kColumns{0x0028, 0x0011, "Columns"},
    kSpacing{0x0028, 0x0030, "PixelSpacing"}, kIntercept{0x0028, 0x1052, "RescaleIntercept"},
    kSlope{0x0028, 0x1053, "RescaleSlope"},
    kPhotometric{0x0028, 0x0004, "PhotometricInterpretation"},
    kBitsAllocated{0x0028, 0x0100, "BitsAllocated"}, kBitsStored{0x0028, 0x0101, "BitsStored"},
    kHighBit{0x0028, 0x0102, "HighBit"},
    kPixelRepresentation{0x0028, 0x0103, "PixelRepresentation"},
    kPixelData{0x7FE0, 0x0010, "PixelData"};

const gdcm::ByteValue* dicomValue(const gdcm::DataSet& ds, const DicomTag& t) {
  const gdcm::Tag tag(t.group, t.element);
  return ds.FindDataElement(tag) ? ds.GetDataElement(tag).GetByteValue() : nullptr;
}

// A text value (UI, CS, DS, IS) without its padding; nullopt when absent or empty.
std::optional<std::string> dicomText(const gdcm::DataSet& ds, const DicomTag& t) {
  const gdcm::ByteValue* v = dicomValue(ds, t);
  if (!v || !v->GetPointer()) return std::nullopt;
  std::string s(v->GetPointer(), std::min<std::size_t>(v->GetLength(), 1024));
  std::replace(s.begin(), s.end(), '\0', ' ');
  s = trim(s);
  return s.empty() ? std::nullopt : std::optional(s);
}

// A US value: two bytes, little-endian as GDCM holds it in memory.
std::optional<std::int64_t> dicomUs(const gdcm::DataSet& ds, const DicomTag& t,
                                    const std::string& file) {
  const gdcm::ByteValue* v = dicomValue(ds, t);
  if (!v) return std::nullopt;
  if (v->GetLength() != 2 || !v->GetPointer()) t.at(file).fail("expected one US value");
  const auto* b = reinterpret_cast<const unsigned char*>(v->GetPointer());
  return std::int64_t(b[0] | b[1] << 8);
}

// Decimal strings separated by backslashes, exactly `n` of them.
std::vector<double> dicomNumbers(const gdcm::DataSet& ds, const DicomTag& t, std::size_t n,
                                 const std::string& file) {
  const std::optional<std::string> s = dicomText(ds, t);
  if (!s) t.at(file).fail("missing");
  std::string spaced = *s;
  std::replace(spaced.begin(), spaced.end(), '\\', ' ');
  return numberList(spaced, n, "", t.at(file));
}

// The slice's header, or nullopt when the file is no image (a DICOMDIR, a report).
std::optional<DicomSlice> readDicomHeader(const fs::path& path, const std::string& file) {
  const Where where{file, ""};
  DicomWalker walker(path, fileSize(path, where), where);
  walker.walk();
  gdcm::Reader reader;
  reader.SetFileName(path.c_str());
  const gdcm::Tag pixelData(0x7FE0, 0x0010);
  bool read = false;
  try {
    read = reader.ReadUpToTag(pixelData, {pixelData});
  } catch (const std::exception& e) {
    where.fail(std::string("GDCM cannot read the file: ") + e.what());
  }
  if (!read) where.fail("GDCM cannot read the file");
  const gdcm::DataSet& ds = reader.GetFile().GetDataSet();
  if (!ds.FindDataElement(gdcm::Tag(kRows.group, kRows.element))) return std::nullopt;

  DicomSlice s;
  s.file = file;
  s.series = dicomText(ds, kSeriesUid).value_or("(none)");
  if (const auto frames = dicomText(ds, kFrames))
    if (const auto n = toInteger(*frames); !n || *n != 1)
      kFrames.at(file).fail(inQuotes(*frames) + " frames: only single-frame images are read");
  const auto rows = dicomUs(ds, kRows, file), columns = dicomUs(ds, kColumns, file);
  if (!rows) kRows.at(file).fail("empty");
  if (!columns) kColumns.at(file).fail("missing");
  s.rows = *rows, s.columns = *columns;

  // The image pixel module as PS3.3 C.7.6.3 has it for grey-scale images. GDCM asserts on
  // some other combinations (a palette without its tables, one bit allocated, …).
  const auto us = [&](const DicomTag& t) {
    const std::optional<std::int64_t> v = dicomUs(ds, t, file);
    if (!v) t.at(file).fail("missing");
    return *v;
  };
  if (const std::int64_t samples = us(kSamples); samples != 1)
    kSamples.at(file).fail(std::to_string(samples) + ": only grey-scale images are read");
  const std::string photometric = dicomText(ds, kPhotometric).value_or("");
  if (photometric != "MONOCHROME1" && photometric != "MONOCHROME2")
    kPhotometric.at(file).fail(inQuotes(photometric) +
                               ": only MONOCHROME1 and MONOCHROME2 images are read");
  const std::int64_t allocated = us(kBitsAllocated), stored = us(kBitsStored),
                     highBit = us(kHighBit), representation = us(kPixelRepresentation);
  if (allocated != 8 && allocated != 16 && allocated != 32)
    kBitsAllocated.at(file).fail(std::to_string(allocated) + ": 8, 16 or 32 are read");
  if (stored < 1 || stored > allocated)
    kBitsStored.at(file).fail(std::to_string(stored) + " of " + std::to_string(allocated) +
                              " bits allocated");
  if (highBit != stored - 1)
    kHighBit.at(file).fail(std::to_string(highBit) +
                           ", not BitsStored − 1 = " + std::to_string(stored - 1));
  if (representation != 0 && representation != 1)
    kPixelRepresentation.at(file).fail(std::to_string(representation) + ", not 0 or 1");
  if (!walker.encapsulated) {
    const std::uint64_t needed =
        std::uint64_t(s.rows) * std::uint64_t(s.columns) * std::uint64_t(allocated / 8);
    if (!walker.nativePixelData) kPixelData.at(file).fail("missing");
    if (*walker.nativePixelData < needed)
      kPixelData.at(file).fail(std::to_string(*walker.nativePixelData) + " bytes, " +
                               std::to_string(s.columns) + "×" + std::to_string(s.rows) +
                               " pixels need " + std::to_string(needed));
  }
  const std::vector<double> o = dicomNumbers(ds, kOrientation, 6, file);
  s.row = {o[0], o[1], o[2]}, s.column = {o[3], o[4], o[5]};
  if (std::abs(glm::length(s.row) - 1.0) > 1e-3 || std::abs(glm::length(s.column) - 1.0) > 1e-3 ||
      std::abs(glm::dot(s.row, s.column)) > 1e-3)
    kOrientation.at(file).fail("not two orthogonal unit vectors");
  const std::vector<double> p = dicomNumbers(ds, kPosition, 3, file);
  s.position = {p[0], p[1], p[2]};
  const std::vector<double> ps = dicomNumbers(ds, kSpacing, 2, file);
  if (!(ps[0] > 0.0 && ps[1] > 0.0)) kSpacing.at(file).fail("not positive");
  s.pixelSpacing = {ps[0], ps[1]};
  // The two come as a pair (PS3.3 C.11.1, Modality LUT); GDCM asserts (aborts) on a slope of
  // 0, which also makes every value the intercept, and on an MR image's intercept without its
  // slope (fuzzing).
  if (dicomText(ds, kIntercept) && !dicomText(ds, kSlope))
    kSlope.at(file).fail("missing beside (0028,1052) RescaleIntercept");
  if (dicomText(ds, kSlope)) s.scaling.slope = dicomNumbers(ds, kSlope, 1, file)[0];
  if (s.scaling.slope == 0.0) kSlope.at(file).fail("is 0");
  if (dicomText(ds, kIntercept)) s.scaling.inter = dicomNumbers(ds, kIntercept, 1, file)[0];
  return s;
}

const VoxelType* dicomVoxelType(const gdcm::PixelFormat& pf) {
  switch (pf.GetScalarType()) {
    case gdcm::PixelFormat::UINT8:
      return &kU8;
    case gdcm::PixelFormat::INT8:
      return &kI8;
    case gdcm::PixelFormat::UINT16:
      return &kU16;
    case gdcm::PixelFormat::INT16:
      return &kI16;
    case gdcm::PixelFormat::UINT32:
      return &kU32;
    case gdcm::PixelFormat::INT32:
      return &kI32;
    case gdcm::PixelFormat::FLOAT32:
      return &kF32;
    case gdcm::PixelFormat::FLOAT64:
      return &kF64;
    default:
      return nullptr;
  }
}

// Reads slice `s`'s pixels into `out` (rows·columns values), rescaled.
const VoxelType& readDicomPixels(const DicomSlice& s, float* out) {
  const Where where{s.file, "(7FE0,0010) PixelData"};
  gdcm::ImageReader reader;
  reader.SetFileName(s.file.c_str());
  bool read = false;
  try {
    read = reader.Read();
  } catch (const std::exception& e) {
    where.fail(std::string("GDCM cannot read the image: ") + e.what());
  }
  if (!read) where.fail("GDCM cannot read the image");
  const gdcm::Image& image = reader.GetImage();
  if (std::int64_t(image.GetColumns()) != s.columns || std::int64_t(image.GetRows()) != s.rows ||
      (image.GetNumberOfDimensions() == 3 && image.GetDimension(2) != 1))
    where.fail("GDCM sees an image of another size than Rows and Columns say");
  const gdcm::PixelFormat& pf = image.GetPixelFormat();
  const VoxelType* type = dicomVoxelType(pf);
  if (pf.GetSamplesPerPixel() != 1 || !type)
    where.fail(std::string("unsupported pixel format ") + pf.GetScalarTypeAsString() + " × " +
               std::to_string(pf.GetSamplesPerPixel()) + " samples");
  const std::size_t n = std::size_t(s.rows) * std::size_t(s.columns);
  if (image.GetBufferLength() != n * std::size_t(type->bytes))
    where.fail("pixel data of " + std::to_string(image.GetBufferLength()) + " bytes, expected " +
               std::to_string(n * std::size_t(type->bytes)));
  std::vector<unsigned char> buffer(n * std::size_t(type->bytes));
  if (!image.GetBuffer(reinterpret_cast<char*>(buffer.data())))
    where.fail("GDCM cannot decode the pixel data");
  convert(*type, buffer.data(), n, false, s.scaling, out);  // GDCM hands native byte order
  return *type;
}

Volume loadDicomSeries(const fs::path& folder, const VolumeLimits& limits) {
  const Where where{folder.string(), ""};
  // GDCM reports on stderr what is reported here by throwing.
  gdcm::Trace::WarningOff();
  gdcm::Trace::ErrorOff();
  gdcm::Trace::DebugOff();

  std::vector<fs::path> files;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
    if (std::error_code e; it->is_regular_file(e)) files.push_back(it->path());
  if (ec) where.fail("cannot list the folder: " + ec.message());
  std::sort(files.begin(), files.end());
  std::vector<DicomSlice> slices;
  for (const fs::path& f : files)
    if (isDicomFile(f))
      if (std::optional<DicomSlice> s = readDicomHeader(f, f.string())) slices.push_back(*s);
  if (slices.empty())
    where.fail("no DICOM images in the folder (" + std::to_string(files.size()) + " files)");

  std::map<std::string, int> series;
  for (const DicomSlice& s : slices) ++series[s.series];
  if (series.size() > 1) {
    std::string list;
    for (const auto& [uid, n] : series)
      list += (list.empty() ? "" : ", ") + uid + " (" + std::to_string(n) +
              (n == 1 ? " image)" : " images)");
    where.fail(std::to_string(series.size()) + " series in the folder, one expected: " + list);
  }

  const DicomSlice& first = slices.front();
  const glm::dvec3 normal = glm::cross(first.row, first.column);
  for (DicomSlice& s : slices) {
    if (s.rows != first.rows || s.columns != first.columns)
      where.fail("images of different sizes: " + std::to_string(first.columns) + "×" +
                 std::to_string(first.rows) + " in " + first.file + ", " +
                 std::to_string(s.columns) + "×" + std::to_string(s.rows) + " in " + s.file);
    if (glm::length(s.row - first.row) > 1e-4 || glm::length(s.column - first.column) > 1e-4)
      where.fail("images of different orientations: " + first.file + " and " + s.file);
    if (glm::length(s.pixelSpacing - first.pixelSpacing) > 1e-4 * glm::length(first.pixelSpacing))
      where.fail("images of different pixel spacings: " + first.file + " and " + s.file);
    s.along = glm::dot(s.position, normal);
  }
  std::stable_sort(slices.begin(), slices.end(),
                   [](const DicomSlice& a, const DicomSlice& b) { return a.along < b.along; });

  // The slices must be evenly spaced: a gap several steps wide is a missing slice.
  const std::size_t n = slices.size();
  double step = std::numeric_limits<double>::infinity();
  for (std::size_t k = 1; k < n; ++k) {
    const double d = slices[k].along - slices[k - 1].along;
    if (d < 1e-4)
      where.fail("two images at the same position, " + mm(slices[k].along) +
                 " along the normal: " + slices[k - 1].file + " and " + slices[k].file);
    step = std::min(step, d);
  }
  for (std::size_t k = 1; k < n; ++k) {
    const double d = slices[k].along - slices[k - 1].along;
    if (d - step <= 0.01 * step) continue;
    const double ratio = d / step;
    const std::string between = " between " + slices[k - 1].file + " and " + slices[k].file +
                                " (at " + mm(slices[k - 1].along) + " and " + mm(slices[k].along) +
                                " along the normal)";
    if (ratio < 1000 && std::abs(ratio - std::round(ratio)) <= 0.01 * ratio)
      where.fail("a gap of " + mm(d) + between + ", the step elsewhere " + mm(step) + ": " +
                 std::to_string(int(std::round(ratio)) - 1) + " slice(s) missing");
    where.fail("uneven slice spacing: " + mm(d) + between + ", " + mm(step) + " elsewhere");
  }
  // Slices of a tilted gantry step sideways too: k's direction goes from the first to the last.
  const glm::dvec3 k = n > 1 ? (slices.back().position - first.position) / double(n - 1)
                             : normal;  // one slice: a unit thickness
  for (std::size_t i = 0; i < n; ++i)
    if (glm::length(slices[i].position - (slices.front().position + double(i) * k)) >
        0.01 * glm::length(k))
      where.fail("the image positions do not lie on a line: " + slices[i].file);

  const std::int64_t d[3] = {first.columns, first.rows, std::int64_t(n)};
  const std::size_t count = checkDims(d, limits, where);
  Volume v;
  v.dims = glm::ivec3(int(d[0]), int(d[1]), int(d[2]));
  // i runs along a row (columns apart), j down a column (rows apart).
  glm::dmat4 m(1.0);
  m[0] = glm::dvec4(first.row * first.pixelSpacing[1], 0.0);
  m[1] = glm::dvec4(first.column * first.pixelSpacing[0], 0.0);
  m[2] = glm::dvec4(k, 0.0);
  m[3] = glm::dvec4(slices.front().position, 1.0);
  v.indexToWorld = checkTransform(toRas(m, true, true), where);
  v.values.resize(count);
  const std::size_t perSlice = std::size_t(first.rows) * std::size_t(first.columns);
  for (std::size_t i = 0; i < n; ++i) {
    const VoxelType& type = readDicomPixels(slices[i], v.values.data() + i * perSlice);
    if (i == 0) v.voxelType = type.name;
    if (v.voxelType != type.name)
      where.fail("images of different pixel types: " + v.voxelType + " in " + slices.front().file +
                 ", " + type.name + " in " + slices[i].file);
  }
  return v;
}

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// `v` with its range; refused when no voxel holds a number (NaN marks missing data, and ±inf
// no colour), as there would be nothing to show.
Volume withValues(Volume v, const Where& where) {
  if (!v.updateRange())
    where.fail(
        "no voxel holds a finite value as a 32-bit float (all are NaN, infinite, or beyond "
        "±3.4e38)");
  return v;
}

}  // namespace

// GDCM is the one third-party reader among the volumes': a series is read in a worker, as
// Assimp and GDAL read theirs (cutaway/core/contained.hpp). Its data dictionary is loaded
// once, by the helper the workers are forked from.
const bool kDicomDictionaryWarm =
    registerContainedWarmUp([] { (void)gdcm::Global::GetInstance().GetDicts(); });
const ContainedReader<Volume, &loadDicomSeries, VolumeLimits> containedDicomSeries(
    "dicom-series", "the DICOM reader");

Volume volumeFromMemory(const MemoryVoxels& voxels, const std::string& source,
                        const std::string& place, const VolumeLimits& limits) {
  const Where where{source, place};
  const VoxelType* type = findVoxelType(voxels.kind, voxels.bytes);
  if (!type)
    where.fail("unsupported voxel type '" + std::string(1, voxels.kind) +
               std::to_string(8 * voxels.bytes) +
               "' (expected unsigned or signed integers of 8, 16 or 32 bits, or floats of 32 or "
               "64 bits)");
  const std::size_t count = checkDims(voxels.dims, limits, where);
  const glm::dmat4& m = voxels.indexToWorld;
  if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0)
    where.fail("the voxel-to-world transform's last row is not 0 0 0 1 (an affine map)");
  Volume v;
  v.indexToWorld = checkTransform(m, where);
  v.dims = glm::ivec3(int(voxels.dims[0]), int(voxels.dims[1]), int(voxels.dims[2]));
  v.voxelType = type->name;
  v.values.resize(count);
  const auto* base = static_cast<const unsigned char*>(voxels.data);
  const std::int64_t* s = voxels.strides;
  const bool rows = s[0] == type->bytes;  // a row along i converts in one call
  float* out = v.values.data();
  for (std::int64_t k = 0; k < voxels.dims[2]; ++k)
    for (std::int64_t j = 0; j < voxels.dims[1]; ++j) {
      const unsigned char* row = base + j * s[1] + k * s[2];
      if (rows) {
        convert(*type, row, std::size_t(voxels.dims[0]), voxels.swapped, {}, out);
        out += voxels.dims[0];
      } else {
        for (std::int64_t i = 0; i < voxels.dims[0]; ++i)
          convert(*type, row + i * s[0], 1, voxels.swapped, {}, out++);
      }
    }
  return withValues(std::move(v), where);
}

Volume importVolume(const std::filesystem::path& file) {
  return importVolume(file, {});
}

Volume importVolume(const std::filesystem::path& file, const VolumeLimits& limits) {
  std::error_code ec;
  if (fs::is_directory(file, ec))
    return withValues(containedDicomSeries(file, limits), {file.string(), ""});
  std::string name = file.filename().string();
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  static constexpr std::pair<const char*, Volume (*)(const fs::path&, const VolumeLimits&)>
      kReaders[] = {{".nii", loadNifti},     {".nii.gz", loadNifti},  {".npy", loadNpy},
                    {".npz", loadNpz},       {".den", loadDen},       {".json", loadRawJson},
                    {".mha", loadMetaImage}, {".mhd", loadMetaImage}, {".nrrd", loadNrrd},
                    {".nhdr", loadNrrd},     {".vtk", loadVtk}};
  Volume (*reader)(const fs::path&, const VolumeLimits&) = nullptr;
  for (const auto& [suffix, r] : kReaders)
    if (endsWith(name, suffix)) reader = r;
  if (!reader)
    throw Error(file.string(), "",
                "unknown volume format (expected .nii, .nii.gz, .npy, .npz, .den, .json, .mha, "
                ".mhd, .nrrd, .nhdr, .vtk or a folder of DICOM images)");
  if (!fs::is_regular_file(file, ec))
    throw Error(
        file.string(), "",
        fs::exists(file, ec) ? "volume file is not a regular file" : "volume file not found");
  return withValues(reader(file, limits), {file.string(), ""});
}

}  // namespace cutaway
