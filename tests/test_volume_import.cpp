// Volume import: three real files checked against numbers read independently with Python,
// NIfTI-1 and NIfTI-2 written here byte by byte (sform, qform, pixdim, scaling, byte order, a
// 4-D series), raw voxels with a JSON header in every type and both byte orders, .npy in C
// and Fortran order, .npz archives written through libzip, .den files, and every bad input.
#include <gtest/gtest.h>
#include <unistd.h>
#include <zip.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "cutaway/core/error.hpp"
#include "cutaway/io/volume_import.hpp"
#include "expect_error.hpp"

namespace fs = std::filesystem;
using namespace cutaway;

using test::expectError;

namespace {

// Debian packages mricron-data, python3-imageio and libvolpack1-dev.
const fs::path kCh2 = "/usr/share/mricron/templates/ch2.nii.gz";
const fs::path kStent = "/usr/lib/python3/dist-packages/imageio/resources/images/stent.npz";
const fs::path kBrain = "/usr/share/doc/libvolpack1-dev/examples/brainsmall.den";

// Writes `v` at byte `at` of `b` (growing it) in little- or big-endian order.
template <typename T>
void putAt(std::string& b, std::size_t at, T v, bool big = false) {
  char raw[sizeof(T)];
  std::memcpy(raw, &v, sizeof(T));
  if (big != (std::endian::native == std::endian::big)) std::reverse(raw, raw + sizeof(T));
  if (b.size() < at + sizeof(T)) b.resize(at + sizeof(T), '\0');
  std::memcpy(b.data() + at, raw, sizeof(T));
}

template <typename T>
std::string encode(const std::vector<T>& values, bool big = false) {
  std::string b;
  for (const T v : values) putAt(b, b.size(), v, big);
  return b;
}

// value(i, j, k) for a volume whose i varies fastest.
template <typename T, typename F>
std::vector<T> fill(glm::ivec3 dims, F value) {
  std::vector<T> out;
  for (int k = 0; k < dims.z; ++k)
    for (int j = 0; j < dims.y; ++j)
      for (int i = 0; i < dims.x; ++i) out.push_back(T(value(i, j, k)));
  return out;
}

glm::vec3 world(const Volume& v, glm::vec3 ijk) {
  return glm::vec3(v.indexToWorld * glm::vec4(ijk, 1.0f));
}

// A single-file NIfTI-1 image (348-byte header, 4 bytes of empty extension flags, voxels).
struct Nifti1 {
  std::int16_t dim[8] = {3, 2, 3, 4, 1, 1, 1, 1};
  std::int16_t datatype = 4, bitpix = 16;  // DT_INT16
  float pixdim[8] = {1, 1, 1, 1, 0, 0, 0, 0};
  float slope = 0, inter = 0;
  std::int16_t qformCode = 0, sformCode = 0;
  float quatern[3] = {0, 0, 0}, qoffset[3] = {0, 0, 0};
  float srow[3][4] = {};
  bool big = false;

  std::string bytes(const std::string& voxels) const {
    std::string b;
    putAt<std::int32_t>(b, 0, 348, big);
    for (int i = 0; i < 8; ++i) putAt(b, 40 + 2 * i, dim[i], big);
    putAt(b, 70, datatype, big);
    putAt(b, 72, bitpix, big);
    for (int i = 0; i < 8; ++i) putAt(b, 76 + 4 * i, pixdim[i], big);
    putAt(b, 108, 352.0f, big);  // vox_offset
    putAt(b, 112, slope, big);
    putAt(b, 116, inter, big);
    putAt(b, 252, qformCode, big);
    putAt(b, 254, sformCode, big);
    for (int i = 0; i < 3; ++i) putAt(b, 256 + 4 * i, quatern[i], big);
    for (int i = 0; i < 3; ++i) putAt(b, 268 + 4 * i, qoffset[i], big);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) putAt(b, 280 + 16 * r + 4 * c, srow[r][c], big);
    b.resize(352, '\0');
    b.replace(344, 4, std::string("n+1\0", 4));
    return b + voxels;
  }
};

// A single-file NIfTI-2 image (540-byte header, 4 bytes of extension flags, voxels); the
// offsets are those of nifti_2_header in nifti2.h.
struct Nifti2 {
  std::int64_t dim[8] = {3, 3, 2, 2, 1, 1, 1, 1};
  std::int16_t datatype = 64, bitpix = 64;  // DT_FLOAT64
  double pixdim[8] = {1, 1, 1, 1, 0, 0, 0, 0};
  double slope = 0, inter = 0;
  std::int32_t qformCode = 0, sformCode = 0;
  double srow[3][4] = {};

  std::string bytes(const std::string& voxels) const {
    std::string b;
    putAt<std::int32_t>(b, 0, 540);
    b.replace(4, 8, std::string("n+2\0\r\n\032\n", 8));
    putAt(b, 12, datatype);
    putAt(b, 14, bitpix);
    for (int i = 0; i < 8; ++i) putAt(b, 16 + 8 * i, dim[i]);
    for (int i = 0; i < 8; ++i) putAt(b, 104 + 8 * i, pixdim[i]);
    putAt<std::int64_t>(b, 168, 544);  // vox_offset
    putAt(b, 176, slope);
    putAt(b, 184, inter);
    putAt(b, 344, qformCode);
    putAt(b, 348, sformCode);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) putAt(b, 400 + 32 * r + 8 * c, srow[r][c]);
    b.resize(544, '\0');
    return b + voxels;
  }
};

// A VolPack .den file as denfile.c's write_den writes it, in either byte order.
std::string den(glm::ivec3 dims, const std::string& voxels, bool big = false,
                std::int32_t mapLength = -1) {
  std::string b;
  putAt<std::int16_t>(b, 0, 1, big);  // map_version
  const std::int16_t len[3] = {std::int16_t(dims.x), std::int16_t(dims.y), std::int16_t(dims.z)};
  for (int group = 0; group < 3; ++group) {  // orig, extr, map: min, max, len
    for (int a = 0; a < 3; ++a) putAt<std::int16_t>(b, b.size(), 0, big);
    for (int a = 0; a < 3; ++a) putAt<std::int16_t>(b, b.size(), std::int16_t(len[a] - 1), big);
    for (int a = 0; a < 3; ++a) putAt<std::int16_t>(b, b.size(), len[a], big);
  }
  putAt<std::int16_t>(b, b.size(), 0, big);  // map_warps
  putAt<std::int32_t>(b, b.size(), mapLength >= 0 ? mapLength : dims.x * dims.y * dims.z, big);
  return b + voxels;
}

