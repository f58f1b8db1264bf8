// Host: brick distribution and tile gathering.
#include "core/cluster/host.h"

#include "core/cluster/node_program.h"
#include "core/composite/image_message.h"
#include "core/util/error.h"
#include "core/volume/brick.h"

namespace kdswap {

namespace {

Message readBrick(const VolumeSource& source, const VoxelBox& owned, int piece) {
  const VolumeInfo& info = source.info();
  const VoxelBox stored = Brick::storedBoxFor(owned, info.dims);
  std::vector<float> values(std::size_t(stored.count()));
  if (!stored.empty()) source.read(stored, values.data());
  return brickMessage(owned, info.dims, info.spacing, std::move(values), piece);
}

}  // namespace

void distributeBricks(const VolumeSource& source, const KdTree& tree, Communicator& host) {
  for (int r = 0; r < tree.ranks(); ++r) host.send(r, kBrickTag, readBrick(source, tree.brick(r), -1));
}

void distributePieces(const VolumeSource& source, const BrickLayout& layout, Communicator& host) {
  for (int b = 0; b < layout.bricks(); ++b) host.send(layout.home(b), kBrickTag, readBrick(source, layout.box(b), b));
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
