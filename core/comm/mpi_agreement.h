// Agreement among MPI ranks before a frame's network runs: every rank prepares on its own (its
// command line, its files, its bricks), and a problem on one rank must stop every rank at once,
// with one message, rather than leave the others waiting in MPI for ever. Collective calls over
// MPI_COMM_WORLD, made by the main thread while no MpiNetwork runs.
#pragma once

#if KDSWAP_HAVE_MPI

#include <string>
#include <vector>

namespace kdswap {

//! This process's rank and the number of ranks in MPI_COMM_WORLD.
int worldRank();
int worldSize();

//! Collective. The lowest rank whose `flag` is true, or -1 when no rank's is.
int firstRankWith(bool flag);

//! Collective. "" when no rank has a problem (`mine` empty everywhere); otherwise, on every rank,
//! the problem of the lowest rank that has one, as "rank R: PROBLEM", or "PROBLEM" when R is 0
//! (rank 0 speaks for all when every rank has the same command line).
std::string firstProblemOfAnyRank(const std::string& mine);

//! Collective. Rank 0 gets every rank's `text` (index = rank); the other ranks get an empty list.
std::vector<std::string> gatherTextOnRankZero(const std::string& text);

}  // namespace kdswap

#endif  // KDSWAP_HAVE_MPI
