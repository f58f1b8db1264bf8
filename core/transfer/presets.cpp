// Preset lookup and transfer-function files.
#include "core/transfer/presets.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/util/error.h"
#include "core/util/file_writer.h"
#include "core/util/json_error.h"

namespace kdswap {
namespace fs = std::filesystem;

std::string assetsDirectory() {
  if (const char* env = std::getenv("KDSWAP_ASSETS"); env && *env) return env;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed = exe.parent_path().parent_path() / "share" / "kdswap" / "assets";
    if (fs::is_directory(installed, ec)) return installed.string();
  }
  return (fs::path(KDSWAP_SOURCE_DIR) / "assets").string();
}

std::vector<std::string> presetNames() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(fs::path(assetsDirectory()) / "presets", ec))
    if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

TransferFunction loadTransferFunction(const std::string& presetOrPath) {
  fs::path path(presetOrPath);
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    const fs::path preset = fs::path(assetsDirectory()) / "presets" / (presetOrPath + ".json");
    if (presetOrPath.find('/') == std::string::npos && fs::is_regular_file(preset, ec)) {
      path = preset;
    } else {
      std::string valid;
      for (const std::string& n : presetNames()) valid += (valid.empty() ? "" : ", ") + n;
      throw Error(presetOrPath + ": no such transfer-function file or preset (presets: " + valid + ")");
    }
  }
  std::ifstream in(path);
  if (!in) throw Error(path.string() + ": cannot open transfer function");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw Error(path.string() + ": not valid JSON: " + jsonErrorText(e));
  }
  TransferFunction tf = TransferFunction::fromJson(j, path.string());
  return tf;
}

void saveTransferFunction(const TransferFunction& tf, const std::string& path) {
  writeFileAtomically(path, tf.toJson().dump(2) + "\n");
}

}  // namespace kdswap
