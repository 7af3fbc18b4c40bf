#!/usr/bin/env bash
# Time until `radarslam localize dds:` has a map from radarslam-map-server (docs/dds.md, "The map
# files layer"): received (every file checked, in its temporary directory) and loaded (loadMap
# done, ready to localise), plus the peak RSS of both programs. Without LATE the localiser starts
# together with the server and times count from the server start; with LATE=1 it starts once the
# server has published, and times count from the localiser start (a late joiner).
#   [LATE=1] [SERVER_ARGS="--files-with-layers"] scripts/map_files_latency.sh MAP [DOMAIN] [BUILD_DIR]
# The localiser takes its scans from DDS (none come), so it exits 1 after --dds-timeout 0.2 s; only
# its log lines are used. Loopback only. Prints one summary line.
set -euo pipefail
map=${1:?usage: map_files_latency.sh MAP [DOMAIN] [BUILD_DIR]}
domain=${2:-151}
build=${3:-build}
server=$build/apps/radarslam-map-server/radarslam-map-server
cli=$build/apps/radarslam
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
stamp() { while IFS= read -r l; do printf '%s %s\n' "$(date +%s.%N)" "$l"; done; }

start=$(date +%s.%N)
# shellcheck disable=SC2086
/usr/bin/time -v "$server" --map "$map" --domain "$domain" ${SERVER_ARGS:-} 2> >(stamp > "$work/server.err") &
server_pid=$!
if [ -n "${LATE:-}" ]; then
  until grep -q "published map" "$work/server.err" 2>/dev/null; do sleep 0.05; done
  start=$(date +%s.%N)
fi
/usr/bin/time -v "$cli" localize "dds:$domain" dds: -o /dev/null -q --dds-timeout 0.2 --map-timeout 60 \
  > "$work/loc.out" 2> >(stamp > "$work/loc.err") || true
sleep 0.2
for pid in $(pgrep -P "$server_pid" -x radarslam-map-s); do kill -TERM "$pid"; done  # the server /usr/bin/time started
wait "$server_pid" || true
sleep 0.1

at() { { grep "$2" "$work/$1" || true; } | head -1 | awk '{print $1}'; }
rss() { awk -F': ' '/Maximum resident set size/ {printf "%.0f", $2 / 1024}' "$work/$1"; }
received=$(at loc.err "received map") loaded=$(at loc.err "localize: map dds:") published=$(at server.err "published map")
[ -n "$received" ] || { cat "$work/loc.err" >&2; exit 1; }
awk -v s="$start" -v r="$received" -v l="$loaded" -v p="$published" -v sr="$(rss server.err)" -v lr="$(rss loc.err)" \
  -v late="${LATE:+late joiner, from the localiser start}" \
  'BEGIN { printf "map received after %.2f s, loaded after %.2f s (server published after %.2f s)%s; peak RSS server %d MiB, localiser %d MiB\n", r - s, l - s, p - s, (late == "" ? ", from the server start" : ", " late), sr, lr }'
grep -h "published map" "$work/server.err" | cut -d' ' -f2- | sed 's/^/  server: /'
grep -h "received map" "$work/loc.err" | cut -d' ' -f2- | sed 's/^/  localiser: /'
