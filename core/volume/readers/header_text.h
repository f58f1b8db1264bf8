// Small text helpers shared by the readers of text headers (NRRD, MetaImage, legacy VTK):
// bounded header reading, line splitting with byte offsets, strict number parsing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace kdswap {

//! Reads at most `maxBytes` from the start of `path`. Throws kdswap::Error if it cannot be opened.
std::string readFilePrefix(const std::string& path, std::size_t maxBytes);

//! Splits the next line off `text` at `pos` (without "\n" or "\r\n"); advances `pos` past the
//! newline. Returns false when no newline follows `pos` (the line is not complete).
bool nextLine(std::string_view text, std::size_t& pos, std::string_view& line);

std::string_view trim(std::string_view s);
std::string lowercase(std::string_view s);
std::vector<std::string_view> splitWords(std::string_view s);

//! Whole-string parses; nullopt on any extra character or overflow.
std::optional<std::int64_t> parseInteger(std::string_view s);
std::optional<double> parseNumber(std::string_view s);

//! Parses exactly `count` whole numbers separated by spaces. nullopt otherwise.
std::optional<std::vector<std::int64_t>> parseSizes(std::string_view s, std::size_t count);

//! `s` fit for a one-line message: at most `maxChars` of it (then "..."), and every byte outside
//! printable ASCII (control bytes, NUL, binary garbage) written as \xNN.
std::string printable(std::string_view s, std::size_t maxChars = 40);
//! printable(s) in double quotes.
std::string quote(std::string_view s, std::size_t maxChars = 40);

//! `name` resolved against the folder of `headerPath` unless it is absolute.
std::string siblingPath(const std::string& headerPath, const std::string& name);

}  // namespace kdswap
