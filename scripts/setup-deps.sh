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
  libassimp-dev          # STL/OBJ/PLY surface import and export (engine/io/SurfaceImport)
  libcgal-dev            # exact self-intersection test of surfaces (engine/mesh/SelfIntersection)
  libtet1.5-dev          # TetGen 1.5: tetrahedralises closed surfaces (engine/meshing/Tetrahedralize)
  libmeshoptimizer-dev   # surface simplification to coarse/fine skin counts (engine/mesh)
  libturbojpeg0-dev      # JPEG: phantom skin texture, streamed frames
  libboost-dev           # Boost 1.74 headers: Beast/Asio HTTP and WebSocket server (server/net), header-only
  libegl-dev             # EGL headers and libEGL (GLVND): off-screen rendering without a display (engine/render)
  libopengl-dev          # libOpenGL (GLVND): OpenGL 3.3 core entry points without GLX (engine/render)
  libgl-dev              # GL/gl.h and GL/glext.h (engine/render)
  libegl-mesa0           # Mesa's EGL vendor: the surfaceless platform used where there is no GPU
  libgl1-mesa-dri        # Mesa's drivers, among them llvmpipe, the CPU rasteriser (CI, this machine)
  libpng-dev             # PNG images: `orthosim render` output, PNG textures (engine/render)
  libstb-dev             # stb_easy_font.h: the bitmap font of the colour-map legend (header only)
  libvtk9-dev            # VTK 9.1: label maps (NIfTI, NRRD) to surfaces (engine/io/LabelMapSurfaces)
  libvtk-dicom-dev       # vtk-dicom 0.8 with GDCM: CT and CBCT DICOM series (engine/volume/DicomSeries)
  libminizip-dev         # minizip (zlib's contrib): a CT scan uploaded as one .zip (server/cases/ScanFiles)
  libhiredis-dev         # hiredis 0.14, the Redis project's own C client: fine jobs on Redis Streams (server/jobs)
  redis-server           # Redis 7.0 (XAUTOCLAIM needs 6.2): the tests of serve --redis start their own
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
