// Frame naming, the JSON-lines stats file and resume bookkeeping for `kdswap animate`.
#include "core/animation/sequence_writer.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "core/image/image_io.h"
#include "core/util/error.h"
#include "core/util/file_writer.h"

namespace kdswap {
namespace fs = std::filesystem;
namespace {

std::string numbered(const std::string& dir, const std::string& stem, int digits, int frame, const std::string& ext) {
  char number[32];
  std::snprintf(number, sizeof number, "%0*d", digits, frame);
  return (fs::path(dir) / (stem + "_" + number + "." + ext)).string();
}

//! Reads the lines of an earlier run. Only the last line may be malformed: a run killed while
//! writing it leaves it cut short, and that frame then simply counts as not done.
std::map<int, nlohmann::json> readRecords(const std::string& path) {
  std::map<int, nlohmann::json> records;
  std::ifstream in(path);
  if (!in) return records;
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) lines.push_back(line);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    nlohmann::json j = nlohmann::json::parse(lines[i], nullptr, false);
    const bool valid = !j.is_discarded() && j.is_object() && j.contains("frame") && j["frame"].is_number_integer();
    if (!valid) {
      if (i + 1 == lines.size()) break;
      throw Error(path + ": line " + std::to_string(i + 1) + " is not a frame record; remove the file to start afresh");
    }
    const int frame = j["frame"].get<int>();
    records[frame] = std::move(j);
  }
  return records;
}

void writeRecords(const std::string& path, const std::map<int, nlohmann::json>& records) {
  std::string text;
  for (const auto& [frame, j] : records) text += j.dump() + "\n";
  writeFileAtomically(path, text);
}

//! A frame left by an earlier run counts only if its image reads back whole: an empty or cut-off
//! file (a full disk, a killed older version) is rendered again.
bool readableImage(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec) || fs::file_size(path, ec) == 0 || ec) return false;
  try {
    return !readImage(path).empty();
  } catch (const Error&) {
    return false;
  }
}

bool matches(const nlohmann::json& record, const nlohmann::json& identity) {
  for (const auto& [key, value] : identity.items())
    if (!record.contains(key) || record[key] != value) return false;
  return true;
}

//! The frame number of a picture this writer names ("frame_0012.png", "phases_0012.png", any
//! number of digits), or -1 for any other file.
int pictureNumber(const std::string& name, std::string& stem, std::string& ext) {
  const std::size_t underscore = name.find('_'), dot = name.rfind('.');
  if (underscore == std::string::npos || dot == std::string::npos || dot <= underscore + 1) return -1;
  stem = name.substr(0, underscore), ext = name.substr(dot + 1);
  const std::string digits = name.substr(underscore + 1, dot - underscore - 1);
  if ((stem != "frame" && stem != "phases") || (ext != "png" && ext != "exr") || digits.size() > 9 ||
      digits.find_first_not_of("0123456789") != std::string::npos)
    return -1;
  return std::stoi(digits);
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

SequenceWriter::SequenceWriter(const SequenceOptions& o)
    : dir_(o.dir),
      extension_(o.extension),
      statsPath_(o.statsPath.empty() ? (fs::path(o.dir) / "stats.jsonl").string() : o.statsPath) {
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec || !fs::is_directory(dir_))
    throw Error(dir_ + ": cannot create the output folder" + (ec ? " (" + ec.message() + ")" : ""));
  if (::access(dir_.c_str(), W_OK) != 0) throw Error(dir_ + ": the output folder is not writable");
  for (int n = std::max(o.frames - 1, 0); n >= 10000; n /= 10) ++digits_;
  if (o.resume) {
    for (auto& [frame, j] : readRecords(statsPath_))
      if (frame >= 0 && frame < o.frames && readableImage(framePath(frame)) &&
          matches(j, o.identity ? o.identity(frame) : nlohmann::json::object()))
        records_[frame] = std::move(j);
  }
  writeRecords(statsPath_, records_);
  // An earlier run's pictures that this one will not overwrite: frames past this run's count,
  // another format, or numbers of another width.
  for (const fs::directory_entry& entry : fs::directory_iterator(dir_, ec)) {
    std::string stem, ext;
    const std::string name = entry.path().filename().string();
    const int frame = pictureNumber(name, stem, ext);
    if (frame < 0 || !entry.is_regular_file(ec)) continue;
    const std::string ours = stem == "frame" ? framePath(frame) : phasesPath(frame);
    if (frame < o.frames && fs::path(ours).filename() == name) continue;
    if (fs::remove(entry.path(), ec)) ++staleRemoved_;
  }
}

std::string SequenceWriter::framePath(int frame) const { return numbered(dir_, "frame", digits_, frame, extension_); }
std::string SequenceWriter::phasesPath(int frame) const { return numbered(dir_, "phases", digits_, frame, "png"); }
std::string SequenceWriter::framePattern() const {
  return (fs::path(dir_) / ("frame_%0" + std::to_string(digits_) + "d." + extension_)).string();
}

bool SequenceWriter::isDone(int frame) const { return records_.count(frame) && fs::exists(framePath(frame)); }

void SequenceWriter::record(const nlohmann::json& line) {
  // Opened per line: one small append per frame, and nothing is left open when a frame throws.
  appendToFile(statsPath_, line.dump() + "\n");
  records_[line.at("frame").get<int>()] = line;
}

SequenceSummary summarizeSequence(const std::map<int, nlohmann::json>& records) {
  std::vector<double> wall, modelled, gather;
  for (const auto& [frame, j] : records) {
    wall.push_back(j.value("wall_s", 0.0));
    modelled.push_back(j.value("modelled_parallel_s", 0.0));
    gather.push_back(j.value("gather_s", 0.0));
  }
  return SequenceSummary{int(records.size()), median(wall), median(modelled), median(gather)};
}

}  // namespace kdswap
