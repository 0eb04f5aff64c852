#!/usr/bin/env bash
# One capacity point of lockbox_server (docs/deploy.md "Capacity"): the server pinned to CPU 0,
# the load generators to CPU 1, MATCHES matches of PLAYERS players for SECONDS; prints the
# server's tick p50/p99, CPU share and RSS read while the matches play, the payload bytes per
# player-second, the machine's load average, and each load generator's verdict.
# usage: capacity.sh [-g GENERATORS] [-l] [-d DELAY] BUILD_DIR lockstep|authoritative|rollback MATCHES PLAYERS SECONDS [SCENE]
# (lockstep with SCENE: the relay also records every match's replay of that scene)
# -g N: N load generator processes (default 1), each with its own match ids and tokens, the
# matches split between them as evenly as they go.
# -d N: lockstep clients' input delay, N frames (lockbox_server_load --input-delay).
# -l: light clients (lockbox_server_load --light): they simulate no scene, so one core of load
# generators drives many more of them; the server's work is the same (an authoritative server
# still steps SCENE for every match), except that lockstep clients send no hash reports.
set -euo pipefail
generators=1
light=
delay=()
while getopts g:ld: opt; do
    case $opt in
        g) generators=$OPTARG ;;
        l) light=--light ;;
        d) delay=(--input-delay "$OPTARG") ;;
        *) exit 2 ;;
    esac
done
shift $((OPTIND - 1))
build=$1 kind=$2 matches=$3 players=$4 seconds=$5 scene=${6:-}
dir=$(mktemp -d)
server_pid=
load_pids=()
cleanup() {
    for pid in "${load_pids[@]}"; do kill -KILL "$pid" 2>/dev/null || true; done
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
# user + system clock ticks of the given processes
cpu_ticks() { for pid in "$@"; do cat "/proc/$pid/stat"; done | awk '{ t += $14 + $15 } END { print t + 0 }'; }

"$build/tools/token/lockbox_token" keygen >"$dir/key"
server_args=(--token-key-file "$dir/key" --port-file "$dir/port" --http-port "$http_port" --log "$dir/log"
    --players-per-match "$players" --max-matches 10000 --max-players 100000 --rate-limit 100000
    --rate-burst 100000 --peer-bandwidth 0 --start-timeout 600 --drain-seconds 1)
# --stagger: every match at its own phase of the 60 Hz frame, as independent matches would be.
load_args=(--key-file "$dir/key" --players "$players" --seconds "$seconds" --stagger $light "${delay[@]}")
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
first=1
for g in $(seq 0 $((generators - 1))); do
    share=$(((matches + generators - 1 - g) / generators))
    [ "$share" -gt 0 ] || continue
    taskset -c 1 "$build/tools/server/lockbox_server_load" --port "$(cat "$dir/port")" "${load_args[@]}" \
        --matches "$share" --first-match "$first" >"$dir/load$g.json" &
    load_pids+=($!)
    first=$((first + share))
done
# Read the server while the matches play: after the slowest start, before the end.
sleep $((seconds - 2))
m1=$(metrics)
c1=$(cpu_ticks "$server_pid")
g1=$(cpu_ticks "${load_pids[@]}")
t1=$(date +%s%N)
sleep 1
m2=$(metrics)
c2=$(cpu_ticks "$server_pid")
g2=$(cpu_ticks "${load_pids[@]}")
t2=$(date +%s%N)
loadavg=$(cut -d' ' -f1-3 /proc/loadavg)
status=0
for pid in "${load_pids[@]}"; do wait "$pid" || status=$?; done
# The share of a core the server, and the load generators together, used over that second, in
# per mille.
cpu_permille=$(((c2 - c1) * 1000000000000 / $(getconf CLK_TCK) / (t2 - t1)))
load_cpu_permille=$(((g2 - g1) * 1000000000000 / $(getconf CLK_TCK) / (t2 - t1)))
bytes=$(($(value lockbox_server_bytes_in_total "$m2") + $(value lockbox_server_bytes_out_total "$m2") -
    $(value lockbox_server_bytes_in_total "$m1") - $(value lockbox_server_bytes_out_total "$m1")))
echo "kind=$kind matches=$matches players=$players" \
    "tick_p50_s=$(awk '/quantile="0.5"/ { print $2 }' <<<"$m2")" \
    "tick_p99_s=$(awk '/quantile="0.99"/ { print $2 }' <<<"$m2")" \
    "cpu_permille=$cpu_permille rss_idle=$rss_idle rss=$(value lockbox_server_resident_bytes "$m2")" \
    "bytes_per_player_second=$((bytes / (matches * players)))" \
    "loadavg=\"$loadavg\" generators=${#load_pids[@]}${light:+ light} load_cpu_permille=$load_cpu_permille load_exit=$status"
cat "$dir"/load*.json
