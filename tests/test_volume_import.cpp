// Volume import: three real files checked against numbers read independently with Python,
// NIfTI-1 and NIfTI-2 written here byte by byte (sform, qform, pixdim, scaling, byte order, a
// 4-D series), raw voxels with a JSON header in every type and both byte orders, .npy in C
// and Fortran order, .npz archives written through libzip, .den files, MetaImage, NRRD and
// VTK files written here as their writers (ITK, teem, VTK) write them, DICOM series written
// through GDCM, and every bad input.
#include <gtest/gtest.h>
#include <unistd.h>
#include <zip.h>
#include <zlib.h>

// The DICOM tests write their series through GDCM.
#include <gdcmDataElement.h>
#include <gdcmDataSet.h>
#include <gdcmFile.h>
#include <gdcmTag.h>
#include <gdcmTransferSyntax.h>
#include <gdcmVR.h>
#include <gdcmWriter.h>

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

// `bytes` deflated as a zlib stream (MetaImage's CompressedData) or, with `gzip`, as a gzip
// file (NRRD's gzip encoding).
std::string deflated(const std::string& bytes, bool gzip = false) {
  z_stream z{};
  EXPECT_EQ(
      deflateInit2(&z, Z_BEST_COMPRESSION, Z_DEFLATED, gzip ? 15 + 16 : 15, 8, Z_DEFAULT_STRATEGY),
      Z_OK);
  std::string out(deflateBound(&z, uLong(bytes.size())), '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
  z.avail_in = uInt(bytes.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = uInt(out.size());
  EXPECT_EQ(deflate(&z, Z_FINISH), Z_STREAM_END);
  out.resize(z.total_out);
  deflateEnd(&z);
  return out;
}

// A MetaImage header as ITK's MetaImageIO writes it; `extra` lines go before ElementDataFile
// and, MetaIO keeping a repeated key's last value, override the defaults.
std::string metaHeader(const std::string& dims, const std::string& type,
                       const std::string& extra = "", const std::string& dataFile = "LOCAL") {
  return "ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\n"
         "CompressedData = False\nTransformMatrix = 1 0 0 0 1 0 0 0 1\nOffset = 0 0 0\n"
         "CenterOfRotation = 0 0 0\nAnatomicalOrientation = RAI\nElementSpacing = 1 1 1\n"
         "DimSize = " +
         dims + "\nElementType = " + type + "\n" + extra + "ElementDataFile = " + dataFile + "\n";
}

// A NRRD header as teem's unu writes it, the given fields after its comment lines.
std::string nrrdHeader(const std::string& fields) {
  return "NRRD0004\n# Complete NRRD file format specification at:\n"
         "# http://teem.sourceforge.net/nrrd/format.html\n" +
         fields;
}

// A VTK legacy header for structured points; `geometry` holds DIMENSIONS, SPACING, ORIGIN.
std::string vtkHeader(const std::string& format, const std::string& geometry, int points,
                      const std::string& type) {
  return "# vtk DataFile Version 3.0\nwritten by a test\n" + format +
         "\nDATASET STRUCTURED_POINTS\n" + geometry + "POINT_DATA " + std::to_string(points) +
         "\nSCALARS scalars " + type + "\nLOOKUP_TABLE default\n";
}

// Numbers as text, `perLine` to a line.
template <typename T>
std::string asText(const std::vector<T>& values, std::size_t perLine = 5) {
  std::string s;
  for (std::size_t i = 0; i < values.size(); ++i)
    s += std::to_string(values[i]) + ((i + 1) % perLine == 0 ? "\n" : " ");
  return s;
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

// One DICOM CT slice written through GDCM, every tag given here as it lies in the file.
struct DicomSpec {
  std::string series = "1.2.826.0.1.3680043.2.1125.1";
  std::string position = "5\\-20\\30";
  std::string orientation = "0\\1\\0\\0\\0\\-1";  // along a row +y, down a column −z
  std::string spacing = "0.5\\0.75";              // between rows, between columns
  std::string slope = "2", intercept = "-1024";
  std::string frames;       // NumberOfFrames, when not empty
  std::string recognition;  // ACR-NEMA's RecognitionCode (0008,0010), when not empty
  std::uint16_t rows = 6, columns = 8;
  bool implicit = false;  // Implicit VR Little Endian instead of Explicit
  bool image = true;      // false: no image pixel module, like a structured report
  std::vector<std::int16_t> pixels;
};

void putDicom(gdcm::DataSet& ds, std::uint16_t group, std::uint16_t element, const char* vr,
              std::string value) {
  const gdcm::VR type = gdcm::VR::GetVRType(vr);
  if (value.size() % 2) value += type == gdcm::VR::UI ? '\0' : ' ';  // values have even lengths
  gdcm::DataElement e(gdcm::Tag(group, element));
  e.SetVR(type);
  e.SetByteValue(value.data(), gdcm::VL(std::uint32_t(value.size())));
  ds.Insert(e);
}

std::string us(std::uint16_t v) {
  return encode<std::uint16_t>({v});
}

void writeDicom(const fs::path& file, const DicomSpec& s, int instance) {
  gdcm::Writer writer;
  writer.SetFileName(file.c_str());
  writer.GetFile().GetHeader().SetDataSetTransferSyntax(
      s.implicit ? gdcm::TransferSyntax::ImplicitVRLittleEndian
                 : gdcm::TransferSyntax::ExplicitVRLittleEndian);
  gdcm::DataSet& ds = writer.GetFile().GetDataSet();
  putDicom(ds, 0x0008, 0x0016, "UI", "1.2.840.10008.5.1.4.1.1.2");  // CT Image Storage
  putDicom(ds, 0x0008, 0x0018, "UI", s.series + "." + std::to_string(instance));
  putDicom(ds, 0x0008, 0x0060, "CS", "CT");
  if (!s.recognition.empty()) putDicom(ds, 0x0008, 0x0010, "SH", s.recognition);
  putDicom(ds, 0x0020, 0x000D, "UI", "1.2.826.0.1.3680043.2.1125.0");
  if (!s.series.empty()) putDicom(ds, 0x0020, 0x000E, "UI", s.series);
  putDicom(ds, 0x0020, 0x0013, "IS", std::to_string(instance));
  if (!s.image) {
    ASSERT_TRUE(writer.Write());
    return;
  }
  if (!s.position.empty()) putDicom(ds, 0x0020, 0x0032, "DS", s.position);
  putDicom(ds, 0x0020, 0x0037, "DS", s.orientation);
  putDicom(ds, 0x0028, 0x0002, "US", us(1));
  putDicom(ds, 0x0028, 0x0004, "CS", "MONOCHROME2");
  if (!s.frames.empty()) putDicom(ds, 0x0028, 0x0008, "IS", s.frames);
  putDicom(ds, 0x0028, 0x0010, "US", us(s.rows));
  putDicom(ds, 0x0028, 0x0011, "US", us(s.columns));
  putDicom(ds, 0x0028, 0x0030, "DS", s.spacing);
  putDicom(ds, 0x0028, 0x0100, "US", us(16));
  putDicom(ds, 0x0028, 0x0101, "US", us(16));
  putDicom(ds, 0x0028, 0x0102, "US", us(15));
  putDicom(ds, 0x0028, 0x0103, "US", us(1));
  putDicom(ds, 0x0028, 0x1052, "DS", s.intercept);
  if (!s.slope.empty()) putDicom(ds, 0x0028, 0x1053, "DS", s.slope);
  std::vector<std::int16_t> pixels = s.pixels;
  pixels.resize(std::size_t(s.rows) * s.columns);
  putDicom(ds, 0x7FE0, 0x0010, "OW", encode(pixels));
  ASSERT_TRUE(writer.Write()) << file;
}

// The series of the DICOM tests: 8 columns × 6 rows × 5 slices, slice k at (5 − 2.5k, −20, 30)
// — 2.5 mm apart along the normal row × column = (−1, 0, 0) — holding i + 10j + 100k − 200,
// rescaled by 2 and −1024 + k.
constexpr glm::ivec3 kSeries{8, 6, 5};
int seriesValue(int i, int j, int k) {
  return i + 10 * j + 100 * k - 200;
}
DicomSpec seriesSlice(int k) {
  DicomSpec s;
  s.position = std::to_string(5 - 2.5 * k) + "\\-20\\30";
  s.intercept = std::to_string(-1024 + k);
  s.implicit = k % 2 == 1;
  s.pixels = fill<std::int16_t>({kSeries.x, kSeries.y, 1},
                                [k](int i, int j, int) { return seriesValue(i, j, k); });
  return s;
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
  // A vox_offset inside the header would read its extension flag as voxels; 0 is "unset":
  // the voxels right after the flag, as NiBabel reads it.
  std::string early = good, unset = good;
  const float ten = 10.0f, none = 0.0f;
  early.replace(108, 4, reinterpret_cast<const char*>(&ten), 4);
  expectError([&] { importVolume(write("early.nii", early)); },
              {"early.nii", "header", "vox_offset 10 lies inside the 348-byte header"});
  unset.replace(108, 4, reinterpret_cast<const char*>(&none), 4);
  EXPECT_EQ(importVolume(write("unset.nii", unset)).values,
            importVolume(write("good.nii", good)).values);
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
  // Beyond the reach of a scene (1e300's squares overflowed, and MetaImage called it singular).
  expectError([&] { importVolume(raw("u8", "[2, 2, 2]", eight, R"(, "spacing": [1e20, 1, 1])")); },
              {"/spacing", "an entry of magnitude 1e+20, beyond the 1e15 a scene may reach"});
  expectError([&] { importVolume(raw("u8", "[2, 2, 2]", eight, R"(, "spacing": [1, 1])")); },
              {"/spacing", "3 numbers"});
  expectError([&] { importVolume(write("bad.json", R"({"file": "x.raw", "dims": [1, 1, 1],)")); },
              {"bad.json", "invalid JSON"});
  expectError([&] { importVolume(raw("u8", "[2, 2, 2]", eight, R"(, "origin": [1e20, 0, 0])")); },
              {"volume.json", "/origin/0", "magnitude 1e+20 is beyond the 1e15"});
  // nlohmann's parser ends its input at a NUL byte: what follows one was ignored.
  expectError(
      [&] {
        importVolume(write(
            "nul.json", std::string(R"({"file": "volume.raw", "dims": [2, 2, 2], "type": "u8"})") +
                            '\0' + "garbage"));
      },
      {"nul.json", "line 1, column 56", "invalid JSON: a NUL byte"});
  expectError(
      [&] {
        importVolume(write("v.json", R"({"file": "nowhere.raw", "dims": [1, 1, 1],
                                                      "type": "u8"})"));
      },
      {"v.json", "/file", "raw file not found", "nowhere.raw"});
  // A path that exists but is no regular file (a folder, a device) is named as such.
  expectError(
      [&] { importVolume(write("dot.json", R"({"file": ".", "dims": [1, 1, 1], "type": "u8"})")); },
      {"dot.json", "/file", "raw file is not a regular file"});
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
// MetaImage

TEST_F(VolumeImportTest, MhaPlacesVoxelsByTransformMatrixSpacingAndOffset) {
  // TransformMatrix's first three numbers are the direction of i (ITK's column-major reading):
  // i along +y, j along −x, k along +z in the file's LPS; in RAS, i along −y and j along +x.
  const fs::path file =
      write("v.mha", metaHeader("2 3 4", "MET_SHORT",
                                "TransformMatrix = 0 1 0 -1 0 0 0 0 1\nElementSpacing = 0.5 2 3\n"
                                "Offset = 10 -5 1\n") +
                         encode(fill<std::int16_t>(kSmall, smallValue)));
  const Volume v = importVolume(file);
  EXPECT_EQ(v.dims, kSmall);
  EXPECT_EQ(v.voxelType, "i16");
  EXPECT_EQ(v.values, fill<float>(kSmall, smallValue));
  EXPECT_EQ(world(v, {0, 0, 0}), glm::vec3(-10, 5, 1));
  EXPECT_EQ(world(v, {1, 0, 0}), glm::vec3(-10, 4.5f, 1));
  EXPECT_EQ(world(v, {1, 2, 3}), glm::vec3(-6, 4.5f, 10));
  EXPECT_EQ(v.spacing(), glm::vec3(0.5f, 2, 3));
  EXPECT_EQ(v.minValue, -50.0f);
  EXPECT_EQ(v.maxValue, float(smallValue(1, 2, 3)));
}

TEST_F(VolumeImportTest, MhaSynonymsBigEndianAndEveryElementType) {
  // MetaIO's older spellings: Position, Orientation, ElementSize, ElementByteOrderMSB.
  const std::string header =
      "ObjectType = Image\nNDims = 3\nDimSize = 2 3 4\nElementType = MET_USHORT\n"
      "ElementByteOrderMSB = True\nPosition = 1 2 3\nOrientation = 1 0 0 0 0 1 0 -1 0\n"
      "ElementSize = 2 2 2\nElementDataFile = LOCAL\n";
  const Volume v = importVolume(write(
      "old.MHA",
      header + encode(fill<std::uint16_t>(
                          kSmall, [](int i, int j, int k) { return 40000 + i + 2 * j + 6 * k; }),
                      true)));
  EXPECT_EQ(v.voxelType, "u16");
  EXPECT_EQ(v.at({1, 2, 3}), 40023.0f);
  EXPECT_EQ(world(v, {1, 1, 1}), glm::vec3(-3, 0, 5));  // j along +z, k along −y (LPS)
  // ElementSpacing wins over ElementSize.
  EXPECT_EQ(importVolume(write("both.mha", metaHeader("1 1 1", "MET_UCHAR",
                                                      "ElementSize = 9 9 9\n"
                                                      "ElementSpacing = 1 2 3\n") +
                                               "x"))
                .spacing(),
            glm::vec3(1, 2, 3));

  struct Case {
    const char* met;
    const char* name;
    std::string bytes;  // voxel 0 and 1, little- then big-endian
    std::string big;
    float first, second;
  };
  const Case cases[] = {
      {"MET_UCHAR", "u8", encode<std::uint8_t>({250, 1}), encode<std::uint8_t>({250, 1}), 250, 1},
      {"MET_CHAR", "i8", encode<std::int8_t>({-120, 1}), encode<std::int8_t>({-120, 1}), -120, 1},
      {"MET_USHORT", "u16", encode<std::uint16_t>({65535, 1}),
       encode<std::uint16_t>({65535, 1}, true), 65535, 1},
      {"MET_SHORT", "i16", encode<std::int16_t>({-30000, 1}),
       encode<std::int16_t>({-30000, 1}, true), -30000, 1},
      {"MET_UINT", "u32", encode<std::uint32_t>({4000000000u, 1}),
       encode<std::uint32_t>({4000000000u, 1}, true), 4000000000.0f, 1},
      {"MET_INT", "i32", encode<std::int32_t>({-2000000000, 1}),
       encode<std::int32_t>({-2000000000, 1}, true), -2000000000.0f, 1},
      {"MET_FLOAT", "f32", encode<float>({-1.25f, 1}), encode<float>({-1.25f, 1}, true), -1.25f, 1},
      {"MET_DOUBLE", "f64", encode<double>({0.1, 1}), encode<double>({0.1, 1}, true), float(0.1),
       1},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.met);
    for (const bool big : {false, true}) {
      const Volume t = importVolume(
          write("t.mha", metaHeader("2 1 1", c.met, big ? "BinaryDataByteOrderMSB = True\n" : "") +
                             (big ? c.big : c.bytes)));
      EXPECT_EQ(t.voxelType, c.name);
      EXPECT_EQ(t.values, std::vector<float>({c.first, c.second}));
    }
  }
}

TEST_F(VolumeImportTest, MhdWithARawFileHeaderSizeAndCompression) {
  const std::string voxels = encode(fill<std::int16_t>(kSmall, smallValue));
  const std::vector<float> expected = fill<float>(kSmall, smallValue);
  write("v.raw", voxels);
  EXPECT_EQ(importVolume(write("v.mhd", metaHeader("2 3 4", "MET_SHORT", "", "v.raw"))).values,
            expected);
  // HeaderSize: bytes to skip in the data file; −1: the data are its last bytes.
  write("skip.raw", "seven b" + voxels);
  EXPECT_EQ(importVolume(
                write("skip.mhd", metaHeader("2 3 4", "MET_SHORT", "HeaderSize = 7\n", "skip.raw")))
                .values,
            expected);
  write("end.raw", std::string(33, '?') + voxels);
  EXPECT_EQ(importVolume(
                write("end.mhd", metaHeader("2 3 4", "MET_SHORT", "HeaderSize = -1\n", "end.raw")))
                .values,
            expected);
  // HeaderSize in a LOCAL file counts from the end of the header.
  EXPECT_EQ(importVolume(write("local.mha", metaHeader("2 3 4", "MET_SHORT", "HeaderSize = 3\n") +
                                                "abc" + voxels))
                .values,
            expected);
  // zlib-compressed, with and without CompressedDataSize, attached and in a file of its own.
  const std::string z = deflated(voxels);
  for (const std::string& size : {std::string(), std::to_string(z.size())}) {
    SCOPED_TRACE("CompressedDataSize " + size);
    const std::string extra =
        "CompressedData = True\n" + (size.empty() ? "" : "CompressedDataSize = " + size + "\n");
    EXPECT_EQ(importVolume(write("z.mha", metaHeader("2 3 4", "MET_SHORT", extra) + z)).values,
              expected);
    write("z.zraw", z);
    EXPECT_EQ(
        importVolume(write("z.mhd", metaHeader("2 3 4", "MET_SHORT", extra, "z.zraw"))).values,
        expected);
  }
  // The compressed size bounds the stream: bytes after it are not read.
  EXPECT_EQ(importVolume(write("zs.mha", metaHeader("2 3 4", "MET_SHORT",
                                                    "CompressedData = True\nCompressedDataSize = " +
                                                        std::to_string(z.size()) + "\n") +
                                             z + "trailing"))
                .values,
            expected);
  // Text voxels.
  const Volume ascii = importVolume(write(
      "a.mha", metaHeader("2 3 4", "MET_SHORT", "BinaryData = False\n") + asText(expected, 7)));
  EXPECT_EQ(ascii.values, expected);
}

TEST_F(VolumeImportTest, MetaImageBadInput) {
  const std::string voxels = encode(fill<std::int16_t>(kSmall, smallValue));
  const auto bad = [&](const std::string& name, const std::string& bytes) {
    return [this, name, bytes] { importVolume(write(name, bytes)); };
  };
  const auto header = [](const std::string& extra, const std::string& dims = "2 3 4",
                         const std::string& type = "MET_SHORT") {
    return metaHeader(dims, type, extra);
  };
  expectError(bad("n.mha", header("NDims = 2\n", "2 3") + voxels),
              {"n.mha", "NDims is 2: only 3-D images are read"});
  expectError(bad("n4.mha", header("NDims = 4\n", "2 3 4 1") + voxels), {"NDims is 4"});
  expectError(bad("d.mha", header("", "2 3") + voxels),
              {"d.mha", "line 11", "DimSize: expected 3 integers, got \"2 3\""});
  expectError(bad("z.mha", header("", "2 0 4") + voxels),
              {"z.mha", "dims must be positive, got 2×0×4"});
  expectError(bad("neg.mha", header("", "2 -3 4") + voxels), {"dims must be positive"});
  expectError(bad("t.mha", header("", "2 3 4", "MET_LONG") + voxels),
              {"t.mha", "line 12", "unsupported ElementType \"MET_LONG\""});
  expectError(bad("t2.mha", header("", "2 3 4", "MET_UCHAR_ARRAY") + voxels),
              {"unsupported ElementType \"MET_UCHAR_ARRAY\""});
  expectError(bad("c.mha", header("ElementNumberOfChannels = 3\n") + voxels),
              {"c.mha", "ElementNumberOfChannels is 3: only single-channel"});
  std::string mesh = header("");
  mesh.replace(mesh.find("Image"), 5, "Mesh");
  expectError(bad("o.mha", mesh + voxels),
              {"o.mha", "line 1", "ObjectType is \"Mesh\": only Image is read"});
  expectError(bad("m.mha", header("TransformMatrix = 1 0 0 0 1 0 0 0\n") + voxels),
              {"m.mha", "TransformMatrix: expected 9 finite numbers"});
  expectError(bad("s.mha", header("TransformMatrix = 1 0 0 1 0 0 0 0 1\n") + voxels),
              {"s.mha", "TransformMatrix", "singular"});
  expectError(bad("sp.mha", header("ElementSpacing = 1 0 1\n") + voxels),
              {"sp.mha", "line 13", "ElementSpacing", "singular"});
  expectError(bad("nan.mha", header("Offset = 0 nan 0\n") + voxels),
              {"Offset: expected 3 finite numbers"});
  expectError(bad("allnan.mha",
                  header("", "2 3 4", "MET_FLOAT") + encode(std::vector<float>(24, std::nanf("")))),
              {"allnan.mha: no voxel holds a finite value as a 32-bit float"});
  expectError(bad("b.mha", header("BinaryData = maybe\n") + voxels),
              {"BinaryData: expected True or False, got \"maybe\""});
  expectError(bad("short.mha", header("") + voxels.substr(0, 47)),
              {"short.mha", "data", "truncated: 47 bytes of voxel data, expected 48"});
  expectError(bad("long.mha", header("") + voxels + "x"),
              {"long.mha", "49 bytes of voxel data, expected 48", "dims disagree"});
  expectError(bad("nodata.mha", "ObjectType = Image\nNDims = 3\nDimSize = 2 3 4\n"),
              {"nodata.mha", "no ElementDataFile line"});
  expectError(bad("nodims.mha", "NDims = 3\nElementType = MET_SHORT\nElementDataFile = LOCAL\n"),
              {"nodims.mha", "header", "no DimSize line"});
  expectError(bad("binary.mha", std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16)),
              {"binary.mha", "line 1", "expected \"Key = Value\", got \"\\x89PNG\""});
  expectError(bad("huge.mha", std::string(2 << 20, 'x')),
              {"huge.mha", "no end of the header in its first 1048576 bytes"});
  expectError(bad("missing.mhd", metaHeader("2 3 4", "MET_SHORT", "", "absent.raw")),
              {"missing.mhd", "data: ", "absent.raw: data file not found"});
  expectError(bad("list.mhd", metaHeader("2 3 4", "MET_SHORT", "", "LIST 2D")),
              {"list.mhd", "lists and patterns of data files are not read"});
  expectError(bad("pattern.mhd", metaHeader("2 3 4", "MET_SHORT", "", "slice%03d.raw 1 4 1")),
              {"pattern.mhd", "lists and patterns"});
  expectError(bad("hs.mha", header("HeaderSize = -2\n") + voxels),
              {"hs.mha", "HeaderSize must be −1"});
  expectError(bad("hs2.mha", header("HeaderSize = 49\n") + voxels),
              {"hs2.mha", "the file ends within the 49 bytes to skip"});
  // Compressed data: corrupt, cut short, longer than the dims, or a size past the file's end.
  std::string z = deflated(voxels);
  const std::string compressed = "CompressedData = True\n";
  expectError(bad("cut.mha", header(compressed) + z.substr(0, z.size() / 2)),
              {"cut.mha", "data", "truncated: ", "bytes of voxel data, expected 48"});
  std::string flipped = z;
  for (std::size_t i = 2; i < flipped.size(); ++i) flipped[i] = char(~flipped[i]);
  expectError(bad("flip.mha", header(compressed) + flipped),
              {"flip.mha", "data", "corrupt compressed data"});
  expectError(bad("notz.mha", header(compressed) + voxels), {"notz.mha", "corrupt compressed"});
  expectError(bad("more.mha", header(compressed) + deflated(voxels + "xy")),
              {"more.mha", "more inflated voxel data than the 48 bytes expected", "dims disagree"});
  expectError(bad("size.mha", header(compressed + "CompressedDataSize = 1000\n") + z),
              {"size.mha", "truncated: " + std::to_string(z.size()) +
                               " bytes of compressed data, expected 1000"});
  expectError(bad("hsz.mha", header(compressed + "HeaderSize = -1\n") + z),
              {"HeaderSize = −1 needs binary, uncompressed data or a CompressedDataSize"});
  // Text voxels: not numbers, out of the type's range, too few.
  expectError(bad("a.mha", header("BinaryData = False\n", "2 1 1", "MET_UCHAR") + "1 x"),
              {"a.mha", "data", "value 1, \"x\", is not a number"});
  expectError(bad("a2.mha", header("BinaryData = False\n", "2 1 1", "MET_UCHAR") + "1 300"),
              {"value 1, \"300\", does not fit u8"});
  expectError(bad("a3.mha", header("BinaryData = False\n", "2 1 1", "MET_UCHAR") + "1.5 3"),
              {"value 0, \"1.5\", does not fit u8"});
  expectError(bad("a4.mha", header("BinaryData = False\n", "2 1 1", "MET_UCHAR") + " 7\n"),
              {"truncated: 1 values, expected 2"});
  expectError([&] { importVolume(write("over.mha", header("") + voxels), {.maxVoxels = 20}); },
              {"over.mha", "line 11", "2×3×4 = 24 voxels exceed the limit of 20"});
}

// ----------------------------------------------------------------------------------------------
// NRRD

TEST_F(VolumeImportTest, NrrdAttachedRawWithSpaceDirectionsAndOrigin) {
  // As Slicer writes a scan: LPS, axes not aligned with the world, key/value pairs, kinds.
  const std::string fields =
      "type: short\ndimension: 3\nspace: left-posterior-superior\nsizes: 2 3 4\n"
      "space directions: (0,0.5,0) (-2,0,0) (0,0,3)\nkinds: domain domain domain\n"
      "endian: little\nencoding: raw\nspace origin: (10,-5,1)\nDICOM_tag:=0008|0060 CT\n"
      "labels: \"i\" \"j\" \"k\"\nspace units: \"mm\" \"mm\" \"mm\"\n\n";
  const Volume v = importVolume(
      write("v.nrrd", nrrdHeader(fields) + encode(fill<std::int16_t>(kSmall, smallValue))));
  EXPECT_EQ(v.dims, kSmall);
  EXPECT_EQ(v.voxelType, "i16");
  EXPECT_EQ(v.values, fill<float>(kSmall, smallValue));
  // (6, −4.5, 10) in the file's LPS, turned to RAS.
  EXPECT_EQ(world(v, {1, 2, 3}), glm::vec3(-6, 4.5f, 10));
  EXPECT_EQ(v.spacing(), glm::vec3(0.5f, 2, 3));
}

TEST_F(VolumeImportTest, NrrdSpacesLineUpInRas) {
  // One voxel grid described in each space: all place voxel (1, 2, 3) at RAS (6, −4.5, 10).
  const std::pair<const char*, const char*> cases[] = {
      {"right-anterior-superior", "(0,0.5,0) (-2,0,0) (0,0,3)\nspace origin: (10,-5,1)"},
      {"RAS", "(0,0.5,0) (-2,0,0) (0,0,3)\nspace origin: (10,-5,1)"},
      {"left-anterior-superior", "(0,0.5,0) (2,0,0) (0,0,3)\nspace origin: (-10,-5,1)"},
      {"left-posterior-superior", "(0,-0.5,0) (2,0,0) (0,0,3)\nspace origin: (-10,5,1)"},
      {"scanner-xyz", "(0,0.5,0) (-2,0,0) (0,0,3)\nspace origin: (10,-5,1)"}};
  for (const auto& [space, placement] : cases) {
    const std::string fields = std::string("type: uchar\ndimension: 3\nspace: ") + space +
                               "\nsizes: 2 3 4\nencoding: raw\nspace directions: " + placement +
                               "\n\n";
    const Volume v = importVolume(write("v.nrrd", nrrdHeader(fields) + std::string(24, '\1')));
    EXPECT_EQ(world(v, {1, 2, 3}), glm::vec3(6, -4.5f, 10)) << space;
  }
}

TEST_F(VolumeImportTest, NrrdGzipAsciiDetachedSkipsAndFourDimensions) {
  const std::string voxels = encode(fill<std::int16_t>(kSmall, smallValue), true);
  const std::vector<float> expected = fill<float>(kSmall, smallValue);
  const std::string common = "type: int16\ndimension: 3\nsizes: 2 3 4\nendian: big\n";
  EXPECT_EQ(importVolume(
                write("g.nrrd", nrrdHeader(common + "encoding: gzip\n\n") + deflated(voxels, true)))
                .values,
            expected);
  // gz, and a zlib stream too: the stream's header tells them apart.
  EXPECT_EQ(
      importVolume(write("z.nrrd", nrrdHeader(common + "encoding: gz\n\n") + deflated(voxels)))
          .values,
      expected);
  // A gzip byte skip counts inflated bytes.
  EXPECT_EQ(importVolume(write("gs.nrrd", nrrdHeader(common + "encoding: gzip\nbyte skip: 5\n\n") +
                                              deflated("12345" + voxels, true)))
                .values,
            expected);
  EXPECT_EQ(importVolume(write("a.nrrd", nrrdHeader("type: short\ndimension: 3\nsizes: 2 3 4\n"
                                                    "encoding: ascii\n\n") +
                                             asText(expected, 4)))
                .values,
            expected);
  // Detached: the data file beside the header, after lines and bytes to skip.
  write("v.raw", "a line\nanother\nxyz" + voxels);
  const Volume d = importVolume(
      write("v.nhdr", nrrdHeader(common + "encoding: raw\ndata file: v.raw\nline skip: 2\n"
                                          "byte skip: 3\nspacings: 0.5 0.25 2\n")));
  EXPECT_EQ(d.values, expected);
  EXPECT_EQ(d.indexToWorld, glm::mat4(glm::vec4(0.5f, 0, 0, 0), glm::vec4(0, 0.25f, 0, 0),
                                      glm::vec4(0, 0, 2, 0), glm::vec4(0, 0, 0, 1)));
  // byte skip −1: the data end the file.
  write("end.raw", std::string(100, '#') + voxels);
  EXPECT_EQ(importVolume(write("end.nhdr", nrrdHeader(common + "encoding: raw\n"
                                                               "datafile: end.raw\n"
                                                               "byteskip: -1\n")))
                .values,
            expected);
  write("v.raw.gz", deflated(voxels, true));
  EXPECT_EQ(importVolume(write("gz.NHDR", nrrdHeader(common + "encoding: gzip\n"
                                                              "data file: v.raw.gz\n")))
                .values,
            expected);
  // 4-D with a first axis of one sample.
  const Volume four = importVolume(write(
      "four.nrrd",
      nrrdHeader("type: float\ndimension: 4\nspace: RAS\nsizes: 1 2 3 4\n"
                 "space directions: none (1,0,0) (0,1,0) (0,0,1)\nendian: little\nencoding: raw\n"
                 "space origin: (1, 2, 3)\nkinds: vector domain domain domain\n\n") +
          encode(fill<float>(kSmall, smallValue))));
  EXPECT_EQ(four.dims, kSmall);
  EXPECT_EQ(four.voxelType, "f32");
  EXPECT_EQ(four.values, expected);
  EXPECT_EQ(world(four, {1, 1, 1}), glm::vec3(2, 3, 4));
  const Volume spaced = importVolume(
      write("s4.nrrd", nrrdHeader("type: uchar\ndimension: 4\nsizes: 1 2 1 1\nspacings: nan 2 3 4\n"
                                  "encoding: raw\n\n") +
                           "ab"));
  EXPECT_EQ(spaced.spacing(), glm::vec3(2, 3, 4));
}

TEST_F(VolumeImportTest, NrrdEveryTypeSpelling) {
  struct Case {
    const char* spelling;
    const char* name;
    std::string bytes;  // big-endian
    float value;
  };
  std::vector<Case> cases;
  for (const char* s : {"signed char", "int8", "int8_t"})
    cases.push_back({s, "i8", encode<std::int8_t>({-100}), -100});
  for (const char* s : {"uchar", "unsigned char", "uint8", "uint8_t"})
    cases.push_back({s, "u8", encode<std::uint8_t>({200}), 200});
  for (const char* s :
       {"short", "short int", "signed short", "signed short int", "int16", "int16_t"})
    cases.push_back({s, "i16", encode<std::int16_t>({-300}, true), -300});
  for (const char* s : {"ushort", "unsigned short", "unsigned short int", "uint16", "uint16_t"})
    cases.push_back({s, "u16", encode<std::uint16_t>({60000}, true), 60000});
  for (const char* s : {"int", "signed int", "int32", "int32_t"})
    cases.push_back({s, "i32", encode<std::int32_t>({-70000}, true), -70000});
  for (const char* s : {"uint", "unsigned int", "uint32", "uint32_t"})
    cases.push_back({s, "u32", encode<std::uint32_t>({70000}, true), 70000});
  cases.push_back({"float", "f32", encode<float>({-1.5f}, true), -1.5f});
  cases.push_back({"double", "f64", encode<double>({0.1}, true), float(0.1)});
  for (const Case& c : cases) {
    SCOPED_TRACE(c.spelling);
    const Volume v = importVolume(
        write("t.nrrd", nrrdHeader(std::string("type: ") + c.spelling +
                                   "\ndimension: 3\nsizes: 1 1 1\nendian: big\nencoding: raw\n\n") +
                            c.bytes));
    EXPECT_EQ(v.voxelType, c.name);
    EXPECT_EQ(v.values, std::vector<float>({c.value}));
  }
}

TEST_F(VolumeImportTest, NrrdBadInput) {
  const std::string voxels = encode(fill<std::int16_t>(kSmall, smallValue));
  const std::string type = "type: short\n", dims = "dimension: 3\n", sizes = "sizes: 2 3 4\n",
                    endian = "endian: little\n", raw = "encoding: raw\n";
  const auto bad = [&](const std::string& name, const std::string& fields,
                       const std::string& data) {
    return [this, name, fields, data] { importVolume(write(name, nrrdHeader(fields) + data)); };
  };
  const std::string ok = type + dims + sizes + endian + raw;
  expectError([&] { importVolume(write("magic.nrrd", "NRRD0009\n" + ok + "\n" + voxels)); },
              {"magic.nrrd", "header", "not a NRRD file"});
  expectError([&] { importVolume(write("empty.nrrd", "")); }, {"empty.nrrd", "not a NRRD file"});
  expectError(bad("d2.nrrd", type + "dimension: 2\nsizes: 2 3\n" + endian + raw + "\n", voxels),
              {"d2.nrrd", "line 5", "dimension is 2: only 3-D volumes"});
  expectError(bad("d4.nrrd", type + "dimension: 4\nsizes: 3 2 3 4\n" + endian + raw + "\n", voxels),
              {"d4.nrrd", "a 4-D volume whose first axis has 3 samples"});
  expectError(bad("s.nrrd", type + dims + "sizes: 2 3\n" + endian + raw + "\n", voxels),
              {"s.nrrd", "line 6", "sizes: expected 3 integers, got \"2 3\""});
  expectError(bad("z.nrrd", type + dims + "sizes: 2 0 4\n" + endian + raw + "\n", ""),
              {"z.nrrd", "dims must be positive, got 2×0×4"});
  expectError(
      [&] { importVolume(write("over.nrrd", nrrdHeader(ok + "\n") + voxels), {.maxVoxels = 10}); },
      {"over.nrrd", "line 6", "2×3×4 = 24 voxels exceed the limit of 10"});
  expectError(bad("t.nrrd", "type: complex\n" + dims + sizes + endian + raw + "\n", voxels),
              {"t.nrrd", "line 4", "unknown type \"complex\""});
  expectError(bad("t64.nrrd", "type: long long\n" + dims + sizes + endian + raw + "\n", voxels),
              {"unsupported type \"long long\""});
  expectError(bad("char.nrrd", "type: char\n" + dims + sizes + raw + "\n", voxels),
              {"unknown type \"char\""});
  expectError(bad("bz.nrrd", type + dims + sizes + endian + "encoding: bzip2\n\n", voxels),
              {"bz.nrrd", "unsupported encoding \"bzip2\" (raw, gzip and ascii are read)"});
  expectError(bad("hex.nrrd", type + dims + sizes + endian + "encoding: hex\n\n", voxels),
              {"unsupported encoding \"hex\""});
  expectError(bad("e.nrrd", type + dims + sizes + endian + "encoding: rot13\n\n", voxels),
              {"unknown encoding \"rot13\""});
  expectError(bad("noendian.nrrd", type + dims + sizes + raw + "\n", voxels),
              {"noendian.nrrd", "header", "no \"endian\" field, needed for short data"});
  expectError(bad("endian.nrrd", type + dims + sizes + "endian: middle\n" + raw + "\n", voxels),
              {"endian: expected little or big"});
  expectError(bad("f.nrrd", ok + "colour: red\n\n", voxels),
              {"f.nrrd", "line 9", "unknown field \"colour\""});
  expectError(bad("twice.nrrd", ok + "type: short\n\n", voxels), {"field \"type\" given twice"});
  expectError(bad("line.nrrd", ok + "no colon here\n\n", voxels),
              {"line.nrrd", "line 9", "expected \"field: description\""});
  expectError(bad("nosize.nrrd", type + dims + endian + raw + "\n", voxels),
              {"nosize.nrrd", "header", "no \"sizes\" field"});
  const std::string space = "space: LPS\n";
  expectError(bad("dir.nrrd", ok + space + "space directions: (1,0,0) (0,1,0)\n\n", voxels),
              {"dir.nrrd", "space directions: expected 3 vectors (or none)"});
  expectError(bad("dir2.nrrd", ok + space + "space directions: (1,0,0) (0,1) (0,0,1)\n\n", voxels),
              {"space directions: expected 3 vectors"});
  expectError(
      bad("dir3.nrrd", ok + space + "space directions: (1,0,0) (0,1,0) (0,0,inf)\n\n", voxels),
      {"space directions: expected 3 vectors"});
  expectError(bad("none.nrrd", ok + space + "space directions: (1,0,0) none (0,0,1)\n\n", voxels),
              {"none.nrrd", "axis 1 of the volume has no direction"});
  expectError(bad("nospace.nrrd", ok + "space directions: (1,0,0) (0,1,0) (0,0,1)\n\n", voxels),
              {"space directions without a \"space\""});
  expectError(
      bad("flat.nrrd", ok + space + "space directions: (1,0,0) (2,0,0) (0,0,1)\n\n", voxels),
      {"flat.nrrd", "line 10", "singular"});
  expectError(bad("sp.nrrd", ok + space + "space: RAS\n\n", voxels), {"given twice"});
  expectError(bad("unk.nrrd", ok + "space: up-down-sideways\n\n", voxels),
              {"unknown space \"up-down-sideways\""});
  expectError(bad("time.nrrd", ok + "space: right-anterior-superior-time\n\n", voxels),
              {"has time as a 4th axis"});
  expectError(bad("sd.nrrd", ok + "space dimension: 2\n\n", voxels),
              {"space dimension is 2: only 3 is read"});
  expectError(bad("spacings.nrrd", ok + "spacings: 1 nan 1\n\n", voxels),
              {"spacings: axis 1 needs a finite spacing, got \"nan\""});
  expectError(bad("short.nrrd", ok + "\n", voxels.substr(0, 40)),
              {"short.nrrd", "data", "truncated: 40 bytes of voxel data, expected 48"});
  expectError(bad("long.nrrd", ok + "\n", voxels + "\n"),
              {"long.nrrd", "49 bytes of voxel data, expected 48", "dims disagree"});
  expectError(bad("noblank.nrrd", ok, ""),
              {"noblank.nrrd", "no \"data file\" field and no blank line before attached data"});
  expectError(bad("nofile.nhdr", ok + "data file: absent.raw\n", ""),
              {"nofile.nhdr", "data: ", "absent.raw: data file not found"});
  expectError(bad("list.nhdr", ok + "data file: LIST\n", ""), {"lists and patterns"});
  expectError(bad("pattern.nhdr", ok + "data file: slice%03d.raw 1 4 1 2\n", ""),
              {"lists and patterns"});
  expectError(bad("ls.nrrd", ok + "line skip: 3\n\n", "one\ntwo\n"),
              {"ls.nrrd", "the file ends within the 3 lines to skip"});
  expectError(bad("bs.nrrd", ok + "byte skip: 100\n\n", voxels),
              {"bs.nrrd", "the file ends within the 100 bytes to skip"});
  expectError(bad("bs2.nrrd", ok + "byte skip: -2\n\n", voxels), {"byte skip must be −1"});
  const std::string gzip = type + dims + sizes + endian + "encoding: gzip\n";
  expectError(bad("bsg.nrrd", gzip + "byte skip: -1\n\n", deflated(voxels, true)),
              {"byte skip −1 needs raw encoding"});
  const std::string gz = deflated(voxels, true);
  expectError(bad("cut.nrrd", gzip + "\n", gz.substr(0, gz.size() - 20)),
              {"cut.nrrd", "data", "truncated"});
  std::string corrupt = gz;
  for (std::size_t i = 10; i < corrupt.size() - 8; ++i) corrupt[i] = char(corrupt[i] ^ 0x55);
  expectError(bad("corrupt.nrrd", gzip + "\n", corrupt),
              {"corrupt.nrrd", "data", "corrupt compressed data"});
  std::string crc = gz;
  crc[crc.size() - 6] = char(crc[crc.size() - 6] ^ 1);  // the CRC-32 in the gzip trailer
  expectError(bad("crc.nrrd", gzip + "\n", crc), {"crc.nrrd", "corrupt compressed data"});
  expectError(bad("gmore.nrrd", gzip + "\n", deflated(voxels + "xx", true)),
              {"gmore.nrrd", "dims disagree"});
  expectError(bad("gskip.nrrd", gzip + "byte skip: 60\n\n", gz),
              {"gskip.nrrd", "the inflated data end within the 60 bytes to skip"});
  const std::string ascii = "type: uchar\n" + dims + "sizes: 2 1 1\nencoding: text\n\n";
  expectError(bad("a.nrrd", ascii, "1 -1"), {"a.nrrd", "data", "value 1, \"-1\", does not fit u8"});
  expectError(bad("a2.nrrd", ascii, "1,2"), {"value 0, \"1,2\", is not a number"});
  expectError(bad("a3.nrrd", ascii, "\n"), {"truncated: 0 values, expected 2"});
}

// ----------------------------------------------------------------------------------------------
// VTK legacy structured points

TEST_F(VolumeImportTest, VtkBinaryAndAscii) {
  const std::vector<float> expected = fill<float>(kSmall, smallValue);
  // vtkStructuredPointsWriter's BINARY output: big-endian, a newline after the data.
  const Volume b = importVolume(write(
      "b.vtk",
      vtkHeader("BINARY", "DIMENSIONS 2 3 4\nSPACING 0.5 2 3\nORIGIN 10 -5 1\n", 24, "short 1") +
          encode(fill<std::int16_t>(kSmall, smallValue), true) + "\n"));
  EXPECT_EQ(b.dims, kSmall);
  EXPECT_EQ(b.voxelType, "i16");
  EXPECT_EQ(b.values, expected);
  EXPECT_EQ(world(b, {1, 2, 3}), glm::vec3(10.5f, -1, 10));
  // ASCII, keywords in any case and order, ASPECT_RATIO for SPACING, CRLF line ends.
  const Volume a = importVolume(
      write("A.VTK",
            "# vtk DataFile Version 2.0\r\ntitle\r\nascii\r\ndataset structured_points\r\n"
            "origin 1 2 3\r\n\r\naspect_ratio 1 1 2\r\ndimensions 2 3 4\r\npoint_data 24\r\n"
            "scalars density float\r\nlookup_table default\r\n" +
                asText(expected, 6) + "\r\nVECTORS v float\r\n"));
  EXPECT_EQ(a.voxelType, "f32");
  EXPECT_EQ(a.values, expected);
  EXPECT_EQ(world(a, {1, 1, 1}), glm::vec3(2, 3, 5));
  // Defaults: spacing 1, origin 0.
  EXPECT_EQ(importVolume(write("d.vtk", vtkHeader("ASCII", "DIMENSIONS 1 1 2\n", 2, "int") + "5 6"))
                .indexToWorld,
            glm::mat4(1.0f));

  struct Case {
    const char* type;
    const char* name;
    std::string bytes;  // big-endian
    float value;
  };
  const Case cases[] = {
      {"unsigned_char", "u8", encode<std::uint8_t>({250}), 250},
      {"char", "i8", encode<std::int8_t>({-120}), -120},
      {"unsigned_short", "u16", encode<std::uint16_t>({65535}, true), 65535},
      {"short", "i16", encode<std::int16_t>({-30000}, true), -30000},
      {"unsigned_int", "u32", encode<std::uint32_t>({4000000000u}, true), 4000000000.0f},
      {"int", "i32", encode<std::int32_t>({-2000000000}, true), -2000000000.0f},
      {"float", "f32", encode<float>({-1.25f}, true), -1.25f},
      {"double", "f64", encode<double>({0.1}, true), float(0.1)},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.type);
    const Volume v = importVolume(
        write("t.vtk", vtkHeader("BINARY", "DIMENSIONS 1 1 1\n", 1, c.type) + c.bytes));
    EXPECT_EQ(v.voxelType, c.name);
    EXPECT_EQ(v.values, std::vector<float>({c.value}));
  }
}

TEST_F(VolumeImportTest, VtkBadInput) {
  const std::string voxels = encode(fill<std::int16_t>(kSmall, smallValue), true);
  const std::string geometry = "DIMENSIONS 2 3 4\n";
  const auto bad = [&](const std::string& name, const std::string& bytes) {
    return [this, name, bytes] { importVolume(write(name, bytes)); };
  };
  expectError(bad("x.vtk", "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\">\n"),
              {"x.vtk", "header", "not a VTK legacy file"});
  expectError(bad("poly.vtk", "# vtk DataFile Version 3.0\nt\nASCII\nDATASET POLYDATA\n"),
              {"poly.vtk", "line 4", "DATASET POLYDATA is not read, only STRUCTURED_POINTS"});
  expectError(bad("grid.vtk", "# vtk DataFile Version 5.1\nt\nBINARY\nDATASET unstructured_grid\n"),
              {"DATASET UNSTRUCTURED_GRID is not read"});
  expectError(bad("fmt.vtk", "# vtk DataFile Version 3.0\nt\nXML\nDATASET STRUCTURED_POINTS\n"),
              {"fmt.vtk", "line 3", "expected ASCII or BINARY, got \"XML\""});
  expectError(bad("title.vtk", "# vtk DataFile Version 3.0\n"), {"no title line"});
  expectError(bad("ds.vtk", "# vtk DataFile Version 3.0\nt\nASCII\nDIMENSIONS 2 3 4\n"),
              {"ds.vtk", "line 4", "expected DATASET"});
  expectError(bad("dims.vtk", vtkHeader("BINARY", "DIMENSIONS 2 3\n", 6, "short") + voxels),
              {"dims.vtk", "line 5", "DIMENSIONS: expected 3 values, got \"DIMENSIONS 2 3\""});
  expectError(bad("nodims.vtk", vtkHeader("BINARY", "SPACING 1 1 1\n", 6, "short") + voxels),
              {"nodims.vtk", "header", "no DIMENSIONS line"});
  expectError(bad("zero.vtk", vtkHeader("BINARY", "DIMENSIONS 2 0 4\n", 0, "short")),
              {"zero.vtk", "dims must be positive, got 2×0×4"});
  expectError(bad("points.vtk", vtkHeader("BINARY", geometry, 25, "short") + voxels),
              {"points.vtk", "line 6", "POINT_DATA 25 disagrees with DIMENSIONS 2×3×4 = 24"});
  expectError(bad("comp.vtk", vtkHeader("BINARY", geometry, 24, "short 3") + voxels),
              {"comp.vtk", "line 7", "SCALARS of 3 components: only 1 is read"});
  expectError(bad("long.vtk", vtkHeader("BINARY", geometry, 24, "long") + voxels),
              {"long.vtk", "unsupported SCALARS type \"long\""});
  expectError(bad("bit.vtk", vtkHeader("BINARY", geometry, 24, "bit") + voxels),
              {"unsupported SCALARS type \"bit\""});
  expectError(bad("vec.vtk", "# vtk DataFile Version 3.0\nt\nBINARY\nDATASET STRUCTURED_POINTS\n" +
                                 geometry + "POINT_DATA 24\nVECTORS v float\n"),
              {"vec.vtk", "the first point data are \"VECTORS\": only SCALARS are read"});
  expectError(bad("cell.vtk", "# vtk DataFile Version 3.0\nt\nBINARY\nDATASET STRUCTURED_POINTS\n" +
                                  geometry + "CELL_DATA 6\n"),
              {"cell.vtk", "unexpected \"CELL_DATA\""});
  expectError(bad("lut.vtk", "# vtk DataFile Version 3.0\nt\nBINARY\nDATASET STRUCTURED_POINTS\n" +
                                 geometry + "POINT_DATA 24\nSCALARS s short\n" + voxels),
              {"lut.vtk", "expected \"LOOKUP_TABLE name\" after SCALARS"});
  expectError(
      bad("nolut.vtk", "# vtk DataFile Version 3.0\nt\nBINARY\nDATASET STRUCTURED_POINTS\n" +
                           geometry + "POINT_DATA 24\nSCALARS s short\n"),
      {"nolut.vtk", "truncated header: no LOOKUP_TABLE"});
  expectError(bad("short.vtk", vtkHeader("BINARY", geometry, 24, "short") + voxels.substr(0, 47)),
              {"short.vtk", "data", "truncated: 47 bytes of voxel data, expected 48"});
  expectError(bad("ascii.vtk", vtkHeader("ASCII", geometry, 24, "short") + "1 2 3"),
              {"ascii.vtk", "data", "truncated: 3 values, expected 24"});
  expectError(bad("range.vtk", vtkHeader("ASCII", "DIMENSIONS 1 1 1\n", 1, "short") + "40000"),
              {"value 0, \"40000\", does not fit i16"});
  expectError(
      bad("sing.vtk", vtkHeader("BINARY", geometry + "SPACING 1 0 1\n", 24, "short") + voxels),
      {"sing.vtk", "line 6", "singular"});
  expectError(
      [&] {
        importVolume(write("over.vtk", vtkHeader("BINARY", geometry, 24, "short") + voxels),
                     {.maxVoxels = 23});
      },
      {"over.vtk", "DIMENSIONS", "2×3×4 = 24 voxels exceed the limit of 23"});
}

// ----------------------------------------------------------------------------------------------
// DICOM series

TEST_F(VolumeImportTest, DicomSeriesSortedPlacedAndRescaled) {
  // File names out of slice order; a text file and a DICOM file without an image beside them.
  for (int k = 0; k < kSeries.z; ++k)
    writeDicom(dir_ / ("im" + std::to_string(k * 3 % 5) + ".dcm"), seriesSlice(k), k + 1);
  write("README.txt", "not DICOM\n");
  DicomSpec report;
  report.image = false;
  writeDicom(dir_ / "report.dcm", report, 99);

  const Volume v = importVolume(dir_);
  EXPECT_EQ(v.dims, kSeries);
  EXPECT_EQ(v.voxelType, "i16");
  for (int k = 0; k < kSeries.z; ++k)
    for (int j = 0; j < kSeries.y; ++j)
      for (int i = 0; i < kSeries.x; ++i)
        ASSERT_EQ(v.at({i, j, k}), float(2 * seriesValue(i, j, k) - 1024 + k)) << i << j << k;
  EXPECT_EQ(v.minValue, 2.0f * -200 - 1024);
  EXPECT_EQ(v.maxValue, 2.0f * seriesValue(7, 5, 4) - 1024 + 4);
  // i along the row direction by the column spacing (PixelSpacing[1] = 0.75), j down the
  // column direction by the row spacing (PixelSpacing[0] = 0.5), k along the normal; the
  // patient's LPS turned to RAS (x and y negated).
  const glm::mat4 expected(glm::vec4(0, -0.75f, 0, 0), glm::vec4(0, 0, -0.5f, 0),
                           glm::vec4(2.5f, 0, 0, 0), glm::vec4(-5, 20, 30, 1));
  EXPECT_EQ(v.indexToWorld, expected);
  EXPECT_EQ(world(v, {7, 5, 4}), glm::vec3(5, 14.75f, 27.5f));
}

TEST_F(VolumeImportTest, DicomTiltedGantrySlicesStepSideways) {
  for (int k = 0; k < 3; ++k) {
    DicomSpec s;
    s.orientation = "1\\0\\0\\0\\1\\0";
    s.position = "0\\" + std::to_string(0.5 * k) + "\\" + std::to_string(2 * k);
    s.slope = "1", s.intercept = "0";
    writeDicom(dir_ / ("s" + std::to_string(k) + ".dcm"), s, k + 1);
  }
  const Volume v = importVolume(dir_);
  EXPECT_EQ(v.dims, glm::ivec3(8, 6, 3));
  EXPECT_EQ(glm::vec3(v.indexToWorld[2]), glm::vec3(0, -0.5f, 2));  // LPS (0, 0.5, 2) in RAS
  EXPECT_EQ(v.values, std::vector<float>(8 * 6 * 3, 0.0f));
}

TEST_F(VolumeImportTest, DicomSeveralSeriesOrAMissingSlice) {
  const fs::path mixed = dir_ / "mixed", gap = dir_ / "gap", uneven = dir_ / "uneven";
  for (const fs::path& d : {mixed, gap, uneven}) fs::create_directories(d);
  for (int k = 0; k < kSeries.z; ++k) {
    writeDicom(mixed / ("a" + std::to_string(k) + ".dcm"), seriesSlice(k), k + 1);
    if (k != 2) writeDicom(gap / ("a" + std::to_string(k) + ".dcm"), seriesSlice(k), k + 1);
  }
  DicomSpec other = seriesSlice(0);
  other.series = "1.2.826.0.1.3680043.2.1125.2";
  writeDicom(mixed / "other.dcm", other, 1);
  expectError([&] { importVolume(mixed); }, {"mixed", "2 series in the folder, one expected",
                                             "1.2.826.0.1.3680043.2.1125.1 (5 images)",
                                             "1.2.826.0.1.3680043.2.1125.2 (1 image)"});
  expectError([&] { importVolume(gap); }, {"gap", "a gap of 5 mm between", "a1.dcm", "a3.dcm",
                                           "(at -2.5 mm and 2.5 mm along the normal)",
                                           "the step elsewhere 2.5 mm: 1 slice(s) missing"});
  for (int k : {0, 1, 3}) {
    DicomSpec s = seriesSlice(k);
    if (k == 3) s.position = "-3.5\\-20\\30";  // 3.5 mm after slice 1, not 2.5 or 5
    writeDicom(uneven / ("u" + std::to_string(k) + ".dcm"), s, k + 1);
  }
  expectError([&] { importVolume(uneven); },
              {"uneven slice spacing: 6 mm between", "u1.dcm", "u3.dcm"});
}

TEST_F(VolumeImportTest, DicomBadInput) {
  // Each case: a folder of the series' first three slices, `change` applied to slice 1.
  int folder = 0;
  const auto series = [&](auto change) {
    const fs::path d = dir_ / ("case" + std::to_string(folder++));
    fs::create_directories(d);
    for (int k = 0; k < 3; ++k) {
      DicomSpec s = seriesSlice(k);
      if (k == 1) change(s);
      writeDicom(d / ("s" + std::to_string(k) + ".dcm"), s, k + 1);
    }
    return d;
  };
  expectError([&] { importVolume(series([](DicomSpec& s) { s.rows = 5; })); },
              {"images of different sizes: 8×6 in", "s0.dcm", "8×5 in", "s1.dcm"});
  expectError(
      [&] { importVolume(series([](DicomSpec& s) { s.orientation = "0\\0\\1\\0\\1\\0"; })); },
      {"images of different orientations", "s1.dcm"});
  expectError([&] { importVolume(series([](DicomSpec& s) { s.spacing = "0.5\\0.5"; })); },
              {"images of different pixel spacings"});
  expectError([&] { importVolume(series([](DicomSpec& s) { s.position = "5\\-20\\30"; })); },
              {"two images at the same position, -5 mm along the normal", "s0.dcm", "s1.dcm"});
  expectError([&] { importVolume(series([](DicomSpec& s) { s.position = "2.5\\-19\\30"; })); },
              {"the image positions do not lie on a line", "s1.dcm"});
  expectError(
      [&] { importVolume(series([](DicomSpec& s) { s.orientation = "0\\1\\0\\0\\1\\0"; })); },
      {"s1.dcm", "(0020,0037) ImageOrientationPatient", "not two orthogonal unit vectors"});
  expectError([&] { importVolume(series([](DicomSpec& s) { s.position = ""; })); },
              {"s1.dcm", "(0020,0032) ImagePositionPatient", "missing"});
  expectError([&] { importVolume(series([](DicomSpec& s) { s.position = "1\\2"; })); },
              {"(0020,0032) ImagePositionPatient", "expected 3 finite numbers"});
  expectError([&] { importVolume(series([](DicomSpec& s) { s.spacing = "0\\0.5"; })); },
              {"(0028,0030) PixelSpacing", "not positive"});
  expectError([&] { importVolume(series([](DicomSpec& s) { s.slope = "two"; })); },
              {"(0028,1053) RescaleSlope", "expected 1 finite number, got \"two\""});
  // GDCM asserted (aborted) on a slope of 0 (fuzzing; tests/data/fuzz/volume-dicom).
  expectError([&] { importVolume(series([](DicomSpec& s) { s.slope = "0.0"; })); },
              {"s1.dcm", "(0028,1053) RescaleSlope", "is 0"});
  expectError(
      [&] { importVolume(series([](DicomSpec& s) { s.slope = ""; })); },
      {"s1.dcm", "(0028,1053) RescaleSlope", "missing beside (0028,1052) RescaleIntercept"});
  expectError(
      [&] { importVolume(series([](DicomSpec& s) { s.frames = "2"; })); },
      {"s1.dcm", "(0028,0008) NumberOfFrames", "\"2\" frames: only single-frame images are read"});
  // A slice without SeriesInstanceUID is a series of its own.
  expectError([&] { importVolume(series([](DicomSpec& s) { s.series = ""; })); },
              {"2 series", "(none) (1 image)"});
  expectError([&] { importVolume(series([](DicomSpec&) {}), {.maxVoxels = 100}); },
              {"8×6×3 = 144 voxels exceed the limit of 100"});
  // A RecognitionCode that is not ACR-NEMA's: GDCM asserted and aborted (fuzzing;
  // tests/data/fuzz/volume-dicom). ACR-NEMA's own is read.
  expectError([&] { importVolume(series([](DicomSpec& s) { s.recognition = "CT-SCAN"; })); },
              {"s1.dcm", "(0008,0010) RecognitionCode \"CT-SCAN \" is not ACR-NEMA's"});
  EXPECT_EQ(importVolume(series([](DicomSpec& s) { s.recognition = "ACR-NEMA 2.0"; })).dims,
            glm::ivec3(8, 6, 3));

  // No images at all.
  fs::create_directories(dir_ / "empty");
  std::ofstream(dir_ / "empty" / "notes.txt") << "no DICOM here";
  expectError([&] { importVolume(dir_ / "empty"); },
              {"empty", "no DICOM images in the folder (1 files)"});

  // A 1 KB file whose element claims 2 GB is refused before GDCM allocates them.
  const fs::path one = series([](DicomSpec&) {});
  std::ifstream in(one / "s0.dcm", std::ios::binary);  // explicit VR
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t pixelData = bytes.rfind(std::string("\xE0\x7F\x10\x00OW", 6));
  ASSERT_NE(pixelData, std::string::npos);
  std::string huge = bytes;
  huge.insert(pixelData, std::string("\x29\x00\x10\x10UN\0\0\xF0\xFF\xFF\x7Fxxxx", 16));
  std::ofstream(one / "s0.dcm", std::ios::binary) << huge;
  expectError([&] { importVolume(one); }, {"s0.dcm", "claims 2147483632 bytes, more than the"});
  std::ofstream(one / "s0.dcm", std::ios::binary) << bytes.substr(0, pixelData + 20);
  expectError([&] { importVolume(one); }, {"s0.dcm", "claims 96 bytes, more than the 8 left"});
  std::ofstream(one / "s0.dcm", std::ios::binary) << bytes.substr(0, 300);
  expectError([&] { importVolume(one); }, {"s0.dcm", "DICOM element"});
}

// ----------------------------------------------------------------------------------------------
// Formats, files and ranges

TEST_F(VolumeImportTest, UnknownFormatOrMissingFile) {
  for (const char* name : {"volume.vti", "volume", "volume.nii.gz.bak", "volume.raw", "v.dcm"})
    expectError([&] { importVolume(write(name, "x")); },
                {name,
                 "unknown volume format (expected .nii, .nii.gz, .npy, .npz, .den, .json, "
                 ".mha, .mhd, .nrrd, .nhdr, .vtk or a folder of DICOM images)"});
  for (const char* name :
       {"absent.nii.gz", "absent.npz", "absent.json", "absent.mha", "absent.nhdr", "absent.vtk"})
    expectError([&] { importVolume(dir_ / name); }, {name, "volume file not found"});
  // A folder is a DICOM series, whatever its name.
  fs::create_directories(dir_ / "folder.nii");
  expectError([&] { importVolume(dir_ / "folder.nii"); }, {"folder.nii", "DICOM"});
}

TEST(VolumeRange, IgnoresNanAndInfinities) {
  Volume v;
  v.updateRange();
  EXPECT_EQ(v.minValue, 0.0f);
  EXPECT_EQ(v.maxValue, 0.0f);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  v.values = {nan, INFINITY, -INFINITY};
  v.minValue = v.maxValue = 5.0f;
  EXPECT_FALSE(v.updateRange()) << "no finite value";
  EXPECT_EQ(v.minValue, 0.0f);
  EXPECT_EQ(v.maxValue, 0.0f);
  v.values = {nan, 3.0f, -INFINITY, -2.0f, INFINITY, nan};
  EXPECT_TRUE(v.updateRange());
  EXPECT_EQ(v.minValue, -2.0f);
  EXPECT_EQ(v.maxValue, 3.0f);
}

// Voxels in memory (the Python module's arrays): element (i, j, k) read through its strides in
// any order and byte order, checked as a file's header is.
TEST(VolumeFromMemory, ReadsThroughStridesAndByteOrder) {
  // A 3 × 2 × 2 block stored k fastest, then j, then i (a C-order [i, j, k] array), as
  // big-endian int16 holding 100·i + 10·j + k.
  std::vector<std::uint16_t> stored(12);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 2; ++j)
      for (int k = 0; k < 2; ++k) {
        const auto value = std::uint16_t(100 * i + 10 * j + k);
        stored[std::size_t(4 * i + 2 * j + k)] = std::uint16_t(value << 8 | value >> 8);
      }
  MemoryVoxels m;
  m.data = stored.data();
  m.dims[0] = 3, m.dims[1] = 2, m.dims[2] = 2;
  m.strides[0] = 8, m.strides[1] = 4, m.strides[2] = 2;
  m.kind = 'i', m.bytes = 2, m.swapped = std::endian::native == std::endian::little;
  m.indexToWorld = glm::dmat4(glm::dvec4(0.5, 0, 0, 0), glm::dvec4(0, 2, 0, 0),
                              glm::dvec4(0, 0, 3, 0), glm::dvec4(1, 2, 3, 1));
  const Volume v = volumeFromMemory(m, "array", "/volumes/0");
  ASSERT_EQ(v.dims, glm::ivec3(3, 2, 2));
  EXPECT_EQ(v.voxelType, "i16");
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 2; ++j)
      for (int k = 0; k < 2; ++k) EXPECT_EQ(v.at({i, j, k}), float(100 * i + 10 * j + k));
  EXPECT_EQ(v.minValue, 0.0f);
  EXPECT_EQ(v.maxValue, 211.0f);
  EXPECT_EQ(v.spacing(), glm::vec3(0.5f, 2.0f, 3.0f));
  EXPECT_EQ(glm::vec3(v.indexToWorld[3]), glm::vec3(1, 2, 3));

  // The same block seen backwards along i (a negative stride from its last row).
  std::vector<float> floats(12);
  for (int i = 0; i < 3; ++i)
    for (int jk = 0; jk < 4; ++jk)
      floats[std::size_t(4 * (2 - i) + jk)] = float(100 * i + 10 * (jk / 2) + jk % 2);
  MemoryVoxels r = m;
  r.data = floats.data() + 8;
  r.strides[0] = -16, r.strides[1] = 8, r.strides[2] = 4;
  r.kind = 'f', r.bytes = 4, r.swapped = false;
  EXPECT_EQ(volumeFromMemory(r, "array", "").values, v.values);
}

