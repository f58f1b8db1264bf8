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

std::string strategyNameList() {
  std::string list;
  for (const std::string& n : strategyNames()) list += (list.empty() ? "" : ", ") + n;
  return list;
}

void checkStrategyName(const std::string& name, const std::string& what) {
  const std::vector<std::string> names = strategyNames();
  if (std::find(names.begin(), names.end(), name) == names.end())
    throw Error(what + " \"" + name + "\": expected one of " + strategyNameList());
}

std::unique_ptr<Strategy> createStrategy(const std::string& name, const CompositeOptions& options) {
  const auto& list = factories();
  auto it = std::find_if(list.begin(), list.end(), [&](const auto& entry) { return entry.first == name; });
  if (it == list.end())
    throw Error("compositing strategy \"" + name + "\": unknown (valid: " + strategyNameList() + ")");
  return it->second(options);
}

}  // namespace kdswap
