// Shared scene options: parsing and validation into a Scene.
#include "app/scene_options.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <vector>

#include "core/cluster/front_to_back_waves.h"
#include "core/composite/registry.h"
#include "core/render/reference_render.h"
#include "core/transfer/presets.h"
#include "core/util/error.h"
#include "core/volume/datasets/dataset.h"
#include "core/volume/reader.h"
#include "core/volume/respaced_source.h"

namespace kdswap {

std::vector<double> parseNumbers(const std::string& text, char separator, const std::string& option) {
  std::vector<double> values;
  for (const std::string& item : splitItems(text, separator)) {
    if (item.empty())
      throw Error(option + " \"" + text + "\": empty item (a '" + std::string(1, separator) + "' too many)");
    std::size_t used = 0;
    double v = 0;
    try {
      v = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != item.size() || !std::isfinite(v))
      throw Error(option + " \"" + text + "\": \"" + item + "\" is not a number");
    values.push_back(v);
  }
  return values;
}

CLI::Validator nonEmpty() {
  return CLI::Validator([](const std::string& value) { return value.empty() ? std::string("empty value") : std::string(); },
                        "", "non-empty");
}

CLI::Validator number() {
  return CLI::Validator(
      [](const std::string& value) {
        char* end = nullptr;
        const double v = std::strtod(value.c_str(), &end);
        if (value.empty() || end != value.c_str() + value.size()) return "\"" + value + "\" is not a number";
        if (!std::isfinite(v)) return "\"" + value + "\" is not a finite number";
        return std::string();
      },
      "", "number");
}

CLI::Validator wholeNumber(std::int64_t min, std::int64_t max) {
  return CLI::Validator(
      [min, max](const std::string& value) {
        const std::size_t start = !value.empty() && (value[0] == '-' || value[0] == '+') ? 1 : 0;
        if (value.size() == start || value.find_first_not_of("0123456789", start) != std::string::npos)
          return "\"" + value + "\" is not a whole number";
        // Out of range, not clamped: CLI11 alone reads 20 digits into an int64 as 2^63 - 1.
        errno = 0;
        const long long v = std::strtoll(value.c_str(), nullptr, 10);
        if (errno == ERANGE || v < min || v > max) return "\"" + value + "\" is out of range";
        return std::string();
      },
      "", "whole number");
}

glm::vec2 parseViewAngles(const std::string& text, const std::string& option) {
  const auto angles = parseNumbers(text, ',', option);
  if (angles.size() != 2) throw Error(option + " \"" + text + "\": expected AZIMUTH,ELEVATION in degrees");
  const glm::vec2 v{float(angles[0]), float(angles[1])};
  if (!validAzimuth(v.x))
    throw Error(option + " \"" + text + "\": azimuth must be from -36000 to 36000 degrees (100 turns)");
  // The same range as --elevation-sweep and key files; the camera is undefined at the poles.
  if (!(v.y > -90.0f && v.y < 90.0f))
    throw Error(option + " \"" + text + "\": elevation must be in (-90, 90) degrees");
  return v;
}

glm::vec2 parseValueRange(const std::string& text, const std::string& option) {
  const auto range = parseNumbers(text, ',', option);
  if (range.size() != 2 || !(range[1] > range[0]))
    throw Error(option + " \"" + text + "\": expected MIN,MAX with MIN < MAX");
  // Rendering maps values with float scale 1 / (MAX - MIN) and bias -MIN / (MAX - MIN)
  // (normalisingScaleBias): each must be finite, or every sample maps to nothing.
  const glm::vec2 r{float(range[0]), float(range[1])};
  const float span = r.y - r.x;
  if (!std::isfinite(r.x) || !std::isfinite(r.y) || !(span > 0.0f) || !std::isfinite(span) ||
      !std::isfinite(1.0f / span) || !std::isfinite(r.x / span))
    throw Error(option + " \"" + text + "\": MIN, MAX and MAX - MIN must be finite floats (below 3.4e38 in size) "
                "and MIN, MAX must differ at float precision");
  return r;
}

bool parseOnOff(const std::string& text, const std::string& option) {
  if (text != "on" && text != "off") throw Error(option + " \"" + text + "\": expected on or off");
  return text == "on";
}

void checkStep(float step, const std::string& option) {
  if (!(step >= 0.01f && step <= 16.0f)) throw Error(option + " must be between 0.01 and 16 voxels");
}

void checkDistance(float radii, const std::string& option) {
  if (!(radii > 0.0f && radii < 1000.0f)) throw Error(option + " must be between 0 and 1000 radii");
}

void checkErt(float ert, const std::string& option) {
  if (!(ert > 0.0f && ert <= 1.0f)) throw Error(option + " must be in (0, 1]");
}

void checkThreads(int threads, const std::string& option) {
  if (threads < 0 || threads > 1024) throw Error(option + " " + std::to_string(threads) + ": must be from 0 to 1024");
}

std::vector<double> parseSpeeds(const std::string& text, const std::string& option) {
  const auto speeds = parseNumbers(text, ',', option);
  for (double v : speeds)
    if (!(v >= 0.01 && v <= 100.0)) throw Error(option + " \"" + text + "\": each speed must be from 0.01 to 100");
  return speeds;
}

TransferFunction loadTransferOption(const std::string& presetOrPath, const std::string& option) {
  std::error_code ec;
  if (std::filesystem::is_directory(presetOrPath, ec))
    throw Error(option + " " + presetOrPath + ": is a folder; expected a preset name or a JSON file");
  try {
    return loadTransferFunction(presetOrPath);
  } catch (const Error& e) {
    throw Error(option + " " + e.what());  // e.what() starts with the name or path
  }
}

void checkOutputFolder(const std::string& path, const std::string& option) {
  if (path.empty()) throw Error(option + ": empty value");
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (std::filesystem::exists(status) && !std::filesystem::is_directory(status))
    throw Error(option + " " + path + ": exists and is not a folder");
  // The nearest existing ancestor must be a folder too ("a/file/b" cannot be made either).
  for (std::filesystem::path p = std::filesystem::absolute(path, ec).parent_path(); !p.empty(); p = p.parent_path()) {
    const auto s = std::filesystem::status(p, ec);
    if (std::filesystem::exists(s)) {
      if (!std::filesystem::is_directory(s)) throw Error(option + " " + path + ": " + p.string() + " is not a folder");
      break;
    }
    if (p == p.parent_path()) break;
  }
}

void parseImageSize(const std::string& text, int& width, int& height) {
  std::vector<double> v;
  try {
    v = parseNumbers(text, 'x', "--size");
  } catch (const Error&) {
    throw Error("--size \"" + text + "\": expected WxH, e.g. 512x512");
  }
  if (v.size() == 1) v.push_back(v[0]);
  if (v.size() != 2) throw Error("--size \"" + text + "\": expected WxH, e.g. 512x512");
  for (double d : v)
    if (d < 1 || d > 16384 || d != std::floor(d))
      throw Error("--size \"" + text + "\": each side must be a whole number from 1 to 16384");
  width = int(v[0]);
  height = int(v[1]);
}

void addSceneOptions(CLI::App* cmd, SceneOptions& o) {
  cmd->add_option("--dataset", o.dataset,
                  "Built-in procedural data set NAME[:N|:WxHxD]: phantom (Shepp-Logan head), vessels, "
                  "turbulence. Default phantom:128")
      ->check(nonEmpty());
  cmd->add_option("--volume", o.volume,
                  "Volume file: .nrrd/.nhdr, .mhd/.mha, .nii/.nii.gz, legacy .vtk, or .raw "
                  "(layout from --raw-* or a name like head_256x256x113_uint16.raw)")
      ->check(nonEmpty());
  addRawLayoutOptions(cmd, o.raw);
  cmd->add_option("--spacing", o.spacing,
                  "Voxel spacing SX,SY,SZ instead of the data's, for any volume (e.g. 1,1,1 to compare with "
                  "a renderer that ignores the header's spacing)")
      ->check(nonEmpty());
  cmd->add_option("--size", o.size, "Image size WxH (1..16384 each)")->check(nonEmpty())->capture_default_str();
  cmd->add_option("--view", o.view, "Orbit view AZIMUTH,ELEVATION in degrees (azimuth -36000..36000, elevation in (-90, 90))")
      ->check(nonEmpty())
      ->capture_default_str();
  cmd->add_option("--distance", o.distance, "Eye distance in bounding-sphere radii, in (0, 1000); the default shows the whole volume")
      ->check(number())
      ->capture_default_str();
  cmd->add_option("--fov", o.fov, "Vertical field of view, 1..170 degrees (orthographic: sets the frame size)")
      ->check(number())
      ->capture_default_str();
  cmd->add_option("--projection", o.projection, "perspective or orthographic")->capture_default_str();
  cmd->add_option("--up", o.up, "Volume axis pointing up on screen: +x -x +y -y +z -z")->capture_default_str();
  cmd->add_option("--step", o.step, "Sample spacing in voxels, 0.01..16 (global lattice; opacity is corrected for it)")
      ->check(number())
      ->capture_default_str();
  cmd->add_option("--tf", o.tf, "Transfer function: a preset name (see assets/presets) or a JSON file "
                                "(kdswap or ParaView colour map). Default: the data set's preset")
      ->check(nonEmpty());
  cmd->add_option("--shading", o.shading, "Phong shading from precomputed gradients: on or off")->capture_default_str();
  cmd->add_option("--jitter", o.jitter, "Per-ray lattice phase (a blue-noise tile over the pixels) against ring artefacts: on or off")->capture_default_str();
  cmd->add_option("--ert", o.ert, "Early ray termination opacity threshold, in (0, 1] (1 disables)")
      ->check(number())
      ->capture_default_str();
  cmd->add_option("--range", o.range,
                  "Scalar range MIN,MAX mapped to [0,1], finite floats with MIN < MAX (default: the data's range)")
      ->check(nonEmpty());
}

void addClusterOptions(CLI::App* cmd, SceneOptions& o) {
  cmd->add_option("--nodes,-n", o.nodes, "Virtual nodes P (1..4096)")->check(wholeNumber())->capture_default_str();
  cmd->add_option("--composite", o.composite, "Compositing strategy: binary-swap, binary-tree, sequential, direct-send, radix-k, 2-3-swap, telescoping")
      ->capture_default_str();
  cmd->add_option("--partition", o.partition, "kd (alternating k-d tree) or slab")->capture_default_str();
  cmd->add_flag("--sparse", o.sparse, "Send only the bounding rectangle of non-empty pixels");
  cmd->add_flag("--waves", o.waves,
                "Front-to-back waves (beyond the paper): nodes render one after another, nearest first, each stopping "
                "its rays where those in front stopped the light, so none samples behind the single-node ray's end "
                "(replaces the occlusion map; with one brick per node)");
  cmd->add_option("--radices", o.radices,
                  "--composite radix-k only: group size of each round, e.g. 4,2 (each 2..4096, product = --nodes; default: prime factors of P in rounds of at most 8, e.g. 64 -> 8,8)")
      ->check(nonEmpty());
  cmd->add_option("--threads", o.threads, "Worker threads, 0..1024 (0 = every core)")->check(wholeNumber())->capture_default_str();
  cmd->add_option("--balance", o.balance,
                  "Plane placement: space (halve space, as the paper) or cost (balance the work estimated "
                  "from the transfer function: visible blocks cost more than empty ones)")
      ->capture_default_str();
  cmd->add_option("--speeds", o.speeds,
                  "Relative node speeds, each 0.01..100, e.g. 1,0.5 (repeated over the P nodes): partitions follow "
                  "them and modelled times divide each node's work by its speed")
      ->check(nonEmpty());
  cmd->add_option("--bricks-per-node", o.bricksPerNode,
                  "Over-decomposition: cut each node's brick into this many (1..64), handed out on demand "
                  "each frame so fast or idle nodes take work from busy ones")
      ->check(wholeNumber())
      ->capture_default_str();
  cmd->add_option("--network", o.network,
                  "Network model for the modelled time: ideal (no cost), cm5 (CM-5 fat tree: 20/10/5 MB/s), "
                  "ethernet10 (10 Mbit/s shared by all nodes)")
      ->capture_default_str();
  cmd->add_option("--voxels", o.voxels,
                  "How nodes store voxels: float (value and gradient as 4 floats, 16 B), compact (16-bit "
                  "integers, 8 B: half the memory, 16-bit precision) or auto (compact above 2^23 voxels)")
      ->capture_default_str();
  cmd->add_option("--stall-timeout", o.stallSeconds,
                  "Abort a frame when nodes wait and no node works or sends for this many seconds, in (0, 86400], naming who waits on whom "
                  "(a long render is never cut short)")
      ->check(number())
      ->capture_default_str();
  cmd->add_flag("--checksums", o.checksums, "Checksum every message and refuse corrupted ones");
  cmd->add_option("--node-execution", o.nodeExecution,
                  "tasks: one oneTBB task per node, waits suspend (default); threads: one OS thread per node "
                  "(the sanitizer builds' default)")
      ->check(nonEmpty())
      ->group("Testing");
  cmd->add_option("--inject-fault", o.injectFault,
                  "Testing: KIND:NODE[:MESSAGE[:DELAY_S]] with KIND throw-render, throw-composite, drop, delay "
                  "or corrupt; the first frame fails with an error naming the node")
      ->check(nonEmpty())
      ->group("Testing");
}

std::unique_ptr<VolumeSource> openDatasetOption(const std::string& spec) {
  const std::string name = spec.substr(0, spec.find(':'));
  std::error_code ec;
  const bool looksLikeFile = name.find_first_of("/.") != std::string::npos || std::filesystem::exists(spec, ec);
  if (!isDatasetSpec(spec) && looksLikeFile) {
    throw Error("--dataset \"" + spec + "\": not a built-in data set (" + datasetNameList() +
                "); a volume file is opened with --volume " + spec);
  }
  return openDataset(spec);
}

Scene buildScene(const SceneOptions& o) {
  Scene scene;
  if (!o.volume.empty() && !o.dataset.empty()) throw Error("give either --volume or --dataset, not both");
  if (!o.volume.empty()) {
    scene.source = openVolumeFile(o.volume, parseRawLayout(o.raw));
  } else {
    checkNoRawLayout(o.raw, "--dataset " + (o.dataset.empty() ? kDefaultDataset + std::string(" (the default)") : o.dataset));
    scene.source = openDatasetOption(o.dataset.empty() ? kDefaultDataset : o.dataset);
  }
  if (!o.spacing.empty()) scene.source = std::make_unique<RespacedSource>(std::move(scene.source), parseSpacing(o.spacing, "--spacing"));
  const VolumeInfo& info = scene.source->info();

  FrameRequest& r = scene.request;
  parseImageSize(o.size, r.width, r.height);
  const glm::vec2 angles = parseViewAngles(o.view, "--view");
  r.view.azimuthDeg = angles.x;
  r.view.elevationDeg = angles.y;
  checkDistance(o.distance);
  r.view.distance = o.distance;
  if (!(o.fov >= 1.0f && o.fov <= 170.0f)) throw Error("--fov must be between 1 and 170 degrees");
  r.view.fovDeg = o.fov;
  r.view.projection = parseProjection(o.projection, "--projection");
  r.view.up = parseUpAxis(o.up, "--up");
  checkStep(o.step);
  r.settings.stepVoxels = o.step;
  r.settings.shading = parseOnOff(o.shading, "--shading");
  r.settings.jitter = parseOnOff(o.jitter, "--jitter");
  checkErt(o.ert);
  r.settings.earlyTermination = o.ert;
  r.settings.frontToBackWaves = o.waves;
  if (!o.range.empty()) r.settings.valueRange = parseValueRange(o.range, "--range");
  r.transfer = !o.tf.empty() ? loadTransferOption(o.tf) : loadTransferFunction(!info.preset.empty() ? info.preset : "grayscale");

  ClusterOptions& c = scene.cluster;
  c.nodes = o.nodes;
  if (o.nodes < 1 || o.nodes > kMaxNodes) throw Error("--nodes " + std::to_string(o.nodes) + ": must be from 1 to 4096");
  checkStrategyName(o.composite);
  c.strategy = o.composite;
  c.partition = parsePartition(o.partition, "--partition");
  c.composite.sparse = o.sparse;
  // Only radix-k reads them: with another strategy they would be silently ignored.
  if (!o.radices.empty() && o.composite != "radix-k")
    throw Error("--radices goes with --composite radix-k (the strategy is " + o.composite + ")");
  if (!o.radices.empty())
    for (double k : parseNumbers(o.radices, ',', "--radices")) {
      if (k < 2 || k > kMaxNodes || k != std::floor(k))
        throw Error("--radices \"" + o.radices + "\": each radix must be a whole number from 2 to " + std::to_string(kMaxNodes));
      c.composite.radices.push_back(int(k));
    }
  checkThreads(o.threads);
  c.threads = o.threads;
  if (!(o.stallSeconds > 0.0 && o.stallSeconds <= 86400.0)) throw Error("--stall-timeout must be between 0 and 86400 seconds");
  c.stallSeconds = o.stallSeconds;
  c.checksums = c.checksums || o.checksums;
  if (!o.nodeExecution.empty()) c.execution = parseNodeExecution(o.nodeExecution);
  if (o.balance != "space" && o.balance != "cost") throw Error("--balance \"" + o.balance + "\": expected space or cost");
  c.balance = o.balance;
  if (o.bricksPerNode < 1 || o.bricksPerNode > 64) throw Error("--bricks-per-node must be from 1 to 64");
  c.bricksPerNode = o.bricksPerNode;
  checkWavesWithBricksPerNode(o.waves, o.bricksPerNode);
  c.voxels = parseVoxelChoice(o.voxels);
  if (c.voxels == VoxelChoice::Float)  // opening the volume assumed the default storage
    checkBrickMemory(info, 16, "--voxels float: " + info.name, "--voxels compact takes half");
  c.balanceTransfer = r.transfer;
  c.balanceRange = resolveValueRange(r.settings, info);
  if (!o.speeds.empty()) {
    const auto speeds = parseSpeeds(o.speeds);
    for (int n = 0; n < c.nodes; ++n) c.speeds.push_back(speeds[std::size_t(n) % speeds.size()]);
  }
  try {
    c.network = networkModel(o.network);
  } catch (const Error& e) {
    throw Error(std::string("--network: ") + e.what());
  }
  if (!o.injectFault.empty()) {
    const std::vector<std::string> parts = splitItems(o.injectFault, ':');
    if (parts.size() < 2 || parts.size() > 4) throw Error("--inject-fault \"" + o.injectFault + "\": expected KIND:NODE[:MESSAGE[:DELAY_S]]");
    scene.fault.kind = parseFaultKind(parts[0]);
    const auto numbers = parseNumbers(o.injectFault.substr(parts[0].size() + 1), ':', "--inject-fault");
    if (!(numbers[0] >= 0 && numbers[0] < c.nodes) || numbers[0] != std::floor(numbers[0]))
      throw Error("--inject-fault: node must be from 0 to " + std::to_string(c.nodes - 1));
    scene.fault.node = int(numbers[0]);
    if (numbers.size() > 1) {
      if (!(numbers[1] >= 0 && numbers[1] <= 1e9) || numbers[1] != std::floor(numbers[1]))
        throw Error("--inject-fault \"" + o.injectFault + "\": MESSAGE must be a whole number from 0 to 1000000000");
      scene.fault.message = int(numbers[1]);
    }
    // A huge delay overflows the sleep's duration and becomes no delay at all.
    constexpr double kMaxFaultDelaySeconds = 3600;
    if (numbers.size() > 2 && !(numbers[2] >= 0 && numbers[2] <= kMaxFaultDelaySeconds))
      throw Error("--inject-fault \"" + o.injectFault + "\": DELAY_S must be from 0 to " +
                  std::to_string(int(kMaxFaultDelaySeconds)) + " seconds");
    if (numbers.size() > 2) scene.fault.delaySeconds = numbers[2];
    if (scene.fault.kind == FaultPlan::Kind::CorruptMessage) c.checksums = true;
  }
  if (c.partition == PartitionKind::Slab) {
    const Camera camera(r.view, glm::vec3(0.0f), info.worldMax(), r.width, r.height);
    c.slabAxis = slabAxisFor(camera);
  }
  return scene;
}

}  // namespace kdswap
