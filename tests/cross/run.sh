#!/usr/bin/env bash
# Cross-compiler / cross-architecture determinism check (docs/determinism.md).
#
# Builds tests/cross/cross_driver.cpp together with the fixed/, core/, replay/, scenefile/ and
# scene-library sources (no CMake; a jumbo build planned by tests/cross/unity.py; xxHash
# header-only through -DXXH_INLINE_ALL) for every configuration ("cell") of
#   {compiler} x {-O0, -O2, -O3 (+ -march=native -ffast-math natively, -ffast-math elsewhere)}
#   x {x86-64 native (g++, clang++, and clang++ with libc++), i686 (static; natively, or under
#      qemu-i386 on a kernel without 32-bit support), aarch64, s390x (big-endian), riscv64,
#      armhf (32-bit ARM) and ppc64el under qemu-user (g++ and clang++ each), wasm32 (em++,
#      Emscripten's clang and libc++, run by node)}
# runs each one against tests/golden/hashes.txt, the fixed-function golden values and
# tests/cross/snapshot_golden.txt, checks that all cells printed the same values, prints a
# pass/fail matrix with per-cell times, and exits non-zero on any mismatch, build failure or
# missing toolchain.
#
# Usage: tests/cross/run.sh [--ci | --quick] [--no-install] [--jobs N] [--only LIST]
#                           [--no-unity] [--keep DIR] [--rev REV]
#   --ci          the CI mode (.ci/run), 10 cells: every architecture, x86-64 with each of its
#                 compilers and the others with one, one flag set each, rotating by day of
#                 year; tumbler stops at step 1 in emulated cells and at step 60 in native
#                 -O0, i686 and wasm32 cells (see $qemu_ci_limits below);
#                 LOCKBOX_CROSS_CLANG_CROSS=0 is ignored (every cell must build and run).
#   --quick       like --ci but without the tumbler limits.
#   --no-install  skip scripts/install-deps.sh --cross (toolchains already present)
#   --jobs N      cells built and run at the same time (default 2: on a 2-core machine one
#                 cell compiles while another runs)
#   --only LIST   only these cells, e.g. "s390x/gcc/1 x86_64/libcxx/2 wasm32/emcc/0"
#                 (arch/compiler/flag index: 0 = -O0, 1 = -O2, 2 = -O3 fast)
#   --no-unity    compile one object per source instead of the jumbo TUs (for comparison)
#   --keep DIR    keep the work directory (logs, unity TUs, executables) in DIR
#   --rev REV     take fixed/, core/, replay/, scenefile/, scenes/ and tests/golden/ from git
#                 revision REV (e.g. HEAD) instead of the working tree; tests/cross/ always
#                 comes from the working tree (for a long run while the tree is being edited)
# Environment: LOCKBOX_CROSS_CLANG_CROSS=0 skips clang for the non-native architectures
#   (not in --ci); LOCKBOX_CROSS_QEMU_O0_MAX_STEP (default 60) limits the steps checked by
#   emulated -O0 builds; LOCKBOX_CROSS_SCENES (driver --scenes syntax, "a,b:N") limits every
#   cell, LOCKBOX_CROSS_QEMU_SCENES the emulated cells, to those scenes. A toolchain that
#   cannot be found is always a failure.
set -u
# The whole script is one brace group: bash parses it completely before running it, so editing
# this file during a long run cannot change the running script.
{
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
mode=full
only=""
install=1
jobs=2
unity=1
keep=""
rev=""
while [ $# -gt 0 ]; do
    case "$1" in
        --ci) mode=ci ;;
        --quick) mode=quick ;;
        --no-install) install=0 ;;
        --jobs) shift; jobs=$1 ;;
        --only) shift; only=$1 ;;
        --no-unity) unity=0 ;;
        --keep) shift; keep=$1 ;;
        --rev) shift; rev=$1 ;;
        *) echo "run.sh: unknown argument '$1'" >&2; exit 2 ;;
    esac
    shift
done

