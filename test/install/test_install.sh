#!/usr/bin/env bash
# Installs radarslam into a temporary prefix and uses it as a library user and an administrator
# would (issue 18): programs and configs from the prefix, an example consumer built with
# find_package(radarslam CONFIG) and with pkg-config, the Debian package's contents and
# dependencies, and the map server's systemd unit (systemd-analyze verify).
#   test/install/test_install.sh BUILD_DIR SOURCE_DIR [REAL_DATA_DIR]
set -euo pipefail
build=$(cd "$1" && pwd)
src=$(cd "$2" && pwd)
real=${3:-}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
prefix=$tmp/prefix
fail() { echo "FAIL: $*" >&2; exit 1; }

echo "== cmake --install into $prefix"
cmake --install "$build" --prefix "$prefix" > "$tmp/install.log"
for p in radarslam radarslam-map-server radarslam-map-client radarslam-scan-publisher; do
  v=$("$prefix/bin/$p" --version 2>&1 | grep -Eo '[0-9]+\.[0-9]+\.[0-9]+ \(git ([0-9a-f]{12}(-dirty)?|unknown)\)' || true)
  [ -n "$v" ] || fail "$p --version does not print the version and git revision"
  echo "$p $v"
done
for f in share/radarslam/config/oxford.yaml share/radarslam/config/dds.xml share/radarslam/idl/nav_msgs/msg/OccupancyGrid.idl \
         include/radarslam/io/dataset.h lib/cmake/radarslam/radarslamConfig.cmake \
         lib/cmake/radarslam/radarslamConfigVersion.cmake lib/pkgconfig/radarslam.pc lib/libradarslam_mrpt_plugin.so \
         lib/systemd/system/radarslam-map-server@.service etc/radarslam/dds.xml lib/sysusers.d/radarslam.conf; do
  [ -e "$prefix/$f" ] || fail "not installed: $f"
done

if [ -n "$real" ] && [ -d "$real/oxford_radar_robotcar_tiny" ]; then
  oxford=$real/oxford_radar_robotcar_tiny
  echo "== the installed radarslam reads its default config from the prefix"
  cp "$prefix/share/radarslam/config/oxford.yaml" "$tmp/oxford.yaml.orig"
  echo "install_test_marker_key: 1" >> "$prefix/share/radarslam/config/oxford.yaml"
  if env -u RADARSLAM_CONFIG_DIR "$prefix/bin/radarslam" odometry "$oxford" -o "$tmp/t.tum" 2> "$tmp/err.txt"; then
    fail "a config with an unknown key in the prefix was not used"
  fi
  grep -q "$prefix/share/radarslam/config/oxford.yaml.*install_test_marker_key" "$tmp/err.txt" ||
    fail "unexpected error: $(cat "$tmp/err.txt")"
  cp "$tmp/oxford.yaml.orig" "$prefix/share/radarslam/config/oxford.yaml"
  env -u RADARSLAM_CONFIG_DIR "$prefix/bin/radarslam" odometry "$oxford" -o "$tmp/t.tum" --quiet > /dev/null
  [ "$(wc -l < "$tmp/t.tum")" -ge 11 ] || fail "installed radarslam odometry wrote too few poses"
elif [ -n "${CI:-}" ] && [ "${CI}" != "0" ] && [ "${CI}" != "false" ]; then
  fail "real data missing in CI: $real"
else
  echo "SKIP (real data not found): installed-program runs"
fi

echo "== example consumer: find_package(radarslam CONFIG)"
cmake -S "$src/examples" -B "$tmp/example" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix" \
  > "$tmp/example.log" 2>&1 || { cat "$tmp/example.log"; fail "example configure"; }
cmake --build "$tmp/example" >> "$tmp/example.log" 2>&1 || { cat "$tmp/example.log"; fail "example build"; }
echo "== example consumer: pkg-config"
# shellcheck disable=SC2046
g++ -std=c++20 -O1 -w "$src/examples/scan_odometry.cpp" -o "$tmp/scan_odometry_pc" \
  $(PKG_CONFIG_PATH="$prefix/lib/pkgconfig" pkg-config --cflags --libs radarslam) 2> "$tmp/pc.log" ||
  { cat "$tmp/pc.log"; fail "pkg-config build"; }
