// FaultPlan: test-only fault injection for the virtual cluster (reliability, issue 9). A plan is
// armed for exactly one frame; the frame must then fail within a bounded time with an error
// naming the node, and the next frame must render correctly.
#pragma once

#include <string>

namespace kdswap {

struct FaultPlan {
  enum class Kind {
    None,
    ThrowInRender,     //!< the node throws before ray casting
    ThrowInComposite,  //!< the node throws when it first sends during compositing
    DropMessage,       //!< the node's n-th compositing message is lost
    DelayMessage,      //!< the node's n-th compositing message is held for delaySeconds
    CorruptMessage,    //!< the node's n-th compositing message has a pixel changed after its checksum
  };
  Kind kind = Kind::None;
  int node = 0;              //!< the misbehaving node
  int message = 0;           //!< which of its messages, for message faults (0 = first)
  double delaySeconds = 0;   //!< for DelayMessage

  bool armed() const { return kind != Kind::None; }
};

//! "throw-render", "throw-composite", "drop", "delay", "corrupt"; throws kdswap::Error.
FaultPlan::Kind parseFaultKind(const std::string& text);

}  // namespace kdswap