# Step limits in --ci. tumbler (2,025 boxes in a rotating drum) takes nine tenths of the light
# scenes' time: about 370 s to step 600 under qemu at -O2 (aarch64), 200 s to step 60 under
# qemu at -O0 (s390x), 500 s to step 600 natively at -O0 (x86-64), and i686 (no native 128-bit
# integers) is about four times slower than x86-64 at any level (figures from a loaded
# machine; docs/determinism.md). So emulated cells check its step 1 only, native -O0 cells,
# every i686 cell and every wasm32 cell (node runs -O2 WebAssembly at about the speed of
# native -O0) its steps 1 and 60; x86-64 -O2/-O3 cells run it in full, and every other light
# scene runs to step 600 everywhere (60 in emulated -O0 cells and wasm32 -O0 cells).
qemu_ci_limits="tumbler:1"
native_slow_ci_limits="tumbler:60"

start=$(date +%s)
if [ "$install" -eq 1 ]; then
    bash "$root/scripts/install-deps.sh" --cross || { echo "run.sh: install-deps.sh --cross failed" >&2; exit 2; }
fi

if [ -n "$keep" ]; then
    work=$keep
    rm -rf "$work" && mkdir -p "$work" || exit 2
else
    work=$(mktemp -d /tmp/lockbox-cross.XXXXXX)
    trap 'rm -rf "$work"' EXIT
fi

# em++ (the wasm32 cells) needs a module path for its optimizer, and a cache it may use.
# shellcheck source=scripts/emscripten-env.sh
. "$root/scripts/emscripten-env.sh" "$work/emcache"

# i686 binaries run natively where the kernel can run 32-bit programs. Some kernels (VMs built
# without IA-32 emulation) cannot: there the i686 cells run under qemu-i386 like the other
# foreign architectures, with the emulated cells' limits.
i686_runner=""
if command -v i686-linux-gnu-g++ > /dev/null 2>&1; then
    printf 'int main() { return 0; }\n' > "$work/i686-probe.cpp"
    if i686-linux-gnu-g++ -static "$work/i686-probe.cpp" -o "$work/i686-probe" > /dev/null 2>&1 &&
        ! "$work/i686-probe" > /dev/null 2>&1; then
        i686_runner="qemu-i386"
        echo "[cross] i686: this kernel cannot run 32-bit programs; the i686 cells run under qemu-i386"
    fi
fi

# A private copy of the sources: a run takes minutes to hours, and the working tree may change
# meanwhile; every cell must build the same code.
src="$work/src"
mkdir -p "$src/tests" "$src/scenes/files"
if [ -n "$rev" ]; then
    git -C "$root" archive "$rev" fixed core replay scenefile scenes/include scenes/src scenes/replay \
        scenes/files/handmade tests/golden |
        tar -x -C "$src" && cp -r "$root/tests/cross" "$src/tests/" ||
        { echo "run.sh: cannot extract the sources of $rev" >&2; exit 2; }
    echo "[cross] sources: $(git -C "$root" rev-parse --short "$rev") ($rev), tests/cross from the working tree"
else
    cp -r "$root/fixed" "$root/core" "$root/replay" "$root/scenefile" "$src/" &&
        cp -r "$root/scenes/include" "$root/scenes/src" "$root/scenes/replay" "$src/scenes/" &&
        cp -r "$root/scenes/files/handmade" "$src/scenes/files/" &&
        cp -r "$root/tests/cross" "$root/tests/golden" "$src/tests/" ||
        { echo "run.sh: cannot copy the sources" >&2; exit 2; }
fi

# The cross compilers do not search /usr/include (x86 packages): give them the header-only
# dependencies of core/ (xxHash, Cereal for snapshots) and of scenefile/ (RapidJSON, through a
# symbolic link to its folder) alone.
mkdir -p "$work/include"
cp /usr/include/xxhash.h "$work/include/" || { echo "run.sh: /usr/include/xxhash.h missing (libxxhash-dev)" >&2; exit 2; }
[ -d /usr/include/cereal ] && cp -r /usr/include/cereal "$work/include/"
# lockbox/Version.h, which CMake generates from cmake/Version.h.in with the version of the
# top-level project() line; the same here (from the working tree also with --rev: the library
# version changes no bits).
version=$(sed -n 's/^project(lockbox VERSION \([0-9]*\)\.\([0-9]*\)\.\([0-9]*\).*/\1 \2 \3/p' "$root/CMakeLists.txt")
[ -n "$version" ] || { echo "run.sh: no project(lockbox VERSION x.y.z) line in CMakeLists.txt" >&2; exit 2; }
read -r vmajor vminor vpatch <<< "$version"
mkdir -p "$work/include/lockbox"
sed -e "s/@PROJECT_VERSION_MAJOR@/$vmajor/g" -e "s/@PROJECT_VERSION_MINOR@/$vminor/g" \
    -e "s/@PROJECT_VERSION_PATCH@/$vpatch/g" "$root/cmake/Version.h.in" > "$work/include/lockbox/Version.h" ||
    { echo "run.sh: cannot generate lockbox/Version.h from cmake/Version.h.in" >&2; exit 2; }
