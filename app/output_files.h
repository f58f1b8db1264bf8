// The files a command will write, checked before it does any work: a mistake found after a long
// render would lose the render, and one found not at all can overwrite the user's data.
#pragma once

#include <string>
#include <vector>

namespace kdswap {

struct OutputFile {
  std::string option;  //!< e.g. "--stats", named in the error
  std::string path;    //!< empty: not given
};

//! Throws kdswap::Error (one line naming the option) when an output's folder does not exist, the
//! output is itself a folder, two outputs name the same file, or an output names one of `inputs`
//! (the volume, a transfer-function file: `--stats head.nrrd` would replace the volume). The same
//! file is found through different spellings, symbolic links and hard links.
void checkOutputFiles(const std::vector<OutputFile>& outputs, const std::vector<std::string>& inputs);

//! `path` when it names an existing file (an option that takes a preset name or a file), else "".
std::string existingFileOrEmpty(const std::string& path);

}  // namespace kdswap
