#!/usr/bin/env bash
# Installs dependencies, builds radarslam (Release) and runs the main job on the embedded default.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/configure.sh
cmake --build build -j"$(nproc)" --target radarslam
./build/apps/radarslam --help
