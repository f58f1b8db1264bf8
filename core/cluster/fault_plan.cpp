// Fault kinds by name, for the test-only --inject-fault option.
#include "core/cluster/fault_plan.h"

#include "core/util/error.h"

namespace kdswap {

FaultPlan::Kind parseFaultKind(const std::string& text) {
  if (text == "throw-render") return FaultPlan::Kind::ThrowInRender;
  if (text == "throw-composite") return FaultPlan::Kind::ThrowInComposite;
  if (text == "drop") return FaultPlan::Kind::DropMessage;
  if (text == "delay") return FaultPlan::Kind::DelayMessage;
  if (text == "corrupt") return FaultPlan::Kind::CorruptMessage;
  throw Error("fault \"" + text + "\": expected throw-render, throw-composite, drop, delay or corrupt");
}

}  // namespace kdswap
