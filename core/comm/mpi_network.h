// MpiNetwork: the interconnect of one MPI rank that hosts K virtual nodes (hybrid: P = ranks x K).
// Node v lives on rank v / K; the host (Communicator::kHost) lives on rank 0. Each local node, and
// the host on rank 0, has a Mailbox as in the in-process network; a send to a node on the same rank
// is a move into its mailbox, a send to another rank goes through MPI. One progress thread per rank
// owns every MPI call while the network runs (MPI_THREAD_SERIALIZED is enough): it sends queued
// messages with MPI_Isend and posts arriving ones into the destination node's mailbox.
#pragma once

#if KDSWAP_HAVE_MPI

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "core/comm/mailbox.h"
#include "core/comm/message.h"

namespace kdswap {

//! MPI_Init_thread / MPI_Finalize for one program run. Throws kdswap::Error if the library cannot
//! give MPI_THREAD_SERIALIZED (calls from the progress thread, then from the main thread).
class MpiSession {
 public:
  MpiSession(int& argc, char**& argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }

 private:
  int rank_ = 0, size_ = 1;
};

class MpiNetwork {
 public:
  //! Starts the progress thread. Collective in spirit: every rank makes one with the same K.
  //! `stallSeconds`: a rank whose nodes wait with no traffic for this long aborts the frame.
  MpiNetwork(int nodesPerRank, double stallSeconds);
  //! Calls finish() if it was not called; never throws.
  ~MpiNetwork();

  int worldRank() const { return rank_; }
  int worldSize() const { return ranks_; }
  int nodesPerRank() const { return perRank_; }
  int nodes() const { return ranks_ * perRank_; }               //!< P, the host not counted
  int firstLocalNode() const { return rank_ * perRank_; }
  int rankOf(int node) const { return node < 0 ? 0 : node / perRank_; }  //!< kHost -> 0
  bool isLocal(int node) const { return rankOf(node) == rank_; }

  //! Mailbox of local node `node` (global index) or of the host (rank 0 only).
  Mailbox& mailbox(int node);
  //! Any thread. Moves `message` (source and tag already set) to node `dest` or kHost: a mailbox
  //! post if `dest` is local, else the progress thread sends it. The message is consumed.
  void deliver(int dest, Message message);

  //! Any thread. Ends the frame on every rank: local waits throw, and the reason is sent to every
  //! other rank, whose waits throw too. The first reason a rank hears wins there.
  void abortAll(const std::string& reason);
  bool aborted() const { return aborted_.load(std::memory_order_acquire); }
  std::string abortReason() const;

  //! Main thread, once every local task has ended, on every rank: waits until this rank's sends
  //! have completed and every rank got that far (MPI_Ibarrier, still receiving meanwhile), then
  //! stops the progress thread. MPI calls from the main thread are allowed from then on.
  void finish();

 private:
  class Progress;  // the progress thread's state (MPI requests), in the .cpp
  friend class Progress;

  void abortLocal(const std::string& reason);
  void noteTraffic() { traffic_.fetch_add(1, std::memory_order_relaxed); }
  std::string describeWaits() const;

  int rank_ = 0, ranks_ = 1, perRank_ = 1;
  //! [0, K): local nodes; [K]: the host, on rank 0 only.
  std::vector<std::unique_ptr<Mailbox>> mailboxes_;
  //! Set by abortLocal (release), read by any thread (acquire) before it trusts abortReason().
  std::atomic<bool> aborted_{false};
  //! Bumped on every delivery and MPI arrival (relaxed): the stall check only compares values.
  std::atomic<std::uint64_t> traffic_{0};
  mutable std::mutex reasonMutex_;  //!< guards reason_; never taken on the message path
  std::string reason_;
  std::unique_ptr<Progress> progress_;
};

}  // namespace kdswap

#endif  // KDSWAP_HAVE_MPI
