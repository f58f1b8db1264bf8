// libFuzzer target: transfer-function JSON (kdswap or ParaView format) through
// loadTransferFunction and TransferFunction::fromJson, then evaluated and baked (issue 9).
#include <cmath>
#include <nlohmann/json.hpp>

#include "core/transfer/presets.h"
#include "core/transfer/transfer_function.h"
#include "tests/fuzz/fuzz_support.h"

namespace {

void exercise(const kdswap::TransferFunction& tf) {
  for (float s : {-1.0f, 0.0f, 0.25f, 0.5f, 1.0f, 2.0f}) {
    const glm::vec4 c = tf.evaluate(s);
    for (int i = 0; i < 4; ++i)
      if (!(c[i] >= 0.0f && c[i] <= 1.0f)) std::abort();  // colours and opacity stay in [0, 1]
  }
  const kdswap::TransferTable table(tf, 0.5f);
  (void)table.maxAlpha(0.0f, 1.0f);
  (void)table.anyVisible(0.2f, 0.4f);
  (void)kdswap::TransferFunction::fromJson(tf.toJson(), "round trip");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    exercise(kdswap::loadTransferFunction(kdswap::fuzz::writeScratch("input.json", data, size)));
  } catch (const kdswap::Error&) {
  }
  const auto j = nlohmann::json::parse(data, data + size, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) return 0;
  try {
    exercise(kdswap::TransferFunction::fromJson(j, "fuzz input"));
  } catch (const kdswap::Error&) {
  }
  return 0;
}
