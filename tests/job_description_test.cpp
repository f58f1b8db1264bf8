// JobDescription: MPI ranks that were started with another volume or other options are told apart
// from ranks that agree, and the difference is named.
#include <doctest/doctest.h>

#include "core/cluster/frame_request.h"
#include "core/cluster/job_description.h"
#include "core/util/error.h"
#include "test_support.h"

namespace kdswap {
namespace {

struct Job {
  std::unique_ptr<MemoryVolume> volume = test::makeBlobs({24, 20, 17});
  FrameRequest request;
  ClusterOptions options;

  Job() { request.transfer = test::testTransfer(); }
  JobDescription describe(int nodesPerRank = 2) const { return describeJob(*volume, request, options, nodesPerRank); }
};

//! The first difference of `a` against `b`, with the names the MPI host uses.
std::string difference(const JobDescription& a, const JobDescription& b) {
  return a.firstDifference(b, "on rank 1", "on rank 0");
}

TEST_CASE("job description: the same job described twice agrees, and survives serialization") {
  const Job a, b;
  CHECK(difference(a.describe(), b.describe()).empty());
  const JobDescription sent = JobDescription::parse(a.describe().serialize(), "rank 1");
  CHECK(difference(sent, b.describe()).empty());
  CHECK(sent.fields == a.describe().fields);
}

TEST_CASE("job description: another file of the same size is told by the voxels of its middle slice") {
  const Job a;
  Job b;
  const glm::ivec3 dims = a.volume->info().dims;
  // One voxel of the middle z slice changed, within the volume's range (same header figures).
  std::vector<float> voxels = a.volume->voxels();
  const std::size_t at = (std::size_t(dims.z / 2) * dims.y + 7) * dims.x + 9;
  voxels[at] = 0.5f * (a.volume->info().minValue + a.volume->info().maxValue) + 1e-3f;
  VolumeInfo info = a.volume->info();
  b.volume = std::make_unique<MemoryVolume>(info, voxels);
  REQUIRE(b.volume->info().minValue == a.volume->info().minValue);
  REQUIRE(b.volume->info().maxValue == a.volume->info().maxValue);
  const std::string d = difference(b.describe(), a.describe());
  CHECK(d.find("volume content") == 0);
  CHECK(d.find("z slices 1, 3, 5, 7, 8, 9, 11, 13, 15)") != std::string::npos);
  CHECK(d.find("on rank 1") != std::string::npos);
  CHECK(d.find("on rank 0") != std::string::npos);
}

TEST_CASE("job description: a difference in another eighth of z than the middle is told too") {
  const Job a;
  const glm::ivec3 dims = a.volume->info().dims;
  for (const int z : {1, 15}) {  // sampled slices of the first and the last eighth
    CAPTURE(z);
    Job b;
    std::vector<float> voxels = a.volume->voxels();
    voxels[(std::size_t(z) * dims.y + 5) * dims.x + 3] = 0.5f * (a.volume->info().minValue + a.volume->info().maxValue);
    b.volume = std::make_unique<MemoryVolume>(a.volume->info(), voxels);
    CHECK(difference(b.describe(), a.describe()).find("volume content") == 0);
  }
}

TEST_CASE("job description: each kind of disagreement is named") {
  const Job reference;
  const JobDescription expected = reference.describe();
  auto check = [&](const Job& other, const char* what, int nodesPerRank = 2) {
    CAPTURE(what);
    const std::string d = difference(other.describe(nodesPerRank), expected);
    CHECK(d.find(std::string(what) + ": ") == 0);
  };
  {
    Job j;
    j.volume = test::makeBlobs({24, 20, 18});
    check(j, "volume size");
  }
  {
    Job j;
    j.volume = test::makeBlobs({24, 20, 17}, glm::vec3(1.0f, 1.0f, 2.0f));
    check(j, "volume spacing");
  }
  {
    Job j;
    j.request.width = 100;
    check(j, "image size");
  }
  {
    Job j;
    j.request.view.azimuthDeg += 1.0f;
    check(j, "view");
  }
  {
    Job j;
    j.request.transfer = TransferFunction::ramp(0.1f, 0.8f);
    check(j, "transfer function");
  }
  {
    Job j;
    j.request.settings.stepVoxels = 1.0f;
    check(j, "render settings");
  }
  {
    Job j;
    j.request.settings.valueRange = glm::vec2(0.0f, 2.0f);
    check(j, "render settings");
  }
  {
    Job j;
    j.options.strategy = "direct-send";
    check(j, "compositing");
  }
  {
    Job j;
    j.options.composite.sparse = true;
    check(j, "compositing");
  }
  {
    Job j;
    j.options.partition = PartitionKind::Slab;
    check(j, "partition");
  }
  {
    Job j;
    j.options.voxels = VoxelChoice::Compact;
    check(j, "voxel storage");
  }
  check(Job(), "nodes per rank", 3);
}

TEST_CASE("job description: what does not change the picture is not compared") {
  const Job a;
  Job b;
  // The same curve under another name, and another volume name (hosts mount files differently).
  b.request.transfer = TransferFunction(a.request.transfer.colors(), a.request.transfer.opacity(), "renamed");
  VolumeInfo info = a.volume->info();
  info.name = "/other/mount/point/blobs.raw";
  b.volume = std::make_unique<MemoryVolume>(info, a.volume->voxels());
  b.options.threads = 7;
  b.options.stallSeconds = 5;
  CHECK(difference(b.describe(), a.describe()).empty());
}

TEST_CASE("job description: a malformed description is an error naming its sender") {
  CHECK_THROWS_WITH_AS(JobDescription::parse("not json", "rank 3 (nodes 6..7)"),
                       doctest::Contains("rank 3 (nodes 6..7): malformed job description"), Error);
  CHECK_THROWS_AS(JobDescription::parse("[[\"size\"]]", "rank 1"), Error);
  // A description from a build that describes jobs otherwise: fewer fields, or others.
  JobDescription fewer = Job().describe();
  fewer.fields.pop_back();
  CHECK(difference(fewer, Job().describe()).find("different fields") != std::string::npos);
  const JobDescription other = JobDescription::parse("[[\"disk size\", \"2\"]]", "rank 1");
  CHECK(difference(other, Job().describe()).find("different fields") != std::string::npos);
}

}  // namespace
}  // namespace kdswap