// An .npy file: the header dict padded with spaces so that the data starts at a multiple of 64.
std::string npy(const std::string& dict, const std::string& voxels, int major = 1) {
  const std::size_t prefix = major == 1 ? 10 : 12;
  std::string header = dict;
  while ((prefix + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  std::string b = "\x93NUMPY";
  b += char(major);
  b += '\0';
  if (major == 1)
    putAt<std::uint16_t>(b, b.size(), std::uint16_t(header.size()));
  else
    putAt<std::uint32_t>(b, b.size(), std::uint32_t(header.size()));
  return b + header + voxels;
}

std::string npyDict(const std::string& descr, const std::string& shape, bool fortran = false) {
  return "{'descr': '" + descr + "', 'fortran_order': " + (fortran ? "True" : "False") +
         ", 'shape': " + shape + ", }";
}

class VolumeImportTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("cutaway-volume-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& name, const std::string& bytes) {
    const fs::path file = dir_ / name;
    std::ofstream(file, std::ios::binary) << bytes;
    return file;
  }

  // The first `n` bytes of `source`, as `name`.
  fs::path truncatedCopy(const fs::path& source, const std::string& name, std::size_t n) {
    std::ifstream in(source, std::ios::binary);
    std::string bytes(n, '\0');
    in.read(bytes.data(), std::streamsize(n));
    bytes.resize(std::size_t(in.gcount()));
    return write(name, bytes);
  }

  // A raw file and its JSON header; `extra` adds keys to the JSON.
  fs::path raw(const std::string& type, const std::string& dims, const std::string& voxels,
               const std::string& extra = "") {
    write("volume.raw", voxels);
    return write("volume.json", R"({"file": "volume.raw", "dims": )" + dims + R"(, "type": ")" +
                                    type + "\"" + extra + "}");
  }

  // An .npz archive with the given members, deflated unless `store`.
  fs::path npz(const std::string& name,
               const std::vector<std::pair<std::string, std::string>>& members,
               bool store = false) {
    const fs::path file = dir_ / name;
    int error = 0;
    zip_t* z = zip_open(file.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
    EXPECT_NE(z, nullptr);
    for (const auto& [member, bytes] : members) {
      zip_source_t* s = zip_source_buffer(z, bytes.data(), bytes.size(), 0);
      const zip_int64_t index = zip_file_add(z, member.c_str(), s, ZIP_FL_OVERWRITE);
      EXPECT_GE(index, 0);
      zip_set_file_compression(z, zip_uint64_t(index), store ? ZIP_CM_STORE : ZIP_CM_DEFLATE, 0);
    }
    EXPECT_EQ(zip_close(z), 0);  // the buffers are read here, while `members` lives
    return file;
  }

  // Raw volumes of `type` holding `values` as 3×2×1 voxels, in both byte orders.
  template <typename T>
  void expectRawType(const std::string& type, const std::vector<T>& values) {
    for (const bool big : {false, true}) {
      SCOPED_TRACE(type + (big ? " big-endian" : " little-endian"));
      const Volume v =
          importVolume(raw(type, "[3, 2, 1]", encode(values, big),
                           big ? R"(, "endianness": "big")" : R"(, "endianness": "little")"));
      EXPECT_EQ(v.dims, glm::ivec3(3, 2, 1));
      EXPECT_EQ(v.voxelType, type);
      ASSERT_EQ(v.values.size(), values.size());
      for (std::size_t i = 0; i < values.size(); ++i) EXPECT_EQ(v.values[i], float(values[i])) << i;
    }
  }

  fs::path dir_;
};

// A NIfTI-1 i16 image of 2×3×4 voxels holding i + 10j + 100k − 50.
const glm::ivec3 kSmall{2, 3, 4};
int smallValue(int i, int j, int k) {
  return i + 10 * j + 100 * k - 50;
}

}  // namespace

// ----------------------------------------------------------------------------------------------
// Real files

TEST_F(VolumeImportTest, Ch2TemplateNiftiGz) {
  const Volume v = importVolume(kCh2);
  EXPECT_EQ(v.dims, glm::ivec3(181, 217, 181));
  EXPECT_EQ(v.voxelType, "u8");
  EXPECT_EQ(v.values.size(), 181u * 217u * 181u);
  // The header read independently with Python:
  //   h = gzip.open(ch2.nii.gz).read(352); struct.unpack('<hh', h[252:256]) → qform_code 0,
  //   sform_code 4 (MNI-152); srow_x/y/z = struct.unpack('<4f', h[280 + 16·r:296 + 16·r]) →
  //   (1, 0, 0, −90), (0, 1, 0, −125), (0, 0, 1, −71); pixdim[1..3] = 1, 1, 1.
  // So the sform: 1 mm axes along RAS+, voxel (90, 125, 71) at the MNI origin.
  const glm::mat4 expected(glm::vec4(1, 0, 0, 0), glm::vec4(0, 1, 0, 0), glm::vec4(0, 0, 1, 0),
                           glm::vec4(-90, -125, -71, 1));
  EXPECT_EQ(v.indexToWorld, expected);
  EXPECT_EQ(v.spacing(), glm::vec3(1.0f));
  EXPECT_EQ(world(v, {90, 125, 71}), glm::vec3(0.0f));
  // Voxels: numpy.frombuffer(gzip data[352:], uint8).reshape(181, 217, 181)[k, j, i], and its
  // min and max.
  EXPECT_EQ(v.at({90, 108, 90}), 33.0f);
  EXPECT_EQ(v.at({100, 120, 60}), 100.0f);
  EXPECT_EQ(v.at({45, 150, 120}), 48.0f);
  EXPECT_EQ(v.at({0, 0, 0}), 0.0f);
  EXPECT_EQ(v.minValue, 0.0f);
  EXPECT_EQ(v.maxValue, 254.0f);
}

