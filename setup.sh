#!/usr/bin/env bash
# Installs the Debian 12 packages pbfengine needs (only those missing), then configures and
# builds it in build/. The binary lands in build/pbfengine.
#
#   ./setup.sh                      install what is missing, build
#   PBF_CMAKE_ARGS="-DPBF_REAL=float" ./setup.sh    extra CMake options
set -euo pipefail
cd "$(dirname "$0")"

packages=(g++ cmake make pkg-config liblua5.4-dev libspdlog-dev libfmt-dev libcli11-dev libgtest-dev
          libbenchmark-dev libstb-dev fonts-dejavu-core libpugixml-dev zlib1g-dev libassimp-dev libopenvdb-dev libhwy-dev openmpi-bin libopenmpi-dev ffmpeg
          python3 python3-numpy python3-matplotlib
          pybind11-dev python3-pytest python3-mpi4py python3-nbconvert python3-ipykernel
          libcpp-httplib-dev nlohmann-json3-dev libjs-three chromium chromium-driver python3-selenium)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup.sh: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}"
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release ${PBF_CMAKE_ARGS:-}
cmake --build build -j"$(nproc)"
echo "setup.sh: built build/pbfengine"
