#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine, builds orthosim and runs it on the built-in demo case
# (the phantom patient, no data to download). Until the planning server lands (issue 5) this
# solves the demo case from the command line and prints where the case and the results are.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)" --target orthosim
./build/server/orthosim demo --out "${1:-orthosim-demo}"