TEST_F(VolumeImportTest, StentNpz) {
  const Volume v = importVolume(kStent);
  // numpy: np.load(stent.npz)['arr_0'] is int16, C order, shape (256, 128, 128), values 0..2000;
  // a[k, j, i] is voxel (i, j, k).
  EXPECT_EQ(v.dims, glm::ivec3(128, 128, 256));
  EXPECT_EQ(v.voxelType, "i16");
  EXPECT_EQ(v.indexToWorld, glm::mat4(1.0f));
  EXPECT_EQ(v.minValue, 0.0f);
  EXPECT_EQ(v.maxValue, 2000.0f);
  EXPECT_EQ(v.at({76, 67, 46}), 2000.0f);  // a[46, 67, 76], the first 2000 in C order
  EXPECT_EQ(v.at({46, 67, 76}), 0.0f);     // a[76, 67, 46]: the axes are not swapped
  EXPECT_EQ(v.at({123, 127, 2}), 1000.0f);
  EXPECT_EQ(v.at({46, 3, 0}), 62.0f);
  EXPECT_EQ(v.at({70, 60, 130}), 1000.0f);
  // int((a == 2000).sum()) and float(a.astype(np.float64).sum()).
  EXPECT_EQ(std::count(v.values.begin(), v.values.end(), 2000.0f), 595);
  double sum = 0;
  for (const float x : v.values) sum += x;
  EXPECT_EQ(sum, 148470906.0);
}

TEST_F(VolumeImportTest, BrainsmallDen) {
  const Volume v = importVolume(kBrain);
  // Python struct: map_version 1 little-endian; map_len (128, 128, 84) at shorts 25..27,
  // map_length 1376256 at byte 58, then the bytes d[i + 128·(j + 128·k)] from byte 62.
  EXPECT_EQ(v.dims, glm::ivec3(128, 128, 84));
  EXPECT_EQ(v.voxelType, "u8");
  EXPECT_EQ(v.indexToWorld, glm::mat4(1.0f));
  EXPECT_EQ(v.at({64, 64, 42}), 65.0f);
  EXPECT_EQ(v.at({0, 0, 0}), 2.0f);
  EXPECT_EQ(v.at({30, 90, 70}), 3.0f);
  EXPECT_EQ(v.at({70, 74, 28}), 201.0f);
  EXPECT_EQ(v.at({127, 127, 83}), 2.0f);
  EXPECT_EQ(v.minValue, 0.0f);
  EXPECT_EQ(v.maxValue, 202.0f);
  double sum = 0;
  for (const float x : v.values) sum += x;
  EXPECT_EQ(sum, 19284185.0);
}

// ----------------------------------------------------------------------------------------------
// NIfTI written here

TEST_F(VolumeImportTest, NiftiSformWinsOverQformAndScalingAppliesInBothByteOrders) {
  for (const bool big : {false, true}) {
    SCOPED_TRACE(big ? "big-endian" : "little-endian");
    Nifti1 n;
    n.big = big;
    n.slope = 2.0f, n.inter = -3.0f;
    n.sformCode = 2;  // aligned to another scan
    const float srow[3][4] = {{0, -2, 0, 10}, {3, 0, 0, -20}, {0, 0, 1.5f, 5}};
    std::memcpy(n.srow, srow, sizeof srow);
    n.qformCode = 1;  // identity rotation, offset elsewhere: must be ignored
    n.qoffset[0] = 100;
    const fs::path file =
        write("scaled.nii", n.bytes(encode(fill<std::int16_t>(kSmall, smallValue), big)));

    const Volume v = importVolume(file);
    EXPECT_EQ(v.dims, kSmall);
    EXPECT_EQ(v.voxelType, "i16");
    for (int k = 0; k < 4; ++k)
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 2; ++i) {
          EXPECT_EQ(v.at({i, j, k}), 2.0f * float(smallValue(i, j, k)) - 3.0f);
          EXPECT_EQ(world(v, {i, j, k}), glm::vec3(-2 * j + 10, 3 * i - 20, 1.5f * k + 5));
        }
    EXPECT_EQ(v.minValue, 2.0f * -50 - 3);
    EXPECT_EQ(v.maxValue, 2.0f * smallValue(1, 2, 3) - 3);
    EXPECT_EQ(v.spacing(), glm::vec3(3, 2, 1.5f));
  }
}

TEST_F(VolumeImportTest, NiftiQformWithoutSform) {
  Nifti1 n;
  n.datatype = 2, n.bitpix = 8;    // DT_UINT8
  n.slope = 0.0f, n.inter = 7.0f;  // a slope of 0 means unscaled, whatever the intercept
  n.qformCode = 1;
  n.quatern[2] = std::sqrt(0.5f);  // 90° about z: x → y, y → −x
  n.pixdim[0] = -1.0f;             // qfac: k runs backwards
  n.pixdim[1] = 2, n.pixdim[2] = 3, n.pixdim[3] = 4;
  n.qoffset[0] = 1, n.qoffset[1] = 2, n.qoffset[2] = 3;
  const fs::path file =
      write("q.nii", n.bytes(encode(fill<std::uint8_t>(
                         kSmall, [](int i, int j, int k) { return 1 + i + 2 * j + 6 * k; }))));
  const Volume v = importVolume(file);
  EXPECT_EQ(v.voxelType, "u8");
  EXPECT_EQ(v.at({1, 2, 3}), 24.0f);
  EXPECT_EQ(v.minValue, 1.0f);
  EXPECT_EQ(v.maxValue, 24.0f);
  const glm::vec3 columns[4] = {{0, 2, 0}, {-3, 0, 0}, {0, 0, -4}, {1, 2, 3}};
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 3; ++r) EXPECT_NEAR(v.indexToWorld[c][r], columns[c][r], 1e-5) << c << r;
}