[ -f /usr/include/rapidjson/reader.h ] || { echo "run.sh: /usr/include/rapidjson missing (rapidjson-dev)" >&2; exit 2; }
ln -s /usr/include/rapidjson "$work/include/rapidjson"

# scenefile/ loads the hand-written scene files of the golden plan (file/<name> lines).
sources=$(cd "$src" && find fixed/src core/src scenefile/src scenes/src -name '*.cpp' | LC_ALL=C sort)
# core/src: the engine's sources include its internal headers from there (Engine.h, dynamics/, state/).
incdirs="fixed/include core/include core/src scenefile/include scenes/include tests/cross"
# The golden replays recorded uncompressed (the cross toolchains have no zstd: replay/ is built
# with LOCKBOX_REPLAY_ZSTD=0) are verified in every cell (tests/cross/ReplayVerify.h).
replay_files=""
if [ -d "$src/replay/src" ]; then
    sources="$sources $(cd "$src" && find replay/src -name '*.cpp' | LC_ALL=C sort)"
    incdirs="$incdirs replay/include scenes/replay/include"
    for f in "$src"/tests/golden/replays/*.lbr; do
        # record.sh records these with --level 0 (chunks stored raw) and names them *_raw.lbr.
        case "$f" in *_raw.lbr) replay_files="$replay_files${replay_files:+,}$f" ;; esac
    done
fi
sources="$sources tests/cross/cross_driver.cpp"
includes="-I$work/include"
for d in $incdirs; do includes="$includes -I$src/$d"; done
defines="-DXXH_INLINE_ALL"
# The snapshot comparison needs b2World::Save; it compiles in once core defines it.
if grep -rqs 'b2World::Save' "$src/core/src"; then defines="$defines -DLOCKBOX_CROSS_SNAPSHOT"; fi
[ -n "$replay_files" ] && defines="$defines -DLOCKBOX_CROSS_REPLAY -DLOCKBOX_REPLAY_ZSTD=0"

if [ "$unity" -eq 1 ]; then
    uargs=""
    for d in $incdirs; do uargs="$uargs -I $d"; done
    # shellcheck disable=SC2086
    tus=$(cd "$src" && python3 tests/cross/unity.py --root . --out "$work/unity" --report $uargs $sources 2> "$work/unity.log") ||
        { cat "$work/unity.log" >&2; echo "run.sh: tests/cross/unity.py failed" >&2; exit 2; }
    echo "[cross] jumbo build: $(echo "$tus" | wc -w) TUs from $(echo "$sources" | wc -w) sources"
    sed 's/^/    /' "$work/unity.log"
else
    tus=""
    for s in $sources; do tus="$tus $src/$s"; done
fi

# Flag sets; index 2 differs natively (-march=native) and across architectures.
flagset() {  # $1 arch, $2 index
    case "$2" in
        0) echo "-O0" ;;
        1) echo "-O2 -DNDEBUG" ;;
        2) if [ "$1" = x86_64 ]; then echo "-O3 -march=native -ffast-math -DNDEBUG"; else echo "-O3 -ffast-math -DNDEBUG"; fi ;;
    esac
}
flaglabel() { case "$1" in 0) echo "-O0" ;; 1) echo "-O2" ;; 2) echo "-O3fast" ;; esac; }

# The architectures, and the compiler families built for each: g++ and clang++ everywhere
# Linux runs, clang++ with LLVM's libc++ instead of libstdc++ natively, and Emscripten's em++
# (clang 14 with libc++, the only compiler for wasm32).
arches="x86_64 i686 aarch64 s390x riscv64 armhf ppc64el wasm32"
families() {  # $1 arch
    case "$1" in
        x86_64) echo "gcc clang libcxx" ;;
        wasm32) echo "emcc" ;;
        *) echo "gcc clang" ;;
    esac
}

triple() {  # $1 arch -> GNU target triple (the cross compiler's prefix and sysroot /usr/<triple>)
    case "$1" in
        armhf) echo "arm-linux-gnueabihf" ;;
        ppc64el) echo "powerpc64le-linux-gnu" ;;
        *) echo "$1-linux-gnu" ;;
    esac
}

compiler() {  # $1 arch, $2 family -> compiler command (empty: switched off)
    case "$1/$2" in
        x86_64/gcc) echo "g++" ;;
        x86_64/clang) echo "clang++" ;;
        x86_64/libcxx) echo "clang++ -stdlib=libc++" ;;
        # -fexceptions: as the wasm preset (cmake/EmscriptenToolchain.cmake), so that a snapshot
        # refused by Restore is caught instead of aborting.
        wasm32/emcc) echo "em++ -fexceptions" ;;
        i686/gcc) echo "i686-linux-gnu-g++ -static" ;;
        */gcc) echo "$(triple "$1")-g++" ;;
        */clang)
            if [ "${LOCKBOX_CROSS_CLANG_CROSS:-1}" = 1 ] || [ "$mode" = ci ]; then
                local extra=""
                [ "$1" = i686 ] && extra=" -static"
                echo "clang++ --target=$(triple "$1")$extra"
            fi ;;
    esac
}

