// Transfer functions: piecewise-linear evaluation and the baked, step-corrected table.
#include <doctest/doctest.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "core/transfer/transfer_function.h"
#include "core/util/error.h"

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

TEST_CASE("a ParaView colour-map export loads as a transfer function, rescaled to [0, 1]") {
  const nlohmann::json paraview = nlohmann::json::parse(R"([{
    "Name": "Cool to Warm", "ColorSpace": "Diverging",
    "RGBPoints": [-100, 0.23, 0.299, 0.754, 0, 0.865, 0.865, 0.865, 300, 0.706, 0.016, 0.15],
    "Points": [-100, 0, 0.5, 0, 300, 0.8, 0.5, 0]
  }])");
  const TransferFunction tf = TransferFunction::fromJson(paraview, "cool-to-warm.json");
  CHECK(tf.name() == "Cool to Warm");
  REQUIRE(tf.colors().size() == 3);
  CHECK(tf.colors()[1].x == doctest::Approx(0.25f));  // 0 in [-100, 300]
  CHECK(tf.evaluate(0.0f).b == doctest::Approx(0.754f));
  CHECK(tf.evaluate(1.0f).a == doctest::Approx(0.8f));
  CHECK(tf.evaluate(0.5f).a == doctest::Approx(0.4f));
  CHECK_THROWS_AS(TransferFunction::fromJson(nlohmann::json::parse(R"({"RGBPoints": [0, 1, 1]})"), "bad.json"), Error);
}

TEST_CASE("a transfer function file with a value that is not a number names the point and the item") {
  const auto message = [](const char* text) {
    try {
      TransferFunction::fromJson(nlohmann::json::parse(text), "tf.json");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(message(R"({"colors": [[0, 1, 1, 1], [1, 1, 1, 1]], "opacity": [[0, 0], [1, "NaN"]]})") ==
        "tf.json: opacity point 1: item 1 is a string, expected a number");
  CHECK(message(R"({"colors": [[0, 1, 1, 1], [1, 1, null, 1]], "opacity": [[0, 0], [1, 1]]})") ==
        "tf.json: colour stop 1: item 2 is null, expected a number");
  CHECK(message(R"({"RGBPoints": [0, 1, 1, [1], 1, 1, 1, 1]})") ==
        "tf.json: RGBPoints: item 3 is an array, expected a number");
  CHECK(message(R"({"colors": {"x": 1}, "opacity": []})") == "tf.json: \"colors\" and \"opacity\" must be lists");
  // Whatever else the JSON library refuses keeps the file's name, without the library's tag.
  const std::string other = message(R"({"name": 5, "colors": [[0, 1, 1, 1]], "opacity": [[0, 1]]})");
  CHECK(other.rfind("tf.json: malformed transfer function: ", 0) == 0);
  CHECK(other.find("json.exception") == std::string::npos);
}
