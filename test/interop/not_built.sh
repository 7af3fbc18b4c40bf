#!/usr/bin/env bash
# Stands in for the Fast DDS interop test when it could not be built (test/interop/CMakeLists.txt):
# skipped (exit 77) on a developer machine, a failure where CI is set.
echo "FastDdsInterop: not built, missing $1; bash scripts/install-deps.sh, then reconfigure (rm -rf build)"
if [ -n "${CI:-}" ]; then
  echo "FastDdsInterop: CI is set: the interop test must run there"
  exit 1
fi
exit 77