TEST_F(VolumeImportTest, NiftiPixdimWithoutQformOrSform) {
  Nifti1 n;
  n.datatype = 512, n.bitpix = 16;  // DT_UINT16
  n.pixdim[1] = 0.5f, n.pixdim[2] = 0.25f, n.pixdim[3] = 2.0f;
  const fs::path file = write(
      "p.nii",
      n.bytes(encode(fill<std::uint16_t>(kSmall, [](int i, int, int) { return 60000 + i; }))));
  const Volume v = importVolume(file);
  EXPECT_EQ(v.voxelType, "u16");
  EXPECT_EQ(v.maxValue, 60001.0f);
  EXPECT_EQ(v.indexToWorld, glm::mat4(glm::vec4(0.5f, 0, 0, 0), glm::vec4(0, 0.25f, 0, 0),
                                      glm::vec4(0, 0, 2.0f, 0), glm::vec4(0, 0, 0, 1)));
  // A 2-D image need not set pixdim[3]; libnifti mends a zero pixdim[1] to 1.
  Nifti1 flat;
  flat.dim[0] = 2, flat.dim[3] = 0;
  flat.pixdim[1] = 0.0f, flat.pixdim[2] = 0.5f, flat.pixdim[3] = 0.0f;
  const Volume f =
      importVolume(write("flat.nii", flat.bytes(encode<std::int16_t>({1, 2, 3, 4, 5, 6}))));
  EXPECT_EQ(f.dims, glm::ivec3(2, 3, 1));
  EXPECT_EQ(f.spacing(), glm::vec3(1, 0.5f, 1));
}

TEST_F(VolumeImportTest, NiftiEveryVoxelType) {
  struct Case {
    std::int16_t datatype, bitpix;
    const char* name;
    std::string bytes;  // the voxel 0's bytes
    float value;
  };
  const Case cases[] = {
      {2, 8, "u8", encode<std::uint8_t>({250}), 250.0f},
      {256, 8, "i8", encode<std::int8_t>({-120}), -120.0f},
      {4, 16, "i16", encode<std::int16_t>({-30000}), -30000.0f},
      {512, 16, "u16", encode<std::uint16_t>({65535}), 65535.0f},
      {8, 32, "i32", encode<std::int32_t>({-2000000000}), -2000000000.0f},
      {768, 32, "u32", encode<std::uint32_t>({4000000000u}), 4000000000.0f},
      {16, 32, "f32", encode<float>({-1.25f}), -1.25f},
      {64, 64, "f64", encode<double>({0.1}), float(0.1)},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    Nifti1 n;
    n.dim[1] = n.dim[2] = n.dim[3] = 1;
    n.datatype = c.datatype, n.bitpix = c.bitpix;
    const Volume v = importVolume(write(std::string(c.name) + ".nii", n.bytes(c.bytes)));
    EXPECT_EQ(v.voxelType, c.name);
    EXPECT_EQ(v.at({0, 0, 0}), c.value);
  }
}

TEST_F(VolumeImportTest, Nifti2WithNonFiniteValues) {
  Nifti2 n;
  n.sformCode = 1;
  const double srow[3][4] = {{-0.5, 0, 0, 40}, {0, 0.5, 0, -30}, {0, 0, 0.75, 12}};
  std::memcpy(n.srow, srow, sizeof srow);
  n.slope = 0.5, n.inter = 1.0;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<double> voxels = {4, nan, -inf, 8, 2, 6, 1e300, 0, -2, 3, 5, 7};
  const Volume v = importVolume(write("two.nii", n.bytes(encode(voxels))));
  EXPECT_EQ(v.dims, glm::ivec3(3, 2, 2));
  EXPECT_EQ(v.voxelType, "f64");
  EXPECT_EQ(v.at({0, 0, 0}), 3.0f);
  EXPECT_TRUE(std::isnan(v.at({1, 0, 0})));
  EXPECT_EQ(v.at({2, 0, 0}), -INFINITY);
  EXPECT_EQ(v.at({0, 0, 1}), INFINITY);  // 0.5e300 overflows float
  EXPECT_EQ(v.at({2, 1, 1}), 4.5f);
  EXPECT_EQ(v.minValue, 0.0f);  // 0.5·(−2) + 1; NaN and ±inf are left out
  EXPECT_EQ(v.maxValue, 5.0f);
  EXPECT_EQ(world(v, {2, 1, 1}), glm::vec3(39, -29.5f, 12.75f));
}

TEST_F(VolumeImportTest, NiftiSeriesYieldsItsFirstVolume) {
  Nifti1 n;
  n.dim[0] = 4, n.dim[1] = 2, n.dim[2] = 2, n.dim[3] = 2, n.dim[4] = 3;
  std::vector<std::int16_t> voxels(24);
  for (int t = 0; t < 24; ++t) voxels[std::size_t(t)] = std::int16_t(t);
  const Volume v = importVolume(write("series.nii", n.bytes(encode(voxels))));
  EXPECT_EQ(v.dims, glm::ivec3(2));
  EXPECT_EQ(v.values, std::vector<float>({0, 1, 2, 3, 4, 5, 6, 7}));
}

TEST_F(VolumeImportTest, NiftiSuffixIsCaseInsensitive) {
  const std::string bytes = Nifti1().bytes(encode(fill<std::int16_t>(kSmall, smallValue)));
  for (const char* name : {"UPPER.NII", "Mixed.Nii", "plain.nii"})
    EXPECT_EQ(importVolume(write(name, bytes)).dims, kSmall) << name;
  fs::copy_file(kCh2, dir_ / "CH2.Nii.Gz");
  EXPECT_EQ(importVolume(dir_ / "CH2.Nii.Gz").dims, glm::ivec3(181, 217, 181));
}

