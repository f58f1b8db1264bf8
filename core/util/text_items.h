// Lists and whole numbers as users type them on a command line or in a data set's name
// ("64,128", "phantom:32x48x64"): one splitting rule and one strict number rule for every parser.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace kdswap {

//! The items between `separator`s, empty ones kept ("1,,2," -> {"1", "", "2", ""}; "" -> {}), so a
//! parser can refuse "64x" rather than read it as "64" (std::getline drops a trailing empty item).
std::vector<std::string> splitItems(std::string_view text, char separator);

//! `text` as a whole number: optional sign, then decimal digits (no "0x", no fraction, no exponent),
//! spaces around it allowed ("1, 2, 4" is a list of three); nullopt otherwise or when it does not
//! fit 64 bits.
std::optional<std::int64_t> parseWholeNumber(std::string_view text);

}  // namespace kdswap
