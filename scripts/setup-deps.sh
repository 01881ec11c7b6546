#!/usr/bin/env bash
# Installs the Debian 12 packages orthosim needs to build, test and run.
# Idempotent: when every package is already installed it prints nothing and exits 0.
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config
  libeigen3-dev
  libsuitesparse-dev
  libopenblas0-pthread   # optimised BLAS for CHOLMOD's supernodal factorisation
  nlohmann-json3-dev
  libcli11-dev
  libgtest-dev
  libassimp-dev          # STL/OBJ/PLY surface import and export (engine/mesh/SurfaceImport)
  libcgal-dev            # exact self-intersection test of surfaces (engine/mesh/SelfIntersection)
  libtet1.5-dev          # TetGen 1.5: tetrahedralises closed surfaces (engine/mesh/Tetrahedralize)
  libmeshoptimizer-dev   # surface simplification to coarse/fine skin counts (engine/mesh)
  libturbojpeg0-dev      # JPEG: phantom skin texture, streamed frames
  libboost-dev           # Boost 1.74 headers: Beast/Asio HTTP and WebSocket server (server/net), header-only
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "setup-deps: installing ${missing[*]}"
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup-deps: done"