# Extra link flags: node's view of the host file system (the driver reads the golden files
# and replays by path) and a heap that grows (tumbler's 2,025 bodies).
linkflags() {  # $1 arch
    case "$1" in
        wasm32) echo "-sNODERAWFS=1 -sALLOW_MEMORY_GROWTH=1" ;;
    esac
}

runner() {  # $1 arch
    case "$1" in
        i686) echo "$i686_runner" ;;
        x86_64) echo "" ;;
        # Without --no-experimental-fetch, node 18 and 20 make Emscripten's loader fetch() the
        # .wasm, which fails for a file path; the flag makes it read the file.
        wasm32) echo "node --no-experimental-fetch" ;;
        armhf) echo "qemu-arm -L /usr/$(triple "$1")" ;;
        ppc64el) echo "qemu-ppc64le -L /usr/$(triple "$1")" ;;
        *) echo "qemu-$1 -L /usr/$(triple "$1")" ;;
    esac
}
emulated() {  # $1 arch: true when its cells run under qemu-user
    case "$(runner "$1")" in qemu-*) return 0 ;; *) return 1 ;; esac
}

# Missing pieces of a cell's toolchain, empty when complete.
missing_tools() {  # $1 arch, $2 compiler command, $3 runner command, $4 family
    local m=""
    command -v "${2%% *}" > /dev/null 2>&1 || m="$m ${2%% *}"
    [ -n "$3" ] && { command -v "${3%% *}" > /dev/null 2>&1 || m="$m ${3%% *}"; }
    case "$1" in
        x86_64 | wasm32) ;;
        *) [ -d "/usr/$(triple "$1")" ] || m="$m /usr/$(triple "$1")" ;;
    esac
    if [ "$4" = libcxx ] && ! echo '#include <vector>' | clang++ -stdlib=libc++ -x c++ -fsyntax-only - > /dev/null 2>&1; then
        m="$m libc++-dev"
    fi
    echo "$m"
}

report_cell() {  # $1 cell: prints its line (and the tail of its logs on failure)
    local arch fam idx dir status bs rs
    IFS=/ read -r arch fam idx <<< "$1"
    dir="$work/$arch-$fam-$idx"
    status=NO-RESULT bs=0 rs=0
    [ -s "$dir/result" ] && read -r status bs rs < "$dir/result"
    # One write, so that the reports of cells finishing together do not interleave.
    local text
    text="[cross] $arch $fam $(flaglabel "$idx"): $status (build $bs s, run $rs s)"
    if [ "$status" != pass ] && [ "$status" != SKIP ]; then
        text="$text
$(tail -n 20 "$dir/build.log" "$dir/run.log" 2>/dev/null | sed 's/^/    /')"
    fi
    printf '%s\n' "$text"
}

# Builds and runs one cell; writes "status build_s run_s" to $dir/result and reports it.
run_cell() {
    build_and_run "$@"
    report_cell "$1/$2/$3"
}

