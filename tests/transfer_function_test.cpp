// Transfer functions: piecewise-linear evaluation and the baked, step-corrected table.
#include <doctest/doctest.h>

#include <cmath>

#include "core/transfer/transfer_function.h"

using namespace kdswap;

TEST_CASE("a transfer function interpolates linearly between its points") {
  const TransferFunction tf({{0.0f, {0.0f, 0.0f, 0.0f}}, {1.0f, {1.0f, 0.5f, 0.0f}}}, {{0.0f, 0.0f}, {0.5f, 0.4f}, {1.0f, 0.4f}});
  CHECK(tf.evaluate(0.5f).r == doctest::Approx(0.5f));
  CHECK(tf.evaluate(0.25f).a == doctest::Approx(0.2f));
  CHECK(tf.evaluate(2.0f).a == doctest::Approx(0.4f));
  const TransferTable table(tf, 0.5f);
  CHECK(table.lookup(0.75f).a == doctest::Approx(1.0f - std::pow(1.0f - 0.4f, 0.5f)).epsilon(1e-4));
}

TEST_CASE("a transfer function maps NaN to its first entry instead of reading out of bounds") {
  const TransferFunction tf({{0.0f, {0.2f, 0.3f, 0.4f}}, {1.0f, {1.0f, 1.0f, 1.0f}}}, {{0.0f, 0.1f}, {1.0f, 0.9f}});
  const glm::vec4 v = tf.evaluate(std::nanf(""));
  CHECK(v.r == doctest::Approx(0.2f));
  CHECK(v.a == doctest::Approx(0.1f));
  const TransferTable table(tf, 1.0f);
  CHECK(table.lookup(std::nanf("")).a == doctest::Approx(0.1f));
}
