#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine, builds orthosim and runs every test (ctest) but the timing
# and resource figures (label perf: ctest --test-dir build -L perf).
# Usage: scripts/test.sh            (build folder: build/)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup-deps.sh
bash scripts/setup-test-deps.sh   # Chromium and playwright-core for the browser test
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"
ctest --test-dir build --output-on-failure -j1 -LE perf "$@"
