// EmptySpaceCache: one brick's empty-space map, kept from frame to frame. The map depends only on
// the brick, on which transfer-table entries have opacity > 0, on the value mapping and on whether
// skipping is on; an orbiting camera, or a colour edit, changes none of them, so rebuilding it for
// every frame (a distance transform over every macro cell) was repeated work.
#pragma once

#include <memory>
#include <vector>

#include "core/render/empty_space_map.h"

namespace kdswap {

class EmptySpaceCache {
 public:
  //! The map for `brick` under this table and mapping: the kept one when the last call's table had
  //! the same visible entries and the other arguments were equal. The owner clears the cache when
  //! the brick itself is replaced.
  std::shared_ptr<const EmptySpaceMap> mapFor(const Brick& brick, const TransferTable& table, float scale, float bias,
                                              bool enabled);
  void clear() { map_.reset(); }

 private:
  TransferTable::VisibleMask visibleMask_{};
  float scale_ = 0.0f, bias_ = 0.0f;
  bool enabled_ = false;
  std::shared_ptr<const EmptySpaceMap> map_;
};

}  // namespace kdswap
