// Lists and whole numbers as typed on a command line: empty items are kept, so that "64x" or
// "64," is refused rather than read as "64", and a whole number is digits with an optional sign.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "core/util/text_items.h"

namespace kdswap {

TEST_CASE("splitItems keeps every item, empty ones too") {
  using Items = std::vector<std::string>;
  CHECK(splitItems("", ',') == Items{});
  CHECK(splitItems("64", 'x') == Items{"64"});
  CHECK(splitItems("32x48x64", 'x') == Items{"32", "48", "64"});
  CHECK(splitItems("64x", 'x') == Items{"64", ""});
  CHECK(splitItems("x64", 'x') == Items{"", "64"});
  CHECK(splitItems("1,,2,", ',') == Items{"1", "", "2", ""});
  CHECK(splitItems(",", ',') == Items{"", ""});
}

TEST_CASE("parseWholeNumber takes decimal digits with an optional sign, spaces around them, and nothing else") {
  CHECK(parseWholeNumber("64") == 64);
  CHECK(parseWholeNumber("+64") == 64);
  CHECK(parseWholeNumber("-3") == -3);
  CHECK(parseWholeNumber("0") == 0);
  CHECK(parseWholeNumber("9223372036854775807") == 9223372036854775807LL);
  CHECK(parseWholeNumber(" 64 ") == 64);  // "1, 2, 4": spaces after the commas are fine
  CHECK(parseWholeNumber("\t-2") == -2);
  for (const char* bad : {"", " ", "+", "-", "+-1", "++1", "6 4", "- 4", "64x", "0x40", "6.0", "1e3", "abc",
                          "9223372036854775808", "99999999999999999999"}) {
    CAPTURE(bad);
    CHECK_FALSE(parseWholeNumber(bad).has_value());
  }
}

}  // namespace kdswap
