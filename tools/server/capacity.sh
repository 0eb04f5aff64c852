#!/usr/bin/env bash
# One capacity point of lockbox_server (docs/deploy.md "Capacity"): the server pinned to CPU 0,
# the load generator to CPU 1, MATCHES matches of PLAYERS players for SECONDS; prints the
# server's tick p50/p99, CPU share and RSS read while the matches play, the payload bytes per
# player-second, and the load generator's verdict.
# usage: capacity.sh BUILD_DIR lockstep|authoritative|rollback MATCHES PLAYERS SECONDS [SCENE]
# (lockstep with SCENE: the relay also records every match's replay of that scene)
set -euo pipefail
build=$1 kind=$2 matches=$3 players=$4 seconds=$5 scene=${6:-}
dir=$(mktemp -d)
server_pid=
cleanup() {
    if [ -n "$server_pid" ] && kill -0 "$server_pid" 2>/dev/null; then kill -KILL "$server_pid"; fi
    rm -rf "$dir"
}
trap cleanup EXIT
http_port=$((20000 + RANDOM % 30000))
metrics() {
    exec 3<>"/dev/tcp/127.0.0.1/$http_port"
    printf 'GET /metrics HTTP/1.0\r\n\r\n' >&3
    cat <&3
    exec 3>&-
}
value() { awk -v n="$1" '$1 == n { print $2 }' <<<"$2"; }
cpu_ticks() { awk '{ print $14 + $15 }' "/proc/$server_pid/stat"; } # user + system, clock ticks

"$build/tools/token/lockbox_token" keygen >"$dir/key"
server_args=(--token-key-file "$dir/key" --port-file "$dir/port" --http-port "$http_port" --log "$dir/log"
    --players-per-match "$players" --max-matches 10000 --max-players 100000 --rate-limit 100000
    --rate-burst 100000 --peer-bandwidth 0 --start-timeout 600 --drain-seconds 1)
load_args=(--key-file "$dir/key" --matches "$matches" --players "$players" --seconds "$seconds")
case $kind in
    lockstep)
        # With a scene: the clients play it and the server records every match's replay.
        if [ -n "$scene" ]; then
            mkdir "$dir/replays"
            server_args+=(--scene "$scene" --replay-dir "$dir/replays")
            load_args+=(--scene "$scene")
        fi
        ;;
    authoritative)
        server_args+=(--match-kind lockstep-authoritative --scene "$scene")
        load_args+=(--scene "$scene")
        ;;
    rollback)
        server_args+=(--match-kind rollback-relay)
        load_args+=(--kind rollback ${scene:+--scene "$scene"})
        ;;
esac
taskset -c 0 "$build/tools/server/lockbox_server" "${server_args[@]}" &
server_pid=$!
for _ in $(seq 100); do [ -s "$dir/port" ] && break; sleep 0.1; done
rss_idle=$(value lockbox_server_resident_bytes "$(metrics)")
taskset -c 1 "$build/tools/server/lockbox_server_load" --port "$(cat "$dir/port")" "${load_args[@]}" \
    >"$dir/load.json" &
load_pid=$!
# Read the server while the matches play: after the slowest start, before the end.
sleep $((seconds - 2))
m1=$(metrics)
c1=$(cpu_ticks)
t1=$(date +%s%N)
sleep 1
m2=$(metrics)
c2=$(cpu_ticks)
t2=$(date +%s%N)
status=0
wait "$load_pid" || status=$?
# The share of a core the server used over that second, in per mille.
cpu_permille=$(((c2 - c1) * 1000000000000 / $(getconf CLK_TCK) / (t2 - t1)))
bytes=$(($(value lockbox_server_bytes_in_total "$m2") + $(value lockbox_server_bytes_out_total "$m2") -
    $(value lockbox_server_bytes_in_total "$m1") - $(value lockbox_server_bytes_out_total "$m1")))
echo "kind=$kind matches=$matches players=$players" \
    "tick_p50_s=$(awk '/quantile="0.5"/ { print $2 }' <<<"$m2")" \
    "tick_p99_s=$(awk '/quantile="0.99"/ { print $2 }' <<<"$m2")" \
    "cpu_permille=$cpu_permille rss_idle=$rss_idle rss=$(value lockbox_server_resident_bytes "$m2")" \
    "bytes_per_player_second=$((bytes / (matches * players)))" \
    "load_exit=$status load=$(cat "$dir/load.json")"
