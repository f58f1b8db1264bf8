// Every volume format and scalar type reads back the values that were written: each case writes
// its own small file (both byte orders, raw and compressed) and compares voxel by voxel.
#include <doctest/doctest.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <zlib.h>

#include "core/util/error.h"
#include "core/volume/reader.h"
#include "test_files.h"

namespace kdswap {
namespace {

namespace fs = std::filesystem;

using test::TempDir;
using test::writeFile;

using test::deflateBytes;

template <typename T>
void append(std::string& out, T value, bool bigEndian) {
  char b[sizeof(T)];
  std::memcpy(b, &value, sizeof(T));
  if (bigEndian != (std::endian::native == std::endian::big))
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
  out.append(b, sizeof(T));
}

//! `values` stored as `type` in the given byte order.
std::string encode(const std::string& type, const std::vector<double>& values, bool bigEndian) {
  std::string out;
  for (double v : values) {
    if (type == "int8") append(out, std::int8_t(v), bigEndian);
    else if (type == "uint8") append(out, std::uint8_t(v), bigEndian);
    else if (type == "int16") append(out, std::int16_t(v), bigEndian);
    else if (type == "uint16") append(out, std::uint16_t(v), bigEndian);
    else if (type == "int32") append(out, std::int32_t(v), bigEndian);
    else if (type == "uint32") append(out, std::uint32_t(v), bigEndian);
    else if (type == "float32") append(out, float(v), bigEndian);
    else if (type == "float64") append(out, double(v), bigEndian);
    else FAIL("unknown type " << type);
  }
  return out;
}

const glm::ivec3 kDims(5, 4, 3);
const char* const kTypes[] = {"int8", "uint8", "int16", "uint16", "int32", "uint32", "float32", "float64"};

//! 60 values spanning much of each type's range, including its sign and its large magnitudes.
std::vector<double> valuesFor(const std::string& type) {
  std::vector<double> v;
  for (int i = 0; i < kDims.x * kDims.y * kDims.z; ++i) {
    if (type == "int8") v.push_back(i * 4 - 120);
    else if (type == "uint8") v.push_back(i * 4 + 19);
    else if (type == "int16") v.push_back(i * 500 - 15000);
    else if (type == "uint16") v.push_back(i * 1100);
    else if (type == "int32") v.push_back(i * 70001 - 2000000);
    else if (type == "uint32") v.push_back(4000000000.0 - i * 1000.0);
    else if (type == "float32") v.push_back(i * 0.25 - 7.5);
    else v.push_back(i * 0.125 - 3.0);
  }
  return v;
}

std::vector<float> readAll(const VolumeSource& source) {
  const glm::ivec3 d = source.info().dims;
  std::vector<float> out(std::size_t(d.x) * d.y * d.z);
  source.read(VoxelBox{{0, 0, 0}, d}, out.data());
  return out;
}

void checkMatches(const VolumeSource& source, const std::vector<double>& expected) {
  const std::vector<float> got = readAll(source);
  REQUIRE(got.size() == expected.size());
  float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
  for (std::size_t i = 0; i < got.size(); ++i) {
    CHECK_MESSAGE(got[i] == float(expected[i]), "voxel " << i);
    lo = std::min(lo, float(expected[i]));
    hi = std::max(hi, float(expected[i]));
  }
  CHECK(source.info().minValue == lo);
  CHECK(source.info().maxValue == hi);
}

//! A NIfTI-1 header (348 bytes + 4 zero extension bytes), vox_offset 352.
std::string niftiHeader(const glm::ivec3& dims, int datatype, int bitpix, bool bigEndian, float slope = 0.0f,
                        float inter = 0.0f, int dim0 = 3, int dim4 = 1, int sizeofHdr = 348) {
  std::string h(352, '\0');
  auto put = [&](std::size_t at, auto value) {
    std::string b;
    append(b, value, bigEndian);
    h.replace(at, b.size(), b);
  };
  put(0, std::int32_t(sizeofHdr));
  const std::int16_t dim[8] = {std::int16_t(dim0), std::int16_t(dims.x), std::int16_t(dims.y), std::int16_t(dims.z),
                               std::int16_t(dim4), 1, 1, 1};
  for (int i = 0; i < 8; ++i) put(40 + 2 * i, dim[i]);
  put(70, std::int16_t(datatype));
  put(72, std::int16_t(bitpix));
  const float pixdim[4] = {1.0f, 0.5f, 0.75f, 2.5f};
  for (int i = 0; i < 4; ++i) put(76 + 4 * i, pixdim[i]);
  put(108, 352.0f);
  put(112, slope);
  put(116, inter);
  h.replace(344, 4, std::string("n+1\0", 4));
  return h;
}

}  // namespace

TEST_CASE("a raw file named NAME_WxHxD_TYPE.raw reads back every scalar type in either byte order") {
  TempDir dir;
  for (const char* type : kTypes)
    for (bool big : {false, true}) {
      CAPTURE(type);
      CAPTURE(big);
      const std::string path = dir.file(std::string("v_5x4x3_") + type + ".raw");
      writeFile(path, encode(type, valuesFor(type), big));
      RawLayout layout;
      layout.bigEndian = big;
      const auto source = openVolumeFile(path, layout);
      CHECK(source->info().type == type);
      CHECK(source->info().dims == kDims);
      checkMatches(*source, valuesFor(type));
    }
}

TEST_CASE("a raw layout given on the command line overrides the file name and skips header bytes") {
  TempDir dir;
  const std::string path = dir.file("scan_9x9x9_uint8.dat");
  writeFile(path, std::string(16, 'H') + encode("int16", valuesFor("int16"), true));
  RawLayout layout;
  layout.dims = kDims;
  layout.type = "int16";
  layout.bigEndian = true;
  layout.spacing = glm::vec3(0.5f, 1.0f, 3.0f);
  layout.headerBytes = 16;
  const auto source = openVolumeFile(path, layout);
  CHECK(source->info().spacing == glm::vec3(0.5f, 1.0f, 3.0f));
  checkMatches(*source, valuesFor("int16"));
}

TEST_CASE("any box of a raw file equals the same box cut from the whole volume") {
  TempDir dir;
  const glm::ivec3 d(7, 5, 6);
  std::vector<double> values;
  for (int i = 0; i < d.x * d.y * d.z; ++i) values.push_back((i * 37) % 1000);
  const std::string path = dir.file("odd_7x5x6_uint16.raw");
  writeFile(path, encode("uint16", values, false));
  const auto source = openVolumeFile(path);
  // Whole slices (one run), whole rows (one run per slice), partial rows, single voxels.
  const VoxelBox boxes[] = {{{0, 0, 2}, {7, 5, 4}}, {{0, 1, 0}, {7, 4, 6}}, {{2, 1, 1}, {6, 5, 5}},
                            {{6, 4, 5}, {7, 5, 6}}, {{0, 0, 0}, {1, 1, 1}}, {{3, 0, 0}, {4, 5, 6}}};
  for (const VoxelBox& box : boxes) {
    std::vector<float> got(box.count());
    source->read(box, got.data());
    std::size_t i = 0;
    for (int z = box.lo.z; z < box.hi.z; ++z)
      for (int y = box.lo.y; y < box.hi.y; ++y)
        for (int x = box.lo.x; x < box.hi.x; ++x, ++i)
          CHECK(got[i] == float(values[(std::size_t(z) * d.y + y) * d.x + x]));
  }
}

TEST_CASE("reads from many threads at once return the same voxels") {
  TempDir dir;
  const glm::ivec3 d(32, 16, 24);
  std::vector<double> values;
  for (int i = 0; i < d.x * d.y * d.z; ++i) values.push_back(std::sin(i * 0.01) * 1000.0);
  const std::string path = dir.file("t_32x16x24_float32.raw");
  writeFile(path, encode("float32", values, false));
  const auto source = openVolumeFile(path);
  std::atomic<int> mismatches{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      for (int rep = 0; rep < 20; ++rep) {
        const VoxelBox box{{t, rep % 8, rep % 12}, {d.x - t, d.y, d.z}};
        std::vector<float> got(box.count());
        source->read(box, got.data());
        std::size_t i = 0;
        for (int z = box.lo.z; z < box.hi.z; ++z)
          for (int y = box.lo.y; y < box.hi.y; ++y)
            for (int x = box.lo.x; x < box.hi.x; ++x, ++i)
              if (got[i] != float(values[(std::size_t(z) * d.y + y) * d.x + x])) ++mismatches;
      }
    });
  for (auto& th : threads) th.join();
  CHECK(mismatches == 0);
}

