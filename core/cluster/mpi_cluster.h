// One frame of the node program on MPI ranks (issue 7): each rank computes the same k-d tree,
// reads its own nodes' bricks straight from the volume source (parallel I/O, no volume broadcast),
// renders and composites them with the unchanged node program; rank 0 is also the host and
// gathers the tiles and every node's report.
#pragma once

#if KDSWAP_HAVE_MPI

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "core/cluster/virtual_cluster.h"
#include "core/comm/mpi_network.h"

namespace kdswap {

//! Message tags of the MPI frame protocol (beside kTileTag): each rank's first node -> host "my
//! rank's job description", host -> node "the ranks agree: load your brick", node -> host "brick
//! loaded", host -> node "start the frame", node -> host "my NodeReport" (JSON text).
inline constexpr int kJobTag = 15;
inline constexpr int kLoadTag = 16;
inline constexpr int kReadyTag = 12;
inline constexpr int kGoTag = 13;
inline constexpr int kReportTag = 14;

struct MpiFrameOutcome {
  bool ok = false;          //!< rank 0: the frame completed; other ranks: no failure seen locally
  std::string error;        //!< rank 0, when !ok: the first failure, naming its node and rank
  FrameResult result;       //!< rank 0, when ok: image, stats (per node), tiles
  int ranks = 1, nodesPerRank = 1;
  std::vector<std::uint64_t> rankPeakRss;  //!< rank 0: peak resident bytes of each rank
  std::vector<double> nodeLoadSeconds;     //!< rank 0: each node's brick read + gradients

  //! FrameStats::toJson() plus "ranks", "nodes_per_rank" and "per_rank" (rank, nodes, memory).
  nlohmann::json statsJson() const;
};

//! Collective: every rank calls it once, with the same request and options (built from the same
//! command line). `source` and `request` are null on a rank that failed to prepare; that rank
//! must already have called network.abortAll(reason). Finishes `network` (no MPI traffic may
//! follow through it). Never throws for a node's failure: it is in the outcome on rank 0.
MpiFrameOutcome renderFrameOverMpi(MpiNetwork& network, const VolumeSource* source, const FrameRequest* request,
                                   const ClusterOptions& options);

}  // namespace kdswap

#endif  // KDSWAP_HAVE_MPI
