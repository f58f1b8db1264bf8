// Strategy: one way of combining the nodes' partial images into a finished frame. Each strategy
// is one file and one line in registry.cpp; it sees only the Communicator, never threads or MPI,
// and reports each phase to the PhaseObserver (that is how the GUI shows the paper's Figure 6).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/comm/communicator.h"
#include "core/image/image.h"
#include "core/partition/kd_tree.h"

namespace kdswap {

//! What a node holds when compositing ends: it alone is responsible for the pixels of `region`
//! (maybe empty); `pixels` covers a part of `region` (pixels outside it are transparent). The
//! pixels usually stay where compositing left them, in a buffer `owner` keeps alive, so the tile
//! reaches the host without another copy.
struct Tile {
  Rect region;
  ImageView pixels;
  std::shared_ptr<const void> owner;

  //! A tile holding `image`'s pixels inside `region`.
  static Tile owning(const Rect& region, Image image) {
    auto kept = std::make_shared<Image>(std::move(image));
    return Tile{region, kept->view(region), kept};
  }
};

//! Told about every compositing phase on every node, so rows of the phase grid line up: a node
//! idle in a phase still reports it (empty region).
class PhaseObserver {
 public:
  virtual ~PhaseObserver() = default;
  //! `partner` is the node exchanged with in this phase, or -1.
  virtual void beginPhase(std::string_view label, int partner) = 0;
  //! The node's region and image after the phase, and the pixels it composited during it.
  virtual void endPhase(const Rect& region, const Image& image, std::int64_t pixelsComposited) = 0;
};

//! The axis a halving or slicing round cuts across: y (axis 1) in round 0, then x, y, ... The
//! first round handles the largest images, and cutting across y gives parts of whole rows, each
//! contiguous in memory (measured: binary swap and radix-k at 1024x1024, P = 8, 25% faster than
//! starting with x).
inline int cutAxis(int round) { return round % 2 == 0 ? 1 : 0; }

struct CompositeOptions {
  bool sparse = false;       //!< send only the bounding rectangle of non-empty pixels
  std::vector<int> radices;  //!< per-round group sizes, for strategies that take them
};

class Strategy {
 public:
  virtual ~Strategy() = default;
  virtual std::string_view name() const = 0;  //!< as typed on the command line
  //! Called on every node with its partial image (any rect inside `frame`). `order` ranks the
  //! nodes front to back for this view. Returns the tile this node finished (maybe empty); the
  //! returned tiles of all nodes partition `frame`.
  virtual Tile compose(Image partial, const Rect& frame, const VisibilityOrder& order, Communicator& comm,
                       PhaseObserver& phases) const = 0;
  //! The k-d tree shape whose subtrees are this strategy's groups for `nodes` nodes (the cluster
  //! builds the partition with it); empty = the binary tree with folded extra nodes. Throws
  //! kdswap::Error if the strategy's options cannot serve `nodes`.
  virtual TreeShape treeShape(int /*nodes*/) const { return {}; }
};

}  // namespace kdswap
