# Sourced by test.sh and run.sh: installs the Debian packages kdswap needs, only those missing.
# Runs apt-get as root, or through sudo otherwise.

KDSWAP_PACKAGES=(
  build-essential cmake ninja-build pkg-config git
  # openimageio-tools: OpenImageIO's CMake config names its tools (iconvert...) and fails without them
  libtbb-dev libglm-dev libglfw3-dev libimgui-dev libopenimageio-dev openimageio-tools doctest-dev
  libcli11-dev nlohmann-json3-dev zlib1g-dev libnifti-dev
  xvfb xauth libgl1-mesa-dri libgl-dev
  libopenmpi-dev openmpi-bin
)

kdswap_install_missing() {
  local missing=()
  local pkg
  for pkg in "${KDSWAP_PACKAGES[@]}" "$@"; do
    if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
      missing+=("$pkg")
    fi
  done
  if [ "${#missing[@]}" -eq 0 ]; then
    return 0
  fi
  echo "kdswap: installing ${missing[*]}"
  local sudo=""
  if [ "$(id -u)" -ne 0 ]; then
    sudo="sudo"
  fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

# Configures and builds into $1 (Release unless CMAKE_BUILD_TYPE says otherwise).
kdswap_build() {
  local root build
  root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
  build="$1"
  shift
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE="${CMAKE_BUILD_TYPE:-Release}" "$@" >/dev/null
  cmake --build "$build" -j"$(nproc)"
}
