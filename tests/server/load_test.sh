#!/usr/bin/env bash
# The match server under load, as real processes on loopback UDP (docs/deploy.md "Load, soak
# and flood"):
#   soak:  8 rollback peers through the relay, spectators taking 32 spectator slots in turn
#          (peer 0, their host, with the server's default budget for that role),
#          2% loss and 0..20 ms jitter on every client's receive side; every final hash agrees
#          (peers and spectators), no desync, the server's memory stays bounded, the drain
#          writes the replay and it verifies.
#   flood: 20 four-player lockstep matches while 50,000 datagrams a second of junk, copied,
#          forged and expired tokens arrive from 64 source ports; every match agrees, nothing
#          is answered to the flood, every flood datagram is counted as refused or dropped.
#   authoritative: 4 two-player matches the server simulates (vertical_stack); no desync
#          between the server's hashes and the clients', the drain writes 4 replays that verify.
# usage: load_test.sh soak|flood|authoritative SECONDS SERVER LOAD TOKEN REPLAY
set -euo pipefail
mode=$1 seconds=$2 server=$3 load=$4 token=$5 replay=$6
dir=$(mktemp -d)
server_pid=
cleanup() {
    if [ -n "$server_pid" ] && kill -0 "$server_pid" 2>/dev/null; then kill -KILL "$server_pid"; fi
    rm -rf "$dir"
}
trap cleanup EXIT

# A TCP port for /metrics that nothing answers on now.
http_port=
for _ in $(seq 50); do
    candidate=$((20000 + RANDOM % 30000))
    if ! (exec 3<>"/dev/tcp/127.0.0.1/$candidate") 2>/dev/null; then http_port=$candidate; break; fi
done
[ -n "$http_port" ] || { echo "FAIL: no free TCP port"; exit 1; }
metrics() { # the server's /metrics page
    exec 3<>"/dev/tcp/127.0.0.1/$http_port"
    printf 'GET /metrics HTTP/1.0\r\n\r\n' >&3
    cat <&3
    exec 3>&-
}
metric() { # metric NAME -> its value in the server's /metrics (0 when absent)
    metrics | awk -v n="$1" '$1 == n { print $2; found=1 } END { if (!found) print 0 }'
}
sum_metric() { # sum of every sample of a labelled metric
    metrics | awk -v n="$1" 'index($1, n "{") == 1 { s += $2 } END { print s + 0 }'
}

"$token" keygen >"$dir/key"
mkdir "$dir/replays"
server_args=(--token-key-file "$dir/key" --port-file "$dir/port" --http-port "$http_port"
    --rate-limit 1000 --rate-burst 2000 --log "$dir/server.log" --drain-seconds 1)
if [ "$mode" = soak ]; then
    server_args+=(--match-kind rollback-relay --players-per-match 8 --spectators-per-match 32
        --scene vertical_stack --replay-dir "$dir/replays")
elif [ "$mode" = authoritative ]; then
    server_args+=(--match-kind lockstep-authoritative --players-per-match 2 --scene vertical_stack
        --replay-dir "$dir/replays")
else
    server_args+=(--players-per-match 4 --max-matches 64)
fi
"$server" "${server_args[@]}" &
server_pid=$!
for _ in $(seq 100); do [ -s "$dir/port" ] && break; sleep 0.1; done
port=$(cat "$dir/port")
sleep 0.5
rss_start=$(metric lockbox_server_resident_bytes)

load_args=(--port "$port" --key-file "$dir/key" --seconds "$seconds")
if [ "$mode" = soak ]; then
    load_args+=(--kind rollback --players 8 --spectators 32 --matches 1 --loss 20 --jitter 20)
elif [ "$mode" = authoritative ]; then
    load_args+=(--players 2 --matches 4 --scene vertical_stack)
else
    load_args+=(--players 4 --matches 20 --threads 2 --flood 50000 --flood-ports 64)
fi
result=$("$load" "${load_args[@]}") || { echo "load: $result"; exit 1; }
echo "load: $result"
sleep 0.3
rss_end=$(metric lockbox_server_resident_bytes)
p99=$(metrics | awk '/quantile="0.99"/ { print $2 }')
desyncs=$(metric lockbox_server_desyncs_total)
refused=$(sum_metric lockbox_server_refused_tokens_total)
dropped=$(sum_metric lockbox_server_dropped_datagrams_total)
echo "server: rss_start=$rss_start rss_end=$rss_end tick_p99_s=$p99 desyncs=$desyncs refused=$refused dropped=$dropped"
[ "$desyncs" = 0 ] || { echo "FAIL: desyncs"; exit 1; }
# Bounded memory: the end within 16 MB of the start.
[ "$rss_end" -le $((rss_start + 16 * 1024 * 1024)) ] || { echo "FAIL: memory grew"; exit 1; }

if [ "$mode" = soak ]; then
    grep -q '"spectators_disagreed":0' <<<"$result" || { echo "FAIL: a spectator disagreed"; exit 1; }
    grep -q '"spectators_agreed":0,' <<<"$result" && { echo "FAIL: no spectator was checked"; exit 1; }
elif [ "$mode" = flood ]; then
    sent=$(sed -n 's/.*"flood_sent":\([0-9]*\).*/\1/p' <<<"$result")
    # Every flood datagram the socket read is counted under one reason; the kernel may drop
    # a few on a loaded machine, never the server's counters more than were sent.
    counted=$((refused + dropped))
    [ "$counted" -le "$sent" ] || { echo "FAIL: counted $counted of $sent"; exit 1; }
    [ "$counted" -ge $((sent * 3 / 4)) ] || { echo "FAIL: counted only $counted of $sent"; exit 1; }
fi

# The drain: SIGTERM, the server exits 0 and every replay written verifies.
kill -TERM "$server_pid"
status=0
wait "$server_pid" || status=$?
server_pid=
[ "$status" = 0 ] || { echo "FAIL: the server exited $status"; exit 1; }
if [ "$mode" = soak ]; then
    "$replay" verify-dir "$dir/replays" | tee "$dir/verify.txt"
    grep -q "1 replays: 1 verified" "$dir/verify.txt" || { echo "FAIL: the replay"; exit 1; }
elif [ "$mode" = authoritative ]; then
    "$replay" verify-dir "$dir/replays" | tee "$dir/verify.txt"
    grep -q "4 replays: 4 verified" "$dir/verify.txt" || { echo "FAIL: the replays"; exit 1; }
fi
echo "PASS"
