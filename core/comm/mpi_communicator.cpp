// MPI communicator: counts traffic the way the in-process one does, so stats compare directly.
#include "core/comm/mpi_communicator.h"

#if KDSWAP_HAVE_MPI

#include "core/util/check.h"

namespace kdswap {

void MpiCommunicator::send(int dest, int tag, Message message) {
  KDSWAP_CHECK(dest == kHost || (dest >= 0 && dest < size()));
  message.source = node_;
  message.tag = tag;
  counters_.bytesSent += message.bytes();
  ++counters_.messagesSent;
  message.flatten();  // lent pixels leave the process as a copy
  network_.deliver(dest, std::move(message));
}

Message MpiCommunicator::receive(int source, int tag) {
  try {
    Message m = network_.mailbox(node_).take(source, tag, counters_.waitSeconds);
    counters_.bytesReceived += m.bytes();
    ++counters_.messagesReceived;
    return m;
  } catch (const MailboxAborted&) {
    throw FrameAborted((node_ < 0 ? std::string("host") : "node " + std::to_string(node_)) +
                       ": frame aborted while waiting for " +
                       (source < 0 ? std::string("the host") : "node " + std::to_string(source)) + " (tag " +
                       std::to_string(tag) + "): " + network_.abortReason());
  }
}

}  // namespace kdswap

#endif  // KDSWAP_HAVE_MPI
