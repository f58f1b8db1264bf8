// Agreement among MPI ranks: flags by MPI_Allgather, texts by MPI_Gather(v) and MPI_Bcast.
#include "core/comm/mpi_agreement.h"

#if KDSWAP_HAVE_MPI

#include <algorithm>
#include <climits>

// The C API only: Open MPI's deprecated C++ bindings would need libmpi_cxx.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>

namespace kdswap {

int worldSize() {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size;
}

int worldRank() {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}

namespace {

//! Texts are one-line messages and job descriptions (~1 KB): cut at 256 KiB, so that a gather from
//! 4096 ranks stays within MPI's int counts.
int lengthOf(const std::string& text) { return int(std::min<std::size_t>(text.size(), std::size_t(1) << 18)); }

}  // namespace

int firstRankWith(bool flag) {
  const int mine = flag ? 1 : 0;
  std::vector<int> flags(std::size_t(worldSize()), 0);
  MPI_Allgather(&mine, 1, MPI_INT, flags.data(), 1, MPI_INT, MPI_COMM_WORLD);
  const auto first = std::find(flags.begin(), flags.end(), 1);
  return first == flags.end() ? -1 : int(first - flags.begin());
}

std::string firstProblemOfAnyRank(const std::string& mine) {
  const int speaker = firstRankWith(!mine.empty());
  if (speaker < 0) return "";
  int length = worldRank() == speaker ? lengthOf(mine) : 0;
  MPI_Bcast(&length, 1, MPI_INT, speaker, MPI_COMM_WORLD);
  std::string problem = worldRank() == speaker ? mine.substr(0, std::size_t(length)) : std::string(std::size_t(length), ' ');
  MPI_Bcast(problem.data(), length, MPI_CHAR, speaker, MPI_COMM_WORLD);
  return speaker == 0 ? problem : "rank " + std::to_string(speaker) + ": " + problem;
}

std::vector<std::string> gatherTextOnRankZero(const std::string& text) {
  const int ranks = worldSize(), rank = worldRank();
  const int length = lengthOf(text);
  std::vector<int> lengths(rank == 0 ? std::size_t(ranks) : 0);
  MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  std::vector<int> offsets(lengths.size(), 0);
  long long total = 0;
  for (std::size_t r = 0; r < lengths.size(); ++r) {
    offsets[r] = int(total);
    total += lengths[r];
  }
  std::string all(std::size_t(total), ' ');
  MPI_Gatherv(text.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(), MPI_CHAR, 0, MPI_COMM_WORLD);
  std::vector<std::string> texts;
  for (std::size_t r = 0; r < lengths.size(); ++r) texts.push_back(all.substr(std::size_t(offsets[r]), std::size_t(lengths[r])));
  return texts;
}

}  // namespace kdswap

#endif  // KDSWAP_HAVE_MPI
