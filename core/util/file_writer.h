// Writing output files so that a failure is always reported and never leaves a partial file:
// the bytes go to a temporary file beside the target, every write, the flush to disk and the
// close are checked (a full disk shows up at any of them), and only then is it renamed into place.
#pragma once

#include <string>
#include <string_view>

namespace kdswap {

//! Replaces `path` with `bytes`. Throws kdswap::Error naming `path` and the cause (for example
//! "No space left on device"); the target then keeps its old contents, or stays absent.
void writeFileAtomically(const std::string& path, std::string_view bytes);

//! From the first call on, a write past the file-size limit (`ulimit -f`) fails with EFBIG, which
//! the writers report, instead of killing the process with SIGXFSZ. The writers here call it.
void reportFileSizeLimitAsError();

//! Appends `bytes` to `path` (created if missing), checking every write and the close.
void appendToFile(const std::string& path, std::string_view bytes);

}  // namespace kdswap