TEST_F(VolumeImportTest, NiftiBadInput) {
  const std::string voxels = encode(fill<std::int16_t>(kSmall, smallValue));
  Nifti1 rgb;
  rgb.datatype = 128, rgb.bitpix = 24;
  expectError([&] { importVolume(write("rgb.nii", rgb.bytes(voxels))); },
              {"rgb.nii", "header", "unsupported NIfTI datatype 128 (RGB24)"});
  Nifti1 complex;
  complex.datatype = 32, complex.bitpix = 64;
  expectError([&] { importVolume(write("c.nii", complex.bytes(voxels))); },
              {"c.nii", "unsupported NIfTI datatype 32 (COMPLEX64)"});
  Nifti1 zero;
  zero.dim[2] = 0;  // libnifti alone would mend this to 1
  expectError([&] { importVolume(write("zero.nii", zero.bytes(voxels))); },
              {"zero.nii", "header", "dims must be positive, got 2×0×4"});
  Nifti1 negative;
  negative.dim[1] = -2;
  expectError([&] { importVolume(write("neg.nii", negative.bytes(voxels))); },
              {"dims must be positive"});
  Nifti1 ndim;
  ndim.dim[0] = 9;
  expectError([&] { importVolume(write("ndim.nii", ndim.bytes(voxels))); }, {"dim[0] is 9"});
  Nifti1 singular;
  singular.sformCode = 1;  // an all-zero sform
  expectError([&] { importVolume(write("singular.nii", singular.bytes(voxels))); },
              {"singular.nii", "sform", "singular"});
  Nifti1 notFinite;
  notFinite.sformCode = 1;
  notFinite.srow[0][0] = notFinite.srow[1][1] = notFinite.srow[2][2] = 1;
  notFinite.srow[1][3] = std::numeric_limits<float>::infinity();
  expectError([&] { importVolume(write("inf.nii", notFinite.bytes(voxels))); },
              {"inf.nii", "sform", "not finite"});

  const std::string good = Nifti1().bytes(voxels);
  expectError([&] { importVolume(write("short.nii", good.substr(0, good.size() - 2))); },
              {"short.nii", "data", "truncated: 46 bytes of voxel data, expected 48"});
  expectError([&] { importVolume(write("head.nii", good.substr(0, 200))); },
              {"head.nii", "header", "truncated header: 200 bytes, expected 348"});
  expectError([&] { importVolume(write("empty.nii", "")); }, {"empty.nii", "sizeof_hdr"});
  std::string noMagic = good;
  noMagic.replace(344, 4, std::string("ni1\0", 4));  // the header of a .hdr/.img pair
  expectError([&] { importVolume(write("magic.nii", noMagic)); }, {"magic.nii", "magic"});
  expectError([&] { importVolume(write("text.nii", std::string(400, 'x'))); },
              {"text.nii", "not a NIfTI-1 or NIfTI-2 file"});
}

TEST_F(VolumeImportTest, NiftiGzTruncatedOrOverTheLimit) {
  // ch2.nii.gz cut inside the voxels: zlib's stream ends early (no crash, no stderr).
  expectError([&] { importVolume(truncatedCopy(kCh2, "cut.nii.gz", 1000000)); },
              {"cut.nii.gz", "data", "truncated: ", "bytes of voxel data, expected 7109137"});
  // Cut inside the gzip-compressed header.
  expectError([&] { importVolume(truncatedCopy(kCh2, "head.nii.gz", 200)); },
              {"head.nii.gz", "header", "truncated header"});
  expectError([&] { importVolume(truncatedCopy(kCh2, "ten.nii.gz", 10)); }, {"ten.nii.gz"});
  expectError([&] { importVolume(kCh2, {.maxVoxels = 1000}); },
              {"ch2.nii.gz", "header", "181×217×181 = 7109137 voxels exceed the limit of 1000"});
}

// ----------------------------------------------------------------------------------------------
// Raw voxels with a JSON header

TEST_F(VolumeImportTest, RawEveryTypeInBothByteOrders) {
  expectRawType<std::uint8_t>("u8", {0, 1, 127, 128, 200, 255});
  expectRawType<std::int8_t>("i8", {0, 1, -1, 127, -128, 5});
  expectRawType<std::uint16_t>("u16", {0, 1, 256, 0x1234, 40000, 65535});
  expectRawType<std::int16_t>("i16", {0, -1, 256, 0x1234, -32768, 32767});
  expectRawType<std::uint32_t>("u32", {0, 1, 65536, 0x12345678, 4000000000u, 7});
  expectRawType<std::int32_t>("i32", {0, -1, 65536, 0x12345678, -2000000000, 7});
  expectRawType<float>("f32", {0.0f, -1.5f, 3.25e10f, 1e-20f, 0.1f, -0.0f});
  expectRawType<double>("f64", {0.0, -1.5, 3.25e10, 1e-20, 0.1, 1e300});
}

TEST_F(VolumeImportTest, RawSpacingOriginAndHeaderBytes) {
  const std::string voxels = encode(fill<std::int16_t>(kSmall, smallValue));
  const fs::path file = raw("i16", "[2, 3, 4]", "skip me" + voxels,
                            R"(, "spacing": [0.5, 2, 3], "origin": [10, -5, 1], "headerBytes": 7)");
  const Volume v = importVolume(file);
  EXPECT_EQ(v.dims, kSmall);
  EXPECT_EQ(v.at({1, 2, 3}), float(smallValue(1, 2, 3)));
  EXPECT_EQ(v.at({0, 0, 0}), -50.0f);
  EXPECT_EQ(world(v, {1, 2, 3}), glm::vec3(10.5f, -1, 10));
  EXPECT_EQ(v.spacing(), glm::vec3(0.5f, 2, 3));
  // Defaults: spacing 1, origin 0, little-endian, no header bytes.
  const Volume plain = importVolume(raw("i16", "[2, 3, 4]", voxels));
  EXPECT_EQ(plain.indexToWorld, glm::mat4(1.0f));
  EXPECT_EQ(plain.values, v.values);
}

TEST_F(VolumeImportTest, RawRelativeToTheJsonFolder) {
  fs::create_directories(dir_ / "sub" / "data");
  std::ofstream(dir_ / "sub" / "data" / "v.raw", std::ios::binary) << std::string(8, '\x07');
  const fs::path file = write("sub/v.json", R"({"file": "data/v.raw", "dims": [2, 2, 2],
                                                 "type": "u8"})");
  EXPECT_EQ(importVolume(file).values, std::vector<float>(8, 7.0f));
}

