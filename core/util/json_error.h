// One printable line for a JSON library error, for messages that name the file in front of it.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace kdswap {

//! `e.what()` without the library's "[json.exception.parse_error.101] " tag, bytes outside
//! printable ASCII as \xNN (the "last read" of a binary file would print raw bytes). A parse error
//! keeps its "at line L, column C".
std::string jsonErrorText(const nlohmann::json::exception& e);

}  // namespace kdswap
