// Sequential compositing, the paper's second baseline: the front-most node sends its image to
// the next in visibility order, which composites and passes it on; the last node holds the frame.
#pragma once

#include "core/composite/strategy.h"

namespace kdswap {

class Sequential : public Strategy {
 public:
  explicit Sequential(const CompositeOptions& options) : options_(options) {}
  std::string_view name() const override { return "sequential"; }
  Tile compose(Image partial, const Rect& frame, const VisibilityOrder& order, Communicator& comm,
               PhaseObserver& phases) const override;

 private:
  CompositeOptions options_;
};

}  // namespace kdswap
