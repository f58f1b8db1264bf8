// Host: brick distribution and tile gathering.
#include "core/cluster/host.h"

#include "core/cluster/node_program.h"
#include "core/composite/image_message.h"
#include "core/util/error.h"
#include "core/volume/brick.h"

namespace kdswap {

void distributeBricks(const VolumeSource& source, const KdTree& tree, Communicator& host) {
  const VolumeInfo& info = source.info();
  for (int r = 0; r < tree.ranks(); ++r) {
    const VoxelBox& owned = tree.brick(r);
    const VoxelBox stored = Brick::storedBoxFor(owned, info.dims);
    Message m;
    m.header = {owned.lo.x, owned.lo.y, owned.lo.z, owned.hi.x, owned.hi.y, owned.hi.z,
                info.dims.x, info.dims.y, info.dims.z};
    m.payload.resize(3 + std::size_t(stored.count()));
    m.payload[0] = info.spacing.x, m.payload[1] = info.spacing.y, m.payload[2] = info.spacing.z;
    if (!stored.empty()) source.read(stored, m.payload.data() + 3);
    host.send(r, kBrickTag, std::move(m));
  }
}

Image assembleTiles(std::vector<Message>& tiles, const Rect& frame, std::vector<Rect>* regions) {
  Image out(frame);
  std::vector<unsigned char> covered(std::size_t(frame.area()), 0);
  std::int64_t coveredCount = 0;
  if (regions) regions->assign(tiles.size(), Rect{});
  for (Message& m : tiles) {
    const std::string who = "tile from node " + std::to_string(m.source);
    if (m.header.size() != 8) throw Error(who + ": malformed header");
    const Rect region{int(m.header[4]), int(m.header[5]), int(m.header[6]), int(m.header[7])};
    m.header.resize(4);
    Image image = imageFromMessage(m);
    if (!frame.contains(region) || !region.contains(image.rect()))
      throw Error(who + ": image lies outside its region or the frame");
    if (regions && m.source >= 0 && std::size_t(m.source) < regions->size()) (*regions)[std::size_t(m.source)] = region;
    for (int y = region.y; y < region.bottom(); ++y)
      for (int x = region.x; x < region.right(); ++x) {
        unsigned char& c = covered[std::size_t(y - frame.y) * frame.w + (x - frame.x)];
        if (c) throw Error(who + ": pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") also belongs to another tile");
        c = 1;
        ++coveredCount;
        out.at(x, y) = image.sample(x, y);
      }
  }
  if (coveredCount != frame.area())
    throw Error("gather: tiles cover " + std::to_string(coveredCount) + " of " + std::to_string(frame.area()) + " pixels");
  return out;
}

}  // namespace kdswap
