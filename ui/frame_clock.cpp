// Per-frame timing of the UI loop: medians and 95th percentiles, idle and while rendering.
#include "ui/frame_clock.h"

#include <algorithm>
#include <cstdio>
#include <ctime>

#include <nlohmann/json.hpp>

namespace kdswap {
namespace {

// CPU time of the calling thread: unlike wall time, not stretched by other processes' load.
double threadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + double(t.tv_nsec) * 1e-9;
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  const std::size_t k = std::min(v.size() - 1, std::size_t(q * double(v.size() - 1) + 0.5));
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
  return v[k];
}

}  // namespace

void FrameClock::begin(double now) {
  const double cpu = threadCpuSeconds();
  if (frameStart_ >= 0) {
    current_.interval = now - frameStart_;
    samples_.push_back(current_);
  }
  current_ = Sample{};
  frameStart_ = lastMark_ = now;
  lastCpu_ = cpu;
}

void FrameClock::mark(Part part, double now) {
  const double cpu = threadCpuSeconds();
  current_.part[std::size_t(part)] += now - lastMark_;
  (part == Wait ? current_.waitCpu : current_.workCpu) += cpu - lastCpu_;
  lastMark_ = now;
  lastCpu_ = cpu;
}

std::string FrameClock::reportJson() const {
  nlohmann::json j;
  for (const bool rendering : {false, true}) {
    std::size_t frames = 0, presented = 0;
    double seconds = 0;
    std::vector<double> interval, work, cpu, waitCpu, fraction;
    std::array<std::vector<double>, kParts> part;
    for (const Sample& s : samples_) {
      if (s.rendering != rendering || s.excluded) continue;
      ++frames;
      seconds += s.interval;
      interval.push_back(s.interval);
      work.push_back(s.part[Take] + s.part[Build] + s.part[Draw] + s.part[Swap]);
      cpu.push_back(s.workCpu);
      waitCpu.push_back(s.waitCpu);
      for (int p = 0; p < kParts; ++p) part[std::size_t(p)].push_back(s.part[std::size_t(p)]);
      if (s.presented) ++presented, fraction.push_back(s.fraction);
    }
    const double median = quantile(interval, 0.5);
    nlohmann::json o = {{"frames", frames},
                        {"seconds", seconds},
                        {"fps_median", median > 0 ? 1.0 / median : 0.0},
                        {"fps_mean", seconds > 0 ? double(frames) / seconds : 0.0},
                        {"interval_ms_median", median * 1e3},
                        {"interval_ms_p95", quantile(interval, 0.95) * 1e3},
                        {"work_ms_median", quantile(work, 0.5) * 1e3},
                        {"work_ms_p95", quantile(work, 0.95) * 1e3},
                        {"work_cpu_ms_median", quantile(cpu, 0.5) * 1e3},
                        {"work_cpu_ms_p95", quantile(cpu, 0.95) * 1e3},
                        {"wait_cpu_ms_median", quantile(waitCpu, 0.5) * 1e3},
                        {"presented", presented},
                        {"presented_fraction_median", quantile(fraction, 0.5)}};
    for (int p = 0; p < kParts; ++p) {
      o["parts_ms_median"][kPartNames[std::size_t(p)]] = quantile(part[std::size_t(p)], 0.5) * 1e3;
      o["parts_ms_p95"][kPartNames[std::size_t(p)]] = quantile(part[std::size_t(p)], 0.95) * 1e3;
    }
    j[rendering ? "rendering" : "idle"] = o;
  }
  return j.dump(2);
}

std::string FrameClock::reportText() const {
  const nlohmann::json j = nlohmann::json::parse(reportJson());
  std::string text;
  for (const char* kind : {"idle", "rendering"}) {
    const nlohmann::json& k = j[kind];
    if (k["frames"].get<std::size_t>() == 0) continue;
    const nlohmann::json& p = k["parts_ms_median"];
    char line[512];
    std::snprintf(line, sizeof line,
                  "UI %-9s %4zu frames in %.1f s: %.1f fps (median interval %.1f ms, p95 %.1f ms); UI thread work %.1f ms "
                  "median (%.1f ms CPU; take %.2f, build %.2f, draw %.2f, swap %.2f; waiting %.1f ms CPU); %zu presented, median %.0f%% "
                  "redrawn\n",
                  kind, k["frames"].get<std::size_t>(), k["seconds"].get<double>(), k["fps_median"].get<double>(),
                  k["interval_ms_median"].get<double>(), k["interval_ms_p95"].get<double>(), k["work_ms_median"].get<double>(),
                  k["work_cpu_ms_median"].get<double>(), p["take"].get<double>(), p["build"].get<double>(),
                  p["draw"].get<double>(), p["swap"].get<double>(), k["wait_cpu_ms_median"].get<double>(),
                  k["presented"].get<std::size_t>(),
                  k["presented_fraction_median"].get<double>() * 100.0);
    text += line;
  }
  return text;
}

}  // namespace kdswap
