// Lock-free MPSC mailbox with task suspension; see mailbox.h for the protocol.
#include "core/comm/mailbox.h"

#include "core/util/clock.h"

namespace kdswap {

Mailbox::~Mailbox() {
  Node* n = head_.exchange(nullptr, std::memory_order_acquire);
  while (n) {
    Node* next = n->next;
    delete n;
    n = next;
  }
}

void Mailbox::post(Message message) {
  Node* node = new Node{std::move(message), head_.load(std::memory_order_relaxed)};
  while (!head_.compare_exchange_weak(node->next, node, std::memory_order_seq_cst, std::memory_order_relaxed)) {
  }
  if (mode_ == WaitMode::BlockThread) {
    head_.notify_one();
    return;
  }
  if (tbb::task::suspend_point sleeper = waiter_.exchange(nullptr, std::memory_order_seq_cst))
    tbb::task::resume(sleeper);
}

void Mailbox::abort() {
  aborted_.store(true, std::memory_order_seq_cst);
  if (mode_ == WaitMode::BlockThread) {
    // A blocked consumer wakes only when head_ changes: post a marker no take() ever matches.
    Message marker;
    marker.tag = kAbortMarkerTag;
    post(std::move(marker));
    return;
  }
  if (tbb::task::suspend_point sleeper = waiter_.exchange(nullptr, std::memory_order_seq_cst))
    tbb::task::resume(sleeper);
}

void Mailbox::drain() {
  Node* list = head_.exchange(nullptr, std::memory_order_acquire);
  // The list is newest first; reverse it so pending_ stays in arrival order.
  Node* reversed = nullptr;
  while (list) {
    Node* next = list->next;
    list->next = reversed;
    reversed = list;
    list = next;
  }
  while (reversed) {
    Node* next = reversed->next;
    pending_.push_back(std::move(reversed->message));
    delete reversed;
    reversed = next;
  }
}

bool Mailbox::findPending(int source, int tag, Message& out) {
  for (auto it = pending_.begin(); it != pending_.end(); ++it) {
    if (it->tag == tag && (source == kAnySource || it->source == source)) {
      out = std::move(*it);
      pending_.erase(it);
      return true;
    }
  }
  return false;
}

bool Mailbox::tryTake(int source, int tag, Message& out) {
  if (findPending(source, tag, out)) return true;
  drain();
  return findPending(source, tag, out);
}

Message Mailbox::take(int source, int tag, double& waitedSeconds) {
  Message out;
  for (;;) {
    if (tryTake(source, tag, out)) return out;
    if (aborted_.load(std::memory_order_seq_cst)) throw MailboxAborted{};
    waitSource_.store(source, std::memory_order_relaxed);
    waitTag_.store(tag, std::memory_order_relaxed);
    waiting_.store(true, std::memory_order_relaxed);
    const double start = nowSeconds();
    if (mode_ == WaitMode::BlockThread) {
      // Waits while the list is empty; abort() notifies, and the loop re-checks aborted_.
      head_.wait(nullptr, std::memory_order_acquire);
      waitedSeconds += nowSeconds() - start;
      waiting_.store(false, std::memory_order_relaxed);
      continue;
    }
    tbb::task::suspend([this](tbb::task::suspend_point self) {
      waiter_.store(self, std::memory_order_seq_cst);
      // Re-check after publishing the waiter: a post or abort that came before it found no one
      // to wake. Whoever takes the waiter back (we or a producer) resumes it, exactly once.
      if (head_.load(std::memory_order_seq_cst) != nullptr || aborted_.load(std::memory_order_seq_cst)) {
        if (tbb::task::suspend_point mine = waiter_.exchange(nullptr, std::memory_order_seq_cst))
          tbb::task::resume(mine);
      }
    });
    waitedSeconds += nowSeconds() - start;
    waiting_.store(false, std::memory_order_relaxed);
  }
}

bool Mailbox::waitingFor(int& source, int& tag) const {
  if (!waiting_.load(std::memory_order_relaxed)) return false;
  source = waitSource_.load(std::memory_order_relaxed);
  tag = waitTag_.load(std::memory_order_relaxed);
  return true;
}

void Mailbox::reset() {
  drain();
  pending_.clear();
  aborted_.store(false, std::memory_order_seq_cst);
  waiter_.store(nullptr, std::memory_order_seq_cst);
  waiting_.store(false, std::memory_order_relaxed);
}

}  // namespace kdswap