TEST_F(VolumeImportTest, RawBadInput) {
  const std::string eight(8, '\0');
  expectError([&] { importVolume(raw("u8", "[2, 2, 2]", eight, R"(, "spacng": [1, 1, 1])")); },
              {"volume.json", "/spacng", "unknown key \"spacng\""});
  expectError([&] { importVolume(write("v.json", R"({"file": "x.raw", "type": "u8"})")); },
              {"v.json", "missing required key \"dims\""});
  expectError([&] { importVolume(raw("u64", "[2, 2, 2]", eight)); },
              {"volume.json", "/type", "unknown value \"u64\""});
  expectError([&] { importVolume(raw("u8", "[2, 2, 2]", eight, R"(, "endianness": "middle")")); },
              {"/endianness", "middle"});
  expectError([&] { importVolume(raw("u8", "[2, 0, 2]", eight)); },
              {"volume.json", "/dims", "dims must be positive, got 2×0×2"});
  expectError([&] { importVolume(raw("u8", "[2, -2, 2]", eight)); },
              {"/dims", "dims must be positive"});
  expectError([&] { importVolume(raw("u8", "[2, 2.5, 2]", eight)); },
              {"/dims/1", "expected an integer"});
  expectError([&] { importVolume(raw("u8", "[2, 2]", eight)); }, {"/dims", "3 integers"});
  expectError(
      [&] { importVolume(raw("u16", "[2, 2, 2]", std::string(15, '\0'))); },
      {"volume.json", "/file", "volume.raw", "truncated: 15 bytes of voxel data, expected 16"});
  expectError([&] { importVolume(raw("u8", "[2, 2, 2]", std::string(9, '\0'))); },
              {"volume.raw", "9 bytes of voxel data, expected 8", "dims disagree"});
  expectError([&] { importVolume(raw("u8", "[2, 2, 2]", eight, R"(, "headerBytes": 9)")); },
              {"/headerBytes", "exceeds"});
  expectError([&] { importVolume(raw("u8", "[2, 2, 2]", eight, R"(, "headerBytes": -1)")); },
              {"/headerBytes", "negative"});
  expectError([&] { importVolume(raw("u8", "[2, 2, 2]", eight, R"(, "spacing": [1, 0, 1])")); },
              {"/spacing", "singular"});
  expectError([&] { importVolume(raw("u8", "[2, 2, 2]", eight, R"(, "spacing": [1, 1])")); },
              {"/spacing", "3 numbers"});
  expectError([&] { importVolume(write("bad.json", R"({"file": "x.raw", "dims": [1, 1, 1],)")); },
              {"bad.json", "invalid JSON"});
  expectError(
      [&] {
        importVolume(write("v.json", R"({"file": "nowhere.raw", "dims": [1, 1, 1],
                                                      "type": "u8"})"));
      },
      {"v.json", "/file", "raw file not found", "nowhere.raw"});
}

TEST_F(VolumeImportTest, LimitsAreCheckedBeforeReadingOrAllocating) {
  expectError(
      [&] { importVolume(raw("u8", "[10, 10, 10]", std::string(1000, '\0')), {.maxVoxels = 999}); },
      {"volume.json", "/dims", "10×10×10 = 1000 voxels exceed the limit of 999"});
  EXPECT_EQ(importVolume(raw("u8", "[10, 10, 10]", std::string(1000, '\0')), {.maxVoxels = 1000})
                .voxelCount(),
            1000u);
  // No raw file at all: the dims alone are refused, and nothing is allocated for them.
  const auto noFile = [&](const std::string& dims) {
    return write("huge.json", R"({"file": "absent.raw", "type": "f64", "dims": )" + dims + "}");
  };
  expectError([&] { importVolume(noFile("[100000, 100000, 100000]")); },
              {"huge.json", "/dims", "= 1000000000000000 voxels exceed the limit of 1073741824"});
  expectError([&] { importVolume(noFile("[2147483647, 2147483647, 2147483647]")); },
              {"/dims", "2147483647×2147483647×2147483647 voxels exceed the limit"});
  expectError(
      [&] { importVolume(noFile("[3000000000, 1, 1]"), {.maxVoxels = std::size_t(1) << 40}); },
      {"/dims", "3000000000×1×1 voxels exceed the limit"});
  expectError([&] { importVolume(noFile("[1, 1, 18446744073709551615]")); },
              {"/dims/2", "integer too large"});
}

// ----------------------------------------------------------------------------------------------
// NumPy

TEST_F(VolumeImportTest, NpyCOrderPutsTheLastAxisFastest) {
  // a[x][y][z] = 100x + 10y + z for shape (2, 3, 4), written in C order: z fastest, so
  // dims = (4, 3, 2) and voxel (i, j, k) = a[k][j][i].
  std::vector<std::int32_t> a;
  for (int x = 0; x < 2; ++x)
    for (int y = 0; y < 3; ++y)
      for (int z = 0; z < 4; ++z) a.push_back(100 * x + 10 * y + z);
  const Volume v = importVolume(write("c.npy", npy(npyDict("<i4", "(2, 3, 4)"), encode(a))));
  EXPECT_EQ(v.dims, glm::ivec3(4, 3, 2));
  EXPECT_EQ(v.voxelType, "i32");
  EXPECT_EQ(v.at({3, 1, 0}), 13.0f);
  EXPECT_EQ(v.at({0, 2, 1}), 120.0f);
  EXPECT_EQ(v.at({2, 0, 1}), 102.0f);
  EXPECT_EQ(v.indexToWorld, glm::mat4(1.0f));
}

TEST_F(VolumeImportTest, NpyFortranOrderPutsTheFirstAxisFastest) {
  // The same array in Fortran order: x fastest, so dims = (2, 3, 4) and voxel (i, j, k) =
  // a[i][j][k].
  std::vector<std::int32_t> a;
  for (int z = 0; z < 4; ++z)
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 2; ++x) a.push_back(100 * x + 10 * y + z);
  const Volume v = importVolume(write("f.npy", npy(npyDict("<i4", "(2, 3, 4)", true), encode(a))));
  EXPECT_EQ(v.dims, glm::ivec3(2, 3, 4));
  EXPECT_EQ(v.at({1, 2, 3}), 123.0f);
  EXPECT_EQ(v.at({0, 1, 3}), 13.0f);
  EXPECT_EQ(v.at({1, 0, 2}), 102.0f);
}

