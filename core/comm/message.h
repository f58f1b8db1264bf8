// Message: what nodes exchange. Payloads are moved, never copied, on the in-process transport:
// after send() the message belongs to the receiver (OSPRay's messaging contract). Bulk data may
// also be lent (FloatLoan): the receiver reads it where the sender keeps it.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace kdswap {

//! Floats lent by the sender instead of moved into a payload: `rows` runs of `rowFloats` floats,
//! `strideFloats` apart from `first`, kept alive by `owner`. The in-process transport hands the
//! loan over as it is (zero-copy compositing); a transport that leaves the process copies it into
//! the payload first (Message::flatten). The sender promises never to write lent floats again.
struct FloatLoan {
  std::shared_ptr<const void> owner;
  const float* first = nullptr;
  std::int64_t rows = 0, rowFloats = 0, strideFloats = 0;

  std::int64_t count() const { return rows * rowFloats; }
  const float* row(std::int64_t i) const { return first + i * strideFloats; }
};

struct Message {
  int source = -1;                   //!< sender's rank (set by the communicator)
  int tag = 0;                       //!< what the message is; strategies name theirs as constants
  std::vector<std::int64_t> header;  //!< small metadata: rectangles, counts, boxes
  std::vector<float> payload;        //!< bulk data: pixels or voxels
  FloatLoan loan;                    //!< more bulk data, lent; reads as if appended to payload
  std::string text;                  //!< serialised settings (JSON), for broadcasts
  std::uint64_t checksum = 0;        //!< of header and payload, when the transport checks (0: unchecked)

  std::uint64_t bytes() const {
    return header.size() * sizeof(std::int64_t) + (payload.size() + std::uint64_t(loan.count())) * sizeof(float) +
           text.size();
  }
  //! Copies the loan's floats onto the end of the payload and drops the loan, so the message owns
  //! all its data (before it leaves the process, or before a test hook edits it).
  void flatten();
};

//! 64-bit hash of a message's header, payload (with the loan appended) and text (never 0), to
//! detect corruption in transit; flatten() does not change it.
std::uint64_t messageChecksum(const Message& message);

}  // namespace kdswap
