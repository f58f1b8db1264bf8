// The --raw-* options: the layout of a headerless .raw --volume file. One place for every command
// that reads a volume file (render, animate, info, bench, export, kdswap-mpi), so all parse alike.
#pragma once

#include <cstdint>
#include <string>

#include <CLI/CLI.hpp>

#include "core/volume/reader.h"

namespace kdswap {

//! The options as given; an empty string (or a skip of 0) is an option not given.
struct RawLayoutOptions {
  std::string dims, type, endian, spacing;
  std::int64_t skip = 0;  //!< signed, so that -1 is refused rather than wrapped
};

//! Adds --raw-dims, --raw-type, --raw-endian, --raw-spacing and --raw-skip to `cmd`.
void addRawLayoutOptions(CLI::App* cmd, RawLayoutOptions& options);
//! The layout the options give, fields not given left unset; marked as coming from a command that
//! has the options (a missing layout names them). Throws kdswap::Error naming the option.
RawLayout parseRawLayout(const RawLayoutOptions& options);
//! Throws kdswap::Error naming the first option given: they describe a raw --volume file, and the
//! command reads `other` instead ("--dataset phantom:16", "--targets").
void checkNoRawLayout(const RawLayoutOptions& options, const std::string& other);
//! The options given as arguments (" --raw-dims 64x64x93 --raw-type uint16"; "" when none), so a
//! recorded command line reproduces the run.
std::string rawLayoutArguments(const RawLayoutOptions& options);

}  // namespace kdswap
