#!/usr/bin/env bash
# Configures the Release build in build/ (idempotent; CI turns warnings into errors).
set -euo pipefail
cd "$(dirname "$0")/.."
werror=OFF
[ -n "${CI:-}" ] && werror=ON
if [ ! -f build/build.ninja ] || [ "${CI:-}" != "$(cat build/.ci-flag 2>/dev/null)" ]; then
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DRADARSLAM_WERROR=$werror >/dev/null
  mkdir -p build && echo "${CI:-}" > build/.ci-flag
fi
