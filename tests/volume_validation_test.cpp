// What every volume format must refuse, or accept the same way, beyond a broken header: values
// and spacings float arithmetic cannot render, volumes with no finite voxel, data files that are
// not files, unprintable bytes in messages, NRRD versions, and raw layout options. Each case
// writes its own small files; refusals are one line naming the file and the problem.
#include <doctest/doctest.h>

#include <sys/stat.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "core/util/error.h"
#include "core/volume/reader.h"
#include "core/volume/respaced_source.h"
#include "test_files.h"

namespace kdswap {
namespace {

namespace fs = std::filesystem;

using test::TempDir;
using test::writeFile;

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

//! The message `open` throws as kdswap::Error ("" if it throws nothing).
template <typename Open>
std::string errorOf(Open open) {
  try {
    open();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

//! Checks `message` is one line that names `path`'s file and contains each of `problems`.
void checkMessage(const std::string& message, const std::string& path, std::initializer_list<std::string> problems) {
  CAPTURE(path);
  CAPTURE(message);
  REQUIRE_MESSAGE(!message.empty(), "accepted without an error");
  CHECK(message.find(fs::path(path).filename().string()) != std::string::npos);
  for (const std::string& problem : problems) CHECK(message.find(problem) != std::string::npos);
  CHECK(message.find('\n') == std::string::npos);
}

void expectRefused(const std::string& path, std::initializer_list<std::string> problems, const RawLayout& layout = {}) {
  checkMessage(errorOf([&] { openVolumeFile(path, layout); }), path, problems);
}

std::string floats(const std::vector<float>& values) {
  std::string out(values.size() * 4, '\0');
  std::memcpy(out.data(), values.data(), out.size());  // little-endian hosts, as the other suites assume
  return out;
}

std::string doubles(const std::vector<double>& values) {
  std::string out(values.size() * 8, '\0');
  std::memcpy(out.data(), values.data(), out.size());
  return out;
}

//! 4x4x4 uint8 voxels 0..63: a small volume with a range, for spacing cases.
std::string ramp() {
  std::string out(64, '\0');
  for (int i = 0; i < 64; ++i) out[std::size_t(i)] = char(i);
  return out;
}

//! 64 floats: `a` at voxel 0, `b` at voxel 63, `fill` elsewhere.
std::vector<float> twoValues(float a, float b, float fill = 0.0f) {
  std::vector<float> v(64, fill);
  v[0] = a;
  v[63] = b;
  return v;
}

std::string nrrd(const std::string& fields, const std::string& data, const std::string& type = "uint8") {
  return "NRRD0004\ntype: " + type + "\ndimension: 3\nsizes: 4 4 4\nendian: little\n" + fields + "encoding: raw\n\n" + data;
}

//! A little-endian NIfTI-1 file of 4x4x4 uint8 with the given pixdim[1..3].
std::string nifti(const glm::vec3& pixdim) {
  std::string h(352, '\0');
  auto put = [&](std::size_t at, auto value) { std::memcpy(h.data() + at, &value, sizeof value); };
  put(0, std::int32_t(348));
  const std::int16_t dim[8] = {3, 4, 4, 4, 1, 1, 1, 1};
  for (int i = 0; i < 8; ++i) put(40 + 2 * i, dim[i]);
  put(70, std::int16_t(2));
  put(72, std::int16_t(8));
  put(76, 1.0f);
  for (int a = 0; a < 3; ++a) put(80 + 4 * a, pixdim[a]);
  put(108, 352.0f);
  std::memcpy(h.data() + 344, "n+1", 4);
  return h + ramp();
}

std::string vtk(const std::string& spacingLine, const std::string& type = "unsigned_char", bool ascii = false,
                const std::string& data = ramp()) {
  return "# vtk DataFile Version 3.0\nt\n" + std::string(ascii ? "ASCII" : "BINARY") +
         "\nDATASET STRUCTURED_POINTS\nDIMENSIONS 4 4 4\n" + spacingLine + "POINT_DATA 64\nSCALARS s " + type +
         "\nLOOKUP_TABLE default\n" + data;
}

std::string mhd(const std::string& fields, const std::string& dataFile = "LOCAL") {
  return "NDims = 3\nDimSize = 4 4 4\nElementType = MET_UCHAR\n" + fields + "ElementDataFile = " + dataFile + "\n";
}

int lines(const std::string& s) { return int(std::count(s.begin(), s.end(), '\n')); }

}  // namespace

TEST_CASE("values whose range or gradients float arithmetic cannot hold are refused; a one-ulp range is kept") {
  TempDir dir;
  const std::string wide = dir.file("wide_4x4x4_float32.raw");
  writeFile(wide, floats(twoValues(3e38f, -3e38f)));
  expectRefused(wide, {"finite values -3e+38 .. 3e+38", "max - min = 6e+38 is too wide for float arithmetic"});
  // Decoded once (gzip), the same check.
  const std::string wideGz = dir.file("wide.nrrd");
  writeFile(wideGz, "NRRD0004\ntype: float\ndimension: 3\nsizes: 4 4 4\nendian: little\nencoding: gzip\n\n" +
                        test::deflateBytes(floats(twoValues(3e38f, -3e38f)), true));
  expectRefused(wideGz, {"too wide for float arithmetic"});

  // Shading squares gradients in float: 2e19 per unit of length overflows, 1e19 does not.
  const std::string steep = dir.file("steep_4x4x4_float32.raw");
  writeFile(steep, floats(twoValues(0.0f, 2e19f)));
  expectRefused(steep, {"gradients up to 2e+19 per unit of length are too steep", "at most 1e+19"});
  RawLayout wider;
  wider.spacing = glm::vec3(2.0f);
  auto spread = openVolumeFile(steep, wider);  // 1e19 per unit: accepted
  CHECK(spread->info().maxValue == 2e19f);
  // A spacing given instead of the data's is checked against the values again.
  checkMessage(errorOf([&] { RespacedSource(std::move(spread), glm::vec3(1.0f)); }), steep, {"too steep"});

  const std::string tiny = dir.file("tiny_4x4x4_float32.raw");
  writeFile(tiny, floats(twoValues(0.0f, std::numeric_limits<float>::denorm_min())));
  expectRefused(tiny, {"is too narrow for float arithmetic (at least 1e-33)"});

  // The narrowest range a float can express still maps (scale 2^23): kept as it is.
  const std::string ulp = dir.file("ulp_4x4x4_float32.raw");
  writeFile(ulp, floats(twoValues(1.0f, std::nextafter(1.0f, 2.0f), 1.0f)));
  const auto source = openVolumeFile(ulp);
  CHECK(source->info().minValue == 1.0f);
  CHECK(source->info().maxValue == std::nextafter(1.0f, 2.0f));

  // The command line: one line, exit 2, for render, info and export alike.
  for (const std::string& command : {"render --size 16x16 --out " + dir.file("x.png") + " --volume ", std::string("info --json "),
                                     "export --type uint16 --out " + dir.file("x.nrrd") + " --volume "}) {
    CAPTURE(command);
    const test::Run run = test::runKdswap(command + wide);
    CHECK(run.code == 2);
    CHECK(run.err.find("wide_4x4x4_float32.raw: finite values") != std::string::npos);
    CHECK(lines(run.err) == 1);
  }
}

TEST_CASE("a volume with no finite voxel is refused; a constant one opens with a one-line warning") {
  TempDir dir;
  const std::string nan = dir.file("nan_4x4x4_float32.raw");
  writeFile(nan, floats(std::vector<float>(64, kNaN)));
  expectRefused(nan, {"no finite voxel values: all 64 voxels are NaN or Inf"});
  std::vector<float> mixed(64, kInf);
  mixed[5] = -kInf;
  mixed[9] = kNaN;
  const std::string gz = dir.file("mixed.nrrd");
  writeFile(gz, "NRRD0004\ntype: float\ndimension: 3\nsizes: 4 4 4\nendian: little\nencoding: gzip\n\n" +
                    test::deflateBytes(floats(mixed), true));
  expectRefused(gz, {"no finite voxel values"});
  std::string words;
  for (int i = 0; i < 64; ++i) words += i % 2 ? "nan " : "inf ";
  const std::string ascii = dir.file("nan.vtk");
  writeFile(ascii, vtk("", "float", true, words + "\n"));
  expectRefused(ascii, {"no finite voxel values"});
  const test::Run render = test::runKdswap("render --size 16x16 --out " + dir.file("x.png") + " --volume " + nan);
  CHECK(render.code == 2);
  CHECK(render.err.find("no finite voxel values") != std::string::npos);
  CHECK(lines(render.err) == 1);

  const std::string constant = dir.file("seven_4x4x4_uint8.raw");
  writeFile(constant, std::string(64, '\7'));
  const test::Run info = test::runKdswap("info " + constant);
  CHECK(info.code == 0);
  CHECK(info.err.find("seven_4x4x4_uint8.raw: every voxel has the value 7: a constant volume has no value range") !=
        std::string::npos);
  CHECK(lines(info.err) == 1);

  // With NaN voxels too: both warnings, one line each.
  const std::string some = dir.file("some_4x4x4_float32.raw");
  writeFile(some, floats(twoValues(kNaN, 2.0f, 2.0f)));
  const test::Run both = test::runKdswap("info " + some);
  CHECK(both.code == 0);
  CHECK(both.err.find("1 NaN/Inf voxels") != std::string::npos);
  CHECK(both.err.find("every finite voxel has the value 2") != std::string::npos);
  CHECK(lines(both.err) == 2);

  // float64 values that differ only beyond float precision collapse to one float: said so.
  const std::string close = dir.file("close_4x4x4_float64.raw");
  std::vector<double> values(64, 1.0);
  values[7] = 1.0 + 1e-12;
  writeFile(close, doubles(values));
  const test::Run collapsed = test::runKdswap("info " + close);
  CHECK(collapsed.code == 0);
  CHECK(collapsed.err.find("every voxel has the value 1 at float precision") != std::string::npos);
}

TEST_CASE("spacings outside 1e-6 .. 1e6, or too unequal to render, are refused in every format and option") {
  TempDir dir;
  auto file = [&](const std::string& name, const std::string& bytes) {
    writeFile(dir.file(name), bytes);
    return dir.file(name);
  };
  expectRefused(file("huge.nrrd", nrrd("spacings: 1e38 1e38 1e38\n", ramp())),
                {"spacings \"1e38 1e38 1e38\": spacing along axis 0 is 1e+38, outside 1e-06 .. 1e+06"});
  expectRefused(file("tiny.nrrd", nrrd("spacings: 1e-38 1 1\n", ramp())),
                {"spacings \"1e-38 1 1\": spacing along axis 0 is 1e-38, outside 1e-06 .. 1e+06"});
  expectRefused(file("dirs.nrrd", nrrd("space directions: (1,0,0) (0,1e38,0) (0,0,1)\n", ramp())),
                {"space directions \"(1,0,0) (0,1e38,0) (0,0,1)\": spacing along axis 1 is 1e+38"});
  expectRefused(file("huge.mha", mhd("ElementSpacing = 1 1e38 1\n") + ramp()),
                {"ElementSpacing = 1 1e38 1: spacing along axis 1 is 1e+38, outside"});
  expectRefused(file("tiny.nii", nifti({1e-38f, 1.0f, 1.0f})), {"pixdim[1..3] = 1e-38 1 1: spacing along axis 0 is 1e-38"});
  expectRefused(file("huge.vtk", vtk("SPACING 1 1 1e20\n")), {"SPACING 1 1 1e20: spacing along axis 2 is 1e+20, outside"});

  // Within the bounds but 3e6 smallest spacings long: the ray march would outgrow float precision.
  expectRefused(file("flat.nrrd", nrrd("spacings: 1e-6 1 1\n", ramp())),
                {"the longest side (3 along axis 1) is 3e+06 times the smallest spacing (1e-06 along axis 0)",
                 "the spacings differ too much to render"});
  const std::string plain = file("plain_4x4x4_uint8.raw", ramp());
  RawLayout layout;
  layout.spacing = glm::vec3(1e-7f, 1.0f, 1.0f);
  expectRefused(plain, {"spacing from the command line: spacing along axis 0 is 1e-07, outside"}, layout);
  checkMessage(errorOf([&] { RespacedSource(openVolumeFile(plain), glm::vec3(1e-6f, 1.0f, 1.0f)); }), plain,
               {"spacing 1e-06 1 1 (replacing the data's): the longest side", "differ too much"});
  const std::string option = errorOf([] { parseSpacing("1e-7,1,1", "--spacing"); });
  CHECK(option.find("--spacing \"1e-7,1,1\": expected SX,SY,SZ, each a number from 1e-06 to 1e+06") != std::string::npos);
  // The bounds themselves are accepted.
  CHECK(RespacedSource(openVolumeFile(plain), glm::vec3(1e-6f)).info().spacing == glm::vec3(1e-6f));
  CHECK(RespacedSource(openVolumeFile(plain), glm::vec3(1e6f)).info().spacing == glm::vec3(1e6f));

  const test::Run run = test::runKdswap("render --size 16x16 --out " + dir.file("x.png") + " --volume " + dir.file("huge.nrrd"));
  CHECK(run.code == 2);
  CHECK(run.err.find("huge.nrrd: spacings") != std::string::npos);
  CHECK(lines(run.err) == 1);
}

TEST_CASE("NaN, Inf and zero spacings are refused naming the field in every format; negative ones are read as their size") {
  TempDir dir;
  auto file = [&](const std::string& name, const std::string& bytes) {
    writeFile(dir.file(name), bytes);
    return dir.file(name);
  };
  file("s.raw", ramp());
  const char* const kBad[] = {"nan", "inf", "0"};
  for (const std::string bad : kBad) {
    CAPTURE(bad);
    const std::string problem = "spacing along axis 0 must be a positive number, not " + bad;
    const std::string row = bad + " 1 1";
    if (bad != "nan")  // NRRD's "unknown", below
      expectRefused(file("s.nrrd", nrrd("spacings: " + row + "\n", ramp())), {"spacings \"" + row + "\": " + problem});
    expectRefused(file("s.mha", mhd("ElementSpacing = " + row + "\n") + ramp()), {"ElementSpacing = " + row + ": " + problem});
    expectRefused(file("s.mhd", mhd("ElementSize = " + row + "\n", "s.raw")), {"ElementSize = " + row + ": " + problem});
    const float value = bad == "nan" ? kNaN : bad == "inf" ? kInf : 0.0f;
    expectRefused(file("s.nii", nifti({value, 1.0f, 1.0f})), {"pixdim[1..3] = " + row + ": " + problem});
    expectRefused(file("s.vtk", vtk("SPACING " + row + "\n")), {"SPACING " + row + ": " + problem});
    expectRefused(file("a.vtk", vtk("ASPECT_RATIO " + row + "\n")), {"ASPECT_RATIO " + row + ": " + problem});
  }
  // NRRD defines NaN as "unknown" (teem accepts it, refusing only Inf and 0): read as 1.
  CHECK(openVolumeFile(file("unknown.nrrd", nrrd("spacings: nan 2 NaN\n", ramp())))->info().spacing == glm::vec3(1, 2, 1));

  // A negative spacing only reverses an axis, which kdswap ignores: every format reads its size.
  const glm::vec3 size(2.0f, 3.0f, 4.0f);
  CHECK(openVolumeFile(file("n.nrrd", nrrd("spacings: -2 3 -4\n", ramp())))->info().spacing == size);
  CHECK(openVolumeFile(file("d.nrrd", nrrd("space directions: (-2,0,0) (0,3,0) (0,0,-4)\n", ramp())))->info().spacing == size);
  CHECK(openVolumeFile(file("n.mha", mhd("ElementSpacing = -2 3 -4\n") + ramp()))->info().spacing == size);
  CHECK(openVolumeFile(file("n.nii", nifti({-2.0f, 3.0f, -4.0f})))->info().spacing == size);
  CHECK(openVolumeFile(file("n.vtk", vtk("SPACING -2 3 -4\n")))->info().spacing == size);
  // On the command line a negative spacing is a mistake, not an orientation.
  RawLayout layout;
  layout.spacing = glm::vec3(-1.0f, 1.0f, 1.0f);
  expectRefused(file("neg_4x4x4_uint8.raw", ramp()),
                {"spacing from the command line: spacing along axis 0 must be a positive number, not -1"}, layout);
}

TEST_CASE("bytes that are not printable text are escaped and capped in messages, which stay whole and one line") {
  TempDir dir;
  const std::string garbage("\x01\x00\x02\x7f\xff" "abc", 8);
  writeFile(dir.file("garbage.vtk"), vtk("", "float", true, "1 2 " + garbage + " 4\n"));
  const std::string message = errorOf([&] { openVolumeFile(dir.file("garbage.vtk")); });
  checkMessage(message, dir.file("garbage.vtk"), {"ASCII value 3 \"\\x01\\x00\\x02\\x7F\\xFFabc\": expected a number"});
  writeFile(dir.file("long.vtk"), vtk("", "float", true, "1 2 " + std::string(500, 'q') + "\n"));
  expectRefused(dir.file("long.vtk"), {"ASCII value 3 \"" + std::string(20, 'q') + "...\": expected a number"});
  writeFile(dir.file("line.nrrd"), "NRRD0004\ntype: uint8\n\x01sizes 4 4 4\n\n");
  expectRefused(dir.file("line.nrrd"), {"header line \"\\x01sizes 4 4 4\": expected \"field: value\""});
  writeFile(dir.file("line.mha"), std::string("NDims = 3\n\x02") + '\0' + "junk\nElementDataFile = LOCAL\n");
  expectRefused(dir.file("line.mha"), {"header line \"\\x02\\x00junk\": expected \"Key = Value\""});
  writeFile(dir.file("mode.vtk"), std::string("# vtk DataFile Version 3.0\nt\nBIN\0ARY\n", 37));
  expectRefused(dir.file("mode.vtk"), {"line 3 \"BIN\\x00ARY\": expected ASCII or BINARY"});
}

TEST_CASE("a directory, device or FIFO given as a volume or its data file is refused as such, naming the header") {
  TempDir dir;
  auto file = [&](const std::string& name, const std::string& bytes) {
    writeFile(dir.file(name), bytes);
    return dir.file(name);
  };
  const std::string head = "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 4 4\nencoding: raw\n";
  expectRefused(file("dot.nhdr", head + "data file: .\n"), {"data file \".\" (", "): is a directory"});
  expectRefused(file("zero.nhdr", head + "data file: /dev/zero\n"),
                {"data file \"/dev/zero\" (/dev/zero): is not a regular file (a device, FIFO or socket)"});
  REQUIRE(::mkfifo(dir.file("pipe.raw").c_str(), 0600) == 0);
  expectRefused(file("pipe.nhdr", head + "data file: pipe.raw\n"), {"data file \"pipe.raw\"", "is not a regular file"});
  expectRefused(file("lost.nhdr", head + "data file: lost.raw\n"), {"lost.raw): no such file"});
  fs::create_directories(dir.file("voxels"));
  expectRefused(file("dir.mhd", mhd("", "voxels")), {"ElementDataFile voxels (", "voxels): is a directory"});
  expectRefused(file("null.mhd", mhd("", "/dev/null")), {"ElementDataFile /dev/null (/dev/null): is not a regular file"});
  // The volume itself: a device or FIFO would be read without end, or block the open.
  fs::create_symlink("/dev/zero", dir.file("device.nrrd"));
  expectRefused(dir.file("device.nrrd"), {"is not a regular file (a device, FIFO or socket): expected a volume file"});
  expectRefused(dir.file("pipe.raw"), {"is not a regular file"});
}

TEST_CASE("NRRD magics NRRD0001 to NRRD0005 are read; other versions are refused by the same words") {
  TempDir dir;
  for (const std::string version : {"1", "4", "5"}) {
    writeFile(dir.file("ok.nrrd"), "NRRD000" + version + "\ntype: uint8\ndimension: 3\nsizes: 4 4 4\nencoding: raw\n\n" + ramp());
    CHECK(openVolumeFile(dir.file("ok.nrrd"))->info().dims == glm::ivec3(4));
  }
  for (const std::string magic : {"NRRD0009", "NRRD0000", "NRRD00045", "NRRD0006"}) {
    CAPTURE(magic);
    writeFile(dir.file("new.nrrd"), magic + "\ntype: uint8\ndimension: 3\nsizes: 4 4 4\nencoding: raw\n\n" + ramp());
    expectRefused(dir.file("new.nrrd"),
                  {"NRRD magic \"" + magic + "\": unsupported format version (expected NRRD0001 .. NRRD0005)"});
  }
  writeFile(dir.file("other.nrrd"), "PNG\n");
  expectRefused(dir.file("other.nrrd"), {"not a NRRD file: first line \"PNG\": expected NRRD0001 .. NRRD0005"});
}

TEST_CASE("raw layout options state their real limits and refuse a negative skip") {
  TempDir dir;
  const std::string raw = dir.file("plain.raw");
  writeFile(raw, ramp());
  const test::Run skip = test::runKdswap("info " + raw + " --raw-dims 4x4x4 --raw-type uint8 --raw-skip -1");
  CHECK(skip.code == 2);
  CHECK(skip.err == "kdswap: --raw-skip -1: expected a number of bytes >= 0\n");
  for (const std::string& command : {"info " + raw + " --raw-type uint8 --raw-dims ",
                                    "render --size 16x16 --out " + dir.file("x.png") + " --raw-type uint8 --volume " + raw +
                                        " --raw-dims "}) {
    for (const std::string dims : {"1000001x2x2", "1x4x4"}) {
      CAPTURE(command + dims);
      const test::Run run = test::runKdswap(command + dims);
      CHECK(run.code == 2);
      CHECK(run.err == "kdswap: --raw-dims \"" + dims + "\": each size must be a whole number from 2 to 1000000\n");
    }
  }
  CHECK(test::runKdswap("info " + raw + " --raw-dims 2x4x8 --raw-type uint8").code == 0);
}

TEST_CASE("a raw layout given for a file whose header gives its layout is refused, naming the format") {
  TempDir dir;
  const std::pair<const char*, const char*> kFormats[] = {
      {"v.nrrd", "NRRD"},         {"v.nhdr", "NRRD"},       {"v.mhd", "MetaImage"}, {"v.mha", "MetaImage"},
      {"v.nii", "NIfTI-1"},       {"v.nii.gz", "NIfTI-1"},  {"v.vtk", "legacy VTK"}};
  RawLayout dims, type, spacing;
  dims.dims = glm::ivec3(4, 4, 4);
  dims.type = "uint8";
  type.type = "float32";
  spacing.spacing = glm::vec3(2.0f);
  for (const auto& [name, format] : kFormats) {
    CAPTURE(name);
    writeFile(dir.file(name), ramp());  // never read: the header would be taken for voxels
    const std::string problem = std::string("applies only to raw files: this is a ") + format +
                                " file, whose header gives its own layout";
    expectRefused(dir.file(name), {problem}, dims);
    expectRefused(dir.file(name), {problem}, type);
    expectRefused(dir.file(name), {problem}, spacing);
  }
  const test::Run run = test::runKdswap("info " + dir.file("v.nhdr") + " --raw-type float32");
  CHECK(run.code == 2);
  CHECK(run.err.find("v.nhdr: a raw layout") != std::string::npos);
  CHECK(run.err.find("raw file layout unknown") == std::string::npos);
  // Any other name is still read as raw when a layout is given.
  writeFile(dir.file("volume.dat"), ramp());
  CHECK(openVolumeFile(dir.file("volume.dat"), dims)->info().maxValue == 63.0f);
}

}  // namespace kdswap
