#!/usr/bin/env bash
# Installs dependencies, builds radarslam (Release) and runs the main job on the embedded default:
# simulate the 4.7 km demo route (seed 1, clear weather, Oxford CTS350-X geometry), track it with
# the radar odometry and evaluate against the simulator's ground truth. A second run reuses the
# simulated sequence and the build. Outputs go to out/demo/ (about 1.2 GB of polar PNGs).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/configure.sh
cmake --build build -j"$(nproc)" --target radarslam
rs=./build/apps/radarslam
out=out/demo
if [ ! -f "$out/sim/gt/radar_odometry.csv" ]; then
  $rs simulate "$out/sim" --force
fi
$rs info "$out/sim"
$rs odometry "$out/sim" -o "$out/odometry.tum" --eval-dir "$out/eval"
$rs cart "$out/sim" "$out/scan0000.png" --peaks
cat <<EOT

Demo outputs in $out/:
  sim/                 simulated sequence (Oxford Radar RobotCar format, ground truth in sim/gt/)
  odometry.tum         estimated radar trajectory (TUM)
  eval/                report.json and plots (trajectory vs ground truth, error per segment length)
  scan0000.png         first scan as a Cartesian image with its Algorithm-1 peak cloud
EOT
