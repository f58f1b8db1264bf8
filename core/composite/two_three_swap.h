// 2-3 swap compositing (Yu, Wang & Ma 2008): any P, every node busy in every round.
#pragma once

#include "core/composite/strategy.h"

namespace kdswap {

class TwoThreeSwap : public Strategy {
 public:
  explicit TwoThreeSwap(const CompositeOptions& options) : options_(options) {}
  std::string_view name() const override { return "2-3-swap"; }
  Tile compose(Image partial, const Rect& frame, const VisibilityOrder& order, Communicator& comm,
               PhaseObserver& phases) const override;
  //! floor(log2 P) levels of 2- and 3-way splits, every leaf at the bottom level.
  TreeShape treeShape(int nodes) const override;

 private:
  CompositeOptions options_;
};

}  // namespace kdswap
