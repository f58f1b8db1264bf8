// Progress text for `kdswap animate`.
#include "core/animation/progress_meter.h"

#include <string>

namespace kdswap {
namespace {

std::string formatDuration(double seconds) {
  const long s = long(seconds + 0.5);
  char text[32];
  if (s >= 3600) std::snprintf(text, sizeof text, "%ldh%02ldm", s / 3600, (s / 60) % 60);
  else if (s >= 60) std::snprintf(text, sizeof text, "%ldm%02lds", s / 60, s % 60);
  else std::snprintf(text, sizeof text, "%lds", s);
  return text;
}

}  // namespace

ProgressMeter::ProgressMeter(std::FILE* out, bool terminal, int total, int alreadyDone, const char* unit,
                             const char* units)
    : out_(out), unit_(unit), units_(units), terminal_(terminal), total_(total), done_(alreadyDone) {}

void ProgressMeter::frameDone() {
  ++done_;
  ++renderedThisRun_;
  if (terminal_) {
    print();
    return;
  }
  const int decile = total_ > 0 ? done_ * 10 / total_ : 10;
  if (decile != lastDecile_) {
    lastDecile_ = decile;
    print();
  }
}

void ProgressMeter::finish() {
  if (terminal_ && renderedThisRun_ > 0) std::fputc('\n', out_);
  std::fflush(out_);
}

void ProgressMeter::print() {
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double fps = elapsed > 0 ? renderedThisRun_ / elapsed : 0.0;
  const std::string left = fps > 0 ? formatDuration((total_ - done_) / fps) : "?";
  std::fprintf(out_, "%s%s %d/%d  %.2f %s/s  %s left%s", terminal_ ? "\r" : "", unit_, done_, total_, fps, units_,
               left.c_str(), terminal_ ? "\033[K" : "\n");
  std::fflush(out_);
}

}  // namespace kdswap
