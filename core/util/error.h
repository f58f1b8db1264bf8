// kdswap::Error: the one exception for user-facing failures (bad input, bad options, I/O).
// Its message is one line: where, what, what was expected. app/ prints it and exits 2.
#pragma once

#include <stdexcept>
#include <string>

namespace kdswap {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace kdswap
