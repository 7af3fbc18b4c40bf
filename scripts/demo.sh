#!/usr/bin/env bash
# Installs dependencies, builds radarslam (Release) and runs the main job on the embedded default:
# simulate the 4.7 km demo route (seed 1, clear weather, Oxford CTS350-X geometry), map it with the
# full RadarSLAM system (tracking, local BA, loop closure, pose graph) into maps/demo and evaluate
# against the simulator's ground truth. A second run reuses the simulated sequence and the build.
# The simulated sequence goes to out/demo/ (about 1.2 GB of polar PNGs).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/configure.sh
cmake --build build -j"$(nproc)" --target radarslam
rs=./build/apps/radarslam
out=out/demo
# The simulation is re-used while the simulator's sources and configs are unchanged.
sim_key=$(cat libradarslam/src/sim/* libradarslam/include/radarslam/sim/* config/sim*.yaml | sha256sum | cut -c1-16)
if [ ! -f "$out/sim/gt/radar_odometry.csv" ] || [ "$(cat "$out/sim.key" 2>/dev/null)" != "$sim_key" ]; then
  $rs simulate "$out/sim" --force
  echo "$sim_key" > "$out/sim.key"
fi
$rs info "$out/sim"
$rs map "$out/sim" -o maps/demo
$rs cart "$out/sim" "$out/scan0000.png" --peaks
cat <<EOT

Demo outputs:
  maps/demo/                 the keyframe map (format: maps/README.md); reuse it with --map demo
  maps/demo/grid.png         occupancy-grid image of the map (also .pgm + ROS YAML, .gridmap)
  maps/demo/trajectory.tum   SLAM trajectory, every scan (odometry.tum: front end only)
  maps/demo/eval/            report.json and plots: trajectory vs ground truth, error per segment length
  maps/demo/summary.txt      loops accepted/rejected, accuracy, speed, memory
  $out/sim/            simulated sequence (Oxford Radar RobotCar format, ground truth in sim/gt/)
  $out/scan0000.png    first scan as a Cartesian image with its Algorithm-1 peak cloud
EOT
