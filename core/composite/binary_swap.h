// Binary-swap compositing (Ma, Painter, Hansen & Krogh 1993, section 3.4, Figure 4); any P.
#pragma once

#include "core/composite/strategy.h"

namespace kdswap {

class BinarySwap : public Strategy {
 public:
  explicit BinarySwap(const CompositeOptions& options) : options_(options) {}
  std::string_view name() const override { return "binary-swap"; }
  Tile compose(Image partial, const Rect& frame, const VisibilityOrder& order, Communicator& comm,
               PhaseObserver& phases) const override;

 private:
  CompositeOptions options_;
};

}  // namespace kdswap
