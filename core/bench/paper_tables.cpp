// The paper's figures, as data. NEVER add a number here without its source in `source`.
#include "core/bench/paper_tables.h"

namespace kdswap {

const std::vector<PaperCell>& paperCells() {
  // Ma, Painter, Hansen & Krogh, "A data distributed, parallel algorithm for ray-traced volume
  // rendering", Parallel Rendering Symposium 1993. The paper itself was not at hand; the one
  // figure below was given in issue 6's brief (render 3.19 s + composite 0.33 s on 512 CM-5
  // nodes, 256^3 vorticity data, 512x512 image). A search of public pages (2024 snapshot) found
  // abstracts of the paper and its 1994 CG&A version but no table text, so no other cell is
  // filled in rather than guessed.
  static const std::vector<PaperCell> cells = {
      {"Table 3 (CM-5)", "vorticity 256^3", "turbulence:256", 512, 512, 3.19, 0.33,
       "issue 6 brief, quoting the paper: 3.19 s + 0.33 s on 512 CM-5 nodes"},
  };
  return cells;
}

std::string paperCoverageNote() {
  return "Paper figures: only the cells listed above are sourced (issue 6 quotes the CM-5 vorticity cell).\n"
         "Tables 1-2 (CM-5, head and vessel data) and 6-8 (networked workstations) are not available to us,\n"
         "so they are not run or compared here; add their cells to core/bench/paper_tables.cpp with the\n"
         "source of each figure, and `kdswap bench --paper` will run and compare them (n/a when a figure\n"
         "is missing).\n";
}

}  // namespace kdswap