TEST_CASE("NaN and Inf in float data are counted, left out of the range, read as the minimum and reported") {
  TempDir dir;
  std::vector<double> values = valuesFor("float32");
  values[3] = std::numeric_limits<double>::quiet_NaN();
  values[10] = std::numeric_limits<double>::infinity();
  values[59] = -std::numeric_limits<double>::infinity();
  for (const std::string name : {"nan_5x4x3_float32.raw", "nan.nrrd"}) {
    CAPTURE(name);
    const std::string path = dir.file(name);
    const std::string data = encode("float32", values, false);
    writeFile(path, name.ends_with(".nrrd") ? "NRRD0004\ntype: float\ndimension: 3\nsizes: 5 4 3\nendian: little\n"
                                              "encoding: gzip\n\n" + deflateBytes(data, true)
                                            : data);
    // Capture stderr to see the one-line warning.
    const std::string logPath = dir.file("stderr.txt");
    std::fflush(stderr);
    const int saved = ::dup(2);
    const int fd = ::open(logPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    ::dup2(fd, 2);
    ::close(fd);
    std::unique_ptr<VolumeSource> source;
    try {
      source = openVolumeFile(path);
    } catch (...) {
      std::fflush(stderr);
      ::dup2(saved, 2);
      ::close(saved);
      throw;
    }
    std::fflush(stderr);
    ::dup2(saved, 2);
    ::close(saved);
    std::ifstream log(logPath);
    const std::string warning((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());

    CHECK(source->info().nonFinite == 3);
    const std::vector<float> got = readAll(*source);
    CHECK(source->info().minValue == -7.5f);
    CHECK(source->info().maxValue == 7.0f);  // 58 * 0.25 - 7.5; voxel 59 is -Inf
    CHECK(got[3] == -7.5f);
    CHECK(got[10] == -7.5f);
    CHECK(got[59] == -7.5f);
    CHECK(got[4] == float(values[4]));
    CHECK(warning.find(path) != std::string::npos);
    CHECK(warning.find("3 NaN/Inf") != std::string::npos);
    CHECK(std::count(warning.begin(), warning.end(), '\n') == 1);
  }
}

TEST_CASE("NRRD reads attached and detached data, raw and gzip, with byte and line skips") {
  TempDir dir;
  const std::vector<double> values = valuesFor("int16");
  const std::string le = encode("int16", values, false), be = encode("int16", values, true);
  const std::string fields = "NRRD0004\n# a comment\ntype: short\ndimension: 3\nsizes: 5 4 3\nkey:=value\n";

  SUBCASE("attached raw, big-endian, spacings") {
    writeFile(dir.file("a.nrrd"), fields + "spacings: 0.5 1 nan\nendian: big\nencoding: raw\n\n" + be);
    const auto source = openVolumeFile(dir.file("a.nrrd"));
    CHECK(source->info().spacing == glm::vec3(0.5f, 1.0f, 1.0f));
    CHECK(source->info().type == "int16");
    checkMatches(*source, values);
  }
  SUBCASE("attached gzip, space directions give the spacing") {
    writeFile(dir.file("b.nrrd"), fields + "space: right-anterior-superior\nspace directions: (0,2,0) (3,0,0) (0,0,-1.5)\n"
                                           "endian: little\nencoding: gzip\n\n" + deflateBytes(le, true));
    const auto source = openVolumeFile(dir.file("b.nrrd"));
    CHECK(source->info().spacing == glm::vec3(2.0f, 3.0f, 1.5f));
    checkMatches(*source, values);
  }
  SUBCASE("detached header, data file beside it, byte skip") {
    writeFile(dir.file("c.raw.data"), "XXXXXXX" + le);
    writeFile(dir.file("c.nhdr"), fields + "endian: little\nencoding: raw\nbyte skip: 7\ndata file: c.raw.data\n");
    checkMatches(*openVolumeFile(dir.file("c.nhdr")), values);
  }
  SUBCASE("detached header, line skip then byte skip") {
    writeFile(dir.file("d.bin"), "first line\nsecond\n##" + le);
    writeFile(dir.file("d.nhdr"), fields + "endian: little\nencoding: raw\nline skip: 2\nbyte skip: 2\ndatafile: d.bin");
    checkMatches(*openVolumeFile(dir.file("d.nhdr")), values);
  }
  SUBCASE("byte skip -1 takes the last bytes of the data file") {
    writeFile(dir.file("e.bin"), std::string(33, '\x7f') + le);
    writeFile(dir.file("e.nhdr"), fields + "endian: little\nencoding: raw\nbyte skip: -1\ndata file: e.bin\n");
    checkMatches(*openVolumeFile(dir.file("e.nhdr")), values);
  }
  SUBCASE("detached gzip with byte skip inside the decompressed data") {
    writeFile(dir.file("f.gz"), deflateBytes("0123" + le, true));
    writeFile(dir.file("f.NHDR"), fields + "endian: little\nencoding: gz\nbyte skip: 4\ndata file: f.gz\n");
    checkMatches(*openVolumeFile(dir.file("f.NHDR")), values);
  }
  SUBCASE("single-byte types need no endian field") {
    writeFile(dir.file("g.nrrd"), "NRRD0001\ntype: uchar\ndimension: 3\nsizes: 5 4 3\nencoding: raw\n\n" +
                                      encode("uint8", valuesFor("uint8"), false));
    checkMatches(*openVolumeFile(dir.file("g.nrrd")), valuesFor("uint8"));
  }
}

TEST_CASE("NRRD type names map to the eight scalar types") {
  TempDir dir;
  const std::pair<const char*, const char*> names[] = {
      {"signed char", "int8"}, {"uchar", "uint8"},         {"short int", "int16"}, {"unsigned short", "uint16"},
      {"int", "int32"},        {"unsigned int", "uint32"}, {"float", "float32"},   {"double", "float64"}};
  for (const auto& [nrrdName, type] : names) {
    CAPTURE(nrrdName);
    writeFile(dir.file("t.nrrd"), std::string("NRRD0005\ntype: ") + nrrdName +
                                      "\ndimension: 3\nsizes: 5 4 3\nendian: big\nencoding: raw\n\n" +
                                      encode(type, valuesFor(type), true));
    const auto source = openVolumeFile(dir.file("t.nrrd"));
    CHECK(source->info().type == type);
    checkMatches(*source, valuesFor(type));
  }
}

TEST_CASE("MetaImage reads .mhd with a data file and .mha with local, compressed or big-endian data") {
  TempDir dir;
  const std::vector<double> values = valuesFor("uint16");
  const std::string head = "ObjectType = Image\nNDims = 3\nDimSize = 5 4 3\nElementType = MET_USHORT\n"
                           "ElementSpacing = 0.5 0.25 2\n";
  SUBCASE("mhd and a separate raw file") {
    writeFile(dir.file("m.raw"), encode("uint16", values, false));
    writeFile(dir.file("m.mhd"), head + "ElementByteOrderMSB = False\nElementDataFile = m.raw\n");
    const auto source = openVolumeFile(dir.file("m.mhd"));
    CHECK(source->info().spacing == glm::vec3(0.5f, 0.25f, 2.0f));
    CHECK(source->info().type == "uint16");
    checkMatches(*source, values);
  }
  SUBCASE("mha with big-endian local data") {
    writeFile(dir.file("m.mha"), head + "BinaryDataByteOrderMSB = True\nElementDataFile = LOCAL\n" +
                                     encode("uint16", values, true));
    checkMatches(*openVolumeFile(dir.file("m.mha")), values);
  }
  SUBCASE("mha with zlib-compressed local data") {
    writeFile(dir.file("z.mha"), head + "CompressedData = True\nCompressedDataSize = 1\nElementDataFile = LOCAL\n" +
                                     deflateBytes(encode("uint16", values, false), false));
    checkMatches(*openVolumeFile(dir.file("z.mha")), values);
  }
  SUBCASE("HeaderSize skips bytes of the data file") {
    writeFile(dir.file("h.raw"), "0123456789" + encode("uint16", values, false));
    writeFile(dir.file("h.mhd"), head + "HeaderSize = 10\nElementDataFile = h.raw\n");
    checkMatches(*openVolumeFile(dir.file("h.mhd")), values);
  }
  SUBCASE("HeaderSize -1 takes the last bytes of the data file") {
    writeFile(dir.file("t.raw"), "some header of unknown length" + encode("uint16", values, false));
    writeFile(dir.file("t.mhd"), head + "HeaderSize = -1\nElementDataFile = t.raw\n");
    checkMatches(*openVolumeFile(dir.file("t.mhd")), values);
  }
}

TEST_CASE("NIfTI-1 reads either header byte order, .nii and .nii.gz, and applies scl_slope") {
  TempDir dir;
  const std::pair<int, const char*> types[] = {{2, "uint8"},    {4, "int16"},    {8, "int32"},   {16, "float32"},
                                               {64, "float64"}, {256, "int8"},   {512, "uint16"}, {768, "uint32"}};
  for (const auto& [code, type] : types)
    for (bool big : {false, true})
      for (bool gz : {false, true}) {
        CAPTURE(type);
        CAPTURE(big);
        CAPTURE(gz);
        const std::string bytes =
            niftiHeader(kDims, code, int(8 * encode(type, {0.0}, big).size()), big) + encode(type, valuesFor(type), big);
        const std::string path = dir.file(gz ? "n.nii.gz" : "n.nii");
        writeFile(path, gz ? deflateBytes(bytes, true) : bytes);
        const auto source = openVolumeFile(path);
        CHECK(source->info().type == type);
        CHECK(source->info().dims == kDims);
        CHECK(source->info().spacing == glm::vec3(0.5f, 0.75f, 2.5f));
        checkMatches(*source, valuesFor(type));
      }
  SUBCASE("scl_slope and scl_inter scale the stored values") {
    std::vector<double> scaled;
    for (double v : valuesFor("int16")) scaled.push_back(float(float(v) * 0.5f + 100.0f));
    writeFile(dir.file("s.nii"), niftiHeader(kDims, 4, 16, true, 0.5f, 100.0f) + encode("int16", valuesFor("int16"), true));
    checkMatches(*openVolumeFile(dir.file("s.nii")), scaled);
  }
  SUBCASE("a 4D header with one volume is a 3D volume") {
    writeFile(dir.file("t.nii"), niftiHeader(kDims, 2, 8, false, 0, 0, 4, 1) + encode("uint8", valuesFor("uint8"), false));
    checkMatches(*openVolumeFile(dir.file("t.nii")), valuesFor("uint8"));
  }
}

TEST_CASE("legacy VTK reads binary version 1.0 with ASPECT_RATIO and ASCII with SPACING") {
  TempDir dir;
  SUBCASE("binary, big-endian short, a blank line before BINARY and a trailing newline") {
    const std::vector<double> values = valuesFor("int16");
    writeFile(dir.file("b.vtk"), "# vtk DataFile Version 1.0\nA title\n\nBINARY\n\nDATASET STRUCTURED_POINTS\n"
                                 "DIMENSIONS 5 4 3\nASPECT_RATIO 1.5 1 0.5\nORIGIN 0.0 0.0 0.0\n\nPOINT_DATA 60\n"
                                 "SCALARS scalars short\nLOOKUP_TABLE default\n" +
                                     encode("int16", values, true) + "\n");
    const auto source = openVolumeFile(dir.file("b.vtk"));
    CHECK(source->info().spacing == glm::vec3(1.5f, 1.0f, 0.5f));
    CHECK(source->info().type == "int16");
    checkMatches(*source, values);
  }
  SUBCASE("ASCII floats over several lines, SPACING, SCALARS with a component count") {
    const std::vector<double> values = valuesFor("float32");
    std::ostringstream text;
    text << "# vtk DataFile Version 3.0\nascii volume\nASCII\nDATASET STRUCTURED_POINTS\nDIMENSIONS 5 4 3\n"
            "ORIGIN 0 0 0\nSPACING 2 2 3\nPOINT_DATA 60\nSCALARS density float 1\nLOOKUP_TABLE default\n";
    for (std::size_t i = 0; i < values.size(); ++i) text << values[i] << (i % 7 == 6 ? "\n" : " ");
    writeFile(dir.file("a.vtk"), text.str());
    const auto source = openVolumeFile(dir.file("a.vtk"));
    CHECK(source->info().spacing == glm::vec3(2.0f, 2.0f, 3.0f));
    CHECK(source->info().type == "float32");
    checkMatches(*source, values);
  }
}

TEST_CASE("file extensions pick the reader whatever their case") {
  TempDir dir;
  writeFile(dir.file("UPPER.NRRD"), "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 5 4 3\nencoding: raw\n\n" +
                                        encode("uint8", valuesFor("uint8"), false));
  writeFile(dir.file("LOUD_5x4x3_UINT8.RAW"), encode("uint8", valuesFor("uint8"), false));
  checkMatches(*openVolumeFile(dir.file("UPPER.NRRD")), valuesFor("uint8"));
  checkMatches(*openVolumeFile(dir.file("LOUD_5x4x3_UINT8.RAW")), valuesFor("uint8"));
}

}  // namespace kdswap
