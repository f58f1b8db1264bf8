// Built-in procedural data sets, selected by "NAME[:SIZE]" (e.g. "phantom:256",
// "vessels:256x256x128"). The one list of them is in dataset.cpp.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/volume/volume_source.h"

namespace kdswap {

//! Parses "NAME[:N | :WxHxD]" and builds the data set. Throws kdswap::Error listing valid names.
std::unique_ptr<VolumeSource> openDataset(const std::string& spec);
std::vector<std::string> datasetNames();
//! The names joined for messages: "phantom, turbulence, vessels".
std::string datasetNameList();
//! True when `spec` names a built-in data set ("phantom", "phantom:64"), not a file.
bool isDatasetSpec(const std::string& spec);
inline constexpr const char* kDefaultDataset = "phantom:128";

}  // namespace kdswap
