#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine, builds orthosim and runs the planning server on the built-in
# demo case (the phantom patient, no data to download). Open http://127.0.0.1:${PORT:-8080}/ or
# talk to ws://127.0.0.1:${PORT:-8080}/ws (docs/protocol.md). Stop with Ctrl-C.
# Usage: scripts/run-demo.sh [DATA_DIR]   (default orthosim-demo; holds the built case, the mesh
#        cache and saved plans, reused by the next run)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)" --target orthosim
exec ./build/server/orthosim serve --port "${PORT:-8080}" --data "${1:-orthosim-demo}"
