// Command-line options shared by every subcommand that renders: the volume, the view, the
// transfer function and render settings, and the virtual cluster. Parsed once into a Scene.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/vec2.hpp>

#include "app/raw_layout_options.h"
#include "core/cluster/frame_request.h"
#include "core/cluster/virtual_cluster.h"
#include "core/transfer/transfer_function.h"
#include "core/composite/registry.h"  // checkStrategyName
#include "core/util/text_items.h"  // splitItems
#include "core/volume/volume_source.h"

namespace kdswap {

struct SceneOptions {
  std::string dataset;
  std::string volume;
  RawLayoutOptions raw;  //!< --raw-*: the layout of a raw --volume file
  std::string spacing;  //!< overrides the data's voxel spacing (any volume or data set)
  std::string size = "512x512";
  std::string view = "30,15";
  float distance = View{}.distance, fov = View{}.fovDeg;
  std::string projection = "perspective", up = "+z";
  float step = 0.5f;
  std::string tf;
  std::string shading = "on";
  std::string jitter = "on";
  float ert = 0.99f;
  std::string range;
  int nodes = 1;
  std::string composite = "binary-swap";
  std::string partition = "kd";
  bool sparse = false;
  bool waves = false;  //!< front-to-back waves (RenderSettings::frontToBackWaves)
  std::string radices;  //!< radix-k group size per round, "4,2,..."; empty = prime factors of P
  int threads = 0;
  double stallSeconds = 60.0;
  std::string injectFault;  //!< test-only: KIND:NODE[:MESSAGE[:DELAY_S]]
  bool checksums = false;
  std::string nodeExecution;  //!< empty: the build's default
  std::string balance = "space";
  std::string speeds;          //!< "1,0.5,..." per node, repeated to P values; empty = all 1
  std::string network = "ideal";
  int bricksPerNode = 1;
  std::string voxels = "auto";  //!< auto, float or compact (VoxelChoice)
};

struct Scene {
  std::unique_ptr<VolumeSource> source;
  FrameRequest request;
  ClusterOptions cluster;
  FaultPlan fault;  //!< test-only, for the first frame
};

//! Adds the volume, view and render options to `cmd`.
void addSceneOptions(CLI::App* cmd, SceneOptions& options);
//! Adds --nodes, --composite, --partition, --sparse, --threads.
void addClusterOptions(CLI::App* cmd, SceneOptions& options);
//! Opens the volume and validates every option. Throws kdswap::Error with one clear line.
Scene buildScene(const SceneOptions& options);
//! openDataset for the value of --dataset. What looks like a file there (a path, a name with a dot,
//! or anything that exists) is refused with the --volume option that opens it, which every
//! subcommand has (kdswap-gui takes files in --dataset, so the slip is easy to make).
std::unique_ptr<VolumeSource> openDatasetOption(const std::string& spec);
//! "WxH" -> (w, h), each 1..16384. Throws kdswap::Error.
void parseImageSize(const std::string& text, int& width, int& height);
//! The value of `option` as finite numbers between `separator`s ("1,0.5" -> {1, 0.5}; "" -> {}).
//! Ranges are the caller's to check. Throws kdswap::Error naming `option`, the text and the item
//! that is not a number (an empty item, as in "1,,2" or "1,2,", is not one).
std::vector<double> parseNumbers(const std::string& text, char separator, const std::string& option);

// Checks shared by every subcommand that renders (render, animate, bench, kdswap-mpi), so each
// option is validated the same way wherever it appears. Each throws kdswap::Error naming `option`.

//! A CLI11 check refusing an empty value: `--volume ""` is a mistake, not "the default".
CLI::Validator nonEmpty();
//! CLI11 checks for numeric options: `--step: "abc" is not a number` instead of CLI11's "Could not
//! convert". They refuse only what the option's type cannot hold; ranges stay with each option.
CLI::Validator number();  //!< a finite decimal number
//! Digits with an optional sign, from `min` to `max` (by default an int's range).
CLI::Validator wholeNumber(std::int64_t min = std::numeric_limits<int>::min(),
                           std::int64_t max = std::numeric_limits<int>::max());
//! "AZIMUTH,ELEVATION" in degrees: azimuth any finite float, elevation in (-90, 90).
glm::vec2 parseViewAngles(const std::string& text, const std::string& option);
//! "MIN,MAX" mapped to [0, 1]: finite floats whose difference and its reciprocal are finite.
glm::vec2 parseValueRange(const std::string& text, const std::string& option);
//! "on" -> true, "off" -> false.
bool parseOnOff(const std::string& text, const std::string& option);
void checkStep(float step, const std::string& option = "--step");        //!< 0.01..16 voxels
void checkErt(float ert, const std::string& option = "--ert");           //!< (0, 1]
void checkDistance(float radii, const std::string& option = "--distance");  //!< (0, 1000) bounding-sphere radii
void checkThreads(int threads, const std::string& option = "--threads");  //!< 0..1024
//! "1,0.5,..." each from 0.01 to 100; "" -> {}.
std::vector<double> parseSpeeds(const std::string& text, const std::string& option = "--speeds");
//! A preset name or a JSON file; a folder is named as one (loadTransferFunction would call it missing).
TransferFunction loadTransferOption(const std::string& presetOrPath, const std::string& option = "--tf");
//! An output folder that exists or can be made: refuses an existing file of that name up front.
void checkOutputFolder(const std::string& path, const std::string& option);

}  // namespace kdswap
