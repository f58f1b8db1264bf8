// Radix-k compositing (Peterka, Goodell, Ross, Shen & Thakur 2009); any P whose radices multiply
// to P. Radices {2, 2, ...} are binary swap, {P} is direct-send.
#pragma once

#include <vector>

#include "core/composite/strategy.h"

namespace kdswap {

class RadixK : public Strategy {
 public:
  explicit RadixK(const CompositeOptions& options) : options_(options) {}
  std::string_view name() const override { return "radix-k"; }
  Tile compose(Image partial, const Rect& frame, const VisibilityOrder& order, Communicator& comm,
               PhaseObserver& phases) const override;
  //! One level per round, the last round's groups at the root.
  TreeShape treeShape(int nodes) const override;
  //! The group size of each round for `nodes` nodes: options.radices if given (their product must
  //! be `nodes`, each at least 2; else kdswap::Error naming a valid factorisation), otherwise the
  //! prime factors of `nodes`, smallest first, multiplied into rounds of at most 8 (8 -> 8;
  //! 12 -> 4, 3; 64 -> 8, 8; 13 -> 13; 1 -> none).
  std::vector<int> radices(int nodes) const;

 private:
  CompositeOptions options_;
};

}  // namespace kdswap
