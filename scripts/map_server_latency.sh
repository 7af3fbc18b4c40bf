#!/usr/bin/env bash
# Time from the start of radarslam-map-server to radarslam-map-client holding the grid and every
# layer, and the peak RSS of both (docs/dds.md, "Measurements"). The client starts together with
# the server (a late joiner of the first publication) and logs the UNIX time each layer arrived.
#   [LAYERS=grid,cloud,octomap] scripts/map_server_latency.sh MAP [DOMAIN] [BUILD_DIR]
# DDS_CONFIG=FILE: both programs use this Cyclone XML instead of the built-in loopback one.
# LAYERS: what the client waits for (one layer: its arrival without the client writing the others
# first). Loopback only (the programs' built-in configuration). Prints one summary line.
set -euo pipefail
map=${1:?usage: map_server_latency.sh MAP [DOMAIN] [BUILD_DIR]}
domain=${2:-150}
build=${3:-build}
server=$build/apps/radarslam-map-server/radarslam-map-server
client=$build/apps/radarslam-map-client/radarslam-map-client
work=$(mktemp -d)
config=()
[ -n "${DDS_CONFIG:-}" ] && config=(--config "$DDS_CONFIG")
trap 'rm -rf "$work"' EXIT

start=$(date +%s.%N)
/usr/bin/time -v "$server" --map "$map" --domain "$domain" "${config[@]}" 2> "$work/server.err" &
server_pid=$!
/usr/bin/time -v "$client" -o "$work/got" --domain "$domain" "${config[@]}" --timeout 120 --layers "${LAYERS:-grid,cloud,octomap}" > "$work/client.out" 2> "$work/client.err" || {
  cat "$work/client.err" >&2
  exit 1
}
kill -TERM "$(pgrep -P "$server_pid")" 2>/dev/null || true
wait "$server_pid" || true

at() { { grep -o "$1 received at UNIX time [0-9.]*" "$work/client.err" || true; } | tail -1 | awk '{print $NF}'; }
rss() { awk -F': ' '/Maximum resident set size/ {printf "%.0f", $2 / 1024}' "$1"; }
grid=$(at grid) overview=$(at "grid overview") cloud=$(at cloud) octo=$(at octomap)
all=$(printf '%s\n' $grid $cloud $octo | sort -g | tail -1)
awk -v s="$start" -v g="${grid:-0}" -v o="${overview:-0}" -v a="$all" -v sr="$(rss "$work/server.err")" \
  -v cr="$(rss "$work/client.err")" -v l="${LAYERS:-grid,cloud,octomap}" \
  'BEGIN { printf "layers %s: %sgrid after %.2f s, every layer after %.2f s (from the server start); peak RSS server %d MiB, client %d MiB\n", l, (o > 0 ? sprintf("grid overview after %.2f s, full ", o - s) : ""), (g > 0 ? g - s : 0), a - s, sr, cr }'
grep -h "published map" "$work/server.err" | sed 's/^/  server: /'
grep -h "received map" "$work/client.out" | sed 's/^/  client: /'
