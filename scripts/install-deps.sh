#!/usr/bin/env bash
# Installs the Debian bookworm packages radarslam needs (as root). Fast when already installed:
# apt is only called for packages that are missing.
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config
  libmrpt-graphslam-dev libeigen3-dev libopencv-dev liboctomap-dev libpng-dev libdeflate-dev
  cyclonedds-dev cyclonedds-tools libceres-dev libtclap-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  mrpt-apps  # rawlog-edit: test_cli_mrpt_plugin reads our rawlogs with MRPT's own tool
  systemd dpkg-dev  # systemd-analyze verify and dpkg-shlibdeps: test/install/test_install.sh
  python3 python3-yaml  # scripts/bench.py (the bench_reduced test), scripts/parameters_doc.py
  # test/interop: a Fast DDS (ROS 2's default DDS) client reads our Cyclone DDS programs; fastddsgen
  # generates its type support at build time and runs on Java (not a declared dependency of it)
  libfastrtps-dev fastddsgen default-jre-headless libssl-dev
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "install-deps: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
