// MpiCommunicator: a node's (or the host's) Communicator over an MpiNetwork, so the node program
// and every compositing strategy run unchanged on MPI ranks. Sends to a node on this rank are
// mailbox moves; sends to other ranks go over MPI point-to-point (see mpi_network.h).
#pragma once

#if KDSWAP_HAVE_MPI

#include "core/comm/communicator.h"
#include "core/comm/mpi_network.h"
#include "core/util/error.h"

namespace kdswap {

//! Thrown by MpiCommunicator::receive when the frame was aborted elsewhere: the failure that
//! caused it has already been reported, so whoever catches this need not report it again.
class FrameAborted : public Error {
 public:
  using Error::Error;
};

class MpiCommunicator : public Communicator {
 public:
  //! `node` is a global node index living on this rank, or kHost on rank 0.
  MpiCommunicator(MpiNetwork& network, int node) : network_(network), node_(node) {}

  int rank() const override { return node_; }
  int size() const override { return network_.nodes(); }
  //! Any thread; never blocks (a remote message is queued for the progress thread).
  void send(int dest, int tag, Message message) override;
  //! From inside a oneTBB task (the wait suspends it). Throws FrameAborted after abortAll.
  Message receive(int source, int tag) override;
  const CommCounters& counters() const override { return counters_; }

 private:
  MpiNetwork& network_;
  int node_;
  CommCounters counters_;
};

}  // namespace kdswap

#endif  // KDSWAP_HAVE_MPI