TEST_F(VolumeImportTest, NpyDtypesAndVersions) {
  const auto one = [&](const std::string& descr, const std::string& bytes, int major = 1) {
    return importVolume(write("v.npy", npy(npyDict(descr, "(1, 1, 2)"), bytes, major)));
  };
  EXPECT_EQ(one("|u1", encode<std::uint8_t>({200, 3})).values, std::vector<float>({200, 3}));
  EXPECT_EQ(one("|i1", encode<std::int8_t>({-100, 3})).values, std::vector<float>({-100, 3}));
  EXPECT_EQ(one("<i2", encode<std::int16_t>({-300, 3})).values, std::vector<float>({-300, 3}));
  EXPECT_EQ(one(">i2", encode<std::int16_t>({-300, 3}, true)).values,
            std::vector<float>({-300, 3}));
  EXPECT_EQ(one("<u2", encode<std::uint16_t>({65000, 3})).values, std::vector<float>({65000, 3}));
  EXPECT_EQ(one("<i4", encode<std::int32_t>({-70000, 3})).values, std::vector<float>({-70000, 3}));
  EXPECT_EQ(one("<u4", encode<std::uint32_t>({70000, 3})).values, std::vector<float>({70000, 3}));
  EXPECT_EQ(one("<f4", encode<float>({-0.5f, 3})).values, std::vector<float>({-0.5f, 3}));
  EXPECT_EQ(one(">f4", encode<float>({-0.5f, 3}, true)).values, std::vector<float>({-0.5f, 3}));
  EXPECT_EQ(one("<f8", encode<double>({0.1, 3})).values, std::vector<float>({float(0.1), 3}));
  EXPECT_EQ(one(">f8", encode<double>({0.1, 3}, true)).values, std::vector<float>({float(0.1), 3}));
  const Volume v2 = one("<i2", encode<std::int16_t>({5, 6}), 2);
  EXPECT_EQ(v2.values, std::vector<float>({5, 6}));
  EXPECT_EQ(v2.voxelType, "i16");
  EXPECT_EQ(one("<i2", encode<std::int16_t>({5, 6}), 3).values, std::vector<float>({5, 6}));
  // Old NumPy wrote Python 2 longs, and the keys may come in any order.
  EXPECT_EQ(importVolume(write("l.npy", npy("{'shape': (1L, 1L, 2L), 'fortran_order': False, "
                                            "'descr': '|u1'}",
                                            encode<std::uint8_t>({1, 2}))))
                .dims,
            glm::ivec3(2, 1, 1));
}

TEST_F(VolumeImportTest, NpyBadInput) {
  const std::string two = encode<std::int16_t>({1, 2});
  const auto bad = [&](const std::string& dict, const std::string& bytes) {
    return [&, dict, bytes] { importVolume(write("bad.npy", npy(dict, bytes))); };
  };
  expectError(bad(npyDict("<c8", "(1, 1, 1)"), std::string(8, '\0')),
              {"bad.npy", "header", "unsupported dtype '<c8'"});
  expectError(bad(npyDict("<i8", "(1, 1, 1)"), std::string(8, '\0')), {"unsupported dtype '<i8'"});
  expectError(bad(npyDict("|b1", "(1, 1, 2)"), two), {"unsupported dtype '|b1'"});
  expectError(bad(npyDict("|u2", "(1, 1, 2)"), std::string(4, '\0')), {"unsupported dtype '|u2'"});
  expectError(bad("{'descr': [('a', '<i4')], 'fortran_order': False, 'shape': (1, 1, 1), }",
                  std::string(4, '\0')),
              {"bad.npy", "unsupported dtype [('a', '<i4')]"});
  expectError(bad(npyDict("<i2", "(2,)"), two), {"shape has 1 dimensions, expected 3"});
  expectError(bad(npyDict("<i2", "(1, 1, 1, 2)"), two), {"shape has 4 dimensions, expected 3"});
  expectError(bad(npyDict("<i2", "(0, 1, 2)"), ""), {"header", "dims must be positive, got 2×1×0"});
  expectError(bad(npyDict("<i2", "(1, 1, 2)"), two.substr(0, 3)),
              {"bad.npy", "data", "truncated: 3 bytes of voxel data, expected 4"});
  expectError(bad(npyDict("<i2", "(1, 1, 2)"), two + "xx"),
              {"bad.npy", "6 bytes of voxel data, expected 4", "dims disagree"});
  expectError(bad("{'descr': '<i2', 'shape': (1, 1, 2), }", two), {"lacks 'fortran_order'"});
  expectError(bad("{'descr': '<i2', 'fortran_order': False, 'shape': (1, 1, 2), 'x': 1}", two),
              {"unknown key 'x'"});
  expectError(bad("{'descr': '<i2', 'fortran_order': 0, 'shape': (1, 1, 2)}", two),
              {"fortran_order"});
  expectError(bad("{'descr': '<i2' 'fortran_order': False}", two), {"header", "expected ','"});
  expectError(
      bad("{'descr': '<i2', 'fortran_order': False, 'shape': " + std::string(100, '(') + "}", two),
      {"nested too deeply"});
  expectError(bad(npyDict("<i2", "(99999999999999999999, 1, 1)"), two), {"integer too large"});
  expectError([&] { importVolume(write("magic.npy", "\x93NUMPX\x01\x00\x00\x00")); },
              {"magic.npy", "header", "no \\x93NUMPY magic"});
  expectError([&] { importVolume(write("v4.npy", std::string("\x93NUMPY\x04\x00\x10\x00", 10))); },
              {"v4.npy", "unsupported .npy format version 4.0"});
  std::string longHeader("\x93NUMPY\x02\x00", 8);
  putAt<std::uint32_t>(longHeader, 8, 0xFFFFFFF0u);
  expectError([&] { importVolume(write("long.npy", longHeader + "{}")); },
              {"long.npy", "header length 4294967280 exceeds the limit"});
  expectError(
      [&] { importVolume(write("cut.npy", npy(npyDict("<i2", "(1, 1, 2)"), two).substr(0, 40))); },
      {"cut.npy", "header length", "exceeds the data size 40"});
  expectError(
      [&] {
        importVolume(write("over.npy", npy(npyDict("<i2", "(64, 64, 64)"), "")),
                     {.maxVoxels = 1000});
      },
      {"over.npy", "64×64×64 = 262144 voxels exceed the limit of 1000"});
}

TEST_F(VolumeImportTest, NpzTakesTheFirstNpyMemberAndNamesIt) {
  const std::string a = npy(npyDict("<u2", "(1, 2, 2)"), encode<std::uint16_t>({1, 2, 3, 4}));
  const std::string b = npy(npyDict("<u2", "(1, 1, 1)"), encode<std::uint16_t>({9}));
  for (const bool store : {false, true}) {
    const fs::path file = npz(
        "two.npz", {{"README.txt", "not an array"}, {"first.npy", a}, {"second.npy", b}}, store);
    const Volume v = importVolume(file);
    EXPECT_EQ(v.dims, glm::ivec3(2, 2, 1));
    EXPECT_EQ(v.values, std::vector<float>({1, 2, 3, 4}));
  }
  expectError(
      [&] {
        importVolume(npz("dtype.npz",
                         {{"arr_0.npy", npy(npyDict("<c8", "(1, 1, 1)"), std::string(8, '\0'))}}));
      },
      {"dtype.npz", "arr_0.npy", "unsupported dtype '<c8'"});
  expectError(
      [&] {
        importVolume(npz("short.npz", {{"arr_0.npy", a.substr(0, a.size() - 1)}}));
      },
      {"short.npz", "arr_0.npy", "truncated: 7 bytes of voxel data, expected 8"});
  expectError(
      [&] {
        importVolume(npz("none.npz", {{"arr_0.txt", a}}));
      },
      {"none.npz", "no .npy member"});
  expectError(
      [&] { importVolume(kStent, {.maxVoxels = 1 << 20}); },
      {"stent.npz", "arr_0.npy", "128×128×256 = 4194304 voxels exceed the limit of 1048576"});
}

