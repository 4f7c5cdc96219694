#!/usr/bin/env bash
# Installs the Debian 12 packages makeway builds against. A no-op when they are all present.
# Usage: scripts/install-deps.sh [--fuzz | --bench | --ros | --format]
#   --fuzz adds clang and its libFuzzer runtime; --format adds clang-format (`make format-check`); --bench adds Open3D (the ICP comparison only);
#   --ros adds roscpp and the ROS master for the node (`make ros`). ROS 1 bags (rosbag_storage and
#   the message headers) are always in: `makeway run --bag` and `simulate --format bag` use them.
set -euo pipefail

packages=(
    build-essential cmake ninja-build pkg-config ccache mold
    libeigen3-dev libnanoflann-dev libtbb-dev libembree-dev
    libassimp-dev libyaml-cpp-dev nlohmann-json3-dev libcli11-dev libspdlog-dev liblzf-dev
    libcairo2-dev libzip-dev robin-map-dev
    libtorch-dev libopenblas0-pthread
    libgtest-dev libgmock-dev libbenchmark-dev
    librosbag-storage-dev libsensor-msgs-dev libnav-msgs-dev libvisualization-msgs-dev libtf2-msgs-dev
)
if [[ "${1:-}" == "--fuzz" ]]; then
    packages+=(clang libclang-rt-14-dev)
elif [[ "${1:-}" == "--bench" ]]; then
    packages+=(libopen3d-dev)
elif [[ "${1:-}" == "--format" ]]; then
    packages+=(clang-format)
elif [[ "${1:-}" == "--ros" ]]; then
    packages+=(libroscpp-dev ros-core python3-rosmaster)
fi

missing=()
for p in "${packages[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
        missing+=("$p")
    fi
done
if [[ ${#missing[@]} -eq 0 ]]; then
    exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then
    if command -v sudo >/dev/null; then
        sudo_cmd=(sudo)
    else
        echo "install-deps: missing packages (${missing[*]}) and not root; install them and retry" >&2
        exit 1
    fi
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done"
