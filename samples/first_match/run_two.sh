#!/bin/sh
# The first-match example as two processes: player 0 starts, player 1 three seconds later, on
# two free UDP ports of 127.0.0.1. Both must exit 0 and print the same final hash, and write
# the same replay bytes, which the game's own replay tool (first_match replay) verifies.
#   run_two.sh PROGRAM FRAMES LATENCY_MS
set -u
program=$1
frames=$2
latency=$3
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
# Two ports the system has just handed out (closed again at once; the match reopens them).
ports=$(python3 -c 'import socket
s = [socket.socket(socket.AF_INET, socket.SOCK_DGRAM) for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(" ".join(str(x.getsockname()[1]) for x in s))')
port0=${ports% *}
port1=${ports#* }
"$program" --player 0 --port "$port0" --peer-port "$port1" --frames "$frames" --latency-ms "$latency" \
    --replay "$dir/p0.lbr" >"$dir/p0" 2>&1 &
pid0=$!
sleep 3
"$program" --player 1 --port "$port1" --peer-port "$port0" --frames "$frames" --latency-ms "$latency" \
    --replay "$dir/p1.lbr" >"$dir/p1" 2>&1
rc1=$?
wait "$pid0"
rc0=$?
echo "--- player 0 (exit $rc0)"
cat "$dir/p0"
echo "--- player 1 (exit $rc1)"
cat "$dir/p1"
hash0=$(grep '^final hash' "$dir/p0")
hash1=$(grep '^final hash' "$dir/p1")
if [ "$rc0" -ne 0 ] || [ "$rc1" -ne 0 ] || [ -z "$hash0" ] || [ "$hash0" != "$hash1" ]; then
    echo "FAILED: the players did not print the same final hash"
    exit 1
fi
echo "both players: $hash0"
if ! cmp "$dir/p0.lbr" "$dir/p1.lbr"; then
    echo "FAILED: the players' replays differ"
    exit 1
fi
echo "both replays: $(wc -c <"$dir/p0.lbr") bytes, identical"
"$program" replay verify "$dir/p0.lbr" || { echo "FAILED: the replay does not verify"; exit 1; }
