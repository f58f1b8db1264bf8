// The published figures of Ma, Painter, Hansen & Krogh (1993) that `kdswap bench --paper` sets
// our times beside. Only figures with a stated source are included; every other cell of the
// paper's Tables 1-3 (CM-5) and 6-8 (workstations) is unknown here and printed as "n/a".
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace kdswap {

struct PaperCell {
  std::string table;     //!< "Table 3 (CM-5)"
  std::string paperData; //!< the paper's data set, e.g. "vorticity 256^3"
  std::string standIn;   //!< our data set spec at the paper's size, e.g. "turbulence:256"
  int imageSize = 0;     //!< square image side
  int nodes = 0;
  std::optional<double> renderSeconds, compositeSeconds;  //!< the paper's figures; empty = unknown
  std::string source;    //!< where the figures come from
};

//! Every paper cell we can run, with the paper's figures where they are sourced.
const std::vector<PaperCell>& paperCells();

//! One paragraph: which tables have no sourced figures, and how to add them.
std::string paperCoverageNote();

}  // namespace kdswap
