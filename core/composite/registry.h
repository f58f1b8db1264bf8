// The one list of compositing strategies, selected by name.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/composite/strategy.h"

namespace kdswap {

//! Throws kdswap::Error listing the valid names when `name` is unknown.
std::unique_ptr<Strategy> createStrategy(const std::string& name, const CompositeOptions& options = {});
std::vector<std::string> strategyNames();
//! The names, comma-separated, for help texts and errors.
std::string strategyNameList();
//! Throws kdswap::Error "`what` "NAME": expected one of ..." when `name` is not registered.
void checkStrategyName(const std::string& name, const std::string& what = "--composite");

}  // namespace kdswap
