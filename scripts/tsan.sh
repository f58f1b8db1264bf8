#!/usr/bin/env bash
# Builds the test suite with ThreadSanitizer and runs the mailbox and cluster tests there; any
# report fails its test, so the stage fails (issue 9).
# Usage: scripts/tsan.sh [ctest arguments...]
#   KDSWAP_TSAN_BUILD  build folder (default <repo>/build-tsan)
#
# What TSan sees: sanitizer builds run each virtual node as its own std::thread
# (NodeExecution::Threads, the default under KDSWAP_SANITIZED), so every message between nodes,
# every mailbox wait and wake-up, the stall watchdog and the host are kdswap's own instrumented
# code. oneTBB gets no worker threads in this build (tests/tsan_serial_tbb.cpp): Debian's libtbb is
# not instrumented and TSan would report its hand-overs as races in kdswap's loop bodies. Tests
# that pick NodeExecution::Tasks on purpose still run: their suspended tasks resume on the one
# thread of their arena, so TSan still checks the mailbox's atomics between that thread and the
# posting threads.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build="${KDSWAP_TSAN_BUILD:-$root/build-tsan}"
source "$root/scripts/deps.sh"
kdswap_install_missing

# The suites under test: the mailbox and everything that runs a virtual cluster.
suites=(mailbox distributed_invariant fault_injection cluster_scale soak composite_strategies front_to_back_waves)

start=$(date +%s)
# RelWithDebInfo: optimised (TSan costs 5-15x already) with line numbers in reports; not Release,
# so KDSWAP_CHECKS (message checksums, invariant checks) stays on. Only the test binary is needed.
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DKDSWAP_SANITIZE=thread -DKDSWAP_GUI=OFF -DKDSWAP_MPI=OFF -DKDSWAP_TSAN_TESTS=OFF >/dev/null
cmake --build "$build" -j"$(nproc)" --target kdswap_tests
built=$(date +%s)

# oneTBB allocates its internal objects from libtbbmalloc when that library sits beside libtbb.
# tbbmalloc recycles freed blocks itself, out of TSan's sight, so a block freed by one thread and
# handed to another looks like a race in the oneTBB templates compiled into kdswap. A copy of
# libtbb in a folder of its own finds no tbbmalloc beside it and falls back to malloc, which TSan
# follows.
libtbb=$(ldd "$build/tests/kdswap_tests" | awk '$1 ~ /^libtbb\.so/ {print $3; exit}')
mkdir -p "$build/libtbb-alone"
cp -L "$libtbb" "$build/libtbb-alone/$(basename "$libtbb")"
export LD_LIBRARY_PATH="$build/libtbb-alone${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"

# ctest names each doctest case after itself; pick the cases of the suites above by asking the
# binary which cases those files hold, and match the names exactly (regex characters escaped).
filter=$(printf '*/%s_test.cpp,' "${suites[@]}")
regex=$("$build/tests/kdswap_tests" --source-file="${filter%,}" --list-test-cases |
  grep -v -e '^\[doctest\] ' -e '^=*$' |
  sed -e 's/[][\\^$.*+?(){}|]/\\&/g' -e 's/^/^/' -e 's/$/$/' | paste -sd '|')
if [ -z "$regex" ]; then
  echo "tsan.sh: no test cases found in ${suites[*]}" >&2
  exit 1
fi

# halt_on_error: the first report ends the test with a failure (exit code 66).
# second_deadlock_stack: lock-order reports show both acquisitions.
export TSAN_OPTIONS="halt_on_error=1:exitcode=66:second_deadlock_stack=1:suppressions=$root/tests/tsan.supp${KDSWAP_EXTRA_TSAN_OPTIONS:+:$KDSWAP_EXTRA_TSAN_OPTIONS}"
cd "$build"
status=0
ctest --output-on-failure -j2 -R "$regex" "$@" || status=$?
echo "tsan.sh: build $((built - start)) s, tests $(( $(date +%s) - built )) s"
exit "$status"
