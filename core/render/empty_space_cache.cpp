// Empty-space cache: rebuild only when something the map depends on changed.
#include "core/render/empty_space_cache.h"

namespace kdswap {

std::shared_ptr<const EmptySpaceMap> EmptySpaceCache::mapFor(const Brick& brick, const TransferTable& table, float scale,
                                                             float bias, bool enabled) {
  const bool same = map_ && scale_ == scale && bias_ == bias && enabled_ == enabled &&
                    visibleMask_ == table.visibleMask();
  if (!same) {
    map_ = std::make_shared<const EmptySpaceMap>(brick, table, scale, bias, enabled);
    visibleMask_ = table.visibleMask();
    scale_ = scale, bias_ = bias, enabled_ = enabled;
  }
  return map_;
}

}  // namespace kdswap
