#!/usr/bin/env bash
# Installs the Debian 12 packages photovr builds and runs with. Idempotent: only
# packages that are not installed yet are fetched, and apt is not touched at all
# when everything is present.
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config make
  libgtest-dev
  libembree-dev libtbb-dev
  libosmesa6-dev libegl-dev libegl1-mesa-dev libgl-dev libgl1-mesa-dri mesa-utils
  libglfw3-dev libglm-dev
  libtinygltf-dev libstb-dev
  nlohmann-json3-dev  # glTF member types, checked before tinygltf drops a wrong one
  libdraco-dev  # KHR_draco_mesh_compression meshes (decoder, and the encoder the tests use)
  libmeshoptimizer-dev  # EXT_meshopt_compression buffers (decoder, and the encoder the tests use)
  libopenimageio-dev openimageio-tools
  libhidapi-dev
  libimgui-dev
  xvfb xauth  # a virtual display for the glfw backend's tests
  parallel  # reference shards and bench jobs with GNU parallel (scripts/cluster/, their tests)
  slurm-wlm munge  # a one-node Slurm cluster for the array-job recipes' test (scripts/cluster/)
  gnuplot-nox  # bench plots (photovr bench)
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "setup: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
