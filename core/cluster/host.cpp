// Host: brick distribution and tile gathering.
#include "core/cluster/host.h"

#include <algorithm>
#include <cstring>

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>

#include "core/cluster/node_program.h"
#include "core/composite/image_message.h"
#include "core/util/error.h"
#include "core/volume/brick.h"

namespace kdswap {

namespace {

//! Rows per task when pasting tiles: 32 KiB of a 512-pixel-wide frame.
constexpr int kRowsPerBand = 4;

Message readBrick(const VolumeSource& source, const VoxelBox& owned, const VoxelStorage& storage, int piece) {
  const VolumeInfo& info = source.info();
  const VoxelBox stored = Brick::storedBoxFor(owned, info.dims);
  std::vector<float> values(std::size_t(stored.count()));
  if (!stored.empty()) source.read(stored, values.data());
  return brickMessage(owned, info.dims, info.spacing, storage, std::move(values), piece);
}

}  // namespace

void distributeBricks(const VolumeSource& source, const KdTree& tree, const VoxelStorage& storage, Communicator& host) {
  for (int r = 0; r < tree.ranks(); ++r) host.send(r, kBrickTag, readBrick(source, tree.brick(r), storage, -1));
}

void distributePieces(const VolumeSource& source, const BrickLayout& layout, const VoxelStorage& storage,
                      Communicator& host) {
  for (int b = 0; b < layout.bricks(); ++b)
    host.send(layout.home(b), kBrickTag, readBrick(source, layout.box(b), storage, b));
}

Image assembleTiles(std::vector<Message>& tiles, const Rect& frame, std::vector<Rect>* regions) {
  Image out(frame);  // transparent where a tile's pixels do not reach
  std::vector<unsigned char> covered(std::size_t(frame.area()), 0);
  std::int64_t coveredCount = 0;
  if (regions) regions->assign(tiles.size(), Rect{});
  std::vector<ImageView> views;  // each tile's pixels, where the node left them
  views.reserve(tiles.size());
  for (Message& m : tiles) {
    const std::string who = "tile from node " + std::to_string(m.source);
    if (m.header.size() != 8) throw Error(who + ": malformed header");
    const Rect region{int(m.header[4]), int(m.header[5]), int(m.header[6]), int(m.header[7])};
    m.header.resize(4);
    const ImageView pixels = viewOfMessage(m);  // read where the node left them (or as received)
    if (region.w < 0 || region.h < 0 || !frame.contains(region) || !region.contains(pixels.rect))
      throw Error(who + ": image lies outside its region or the frame");
    if (regions && m.source >= 0 && std::size_t(m.source) < regions->size()) (*regions)[std::size_t(m.source)] = region;
    for (int y = region.y; y < region.bottom(); ++y) {
      unsigned char* row = &covered[std::size_t(y - frame.y) * frame.w + (region.x - frame.x)];
      const auto taken = std::find(row, row + region.w, 1);
      if (taken != row + region.w)
        throw Error(who + ": pixel (" + std::to_string(region.x + int(taken - row)) + ", " + std::to_string(y) +
                    ") also belongs to another tile");
      std::memset(row, 1, std::size_t(region.w));
      coveredCount += region.w;
    }
    if (!pixels.empty()) views.push_back(pixels);
  }
  if (coveredCount != frame.area())
    throw Error("gather: tiles cover " + std::to_string(coveredCount) + " of " + std::to_string(frame.area()) + " pixels");
  // Pasted in bands of rows on the calling arena's threads (the tiles are disjoint, so bands write
  // apart): copied by one thread, they took ~4% of a 512^2 frame at P = 64 with waves.
  const auto paste = [&](const tbb::blocked_range<int>& rows) {
    for (const ImageView& pixels : views)
      for (int y = std::max(rows.begin(), pixels.rect.y); y < std::min(rows.end(), pixels.rect.bottom()); ++y)
        std::memcpy(&out.at(pixels.rect.x, y), pixels.row(y), sizeof(Rgba) * std::size_t(pixels.rect.w));
  };
  tbb::parallel_for(tbb::blocked_range<int>(frame.y, frame.bottom(), kRowsPerBand), paste);
  return out;
}

}  // namespace kdswap