TEST_F(VolumeImportTest, CorruptNpz) {
  // stent.npz cut short: the zip's central directory, at its end, is gone.
  expectError([&] { importVolume(truncatedCopy(kStent, "cut.npz", 100000)); },
              {"cut.npz", "not a readable .npz (zip) archive"});
  expectError([&] { importVolume(write("text.npz", "PK but not a zip")); },
              {"text.npz", "not a readable .npz (zip) archive"});
  // Bytes changed inside the deflated member: inflate or the CRC check fails.
  std::ifstream in(kStent, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (std::size_t i = 400000; i < 400064; ++i) bytes[i] = char(~bytes[i]);
  expectError([&] { importVolume(write("flipped.npz", bytes)); },
              {"flipped.npz", "arr_0.npy", "corrupt zip member"});
  // A stored member whose data was changed after its CRC was written.
  const std::string a = npy(npyDict("<u2", "(1, 2, 2)"), encode<std::uint16_t>({1, 2, 3, 4}));
  std::string stored;
  {
    const fs::path file = npz("stored.npz", {{"arr_0.npy", a}}, true);
    std::ifstream s(file, std::ios::binary);
    stored.assign(std::istreambuf_iterator<char>(s), std::istreambuf_iterator<char>());
  }
  const std::size_t at = stored.find(a);
  ASSERT_NE(at, std::string::npos);
  stored[at + a.size() - 1] ^= 0x40;
  expectError([&] { importVolume(write("crc.npz", stored)); },
              {"crc.npz", "arr_0.npy", "corrupt zip member"});
}

// ----------------------------------------------------------------------------------------------
// VolPack .den

TEST_F(VolumeImportTest, DenInBothByteOrders) {
  const std::vector<std::uint8_t> voxels =
      fill<std::uint8_t>({3, 2, 2}, [](int i, int j, int k) { return 1 + i + 3 * j + 6 * k; });
  for (const bool big : {false, true}) {
    const Volume v = importVolume(write("v.den", den({3, 2, 2}, encode(voxels), big)));
    EXPECT_EQ(v.dims, glm::ivec3(3, 2, 2));
    EXPECT_EQ(v.voxelType, "u8");
    EXPECT_EQ(v.at({2, 1, 1}), 12.0f);
    EXPECT_EQ(v.minValue, 1.0f);
    EXPECT_EQ(v.maxValue, 12.0f);
  }
}

TEST_F(VolumeImportTest, DenBadInput) {
  const std::string twelve(12, '\x05');
  expectError(
      [&] {
        importVolume(write("short.den", den({3, 2, 2}, twelve.substr(0, 11))));
      },
      {"short.den", "data", "truncated: 11 bytes of voxel data, expected 12"});
  expectError(
      [&] {
        importVolume(write("long.den", den({3, 2, 2}, twelve + "x")));
      },
      {"long.den", "13 bytes of voxel data, expected 12", "dims disagree"});
  expectError(
      [&] {
        importVolume(write("len.den", den({3, 2, 2}, twelve, false, 13)));
      },
      {"len.den", "header", "inconsistent header: map_length 13"});
  expectError(
      [&] {
        importVolume(write("zero.den", den({3, 0, 2}, "")));
      },
      {"zero.den", "header", "dims must be positive, got 3×0×2"});
  expectError(
      [&] {
        importVolume(write("neg.den", den({3, -2, 2}, "")));
      },
      {"dims must be positive"});
  std::string magic = den({3, 2, 2}, twelve);
  magic[0] = 2;
  expectError([&] { importVolume(write("magic.den", magic)); },
              {"magic.den", "not a VolPack density file"});
  expectError(
      [&] {
        importVolume(write("head.den", den({3, 2, 2}, "").substr(0, 30)));
      },
      {"head.den", "truncated header: 30 bytes, expected at least 62"});
  expectError([&] { importVolume(kBrain, {.maxVoxels = 1000}); },
              {"brainsmall.den", "128×128×84 = 1376256 voxels exceed the limit of 1000"});
}

// ----------------------------------------------------------------------------------------------
// Formats, files and ranges

TEST_F(VolumeImportTest, UnknownFormatOrMissingFile) {
  for (const char* name : {"volume.vtk", "volume", "volume.nii.gz.bak", "volume.raw"})
    expectError(
        [&] { importVolume(write(name, "x")); },
        {name, "unknown volume format (expected .nii, .nii.gz, .npy, .npz, .den or .json)"});
  for (const char* name : {"absent.nii.gz", "absent.npz", "absent.json"})
    expectError([&] { importVolume(dir_ / name); }, {name, "volume file not found"});
  fs::create_directories(dir_ / "folder.nii");
  expectError([&] { importVolume(dir_ / "folder.nii"); }, {"volume file not found"});
}

TEST(VolumeRange, IgnoresNanAndInfinities) {
  Volume v;
  v.updateRange();
  EXPECT_EQ(v.minValue, 0.0f);
  EXPECT_EQ(v.maxValue, 0.0f);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  v.values = {nan, INFINITY, -INFINITY};
  v.minValue = v.maxValue = 5.0f;
  v.updateRange();
  EXPECT_EQ(v.minValue, 0.0f);
  EXPECT_EQ(v.maxValue, 0.0f);
  v.values = {nan, 3.0f, -INFINITY, -2.0f, INFINITY, nan};
  v.updateRange();
  EXPECT_EQ(v.minValue, -2.0f);
  EXPECT_EQ(v.maxValue, 3.0f);
}
