// JobDescription: what every MPI rank must agree on to render one frame together. Each rank parses
// its own command line and opens its own copy of the volume, so an MPMD launch with two files, or
// a host whose copy of the file differs, would otherwise render a mixed image without a word. The
// ranks describe their job the same way and rank 0 compares each rank's description with its own.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace kdswap {

class VolumeSource;
struct FrameRequest;
struct ClusterOptions;

struct JobDescription {
  //! (what, value) in a fixed order; values are text, floats written to round trip exactly.
  std::vector<std::pair<std::string, std::string>> fields;

  std::string serialize() const;
  //! Throws kdswap::Error naming `from` when the text is not a serialized description.
  static JobDescription parse(const std::string& text, const std::string& from);

  //! Empty when the two agree; otherwise the first field that differs, as "WHAT: VALUE NAME,
  //! REFERENCE_VALUE REFERENCE_NAME" (one line), e.g. names "on rank 2" and "on rank 0".
  std::string firstDifference(const JobDescription& reference, const std::string& name,
                              const std::string& referenceName) const;
};

//! The volume's header figures (dims, spacing, type, value range) and a CRC-32 of the voxels of
//! its middle z slice and of one slice in each eighth of z (file content that headers do not show:
//! another time step, another patient),
//! the request (view, size, transfer function, settings) and the options that shape the partition
//! and the compositing. Not the file's path: hosts may mount the same file at different places.
JobDescription describeJob(const VolumeSource& source, const FrameRequest& request, const ClusterOptions& options,
                           int nodesPerRank);

}  // namespace kdswap
