// In-process transport: messages are moved between mailboxes; nothing is copied.
#include "core/comm/inproc_network.h"

#include "core/util/check.h"
#include "core/util/error.h"

namespace kdswap {

InprocNetwork::InprocNetwork(int nodes, Mailbox::WaitMode waitMode) {
  mailboxes_.reserve(std::size_t(nodes) + 1);
  for (int i = 0; i <= nodes; ++i) mailboxes_.push_back(std::make_unique<Mailbox>(waitMode));
}

void InprocNetwork::abort(const std::string& reason) {
  {
    std::lock_guard<std::mutex> lock(reasonMutex_);
    if (reason_.empty()) reason_ = reason;
  }
  aborted_.store(true, std::memory_order_release);
  for (auto& box : mailboxes_) box->abort();
}

std::string InprocNetwork::abortReason() const {
  std::lock_guard<std::mutex> lock(reasonMutex_);
  return reason_;
}

void InprocNetwork::reset() {
  for (auto& box : mailboxes_) box->reset();
  std::lock_guard<std::mutex> lock(reasonMutex_);
  reason_.clear();
  aborted_.store(false, std::memory_order_release);
}

int InprocNetwork::waitingCount() const {
  int count = 0;
  for (const auto& box : mailboxes_) {
    int source = 0, tag = 0;
    if (box->waitingFor(source, tag)) ++count;
  }
  return count;
}

std::string InprocNetwork::describeWaits() const {
  std::string text;
  int shown = 0, total = 0;
  for (std::size_t i = 0; i < mailboxes_.size(); ++i) {
    int source = 0, tag = 0;
    if (!mailboxes_[i]->waitingFor(source, tag)) continue;
    ++total;
    if (shown++ >= 8) continue;
    const int rank = int(i) - 1;
    if (!text.empty()) text += "; ";
    text += (rank < 0 ? std::string("host") : "node " + std::to_string(rank)) + " waits for " +
            (source == Mailbox::kAnySource ? std::string("any node")
             : source < 0                  ? std::string("the host")
                                           : "node " + std::to_string(source)) +
            " (tag " + std::to_string(tag) + ")";
  }
  if (total > shown) text += "; and " + std::to_string(total - shown) + " more";
  return text.empty() ? "no node is waiting" : text;
}

void InprocCommunicator::send(int dest, int tag, Message message) {
  KDSWAP_CHECK(dest == kHost || (dest >= 0 && dest < size()));
  message.source = rank_;
  message.tag = tag;
  counters_.bytesSent += message.bytes();
  ++counters_.messagesSent;
  if (checksums_) message.checksum = messageChecksum(message);
  if (filter_) {
    struct InTransport {  // a filter may sleep (a delayed message) or throw
      InprocNetwork& network;
      explicit InTransport(InprocNetwork& n) : network(n) { network.enterTransport(); }
      ~InTransport() { network.leaveTransport(); }
    } inTransport(network_);
    if (!filter_(message)) return;  // dropped by fault injection
  }
  network_.mailbox(dest).post(std::move(message));
  network_.countDelivery();
}

Message InprocCommunicator::receive(int source, int tag) {
  try {
    Message m = network_.mailbox(rank_).take(source, tag, counters_.waitSeconds);
    counters_.bytesReceived += m.bytes();
    ++counters_.messagesReceived;
    // No "node N: " here: the cluster prefixes every node's error with it (runOnNodes).
    if (m.checksum != 0 && m.checksum != messageChecksum(m))
      throw Error("message from " +
                  (m.source < 0 ? std::string("the host") : "node " + std::to_string(m.source)) + " (tag " +
                  std::to_string(m.tag) + ") failed its checksum: corrupted in transit, not composited");
    return m;
  } catch (const MailboxAborted&) {
    throw Error("node " + std::to_string(rank_) + ": frame aborted while waiting for " +
                (source < 0 ? std::string("the host") : "node " + std::to_string(source)) + " (tag " +
                std::to_string(tag) + "): " + network_.abortReason());
  }
}

}  // namespace kdswap
