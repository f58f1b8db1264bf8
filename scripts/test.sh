#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine (installs what is missing), builds kdswap and runs every test.
# Usage: scripts/test.sh [ctest arguments...]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
source "$root/scripts/deps.sh"
kdswap_install_missing
kdswap_build "$root/build"
cd "$root/build"
ctest --output-on-failure -j2 "$@"