build_and_run() {  # $1 arch, $2 family, $3 flag index
    local arch=$1 fam=$2 idx=$3
    local dir="$work/$arch-$fam-$idx" cxx flags run t0 t1 t2 miss exe
    mkdir -p "$dir"
    cxx=$(compiler "$arch" "$fam")
    run=$(runner "$arch")
    [ -z "$cxx" ] && { echo "SKIP 0 0" > "$dir/result"; return; }
    miss=$(missing_tools "$arch" "$cxx" "$run" "$fam")
    if [ -n "$miss" ]; then
        echo "missing:$miss" > "$dir/build.log"
        echo "NO-TOOLCHAIN 0 0" > "$dir/result"; return
    fi
    flags=$(flagset "$arch" "$idx")
    t0=$(date +%s)
    local tu n=0 objs=""
    for tu in $tus; do
        # shellcheck disable=SC2086
        if ! $cxx -std=c++20 $flags $defines $includes -c "$tu" -o "$dir/$n.o" >> "$dir/build.log" 2>&1; then
            echo "BUILD-FAIL $(( $(date +%s) - t0 )) 0" > "$dir/result"; return
        fi
        objs="$objs $dir/$n.o"
        n=$((n + 1))
    done
    # Emscripten writes the program as a loader (.js) beside its module (.wasm).
    exe="$dir/cross_driver"
    [ "$arch" = wasm32 ] && exe="$dir/cross_driver.js"
    # shellcheck disable=SC2086
    if ! $cxx -std=c++20 $flags $objs $(linkflags "$arch") -o "$exe" >> "$dir/build.log" 2>&1; then
        echo "LINK-FAIL $(( $(date +%s) - t0 )) 0" > "$dir/result"; return
    fi
    t1=$(date +%s)
    local args=()
    [ -n "${LOCKBOX_CROSS_SCENES:-}" ] && args+=(--scenes "$LOCKBOX_CROSS_SCENES")
    if emulated "$arch"; then
        # Emulated unoptimised builds are the slowest cells by far: they check steps <= 60
        # only (LOCKBOX_CROSS_QEMU_O0_MAX_STEP overrides; 600 gives the full lines).
        [ "$idx" = 0 ] && args+=(--max-step "${LOCKBOX_CROSS_QEMU_O0_MAX_STEP:-60}")
        [ -n "${LOCKBOX_CROSS_QEMU_SCENES:-}" ] && args+=(--scenes "$LOCKBOX_CROSS_QEMU_SCENES")
        [ "$mode" = ci ] && args+=(--limits "$qemu_ci_limits")
    elif [ "$mode" = ci ] && { [ "$idx" = 0 ] || [ "$arch" = i686 ] || [ "$arch" = wasm32 ]; }; then
        args+=(--limits "$native_slow_ci_limits")
        # Unoptimised WebAssembly runs at about a twentieth of native speed under node: in CI
        # it checks the steps <= 60, as emulated -O0 cells do.
        [ "$arch" = wasm32 ] && [ "$idx" = 0 ] && args+=(--max-step 60)
    fi
    local status=FAIL
    # shellcheck disable=SC2086
    [ -n "$replay_files" ] && args+=(--replays "$replay_files")
    if $run "$exe" "$src/tests/golden/hashes.txt" --snapshot-golden "$src/tests/cross/snapshot_golden.txt" \
        "${args[@]}" > "$dir/run.log" 2> "$dir/time.log"; then
        status=pass
    fi
    t2=$(date +%s)
    echo "$status $((t1 - t0)) $((t2 - t1))" > "$dir/result"
}

