#!/bin/sh
# Instruction counts (valgrind callgrind) of world stepping for small scenes on both engines
# (the microsecond scenes, whose wall time is noise, are judged by these counts):
# Ir(--steps N) - Ir(--steps 0), so scene building and process start-up cancel out. Unlike wall
# time, the count does not move with machine load; it is the regression guard for step cost.
#
#   bench/results/callgrind.sh BUILD_DIR   (a release build with lockbox_bench)
# Writes bench/results/callgrind.csv and prints it.
set -eu
build=${1:?usage: callgrind.sh BUILD_DIR}
bench="$build/bench/lockbox_bench"
out="$(dirname "$0")/callgrind.csv"  # move it under <machine>/ to keep it
ir() {
    valgrind --tool=callgrind --callgrind-out-file=/dev/null "$bench" --no-profile "$@" 2>&1 >/dev/null |
        sed -n 's/.*Collected : \([0-9]*\).*/\1/p'
}
echo "scene,steps,engine,instructions,instructions_per_step" > "$out"
for spec in hello:60 pyramid20:120 chain60:120 ragdolls:120 vertical_stack:60 \
    bullet_wall_dynamic:60 bullet_wall_bullet:60 bullet_wall_nocontinuous:60 \
    bullet_stack_dynamic:60 bullet_stack_bullet:60 bullet_stack_nocontinuous:60; do
    scene=${spec%%:*}
    steps=${spec##*:}
    for engine in lockbox box2d-float; do
        full=$(ir --scene "$scene" --engine "$engine" --steps "$steps")
        empty=$(ir --scene "$scene" --engine "$engine" --steps 0)
        delta=$((full - empty))
        echo "$scene,$steps,$engine,$delta,$((delta / steps))" >> "$out"
    done
done
cat "$out"
