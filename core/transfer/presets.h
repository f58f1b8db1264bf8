// Transfer-function presets, stored as JSON in assets/presets/, and loading by name or path.
#pragma once

#include <string>
#include <vector>

#include "core/transfer/transfer_function.h"

namespace kdswap {

//! The assets folder: $KDSWAP_ASSETS, else <exe>/../share/kdswap/assets, else the source tree's.
std::string assetsDirectory();
std::vector<std::string> presetNames();
//! A preset name (e.g. "phantom") or a path to a JSON file (kdswap or ParaView format).
//! Throws kdswap::Error naming the preset or file and listing the presets.
TransferFunction loadTransferFunction(const std::string& presetOrPath);
//! Writes `tf` as kdswap JSON. Throws kdswap::Error.
void saveTransferFunction(const TransferFunction& tf, const std::string& path);

}  // namespace kdswap
