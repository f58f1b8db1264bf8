// Output checks: same-file tests by canonical path, and by file identity where the file exists.
#include "app/output_files.h"

#include <filesystem>
#include <system_error>

#include "core/util/error.h"

namespace kdswap {
namespace {

namespace fs = std::filesystem;

//! Whether two paths name one file: the same canonical path (the file need not exist), or, both
//! existing, the same file (a hard link).
bool sameFile(const std::string& a, const std::string& b) {
  std::error_code ec;
  const fs::path ca = fs::weakly_canonical(fs::absolute(a, ec), ec);
  if (ec) return false;
  const fs::path cb = fs::weakly_canonical(fs::absolute(b, ec), ec);
  if (ec) return false;
  if (ca == cb) return true;
  return fs::exists(ca, ec) && fs::exists(cb, ec) && fs::equivalent(ca, cb, ec) && !ec;
}

}  // namespace

void checkOutputFiles(const std::vector<OutputFile>& outputs, const std::vector<std::string>& inputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const OutputFile& o = outputs[i];
    if (o.path.empty()) continue;
    std::error_code ec;
    if (fs::is_directory(o.path, ec)) throw Error(o.option + " " + o.path + ": is a directory, not a file to write");
    const fs::path parent = fs::absolute(o.path, ec).parent_path();
    if (!fs::is_directory(parent, ec)) throw Error(o.option + " " + o.path + ": folder " + parent.string() + " does not exist");
    for (const std::string& input : inputs)
      if (!input.empty() && sameFile(o.path, input))
        throw Error(o.option + " " + o.path + ": is an input of this command (" + input + "); it would be overwritten");
    for (std::size_t j = 0; j < i; ++j)
      if (!outputs[j].path.empty() && sameFile(o.path, outputs[j].path))
        throw Error(o.option + " " + o.path + ": the same file as " + outputs[j].option +
                    "; one would overwrite the other");
  }
}

std::string existingFileOrEmpty(const std::string& path) {
  std::error_code ec;
  return !path.empty() && fs::is_regular_file(path, ec) ? path : std::string();
}

}  // namespace kdswap
