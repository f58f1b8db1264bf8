// Bad volume files are refused with one line naming the file and the problem: never a crash, a
// hang or a huge allocation. Each case writes its own broken file.
#include <doctest/doctest.h>

#include <unistd.h>

#include <atomic>
#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include <glm/vec4.hpp>
#include <zlib.h>

#include "core/util/error.h"
#include "core/volume/reader.h"
#include "test_files.h"

namespace kdswap {
namespace {

namespace fs = std::filesystem;

using test::TempDir;
using test::writeFile;

std::string gzipBytes(const std::string& raw) { return test::deflateBytes(raw, true); }

//! Opens `path` expecting kdswap::Error; checks its message is one line that names the file
//! and contains `problem`.
void expectRefused(const std::string& path, const std::string& problem, const RawLayout& layout = {}) {
  CAPTURE(path);
  std::string message;
  try {
    openVolumeFile(path, layout);
  } catch (const Error& e) {
    message = e.what();
  }
  CAPTURE(message);
  REQUIRE_MESSAGE(!message.empty(), "opened without an error");
  CHECK(message.find(fs::path(path).filename().string()) != std::string::npos);
  CHECK(message.find(problem) != std::string::npos);
  CHECK(message.find('\n') == std::string::npos);
}

const std::string kNrrdStart = "NRRD0004\ntype: uint8\ndimension: 3\n";

//! A little-endian NIfTI-1 header with vox_offset 352, then `dataBytes` bytes of zeros.
std::string nifti(int dim0, glm::ivec4 dims, int datatype, int bitpix, std::size_t dataBytes, int sizeofHdr = 348,
                  const char* magic = "n+1") {
  std::string h(352 + dataBytes, '\0');
  auto put = [&](std::size_t at, auto value) { std::memcpy(h.data() + at, &value, sizeof value); };
  put(0, std::int32_t(sizeofHdr));
  put(40, std::int16_t(dim0));
  for (int i = 0; i < 4; ++i) put(42 + 2 * i, std::int16_t(dims[i]));
  put(50, std::int16_t(1));
  put(70, std::int16_t(datatype));
  put(72, std::int16_t(bitpix));
  for (int i = 0; i < 4; ++i) put(76 + 4 * i, 1.0f);
  put(108, 352.0f);
  std::memcpy(h.data() + 344, magic, std::strlen(magic) + 1);
  return h;
}

}  // namespace

TEST_CASE("a missing file, a folder or an unknown extension are refused by name") {
  TempDir dir;
  expectRefused(dir.file("nowhere.nrrd"), "no such file");
  fs::create_directories(dir.file("folder.nrrd"));
  expectRefused(dir.file("folder.nrrd"), "is a directory");
  writeFile(dir.file("volume.xyz"), "data");
  expectRefused(dir.file("volume.xyz"), "unknown volume format: expected .nrrd/.nhdr (NRRD), .mhd/.mha (MetaImage), "
                                        ".nii/.nii.gz (NIfTI-1), .vtk (legacy VTK), .raw");
}

TEST_CASE("raw files with the wrong size or no layout are refused") {
  TempDir dir;
  writeFile(dir.file("short_4x4x4_uint16.raw"), std::string(127, '\0'));
  expectRefused(dir.file("short_4x4x4_uint16.raw"), "truncated: 4x4x4 uint16 needs 128 bytes");
  writeFile(dir.file("long_4x4x4_uint8.raw"), std::string(65, '\0'));
  expectRefused(dir.file("long_4x4x4_uint8.raw"), "header and data size disagree");
  writeFile(dir.file("plain.raw"), std::string(64, '\0'));
  // Without --raw-* options (the GUI) the message offers only the name pattern and a header.
  expectRefused(dir.file("plain.raw"),
                "raw file layout unknown: no dimensions and no sample type: rename it NAME_WxHxD_TYPE.raw, e.g. "
                "head_256x256x113_uint16.raw (TYPE: int8 uint8");
  expectRefused(dir.file("plain.raw"), "), or describe it with a .nhdr header");
  writeFile(dir.file("odd_4x4x4_complex64.raw"), std::string(64, '\0'));
  expectRefused(dir.file("odd_4x4x4_complex64.raw"), "type \"complex64\": unsupported (expected one of int8 uint8");
  RawLayout layout;
  layout.dims = glm::ivec3(4, 4, 4);
  layout.type = "int64";
  expectRefused(dir.file("plain.raw"), "type \"int64\": unsupported", layout);
}

TEST_CASE("zero, negative, overflowing and too large dimensions are refused before any allocation") {
  TempDir dir;
  writeFile(dir.file("zero_0x4x4_uint8.raw"), "");
  expectRefused(dir.file("zero_0x4x4_uint8.raw"), "every size must be a whole number from 2");
  writeFile(dir.file("over_99999999999999999999x4x4_uint8.raw"), "");
  expectRefused(dir.file("over_99999999999999999999x4x4_uint8.raw"), "overflow");
  writeFile(dir.file("big_3000000000x4x4_uint8.raw"), "");
  expectRefused(dir.file("big_3000000000x4x4_uint8.raw"), "from 2 to 2147483647");
  writeFile(dir.file("huge_100000x100000x100000_uint8.raw"), "");
  expectRefused(dir.file("huge_100000x100000x100000_uint8.raw"), "is available");

  writeFile(dir.file("zero.nrrd"), kNrrdStart + "sizes: 256 256 0\nencoding: raw\n\n");
  expectRefused(dir.file("zero.nrrd"), "sizes \"256 256 0\": every size must be a whole number from 2");
  writeFile(dir.file("negative.nrrd"), kNrrdStart + "sizes: 16 -16 16\nencoding: raw\n\n");
  expectRefused(dir.file("negative.nrrd"), "every size must be");
  writeFile(dir.file("overflow.nrrd"), kNrrdStart + "sizes: 16 16 18446744073709551617\nencoding: raw\n\n");
  expectRefused(dir.file("overflow.nrrd"), "expected 3 whole numbers");
  writeFile(dir.file("huge.nrrd"), kNrrdStart + "sizes: 100000 100000 100000\nencoding: raw\n\n");
  expectRefused(dir.file("huge.nrrd"), "for voxels and gradients, but only");
}

TEST_CASE("NRRD headers with unsupported or missing fields are refused") {
  TempDir dir;
  auto nrrd = [&](const std::string& name, const std::string& text) {
    writeFile(dir.file(name), text);
    return dir.file(name);
  };
  expectRefused(nrrd("d4.nrrd", "NRRD0004\ntype: uint8\ndimension: 4\nsizes: 2 4 4 4\nencoding: raw\n\n"),
                "dimension \"4\": only 3D volumes are supported");
  expectRefused(nrrd("d2.nrrd", "NRRD0004\ntype: uint8\ndimension: 2\nsizes: 4 4\nencoding: raw\n\n"),
                "dimension \"2\": only 3D volumes are supported");
  expectRefused(nrrd("sizes.nrrd", kNrrdStart + "sizes: 4 4\nencoding: raw\n\n"), "expected 3 whole numbers");
  expectRefused(nrrd("type.nrrd", "NRRD0004\ntype: long long\ndimension: 3\nsizes: 4 4 4\nencoding: raw\n\n"),
                "type \"long long\": unsupported");
  expectRefused(nrrd("block.nrrd", "NRRD0004\ntype: block\ndimension: 3\nsizes: 4 4 4\nencoding: raw\n\n"),
                "type \"block\": unsupported");
  expectRefused(nrrd("enc.nrrd", kNrrdStart + "sizes: 4 4 4\nencoding: bzip2\n\n"),
                "encoding \"bzip2\": unsupported (expected raw or gzip)");
  expectRefused(nrrd("ascii.nrrd", kNrrdStart + "sizes: 4 4 4\nencoding: ascii\n\n1 2 3"), "encoding \"ascii\"");
  expectRefused(nrrd("endian.nrrd", "NRRD0004\ntype: uint16\ndimension: 3\nsizes: 4 4 4\nencoding: raw\n\n"),
                "no \"endian\" field");
  expectRefused(nrrd("noenc.nrrd", kNrrdStart + "sizes: 4 4 4\n\n"), "no \"encoding\" field");
  expectRefused(nrrd("magic.nrrd", "NRRX0004\n"), "not a NRRD file");
  expectRefused(nrrd("binary.nrrd", std::string("\x89PNG\r\n\x1a\n\0\0\0", 11)), "not a NRRD file");
  expectRefused(nrrd("noblank.nrrd", kNrrdStart + "sizes: 4 4 4\nencoding: raw"), "no blank line");
  expectRefused(nrrd("line.nrrd", kNrrdStart + "sizes 4 4 4\nencoding: raw\n\n"), "expected \"field: value\"");
  expectRefused(nrrd("spacing.nrrd", kNrrdStart + "sizes: 4 4 4\nspacings: 1 0 1\nencoding: raw\n\n" + std::string(64, 'x')),
                "spacing along axis 1 must be a positive number");
  expectRefused(nrrd("multi.nhdr", kNrrdStart + "sizes: 4 4 4\nencoding: raw\ndata file: slice%03d.raw 1 4 1\n"),
                "only a single data file is supported");
}

TEST_CASE("NRRD data that are truncated, too long, missing or corrupt are refused") {
  TempDir dir;
  writeFile(dir.file("short.nrrd"), kNrrdStart + "sizes: 4 4 4\nencoding: raw\n\n" + std::string(63, 'x'));
  expectRefused(dir.file("short.nrrd"), "truncated: 4x4x4 uint8 needs 64 bytes");
  writeFile(dir.file("long.nrrd"), kNrrdStart + "sizes: 4 4 4\nencoding: raw\n\n" + std::string(65, 'x'));
  expectRefused(dir.file("long.nrrd"), "header and data size disagree");
  writeFile(dir.file("lost.nhdr"), kNrrdStart + "sizes: 4 4 4\nencoding: raw\ndata file: lost.raw\n");
  expectRefused(dir.file("lost.nhdr"), "data file \"lost.raw\"");
  expectRefused(dir.file("lost.nhdr"), "lost.raw): no such file");
  writeFile(dir.file("nodata.nhdr"), kNrrdStart + "sizes: 4 4 4\nencoding: raw\n");
  expectRefused(dir.file("nodata.nhdr"), "no \"data file\" field");

  const std::string gz = gzipBytes(std::string(64, 'x'));
  writeFile(dir.file("corrupt.nrrd"), kNrrdStart + "sizes: 4 4 4\nencoding: gzip\n\n" + "this is not gzip at all, no");
  expectRefused(dir.file("corrupt.nrrd"), "corrupt compressed data");
  std::string flipped = gz;
  flipped[gz.size() / 2] = char(flipped[gz.size() / 2] ^ 0x55);
  flipped[gz.size() / 2 + 1] = char(flipped[gz.size() / 2 + 1] ^ 0xaa);
  writeFile(dir.file("flipped.nrrd"), kNrrdStart + "sizes: 4 4 4\nencoding: gzip\n\n" + flipped);
  expectRefused(dir.file("flipped.nrrd"), "corrupt compressed data");
  writeFile(dir.file("cut.nrrd"), kNrrdStart + "sizes: 4 4 4\nencoding: gzip\n\n" + gz.substr(0, gz.size() / 2));
  expectRefused(dir.file("cut.nrrd"), "compressed data ends early: the file is truncated");
  writeFile(dir.file("few.nrrd"), kNrrdStart + "sizes: 4 4 5\nencoding: gzip\n\n" + gz);
  expectRefused(dir.file("few.nrrd"), "truncated: compressed data holds 64 bytes, 4x4x5 uint8 needs 80");
  writeFile(dir.file("many.nrrd"), kNrrdStart + "sizes: 4 4 3\nencoding: gzip\n\n" + gz);
  expectRefused(dir.file("many.nrrd"), "header and data size disagree: compressed data holds more than the 48 bytes");
}

TEST_CASE("MetaImage headers and data that are wrong are refused") {
  TempDir dir;
  const std::string head = "NDims = 3\nDimSize = 4 4 4\nElementType = MET_UCHAR\n";
  auto mhd = [&](const std::string& name, const std::string& text) {
    writeFile(dir.file(name), text);
    return dir.file(name);
  };
  writeFile(dir.file("ok.raw"), std::string(64, 'x'));
  expectRefused(mhd("n2.mhd", "NDims = 2\nDimSize = 4 4\nElementType = MET_UCHAR\nElementDataFile = ok.raw\n"),
                "NDims = 2: only 3D volumes are supported");
  expectRefused(mhd("type.mhd", "NDims = 3\nDimSize = 4 4 4\nElementType = MET_LONG_LONG\nElementDataFile = ok.raw\n"),
                "ElementType = MET_LONG_LONG: unsupported");
  expectRefused(mhd("rgb.mhd", head + "ElementNumberOfChannels = 3\nElementDataFile = ok.raw\n"), "only scalar volumes");
  expectRefused(mhd("zero.mhd", "NDims = 3\nDimSize = 4 0 4\nElementType = MET_UCHAR\nElementDataFile = ok.raw\n"),
                "DimSize \"4 0 4\": every size must be");
  expectRefused(mhd("lost.mhd", head + "ElementDataFile = lost.raw\n"), "ElementDataFile lost.raw");
  expectRefused(mhd("nofile.mhd", head), "no ElementDataFile line");
  expectRefused(mhd("ascii.mhd", head + "BinaryData = False\nElementDataFile = ok.raw\n"), "only binary data");
  expectRefused(mhd("list.mhd", head + "ElementDataFile = LIST\n"), "only LOCAL or a single file");
  writeFile(dir.file("short.raw"), std::string(60, 'x'));
  expectRefused(mhd("short.mhd", head + "ElementDataFile = short.raw\n"), "truncated");
  expectRefused(mhd("cut.mha", head + "CompressedData = True\nElementDataFile = LOCAL\n" + gzipBytes(std::string(64, 'x')).substr(0, 20)),
                "compressed data ends early");
}

TEST_CASE("NIfTI files with bad headers, shapes or data are refused") {
  TempDir dir;
  auto nii = [&](const std::string& name, const std::string& bytes) {
    writeFile(dir.file(name), bytes);
    return dir.file(name);
  };
  expectRefused(nii("tiny.nii", std::string(100, '\0')), "truncated: a NIfTI-1 header needs 348 bytes, the file has 100");
  expectRefused(nii("size.nii", nifti(3, {4, 4, 4, 1}, 2, 8, 64, 349)), "not a NIfTI-1 file: sizeof_hdr");
  expectRefused(nii("two.nii", nifti(3, {4, 4, 4, 1}, 2, 8, 64, 540)), "NIfTI-2 header");
  expectRefused(nii("magic.nii", nifti(3, {4, 4, 4, 1}, 2, 8, 64, 348, "ni1")), "separate .hdr/.img pairs");
  expectRefused(nii("series.nii", nifti(4, {4, 4, 4, 10}, 2, 8, 640)),
                "dim[0] = 4 (4x4x4x10): only a single 3D volume is supported");
  expectRefused(nii("flat.nii", nifti(2, {4, 4, 1, 1}, 2, 8, 16)), "dim[0] = 2 (4x4): only 3D volumes are supported");
  expectRefused(nii("rgb.nii", nifti(3, {4, 4, 4, 1}, 128, 24, 192)), "datatype 128: unsupported");
  expectRefused(nii("bitpix.nii", nifti(3, {4, 4, 4, 1}, 4, 8, 128)), "bitpix 8 disagrees with datatype int16");
  expectRefused(nii("neg.nii", nifti(3, {4, -4, 4, 1}, 2, 8, 64)), "every size must be");
  expectRefused(nii("short.nii", nifti(3, {4, 4, 4, 1}, 2, 8, 63)), "truncated");
  const char notDeflate[] = "\x1f\x8b\x08\x00 definitely not deflate data, sorry";  // gzip header, then junk
  expectRefused(nii("bad.nii.gz", std::string(notDeflate, sizeof notDeflate - 1)), "corrupt compressed data");
  const std::string gz = gzipBytes(nifti(3, {4, 4, 4, 1}, 2, 8, 64));
  expectRefused(nii("cut.nii.gz", gz.substr(0, gz.size() - 12)), "ends early");
  expectRefused(nii("few.nii.gz", gzipBytes(nifti(3, {4, 4, 4, 1}, 2, 8, 60))), "compressed data holds 60 bytes");
}

TEST_CASE("legacy VTK files with unsupported content or wrong sizes are refused") {
  TempDir dir;
  const std::string head = "# vtk DataFile Version 3.0\nt\nBINARY\nDATASET STRUCTURED_POINTS\nDIMENSIONS 4 4 4\n";
  auto vtk = [&](const std::string& name, const std::string& text) {
    writeFile(dir.file(name), text);
    return dir.file(name);
  };
  expectRefused(vtk("count.vtk", head + "POINT_DATA 60\nSCALARS s unsigned_char\nLOOKUP_TABLE default\n" + std::string(64, 'x')),
                "header and data size disagree: POINT_DATA 60, DIMENSIONS 4x4x4 make 64 points");
  expectRefused(vtk("grid.vtk", "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 3 float\n"),
                "only DATASET STRUCTURED_POINTS is supported");
  expectRefused(vtk("bit.vtk", head + "POINT_DATA 64\nSCALARS s bit\nLOOKUP_TABLE default\n" + std::string(8, 'x')),
                "SCALARS type \"bit\": unsupported");
  expectRefused(vtk("vec.vtk", head + "POINT_DATA 64\nSCALARS s float 3\nLOOKUP_TABLE default\n"), "only 1 component");
  expectRefused(vtk("short.vtk", head + "POINT_DATA 64\nSCALARS s short\nLOOKUP_TABLE default\n" + std::string(100, 'x')),
                "truncated");
  expectRefused(vtk("mode.vtk", "# vtk DataFile Version 3.0\nt\nXML\n"), "expected ASCII or BINARY");
  expectRefused(vtk("magic.vtk", "<VTKFile type=\"ImageData\">\n"), "not a legacy VTK file");
  expectRefused(vtk("vectors.vtk", head + "POINT_DATA 64\nVECTORS v float\n"), "keyword \"VECTORS\": unsupported");
  expectRefused(vtk("early.vtk", head + "POINT_DATA 64\n"), "the header ends before the scalar data");
  const std::string ascii = "# vtk DataFile Version 3.0\nt\nASCII\nDATASET STRUCTURED_POINTS\nDIMENSIONS 2 2 2\n"
                            "POINT_DATA 8\nSCALARS s float\nLOOKUP_TABLE default\n";
  expectRefused(vtk("few.vtk", ascii + "1 2 3 4 5 6 7\n"), "truncated: ASCII data hold 7 values, expected 8");
  expectRefused(vtk("word.vtk", ascii + "1 2 3 four 5 6 7 8\n"), "ASCII value 4 \"four\": expected a number");
}

}  // namespace kdswap
