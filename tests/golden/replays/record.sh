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
