// Message: what nodes exchange. Payloads are moved, never copied, on the in-process transport:
// after send() the message belongs to the receiver (OSPRay's messaging contract).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace kdswap {

struct Message {
  int source = -1;                   //!< sender's rank (set by the communicator)
  int tag = 0;                       //!< what the message is; strategies name theirs as constants
  std::vector<std::int64_t> header;  //!< small metadata: rectangles, counts, boxes
  std::vector<float> payload;        //!< bulk data: pixels or voxels
  std::string text;                  //!< serialised settings (JSON), for broadcasts
  std::uint64_t checksum = 0;        //!< of header and payload, when the transport checks (0: unchecked)

  std::uint64_t bytes() const {
    return header.size() * sizeof(std::int64_t) + payload.size() * sizeof(float) + text.size();
  }
};

//! 64-bit hash of a message's header, payload and text (never 0), to detect corruption in transit.
std::uint64_t messageChecksum(const Message& message);

}  // namespace kdswap
