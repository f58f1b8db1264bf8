#!/usr/bin/env bash
# Builds kdswap with AddressSanitizer + UndefinedBehaviorSanitizer (Debug) and runs every ctest
# suite there; any sanitizer report aborts its test, so the stage fails (issue 9).
# Usage: scripts/sanitize.sh [ctest arguments...]
#   KDSWAP_SANITIZE_BUILD  build folder (default <repo>/build-asan)
#   KDSWAP_SANITIZE_MPI    ON/OFF: also build and run tests/mpi under the sanitizers (default OFF:
#                          LeakSanitizer reports Open MPI 4.1's own allocations, e.g. in
#                          ompi_op_base_op_select and its dlopen'ed components, as leaks at exit)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build="${KDSWAP_SANITIZE_BUILD:-$root/build-asan}"
source "$root/scripts/deps.sh"
kdswap_install_missing

start=$(date +%s)
# Debug keeps asserts and KDSWAP_CHECKS; -O1 (what the ASan documentation suggests for reasonable
# speed) runs the suite several times faster than Debug's -O0; -g1 (line tables) is enough for
# the reports' stacks and compiles faster than -g.
CMAKE_BUILD_TYPE=Debug kdswap_build "$build" -DCMAKE_CXX_FLAGS_DEBUG="-g1 -O1" \
  -DKDSWAP_SANITIZE=address,undefined -DKDSWAP_GUI=OFF -DKDSWAP_TSAN_TESTS=OFF \
  -DKDSWAP_MPI="${KDSWAP_SANITIZE_MPI:-OFF}"
built=$(date +%s)

# ASan stops at its first report (its default); abort_on_error turns the stop into SIGABRT, which
# doctest reports with the test case's name. LeakSanitizer is on (the default on Linux).
# UBSan only prints by default: halt_on_error makes its first report fail the test too.
# detect_stack_use_after_return stays at its default, off: its fake stacks cannot follow the stack
# switches of oneTBB's suspended tasks, which the tests that pick NodeExecution::Tasks still make
# (nodes run as threads by default here, KDSWAP_SANITIZED).
export ASAN_OPTIONS="abort_on_error=1:strict_string_checks=1:check_initialization_order=1${KDSWAP_EXTRA_ASAN_OPTIONS:+:$KDSWAP_EXTRA_ASAN_OPTIONS}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
cd "$build"
status=0
ctest --output-on-failure -j2 "$@" || status=$?
echo "sanitize.sh: build $((built - start)) s, tests $(( $(date +%s) - built )) s"
exit "$status"
