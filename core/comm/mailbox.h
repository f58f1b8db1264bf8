// Mailbox: one node's incoming messages. Lock-free multi-producer, single-consumer: producers
// push onto an atomic list (Treiber stack) and the consumer takes the whole list at once, so no
// mutex or condition variable is on the send or receive path. A consumer with nothing to read
// suspends its oneTBB task (tbb::task::suspend); the next post resumes it. Suspended tasks hold no
// worker thread, so thousands of waiting nodes run on two threads.
//
// Ordering: one producer's posts are pushed in program order and the consumer reverses each
// batch it takes, so messages between a pair of nodes arrive in the order sent.
#pragma once

#include <atomic>
#include <deque>

#include <oneapi/tbb/task.h>

#include "core/comm/message.h"

namespace kdswap {

//! Thrown by Mailbox::take when the mailbox was aborted while (or before) waiting.
struct MailboxAborted {};

class Mailbox {
 public:
  static constexpr int kAnySource = -2;
  static constexpr int kAbortMarkerTag = -2147483647;  //!< never a real tag

  //! How an empty take() waits: suspend the calling oneTBB task (virtual nodes), or block the
  //! calling thread on the atomic list head (C++20 atomic wait: a futex, still no mutex) for
  //! consumers that are plain threads, such as an MPI progress loop or a ThreadSanitizer test.
  enum class WaitMode { SuspendTask, BlockThread };

  explicit Mailbox(WaitMode mode = WaitMode::SuspendTask) : mode_(mode) {}
  Mailbox(const Mailbox&) = delete;
  Mailbox& operator=(const Mailbox&) = delete;
  ~Mailbox();

  //! Any thread. The message belongs to the mailbox (then its consumer) from here on.
  void post(Message message);
  //! Consumer only (from inside a oneTBB task in SuspendTask mode): the next message from `source` (or kAnySource)
  //! with `tag`, suspending until one arrives. Adds the time spent suspended to `waitedSeconds`.
  //! Throws MailboxAborted once abort() has been called and no matching message is queued.
  Message take(int source, int tag, double& waitedSeconds);
  //! Consumer only, never waits: true and the message if one matches now.
  bool tryTake(int source, int tag, Message& out);
  //! Any thread: wakes the consumer for good; its waits throw MailboxAborted from now on.
  void abort();
  //! Any thread, diagnostic only: what the consumer is waiting for, if it is waiting.
  bool waitingFor(int& source, int& tag) const;
  //! Resets after an aborted frame (consumer gone, no concurrent use): drops queued messages.
  void reset();

 private:
  struct Node {
    Message message;
    Node* next;
  };

  void drain();                                   // consumer: move posted messages to pending_
  bool findPending(int source, int tag, Message& out);  // consumer

  //! Posted, not yet drained; newest first. Producers CAS-push (release); the consumer exchanges
  //! it with null (acquire), which makes each message's contents visible to the consumer.
  std::atomic<Node*> head_{nullptr};
  //! The consumer's suspend point while it sleeps. Written by the consumer (seq_cst store) before
  //! it re-checks head_; producers and abort() exchange it with null (seq_cst) after publishing,
  //! so either the consumer sees the new message or the producer sees the waiter: never neither.
  std::atomic<tbb::task::suspend_point> waiter_{nullptr};
  //! Set once by abort() (seq_cst, same handshake as head_), read by the consumer.
  std::atomic<bool> aborted_{false};
  //! Diagnostic copy of the consumer's wait (relaxed: read only by the stall reporter).
  std::atomic<int> waitSource_{0}, waitTag_{0};
  std::atomic<bool> waiting_{false};
  std::deque<Message> pending_;  //!< consumer only: drained, in arrival order
  const WaitMode mode_;
};

}  // namespace kdswap
