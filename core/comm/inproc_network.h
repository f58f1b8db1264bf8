// InprocNetwork: the virtual cluster's interconnect, one Mailbox per node plus one for the host.
// InprocCommunicator: a node's (or the host's) Communicator over it.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "core/comm/communicator.h"
#include "core/comm/mailbox.h"

namespace kdswap {

class InprocNetwork {
 public:
  //! `waitMode`: SuspendTask when nodes are oneTBB tasks, BlockThread when each node is a thread.
  explicit InprocNetwork(int nodes, Mailbox::WaitMode waitMode = Mailbox::WaitMode::SuspendTask);

  int nodes() const { return int(mailboxes_.size()) - 1; }
  //! Mailbox of `rank` (0 .. nodes-1) or Communicator::kHost.
  Mailbox& mailbox(int rank) { return *mailboxes_[std::size_t(rank + 1)]; }

  //! Ends the current frame: every waiting or future receive throws kdswap::Error(reason).
  //! The first reason wins. Any thread.
  void abort(const std::string& reason);
  bool aborted() const { return aborted_.load(std::memory_order_acquire); }
  std::string abortReason() const;
  //! Clears an abort and drops undelivered messages, between frames (no task running).
  void reset();

  //! Messages delivered so far; the stall watchdog reads it to see progress (relaxed).
  std::uint64_t delivered() const { return delivered_.load(std::memory_order_relaxed); }
  void countDelivery() { delivered_.fetch_add(1, std::memory_order_relaxed); }
  //! "node 3 waits for node 2 (tag 101); ..." for every node currently waiting.
  std::string describeWaits() const;
  //! Participants currently blocked in a receive (their mailbox waits).
  int waitingCount() const;
  //! Senders held up inside the transport (fault injection's delays): they wait on the network,
  //! not on their own work, so the stall watchdog counts them with the waiting ones.
  int inTransport() const { return inTransport_.load(std::memory_order_relaxed); }
  void enterTransport() { inTransport_.fetch_add(1, std::memory_order_relaxed); }
  void leaveTransport() { inTransport_.fetch_sub(1, std::memory_order_relaxed); }

 private:
  std::vector<std::unique_ptr<Mailbox>> mailboxes_;
  std::atomic<bool> aborted_{false};
  std::atomic<std::uint64_t> delivered_{0};
  std::atomic<int> inTransport_{0};
  mutable std::mutex reasonMutex_;  //!< guards reason_ only; never taken on the message path
  std::string reason_;
};

class InprocCommunicator : public Communicator {
 public:
  //! Test hook run on every outgoing message after its checksum is taken: may change it, sleep,
  //! throw, or return false to drop it (fault injection).
  using SendFilter = std::function<bool(Message&)>;

  InprocCommunicator(InprocNetwork& network, int rank, bool checksums = false, SendFilter filter = {})
      : network_(network), rank_(rank), checksums_(checksums), filter_(std::move(filter)) {}

  int rank() const override { return rank_; }
  int size() const override { return network_.nodes(); }
  void send(int dest, int tag, Message message) override;
  Message receive(int source, int tag) override;
  const CommCounters& counters() const override { return counters_; }

 private:
  InprocNetwork& network_;
  int rank_;
  bool checksums_;
  SendFilter filter_;
  CommCounters counters_;
};

}  // namespace kdswap