if [ -n "${oxford:-}" ]; then
  for exe in "$tmp/example/scan_odometry" "$tmp/scan_odometry_pc"; do
    "$exe" "$oxford" 4 > "$tmp/out.txt"
    [ "$(grep -c '^scan [0-9]* stamp_ns [0-9]* azimuths 400 bins 3768' "$tmp/out.txt")" = 4 ] || fail "$exe output: $(cat "$tmp/out.txt")"
    grep -q ' tracking$' "$tmp/out.txt" || fail "$exe did not track: $(cat "$tmp/out.txt")"
  done
  echo "example consumers read the scans and tracked them"
fi

echo "== systemd unit"
cp "$prefix/lib/systemd/system/radarslam-map-server@.service" "$tmp/radarslam-map-server@demo.service"
grep -q "^ExecStart=$prefix/bin/radarslam-map-server " "$tmp/radarslam-map-server@demo.service" ||
  fail "ExecStart does not name the installed server"
systemd-analyze verify "$tmp/radarslam-map-server@demo.service" || fail "systemd-analyze verify"
for opt in ProtectSystem=strict NoNewPrivileges=yes ReadOnlyPaths=/var/lib/radarslam User=radarslam \
           Restart=on-failure 'ExecReload=/bin/kill -HUP $MAINPID'; do
  grep -qF -- "$opt" "$tmp/radarslam-map-server@demo.service" || fail "unit lacks $opt"
done

echo "== Debian package (cpack -G DEB)"
(cd "$build" && cpack -G DEB -B "$tmp/pkg" > "$tmp/cpack.log" 2>&1) || { cat "$tmp/cpack.log"; fail "cpack"; }
version=$(sed -n 's/^set(CPACK_PACKAGE_VERSION "\(.*\)")/\1/p' "$build/CPackConfig.cmake")
deb=$tmp/pkg/radarslam_${version}_amd64.deb
[ -f "$deb" ] || fail "no $deb: $(ls "$tmp/pkg")"
dpkg-deb -c "$deb" | awk '{print $6}' > "$tmp/contents.txt"
for f in ./usr/bin/radarslam ./usr/bin/radarslam-map-server ./usr/bin/radarslam-map-client ./usr/bin/radarslam-scan-publisher \
         ./usr/lib/libradarslam_mrpt_plugin.so ./usr/lib/cmake/radarslam/radarslamConfig.cmake ./usr/lib/pkgconfig/radarslam.pc \
         ./usr/include/radarslam/io/dataset.h ./usr/share/radarslam/config/oxford.yaml ./usr/share/radarslam/idl/radarslam/msg/MapInfo.idl \
         ./usr/lib/systemd/system/radarslam-map-server@.service ./etc/radarslam/dds.xml ./usr/lib/sysusers.d/radarslam.conf; do
  grep -qxF "$f" "$tmp/contents.txt" || fail "$deb lacks $f"
done
dpkg-deb -I "$deb" > "$tmp/info.txt"
grep -q '^ Package: radarslam$' "$tmp/info.txt" || fail "package name"
depends=$(sed -n 's/^ Depends: //p' "$tmp/info.txt")
for d in libmrpt-obs2.5 libmrpt-maps2.5 libopencv-core406 libopencv-imgcodecs406 liboctomap1.9 libddsc0debian libpng16-16; do
  echo "$depends" | grep -q "\b$d\b" || fail "Depends lacks $d: $depends"
done
dpkg-deb -f "$deb" Version | grep -qx "$version" || fail "version"
dpkg-deb --ctrl-tarfile "$deb" | tar -t | grep -q conffiles || fail "no conffiles"
echo "deb: $(basename "$deb"), $(wc -l < "$tmp/contents.txt") entries, Depends: $depends"
echo "1 passed, 0 failed"
