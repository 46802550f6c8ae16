#!/usr/bin/env bash
# Installs the Debian 12 packages Bounce needs to build, run and test.
# Idempotent: asks dpkg first and only calls apt-get for what is missing,
# so a second run takes well under a second.
set -euo pipefail

packages=(
  build-essential cmake pkg-config ccache
  libglfw3-dev libglm-dev libosmesa6-dev libimgui-dev libopenmesh-dev
  libembree-dev libtbb-dev python3-glad libgtest-dev
  libstb-dev nlohmann-json3-dev libcli11-dev libeigen3-dev libpolyclipping-dev
  libtinygltf-dev libtinyexr-dev libnanoflann-dev libassimp-dev assimp-testmodels libdraco-dev
  ninja-build xvfb xauth x11-utils libx11-dev
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "install-deps: installing ${missing[*]}" >&2
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done" >&2
