// The brick message, the one large message of the virtual cluster and of MPI: a node rebuilds
// exactly the brick the host cut (box, volume size, spacing, voxel storage, values), and a message
// with a wrong header, a box outside the volume, an unknown storage format or the wrong number of
// voxels is refused with an error instead of building a brick from it.
#include <doctest/doctest.h>

#include "core/cluster/node_program.h"
#include "core/comm/inproc_network.h"
#include "core/util/error.h"

using namespace kdswap;

namespace {

// Touches the volume's last sample plane in y (owned boxes end at dims - 1 there).
const VoxelBox kOwned{glm::ivec3(4, 0, 2), glm::ivec3(12, 7, 10)};
const glm::ivec3 kDims(16, 8, 12);
const glm::vec3 kSpacing(1.0f, 1.5f, 2.0f);

//! Values of the brick's stored box (owned plus its replicated layer), distinct per voxel.
std::vector<float> storedValues() {
  const VoxelBox stored = Brick::storedBoxFor(kOwned, kDims);
  std::vector<float> values(std::size_t(stored.count()));
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = float(i % 97) / 96.0f;
  return values;
}

//! The node's receiveBrick on `m`, sent by the host over an in-process network.
NodeState received(Message m) {
  InprocNetwork network(1, Mailbox::WaitMode::BlockThread);
  InprocCommunicator host(network, Communicator::kHost), node(network, 0);
  host.send(0, kBrickTag, std::move(m));
  NodeState state;
  receiveBrick(state, node);
  return state;
}

}  // namespace

TEST_CASE("a brick message rebuilds the host's brick on the node, in float and in compact storage") {
  for (const VoxelStorage& storage : {VoxelStorage{}, VoxelStorage::compact(0.0f, 1.0f, kSpacing)}) {
    CAPTURE(storage.compactFormat());
    const std::vector<float> values = storedValues();
    const NodeState state = received(brickMessage(kOwned, kDims, kSpacing, storage, values));
    const Brick& brick = state.brick;
    CHECK(state.rank == 0);
    CHECK(brick.owned().lo == kOwned.lo);
    CHECK(brick.owned().hi == kOwned.hi);
    CHECK(brick.volumeDims() == kDims);
    CHECK(brick.spacing() == kSpacing);
    CHECK(brick.storage().compactFormat() == storage.compactFormat());
    CHECK(brick.storage().valueOrigin == storage.valueOrigin);
    CHECK(brick.storage().valueStep == storage.valueStep);
    CHECK(brick.storage().gradientScale == storage.gradientScale);
    // The voxels the node holds, values and gradients, are those of the host's brick (compact
    // storage: to its 16-bit levels).
    const Brick reference(kOwned, kDims, kSpacing, std::vector<float>(values), Brick::Shipping::No,
                          Brick::kCellShiftByVolume, storage);
    int differ = 0;
    for (int z = kOwned.lo.z; z < kOwned.hi.z; ++z)
      for (int y = kOwned.lo.y; y < kOwned.hi.y; ++y)
        for (int x = kOwned.lo.x; x < kOwned.hi.x; ++x) {
          if (storage.compactFormat()) {
            const CompactVoxel &a = brick.compactVoxel(x, y, z), &b = reference.compactVoxel(x, y, z);
            differ += a.value != b.value || a.gradient[0] != b.gradient[0] || a.gradient[1] != b.gradient[1] ||
                      a.gradient[2] != b.gradient[2];
          } else {
            const Voxel &a = brick.voxel(x, y, z), &b = reference.voxel(x, y, z);
            differ += a.value != b.value || a.gradient != b.gradient;
          }
        }
    CHECK(differ == 0);
  }
}

TEST_CASE("a sub-brick message is kept under its number, apart from the node's own brick") {
  const NodeState state = received(brickMessage(kOwned, kDims, kSpacing, VoxelStorage{}, storedValues(), 5));
  REQUIRE(state.pieces.count(5) == 1);
  CHECK(state.pieces.at(5).owned().hi == kOwned.hi);
  CHECK(state.pieces.at(5).shippable());  // a sub-brick may travel on to another node
  CHECK(state.brick.owned().count() == 0);
}

TEST_CASE("malformed brick messages are refused") {
  Message shortHeader = brickMessage(kOwned, kDims, kSpacing, VoxelStorage{}, storedValues());
  shortHeader.header.pop_back();
  CHECK_THROWS_WITH_AS(received(std::move(shortHeader)), "malformed brick message", Error);

  Message unknownFormat = brickMessage(kOwned, kDims, kSpacing, VoxelStorage{}, storedValues());
  unknownFormat.payload[3] = 2.0f;  // the storage format: 0 float, 1 compact
  CHECK_THROWS_WITH_AS(received(std::move(unknownFormat)), "malformed brick message", Error);

  std::vector<float> fewer = storedValues();
  fewer.pop_back();
  CHECK_THROWS_WITH_AS(received(brickMessage(kOwned, kDims, kSpacing, VoxelStorage{}, fewer)),
                       "brick message holds the wrong number of voxels", Error);

  // A box past the last sample plane would read voxels the message does not hold.
  const VoxelBox pastTheEnd{glm::ivec3(4, 0, 2), glm::ivec3(12, 8, 10)};
  std::vector<float> values(std::size_t(Brick::storedBoxFor(pastTheEnd, kDims).count()), 0.5f);
  CHECK_THROWS_WITH_AS(received(brickMessage(pastTheEnd, kDims, kSpacing, VoxelStorage{}, values)),
                       "brick message: its box lies outside the volume", Error);

  Message negative = brickMessage(kOwned, kDims, kSpacing, VoxelStorage{}, storedValues());
  negative.header[0] = -1;
  CHECK_THROWS_WITH_AS(received(std::move(negative)), "malformed brick message", Error);

  Message noPreamble;
  noPreamble.header = {0, 0, 0, 2, 2, 2, 2, 2, 2};
  CHECK_THROWS_WITH_AS(received(std::move(noPreamble)), "malformed brick message", Error);
}
