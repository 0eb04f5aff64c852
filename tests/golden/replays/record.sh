#!/usr/bin/env bash
# Re-records the golden replay corpus. Run it only on purpose: in the commit that bumps
# b2_determinismVersion (or the replay format), never to make a failing verify pass.
#   tests/golden/replays/record.sh <path to the lockbox_replay program>
set -euo pipefail
tool="${1:?usage: record.sh path/to/lockbox_replay}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
"$tool" record --scene hello --frames 300 --players 2 --seed 1 --keyframe-interval 100 --out "$here/hello.lbr"
"$tool" record --scene car --frames 240 --players 2 --seed 2 --keyframe-interval 120 --stage-hashes --out "$here/car.lbr"
"$tool" record --scene rain --frames 120 --players 2 --seed 3 --keyframe-interval 0 --out "$here/rain.lbr"
"$tool" record --scene bullet_stack_bullet --frames 180 --players 1 --seed 4 --keyframe-interval 60 --hash-interval 4 --out "$here/bullet_stack_bullet.lbr"
# Uncompressed copies for tests/cross/run.sh (its cross builds have no zstd): every architecture
# verifies these.
"$tool" record --scene ragdolls --frames 120 --players 2 --seed 5 --keyframe-interval 0 --level 0 --out "$here/ragdolls_raw.lbr"
"$tool" record --scene vertical_stack --frames 180 --players 2 --seed 6 --keyframe-interval 0 --stage-hashes --level 0 --out "$here/vertical_stack_raw.lbr"
