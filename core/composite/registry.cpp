// The only list of compositing strategies (IceT's select.c, pbrt's dispatch).
#include "core/composite/registry.h"

#include <algorithm>
#include <functional>
#include <utility>

#include "core/composite/binary_swap.h"
#include "core/composite/binary_tree.h"
#include "core/composite/direct_send.h"
#include "core/composite/radix_k.h"
#include "core/composite/sequential.h"
#include "core/composite/telescoping.h"
#include "core/composite/two_three_swap.h"
#include "core/util/error.h"

namespace kdswap {
namespace {

using Factory = std::function<std::unique_ptr<Strategy>(const CompositeOptions&)>;

template <typename T>
Factory make() {
  return [](const CompositeOptions& o) { return std::make_unique<T>(o); };
}

// In the order listed to users: the paper's strategy and its two baselines, then the later ones.
const std::vector<std::pair<std::string, Factory>>& factories() {
  static const std::vector<std::pair<std::string, Factory>> list = {
      {"binary-swap", make<BinarySwap>()},
      {"binary-tree", make<BinaryTree>()},
      {"sequential", make<Sequential>()},
      {"direct-send", make<DirectSend>()},
      {"radix-k", make<RadixK>()},
      {"2-3-swap", make<TwoThreeSwap>()},
      {"telescoping", make<Telescoping>()},
  };
  return list;
}

}  // namespace

std::vector<std::string> strategyNames() {
  std::vector<std::string> names;
  for (const auto& [name, factory] : factories()) names.push_back(name);
  return names;
}

std::unique_ptr<Strategy> createStrategy(const std::string& name, const CompositeOptions& options) {
  const auto& list = factories();
  auto it = std::find_if(list.begin(), list.end(), [&](const auto& entry) { return entry.first == name; });
  if (it == list.end()) {
    std::string valid;
    for (const std::string& n : strategyNames()) valid += (valid.empty() ? "" : ", ") + n;
    throw Error("compositing strategy \"" + name + "\": unknown (valid: " + valid + ")");
  }
  return it->second(options);
}

}  // namespace kdswap
