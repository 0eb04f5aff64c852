#!/usr/bin/env bash
# Cross-compiler / cross-architecture determinism check (issue 7, docs/determinism.md).
#
# Builds tests/cross/cross_driver.cpp together with the fixed/, core/ and scene-library sources
# (no CMake, xxHash header-only via -DXXH_INLINE_ALL) for every configuration of
#   {g++, clang++} x {-O0, -O2, -O3 (+ -march=native -ffast-math natively, -ffast-math cross)}
#   x {x86-64 native, i686 (static, runs natively), aarch64 and s390x (qemu-user)}
# runs each one against tests/golden/hashes.txt and the fixed-function golden values, prints a
# pass/fail matrix, and exits non-zero on any mismatch or build failure.
#
# Usage: tests/cross/run.sh [--quick] [--no-install] [--jobs N]
#   --quick       every architecture and compiler, one flag set each, rotating by day of year
#   --no-install  skip scripts/install-deps.sh --cross (toolchains already present)
#   --jobs N      parallel compile jobs per configuration (default 2)
#   --only LIST   only these cells, e.g. "s390x/gcc/1 x86_64/clang/2" (arch/compiler/flag index:
#                 0 = -O0, 1 = -O2, 2 = -O3 fast), in the given order
# Environment: LOCKBOX_CROSS_CLANG_CROSS=0 skips clang for the non-native architectures;
#   LOCKBOX_CROSS_QEMU_O0_MAX_STEP (default 60) limits the steps checked by emulated -O0 builds.
set -u

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
quick=0
only=""
install=1
jobs=2
while [ $# -gt 0 ]; do
    case "$1" in
        --quick) quick=1 ;;
        --no-install) install=0 ;;
        --jobs) shift; jobs=$1 ;;
        --only) shift; only=$1 ;;
        *) echo "run.sh: unknown argument '$1'" >&2; exit 2 ;;
    esac
    shift
done

start=$(date +%s)
if [ "$install" -eq 1 ]; then
    bash "$root/scripts/install-deps.sh" --cross || { echo "run.sh: install-deps.sh --cross failed" >&2; exit 2; }
fi

work=$(mktemp -d /tmp/lockbox-cross.XXXXXX)
trap 'rm -rf "$work"' EXIT

# The cross compilers do not search /usr/include (x86 packages): give them xxhash.h alone.
mkdir -p "$work/include"
cp /usr/include/xxhash.h "$work/include/" || { echo "run.sh: /usr/include/xxhash.h missing (libxxhash-dev)" >&2; exit 2; }

sources=$(cd "$root" && find fixed/src core/src samples/scenes/src -name '*.cpp' | LC_ALL=C sort)
sources="$sources tests/cross/cross_driver.cpp"
includes="-I$root/fixed/include -I$root/core/include -I$root/samples/scenes/include -I$root/tests/cross -I$work/include"

# Flag sets; index 2 differs natively (-march=native) and across architectures.
flagset() {  # $1 arch, $2 index
    case "$2" in
        0) echo "-O0" ;;
        1) echo "-O2 -DNDEBUG" ;;
        2) if [ "$1" = x86_64 ]; then echo "-O3 -march=native -ffast-math -DNDEBUG"; else echo "-O3 -ffast-math -DNDEBUG"; fi ;;
    esac
}
flaglabel() { case "$1" in 0) echo "-O0" ;; 1) echo "-O2" ;; 2) echo "-O3fast" ;; esac; }

compiler() {  # $1 arch, $2 family -> compiler command (empty: unavailable)
    case "$1/$2" in
        x86_64/gcc) echo "g++" ;;
        x86_64/clang) echo "clang++" ;;
        i686/gcc) echo "i686-linux-gnu-g++ -static" ;;
        aarch64/gcc) echo "aarch64-linux-gnu-g++" ;;
        s390x/gcc) echo "s390x-linux-gnu-g++" ;;
        */clang)
            if [ "${LOCKBOX_CROSS_CLANG_CROSS:-1}" = 1 ]; then
                local extra=""
                [ "$1" = i686 ] && extra=" -static"
                echo "clang++ --target=$1-linux-gnu$extra"
            fi ;;
    esac
}