TEST(VolumeFromMemory, RefusesBadTypesDimsAndPlacements) {
  float one = 1.0f;
  MemoryVoxels m;
  m.data = &one;
  m.dims[0] = m.dims[1] = m.dims[2] = 1;
  m.kind = 'c', m.bytes = 8;
  expectError([&] { volumeFromMemory(m, "array", "/volumes/2"); },
              {"array: /volumes/2: unsupported voxel type 'c64'"});
  m.kind = 'f', m.bytes = 4;
  m.dims[1] = 0;
  expectError([&] { volumeFromMemory(m, "array", ""); }, {"dims must be positive, got 1×0×1"});
  m.dims[1] = std::int64_t(1) << 31;
  expectError([&] { volumeFromMemory(m, "array", ""); }, {"exceed the limit"});
  m.dims[1] = 1;
  m.indexToWorld[2][2] = 0.0;
  expectError([&] { volumeFromMemory(m, "array", ""); }, {"transform is singular"});
  m.indexToWorld[2][2] = std::numeric_limits<double>::infinity();
  expectError([&] { volumeFromMemory(m, "array", ""); }, {"transform is not finite"});
  m.indexToWorld = glm::dmat4(1.0);
  m.indexToWorld[2][3] = 0.5;  // a projective last row
  expectError([&] { volumeFromMemory(m, "array", ""); }, {"last row is not 0 0 0 1"});
  m.indexToWorld = glm::dmat4(1.0);
  one = std::numeric_limits<float>::quiet_NaN();  // nothing but missing data: nothing to show
  expectError([&] { volumeFromMemory(m, "array", "/volumes/1"); },
              {"array: /volumes/1: no voxel holds a finite value as a 32-bit float"});
}
