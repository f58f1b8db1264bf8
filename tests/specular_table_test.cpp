// specularTableFor: pow(x, shininess) at x = i / kSpecularEntries, made once per exponent and shared
// by every caster that asks for it.
#include <doctest/doctest.h>

#include <cmath>

#include "core/render/sample_shader.h"
#include "core/render/specular_table.h"

using namespace kdswap;

TEST_CASE("specular tables: pow at each entry, one shared table per exponent, other exponents apart") {
  const auto twenty = specularTableFor(20.0f);
  REQUIRE(twenty->size() == std::size_t(kSpecularEntries + 1));
  for (int i = 0; i <= kSpecularEntries; ++i) {
    const float exact = std::pow(float(i) / kSpecularEntries, 20.0f);
    CHECK((*twenty)[std::size_t(i)] == (exact < 0x1p-64f ? 0.0f : exact));  // tiny ones are 0
  }
  CHECK(twenty->front() == 0.0f);
  CHECK(twenty->back() == 1.0f);
  CHECK(specularTableFor(20.0f) == twenty);  // the same table, not a copy
  const auto five = specularTableFor(5.0f);
  CHECK(five != twenty);
  CHECK((*five)[std::size_t(kSpecularEntries / 2)] == std::pow(0.5f, 5.0f));
  // Many other exponents later (a slider dragged): an evicted exponent is made again, equal, and a
  // table still held stays valid.
  for (int s = 1; s <= 10; ++s) specularTableFor(float(s) + 0.5f);
  const auto again = specularTableFor(20.0f);
  CHECK(*again == *twenty);
  CHECK((*twenty)[std::size_t(kSpecularEntries)] == 1.0f);
}

TEST_CASE("specular tables hold no subnormal entry (each would cost Intel cores a microcode assist)") {
  for (const float shininess : {1.0f, 24.0f, 100.0f, 128.0f, 1000.0f}) {
    CAPTURE(shininess);
    const auto table = specularTableFor(shininess);
    int zeros = 0;
    for (const float v : *table) {
      CHECK(std::fpclassify(v) != FP_SUBNORMAL);
      CHECK((v == 0.0f || v >= 0x1p-64f));
      zeros += v == 0.0f;
    }
    CHECK(zeros >= 1);                 // pow(0, s)
    CHECK(table->back() == 1.0f);      // the highlight's peak is kept
    if (shininess >= 24.0f) CHECK(zeros > 1);  // pow(4 / 256, 24) = 2^-144 would be subnormal
  }
}