runner() {  # $1 arch
    case "$1" in
        aarch64) echo "qemu-aarch64 -L /usr/aarch64-linux-gnu" ;;
        s390x) echo "qemu-s390x -L /usr/s390x-linux-gnu" ;;
        *) echo "" ;;
    esac
}

build_and_run() {  # $1 arch, $2 family, $3 flag index -> prints status, returns 0 on pass
    local arch=$1 fam=$2 idx=$3
    local cxx flags dir exe
    cxx=$(compiler "$arch" "$fam")
    [ -z "$cxx" ] && { echo "SKIP"; return 0; }
    flags=$(flagset "$arch" "$idx")
    dir="$work/$arch-$fam-$idx"
    mkdir -p "$dir"
    exe="$dir/cross_driver"
    # One object per source, $jobs at a time; the link step uses the same flags.
    # shellcheck disable=SC2086
    if ! printf '%s\n' $sources | xargs -P "$jobs" -I{} sh -c \
        'o="$0/$(echo "{}" | tr / _).o"; cd "$1" && $2 -std=c++20 $3 -DXXH_INLINE_ALL $4 -c "{}" -o "$o"' \
        "$dir" "$root" "$cxx" "$flags" "$includes" > "$dir/build.log" 2>&1; then
        echo "BUILD-FAIL"; return 1
    fi
    # shellcheck disable=SC2086
    if ! $cxx -std=c++20 $flags "$dir"/*.o -o "$exe" >> "$dir/build.log" 2>&1; then
        echo "LINK-FAIL"; return 1
    fi
    local run limit=""
    run=$(runner "$arch")
    # Emulated unoptimised builds are the slowest cell by far: they check steps <= 60 only
    # (LOCKBOX_CROSS_QEMU_O0_MAX_STEP overrides; 600 gives the full lines).
    if [ -n "$run" ] && [ "$idx" = 0 ]; then limit="--max-step ${LOCKBOX_CROSS_QEMU_O0_MAX_STEP:-60}"; fi
    # shellcheck disable=SC2086
    if $run "$exe" "$root/tests/golden/hashes.txt" $limit > "$dir/run.log" 2>&1; then
        echo "pass"; return 0
    fi
    echo "FAIL"; return 1
}

arches="x86_64 i686 aarch64 s390x"
families="gcc clang"
day=$((10#$(date +%j)))
failures=0
declare -A result
declare -A secs
cells=""
k=0
for arch in $arches; do
    for fam in $families; do
        if [ "$quick" -eq 1 ]; then
            cells="$cells $arch/$fam/$(( (day + k) % 3 ))"
        else
            cells="$cells $arch/$fam/0 $arch/$fam/1 $arch/$fam/2"
        fi
        k=$((k + 1))
    done
done
[ -n "$only" ] && cells=$only
for cell in $cells; do
    IFS=/ read -r arch fam idx <<< "$cell"
    t0=$(date +%s)
    status=$(build_and_run "$arch" "$fam" "$idx")
    [ "$status" = pass ] || [ "$status" = SKIP ] || failures=$((failures + 1))
    result[$arch/$fam/$idx]=$status
    secs[$arch/$fam/$idx]=$(( $(date +%s) - t0 ))
    echo "[cross] $arch $fam $(flaglabel "$idx"): $status (${secs[$arch/$fam/$idx]} s)"
    if [ "$status" != pass ] && [ "$status" != SKIP ]; then
        tail -n 20 "$work/$arch-$fam-$idx/build.log" "$work/$arch-$fam-$idx/run.log" 2>/dev/null | sed 's/^/    /'
    fi
done
echo
printf '%-8s %-6s %-12s %-12s %-12s\n' arch cc "-O0" "-O2" "-O3fast"
for arch in $arches; do
    for fam in $families; do
        printf '%-8s %-6s' "$arch" "$fam"
        for idx in 0 1 2; do
            cell=${result[$arch/$fam/$idx]:--}
            [ "$cell" != - ] && cell="$cell(${secs[$arch/$fam/$idx]}s)"
            printf ' %-12s' "$cell"
        done
        printf '\n'
    done
done
echo "total time: $(( $(date +%s) - start )) s; mode: $([ "$quick" -eq 1 ] && echo quick || echo full)"
if [ "$failures" -ne 0 ]; then
    echo "cross: $failures configuration(s) FAILED"
    exit 1
fi
echo "cross: all configurations match the golden hashes"
