// Direct-send compositing (Hsu 1993; Neumann 1994): one round, every node to every node; any P.
#pragma once

#include "core/composite/strategy.h"

namespace kdswap {

class DirectSend : public Strategy {
 public:
  explicit DirectSend(const CompositeOptions& options) : options_(options) {}
  std::string_view name() const override { return "direct-send"; }
  Tile compose(Image partial, const Rect& frame, const VisibilityOrder& order, Communicator& comm,
               PhaseObserver& phases) const override;

 private:
  CompositeOptions options_;
};

}  // namespace kdswap