# --ci and --quick: x86-64 with each of its three compilers, and every other architecture
# with one compiler, alternating between architectures (about half gcc, half clang on any day)
# and from day to day; each cell at one flag set, rotating by day. Six days cover every cell
# of the full matrix.
day=$((10#$(date +%j)))
cells=""
k=0
a=0
for arch in $arches; do
    fams=$(families "$arch")
    if [ "$mode" != full ] && [ "$arch" != x86_64 ]; then
        read -r -a listed <<< "$fams"
        fams=${listed[$(( (day + a) % ${#listed[@]} ))]}
    fi
    for fam in $fams; do
        if [ "$mode" = full ]; then
            cells="$cells $arch/$fam/0 $arch/$fam/1 $arch/$fam/2"
        else
            cells="$cells $arch/$fam/$(( (day + k) % 3 ))"
        fi
        k=$((k + 1))
    done
    a=$((a + 1))
done
[ -n "$only" ] && cells=$only

# Longest first (emulated, then unoptimised), so the short native cells fill the gaps at the
# end; ties keep the listed order.
order=$(for cell in $cells; do
    IFS=/ read -r arch fam idx <<< "$cell"
    w=0
    emulated "$arch" && w=2
    [ "$idx" = 0 ] && w=$((w + 1))
    echo "$((9 - w)) $cell"
done | sort -s -k1,1n | cut -d' ' -f2)

# $jobs cells at a time: each compiles its TUs one after the other, then runs, so on two
# cores one cell's compile overlaps another's (usually emulated) run.
running=0
for cell in $order; do
    if [ "$running" -ge "$jobs" ]; then
        wait -n
        running=$((running - 1))
    fi
    IFS=/ read -r arch fam idx <<< "$cell"
    run_cell "$arch" "$fam" "$idx" &
    running=$((running + 1))
done
wait

failures=0
declare -A result
declare -A secs
for cell in $cells; do
    IFS=/ read -r arch fam idx <<< "$cell"
    # A cell that wrote no result (killed, or its shell failed) is a failure too.
    status=NO-RESULT bs=0 rs=0
    [ -s "$work/$arch-$fam-$idx/result" ] && read -r status bs rs < "$work/$arch-$fam-$idx/result"
    result[$cell]=$status
    secs[$cell]=$((bs + rs))
    # A missing toolchain (NO-TOOLCHAIN) is a failure: only LOCKBOX_CROSS_CLANG_CROSS=0
    # outside --ci gives SKIP.
    case "$status" in
        pass | SKIP) ;;
        *) failures=$((failures + 1)) ;;
    esac
done

# Every value printed by any two cells for the same item (function, scene step, snapshot) must
# agree, whatever the golden file says: this separates a stale golden file (all cells agree
# on new values) from a real cross-build difference.
logs=""
for cell in $cells; do
    IFS=/ read -r arch fam idx <<< "$cell"
    [ -s "$work/$arch-$fam-$idx/run.log" ] && logs="$logs $work/$arch-$fam-$idx/run.log"
done
divergent=0
if [ -n "$logs" ]; then
    # shellcheck disable=SC2086
    awk -v work="$work/" '
        $1 == "PASS:" || $1 == "FAIL:" { next }
        {
            cell = substr(FILENAME, length(work) + 1); sub("/run.log$", "", cell)
            item = ($2 == "function" || $2 == "snapshot" || $2 == "replay") ? $2 " " $3 : $2
            for (i = 2; i <= NF; ++i) {
                if (index($i, "=") == 0) continue
                split($i, kv, "=")
                key = item " " kv[1]
                if (!(key in value)) { value[key] = kv[2]; first[key] = cell }
                else if (value[key] != kv[2] && !(key in reported)) {
                    reported[key] = 1; ++n
                    printf "[cross] DIVERGENCE %s: %s=%s in %s, %s in %s\n", item, kv[1], value[key], first[key], kv[2], cell
                }
            }
        }
        END { exit n > 0 }' $logs || divergent=1
fi

# The snapshot and replay lines (all cells printed the same ones unless a DIVERGENCE was
# reported above).
if [ -n "$logs" ]; then
    # shellcheck disable=SC2086
    grep -hE ' (snapshot|replay) ' $logs | sort | uniq -c | while read -r n line; do
        echo "[cross] $n cell(s) printed: $line"
    done
fi

echo
printf '%-8s %-6s %-18s %-18s %-18s\n' arch cc "-O0" "-O2" "-O3fast"
for arch in $arches; do
    for fam in $(families "$arch"); do
        printf '%-8s %-6s' "$arch" "$fam"
        for idx in 0 1 2; do
            cell=${result[$arch/$fam/$idx]:--}
            [ "$cell" != - ] && cell="$cell(${secs[$arch/$fam/$idx]}s)"
            printf ' %-18s' "$cell"
        done
        printf '\n'
    done
done
echo "total time: $(( $(date +%s) - start )) s; mode: $mode; $(echo "$tus" | wc -w) TU(s) per cell; jobs: $jobs"
if [ "$divergent" -ne 0 ]; then
    echo "cross: cells DISAGREE with each other (see DIVERGENCE lines): a real cross-build difference"
fi
if [ "$failures" -ne 0 ] || [ "$divergent" -ne 0 ]; then
    echo "cross: $failures configuration(s) FAILED"
    exit 1
fi
echo "cross: all configurations match the golden hashes and each other"
exit 0
}
