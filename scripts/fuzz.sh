#!/usr/bin/env bash
# Builds the libFuzzer targets of tests/fuzz (one per file parser; clang, ASan + UBSan), replays
# tests/fuzz/regressions/<format>/*, then fuzzes each target for SECONDS from its seed corpus.
# Fails on any crash, sanitizer report, leak, timeout or out-of-memory (issue 9).
# Usage: scripts/fuzz.sh [SECONDS]   (default 60 per target)
#   KDSWAP_FUZZ_BUILD    build folder (default <repo>/build-fuzz); crash inputs land in its artifacts/
#   KDSWAP_FUZZ_TARGETS  formats to run (default: all of them)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds="${1:-60}"
build="${KDSWAP_FUZZ_BUILD:-$root/build-fuzz}"
targets=(${KDSWAP_FUZZ_TARGETS:-raw_name nrrd metaimage nifti vtk transfer_function})
source "$root/scripts/deps.sh"
# clang: the compiler; libclang-rt-14-dev: libclang_rt.fuzzer (-fsanitize=fuzzer) and the sanitizer runtimes.
kdswap_install_missing clang libclang-rt-14-dev

start=$(date +%s)
CC=clang CXX=clang++ cmake -S "$root/tests/fuzz" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE= >/dev/null
cmake --build "$build" -j"$(nproc)"
echo "fuzz.sh: built in $(( $(date +%s) - start )) s"

export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:allocator_may_return_null=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# -malloc_limit_mb: one allocation over 2 GiB is a failure even if the host could serve it; the
# fuzz targets report 1 GiB available, so validateVolumeInfo refuses any bigger volume first.
limits=(-max_len=4096 -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048)
failed=()
for t in "${targets[@]}"; do
  fuzzer="$build/fuzz_$t"
  artifacts="$build/artifacts/$t"
  mkdir -p "$artifacts"
  regressions=("$root/tests/fuzz/regressions/$t"/*)
  if [ -e "${regressions[0]}" ]; then
    echo "== fuzz_$t: replaying ${#regressions[@]} regression input(s)"
    if ! "$fuzzer" "${limits[@]}" -artifact_prefix="$artifacts/" "${regressions[@]}" >"$artifacts/replay.log" 2>&1; then
      tail -n 40 "$artifacts/replay.log"
      failed+=("$t (regression replay)")
      continue
    fi
  fi
  # New inputs go to a working copy of the seeds, never into the source tree.
  corpus="$build/corpus/$t"
  mkdir -p "$corpus"
  cp -n "$root/tests/fuzz/corpus/$t"/* "$corpus/"
  echo "== fuzz_$t: ${seconds} s"
  if ! "$fuzzer" "${limits[@]}" -max_total_time="$seconds" -print_final_stats=1 \
       -artifact_prefix="$artifacts/" "$corpus" >"$artifacts/fuzz.log" 2>&1; then
    tail -n 60 "$artifacts/fuzz.log"
    echo "fuzz_$t failed; reproduce with: $fuzzer $artifacts/<crash-|leak-|timeout-|oom-file>"
    failed+=("$t")
  else
    grep -E '^(#[0-9]+.*DONE|stat::number_of_executed_units)' "$artifacts/fuzz.log" | tail -n 1
  fi
done
echo "fuzz.sh: total $(( $(date +%s) - start )) s"
if [ "${#failed[@]}" -ne 0 ]; then
  echo "fuzz.sh: FAILED: ${failed[*]}"
  exit 1
fi
