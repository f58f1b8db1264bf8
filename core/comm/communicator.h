// Communicator: the only way nodes talk (IceT's communicator table). The node program, the
// partition and every compositing strategy are written against it; transports implement it
// (in-process mailboxes, MPI).
#pragma once

#include <cstdint>

#include "core/comm/message.h"

namespace kdswap {

//! Traffic and waiting seen by one node's communicator, cumulative since it was made.
struct CommCounters {
  std::uint64_t bytesSent = 0, bytesReceived = 0;
  std::uint64_t messagesSent = 0, messagesReceived = 0;
  double waitSeconds = 0.0;  //!< time spent blocked in receive()
};

class Communicator {
 public:
  static constexpr int kHost = -1;  //!< the host program's rank (data distributor, image gatherer)

  virtual ~Communicator() = default;
  virtual int rank() const = 0;  //!< this node, 0 .. size()-1
  virtual int size() const = 0;  //!< number of nodes (the host is not counted)
  //! Sends `message` to node `dest` (or kHost) with `tag`; the message is consumed. Messages
  //! between a pair of ranks arrive in the order sent. Never blocks on the receiver.
  virtual void send(int dest, int tag, Message message) = 0;
  //! Waits for the next message from `source` with `tag`. On the in-process transport the wait
  //! suspends the node's task and frees the worker thread. Throws kdswap::Error if the frame is
  //! aborted (another node failed, or the wait stalled past the cluster's time limit).
  virtual Message receive(int source, int tag) = 0;
  virtual const CommCounters& counters() const = 0;
};

}  // namespace kdswap
