// SpecularTable: pow(x, shininess) tabulated at x = i / kSpecularEntries (i = 0 .. kSpecularEntries),
// which the shader interpolates between entries. Every brick's caster in a frame uses the same
// exponent, so one table per exponent is made and shared: built per caster, a 64-node frame paid
// 64 x 257 calls of pow (0.17 ms a frame).
#pragma once

#include <memory>
#include <vector>

namespace kdswap {

//! The table for `shininess` (kSpecularEntries + 1 floats); shared, never changed once made. The
//! last few exponents asked for are kept, so a slider dragged through many values keeps little.
std::shared_ptr<const std::vector<float>> specularTableFor(float shininess);

}  // namespace kdswap
