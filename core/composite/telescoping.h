// Telescoping binary swap (Moreland, Kendall, Peterka & Huang 2011, IceT): any P without folding.
#pragma once

#include "core/composite/strategy.h"

namespace kdswap {

class Telescoping : public Strategy {
 public:
  explicit Telescoping(const CompositeOptions& options) : options_(options) {}
  std::string_view name() const override { return "telescoping"; }
  Tile compose(Image partial, const Rect& frame, const VisibilityOrder& order, Communicator& comm,
               PhaseObserver& phases) const override;
  //! One complete binary subtree per power-of-two group, each beside the subtree of the smaller ones.
  TreeShape treeShape(int nodes) const override;

 private:
  CompositeOptions options_;
};

}  // namespace kdswap
