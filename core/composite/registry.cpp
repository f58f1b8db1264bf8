// The only list of compositing strategies (IceT's select.c, pbrt's dispatch).
#include "core/composite/registry.h"

#include <functional>
#include <map>

#include "core/composite/binary_swap.h"
#include "core/composite/binary_tree.h"
#include "core/composite/sequential.h"
#include "core/util/error.h"

namespace kdswap {
namespace {

using Factory = std::function<std::unique_ptr<Strategy>(const CompositeOptions&)>;

template <typename T>
Factory make() {
  return [](const CompositeOptions& o) { return std::make_unique<T>(o); };
}

const std::map<std::string, Factory>& factories() {
  static const std::map<std::string, Factory> list = {
      {"binary-swap", make<BinarySwap>()},
      {"binary-tree", make<BinaryTree>()},
      {"sequential", make<Sequential>()},
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
  auto it = factories().find(name);
  if (it == factories().end()) {
    std::string valid;
    for (const std::string& n : strategyNames()) valid += (valid.empty() ? "" : ", ") + n;
    throw Error("compositing strategy \"" + name + "\": unknown (valid: " + valid + ")");
  }
  return it->second(options);
}

}  // namespace kdswap
