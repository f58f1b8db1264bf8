// Binary-tree compositing, the paper's first baseline: pairs merge whole images, half the nodes
// go idle at each level, and node 0 ends with the frame.
#pragma once

#include "core/composite/strategy.h"

namespace kdswap {

class BinaryTree : public Strategy {
 public:
  explicit BinaryTree(const CompositeOptions& options) : options_(options) {}
  std::string_view name() const override { return "binary-tree"; }
  Tile compose(Image partial, const Rect& frame, const VisibilityOrder& order, Communicator& comm,
               PhaseObserver& phases) const override;

 private:
  CompositeOptions options_;
};

}  // namespace kdswap
