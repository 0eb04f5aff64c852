#!/usr/bin/env bash
# Builds samples/consumer, a CMake project of its own, against lockbox in the ways a user gets it,
# and checks that every build prints the final hash of the in-tree hello world (built in the same
# project against the same lockbox, and equal in every build):
#
#   static  static libraries installed into a prefix: find_package(lockbox 0.9 COMPONENTS core
#           net replay scenefile), every installed header compiled and lockbox::lockbox linked,
#           a b2dJson save and load through lockbox::scenefile, and a build through pkg-config
#           (lockbox-core)
#   shared  the same with BUILD_SHARED_LIBS=ON (hidden visibility, LOCKBOX_API)
#   subdir  add_subdirectory of the source tree, physics only (LOCKBOX_BUILD_REPLAY=OFF,
#           LOCKBOX_BUILD_NET=OFF, LOCKBOX_BUILD_SCENEFILE=OFF), configured with zstd, ENet and
#           RapidJSON hidden from every find_* call
#           (CMAKE_FIND_ROOT_PATH on a folder that holds only xxHash and Cereal); as a control,
#           the same configuration with replay on must fail naming libzstd-dev
#   fetch   FetchContent from a source archive of the tree (configure only: it builds what
#           subdir builds); tests, samples and benchmarks must be off
#   deb     the lockbox-dev .deb that CPack makes from the static build, installed with dpkg -i,
#           used through find_package and pkg-config, then removed
#
# Library builds compile the libraries only (no tests, samples or benchmarks), as unity builds
# (about half the time; the release build and the subdir step keep one unit per file), with
# ccache when it is installed. Every consumer compile line is checked for our private flags (warnings,
# -ffp-contract, sanitizers), which must not reach it.
#
# Usage: scripts/check-consumer.sh [--only "static shared subdir fetch deb"] [--keep DIR]
# The deb step needs root (or sudo) and refuses to run if lockbox-dev is installed already.
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

steps="static shared subdir fetch deb"
keep=""
while [ $# -gt 0 ]; do
    case "$1" in
        --only) shift; steps=$1 ;;
        --keep) shift; keep=$1 ;;
        *) echo "check-consumer.sh: unknown argument '$1' (expected --only LIST or --keep DIR)" >&2; exit 2 ;;
    esac
    shift
done

bash scripts/install-deps.sh

if [ -n "$keep" ]; then
    work=$(realpath -m "$keep")
    rm -rf "$work" && mkdir -p "$work"
else
    work=$(mktemp -d /tmp/lockbox-consumer.XXXXXX)
fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
deb_installed=0
cleanup() {
    if [ "$deb_installed" -eq 1 ]; then
        "${sudo_cmd[@]}" dpkg -r lockbox-dev > /dev/null || echo "check-consumer: could not remove lockbox-dev" >&2
    fi
    # An if, not `[ ] && rm`: a false test as the trap's last command would become the exit status.
    if [ -z "$keep" ]; then rm -rf "$work"; fi
}
trap cleanup EXIT

generator=(-G Ninja)
launcher=()
if command -v ccache > /dev/null 2>&1; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
libs_only=(-DLOCKBOX_BUILD_TESTS=OFF -DLOCKBOX_BUILD_SAMPLES=OFF -DLOCKBOX_BUILD_BENCH=OFF -DCMAKE_UNITY_BUILD=ON)
hello="$repo_root/samples/hello_world/main.cpp"
hashes=()

fail() {
    echo "check-consumer: $*" >&2
    exit 1
}

step_start() {
    step_t0=$SECONDS
    printf '\n--- consumer: %s\n' "$1"
}
step_end() { printf -- '--- consumer: %s ok in %ds\n' "$1" "$((SECONDS - step_t0))"; }

# Builds lockbox's libraries in $work/$1 (extra cmake arguments follow).
build_lockbox() {
    local dir="$work/$1"
    shift
    cmake -S "$repo_root" -B "$dir" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" "${libs_only[@]}" \
        "$@" > "$dir.configure.log" || { cat "$dir.configure.log"; fail "configuring lockbox failed"; }
    cmake --build "$dir" -j 2
}

# Configures and builds samples/consumer in $work/$1 (extra cmake arguments follow), runs it and
# the hello world, and checks that both end with the same hash.
build_consumer() {
    local name=$1
    local dir="$work/consumer-$name"
    shift
    cmake -S "$repo_root/samples/consumer" -B "$dir" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" \
        -DLOCKBOX_CONSUMER_HELLO_WORLD="$hello" "$@"
    cmake --build "$dir" -j 2
    check_private_flags "$dir"
    run_and_compare "$name" "$dir/consumer" "$dir/hello_world"
}

# Our warnings, -Werror, -ffp-contract=off and sanitizer flags must not reach a consumer's compile line.
check_private_flags() {
    local line
    local commands
    commands=$(ninja -C "$1" -t commands consumer)
    line=$(grep -m 1 -- 'main\.cpp' <<< "$commands" || true)
    [ -n "$line" ] || fail "no compile line for main.cpp in $1"
    if grep -Eq -- '(^| )-(W[a-z]|Werror|ffp-contract|fsanitize)' <<< "$line"; then
        fail "a private lockbox flag reached the consumer's compile line: $line"
    fi
}

# Runs $2 (the consumer) and $3 (the in-tree hello world); their last lines must be the same hash.
run_and_compare() {
    local out want got
    out=$("$2") || fail "$1: consumer failed"
    printf '%s\n' "$out"
    got=$(tail -n 1 <<< "$out")
    want=$("$3" | tail -n 1) || fail "$1: hello world failed"
    [[ "$got" == hash\ 0x* ]] || fail "$1: the consumer's last line is not a hash: $got"
    [ "$got" = "$want" ] || fail "$1: consumer printed '$got', the hello world '$want'"
    echo "$1: consumer and hello world agree: $got"
    hashes+=("$got")
}

# Runs the consumer's scenefile program ($1 names the build): a world saved as b2dJson and loaded
# back must step to the same hash.
run_scene_file() {
    local program="$work/consumer-$1/consumer_scene_file"
    [ -x "$program" ] || fail "$1: consumer_scene_file was not built (scenefile component missing?)"
    "$program" || fail "$1: consumer_scene_file failed"
}

# A build through pkg-config alone: one compile and link of the consumer.
build_with_pkg_config() {
    local out="$work/consumer-$1-pkg-config"
    # shellcheck disable=SC2046
    g++ -std=c++20 -O2 samples/consumer/main.cpp $(pkg-config --cflags --libs lockbox-core) -o "$out" ||
        fail "$1: building with pkg-config failed"
    run_and_compare "$1 (pkg-config)" "$out" "$work/consumer-$1/hello_world"
}

for step in $steps; do
    case "$step" in
        static)
            step_start "static libraries installed into a prefix"
            # /usr as the configured prefix gives Debian's multiarch libdir, which the .deb needs.
            build_lockbox static -DCMAKE_INSTALL_PREFIX=/usr
            cmake --install "$work/static" --prefix "$work/prefix-static" > /dev/null
            echo "installed: $(find "$work/prefix-static" -name '*.h' | wc -l) headers," \
                "$(find "$work/prefix-static" -name '*.a' | wc -l) static libraries"
            build_consumer static -DCMAKE_PREFIX_PATH="$work/prefix-static" \
                -DLOCKBOX_CONSUMER_COMPONENTS="core;net;replay;scenefile" -DLOCKBOX_CONSUMER_CHECK_HEADERS=ON
            run_scene_file static
            pc_dir=$(dirname "$(find "$work/prefix-static" -name lockbox.pc)")
            PKG_CONFIG_PATH="$pc_dir" build_with_pkg_config static
            step_end static
            ;;
        shared)
            step_start "shared libraries installed into a prefix"
            build_lockbox shared -DBUILD_SHARED_LIBS=ON
            cmake --install "$work/shared" --prefix "$work/prefix-shared" > /dev/null
            build_consumer shared -DCMAKE_PREFIX_PATH="$work/prefix-shared" \
                -DLOCKBOX_CONSUMER_COMPONENTS="core;net;replay;scenefile" -DLOCKBOX_CONSUMER_CHECK_HEADERS=ON
            run_scene_file shared
            needed=$(ldd "$work/consumer-shared/consumer")
            grep -q 'liblockbox_core\.so' <<< "$needed" || fail "shared: the consumer is not linked to liblockbox_core.so"
            for lib in "$work"/prefix-shared/lib*/liblockbox_*.so; do
                symbols=$(nm -D --defined-only "$lib")
                echo "$(basename "$lib"): $(grep -c ' [TWVBDR] ' <<< "$symbols") exported symbols"
            done
            step_end shared
            ;;
        subdir)
            step_start "add_subdirectory, physics only, with zstd and ENet out of reach"
            # A folder in which find_* sees only what core needs: xxHash and Cereal.
            root="$work/find-root"
            cereal_config=$(find /usr/lib /usr/share -name cerealConfig.cmake -print -quit)
            [ -n "$cereal_config" ] || fail "cerealConfig.cmake not found (libcereal-dev)"
            for f in /usr/include/xxhash.h /usr/include/cereal "$(dirname "$cereal_config")" \
                "$(g++ -print-file-name=libxxhash.so)"; do
                mkdir -p "$root$(dirname "$f")"
                ln -s "$f" "$root$f"
            done
            hide=(-DCMAKE_FIND_ROOT_PATH="$root" -DCMAKE_FIND_ROOT_PATH_MODE_INCLUDE=ONLY
                -DCMAKE_FIND_ROOT_PATH_MODE_LIBRARY=ONLY -DCMAKE_FIND_ROOT_PATH_MODE_PACKAGE=ONLY
                -DCMAKE_FIND_ROOT_PATH_MODE_PROGRAM=NEVER)
            # Control: with replay on, the same configuration must fail for want of zstd.
            if cmake -S samples/consumer -B "$work/control" "${generator[@]}" "${hide[@]}" \
                -DLOCKBOX_CONSUMER_SOURCE_DIR="$repo_root" -DLOCKBOX_BUILD_SCENEFILE=OFF > "$work/control.log" 2>&1; then
                fail "subdir: zstd was found although it should be out of reach"
            fi
            grep -q 'libzstd-dev' "$work/control.log" || { cat "$work/control.log"; fail "subdir: the control failed for another reason"; }
            echo "control: with LOCKBOX_BUILD_REPLAY on, configuring fails: $(grep -o 'zstd not found[^(]*' "$work/control.log")"
            build_consumer subdir "${hide[@]}" -DLOCKBOX_CONSUMER_SOURCE_DIR="$repo_root" \
                -DLOCKBOX_BUILD_REPLAY=OFF -DLOCKBOX_BUILD_NET=OFF -DLOCKBOX_BUILD_SCENEFILE=OFF
            if grep -Eqi 'zstd|enet|rapidjson' "$work/consumer-subdir/build.ninja"; then
                fail "subdir: the physics-only build mentions zstd, ENet or RapidJSON"
            fi
            libs=$(cd "$work/consumer-subdir" && find . -name 'liblockbox_*' | sort | xargs -n1 basename | tr '\n' ' ')
            [ "$libs" = "liblockbox_core.a liblockbox_fixed.a " ] || fail "subdir: built $libs"
            echo "subdir: built $libs; no zstd, ENet or RapidJSON anywhere in the build"
            step_end subdir
            ;;
        fetch)
            step_start "FetchContent from a source archive (configure only)"
            git ls-files -z --cached --others --exclude-standard |
                tar -C "$repo_root" --null -T - --ignore-failed-read -czf "$work/lockbox-src.tar.gz" 2> /dev/null
            dir="$work/consumer-fetch"
            cmake -S samples/consumer -B "$dir" "${generator[@]}" -DLOCKBOX_CONSUMER_FETCH="$work/lockbox-src.tar.gz" \
                > "$work/fetch.log" || { cat "$work/fetch.log"; fail "fetch: configuring failed"; }
            for option in TESTS SAMPLES BENCH; do
                grep -q "^LOCKBOX_BUILD_$option:BOOL=OFF" "$dir/CMakeCache.txt" ||
                    fail "fetch: LOCKBOX_BUILD_$option is not off under FetchContent"
            done
            if grep -q 'GTest_DIR\|benchmark_DIR' "$dir/CMakeCache.txt"; then
                fail "fetch: GoogleTest or Google Benchmark was looked for"
            fi
            targets=$(ninja -C "$dir" -t targets all)
            grep -q '^consumer:' <<< "$targets" || fail "fetch: no consumer target"
            echo "fetch: configured; tests, samples and benchmarks off; $(grep -c '\.o: CXX_COMPILER' <<< "$targets") objects to build"
            step_end fetch
            ;;
        deb)
            step_start "the lockbox-dev .deb"
            [ -d "$work/static" ] || fail "deb: needs the static step first"
            if [ "$(dpkg-query -W -f='${Status}' lockbox-dev 2> /dev/null || true)" = "install ok installed" ]; then
                fail "deb: lockbox-dev is installed already; remove it first (dpkg -r lockbox-dev)"
            fi
            (cd "$work/static" && cpack -G DEB > "$work/cpack.log") || { cat "$work/cpack.log"; fail "cpack failed"; }
            deb=$(find "$work/static/packages" -maxdepth 1 -name 'lockbox-dev_*.deb')
            echo "$(basename "$deb"): $(du -k "$deb" | cut -f1) KiB, $(dpkg-deb -c "$deb" | grep -vc '/$') files;" \
                "Depends: $(dpkg-deb -f "$deb" Depends)"
            "${sudo_cmd[@]}" dpkg -i "$deb" > /dev/null
            deb_installed=1
            build_consumer deb -DLOCKBOX_CONSUMER_COMPONENTS="core;net;replay;scenefile" -DLOCKBOX_CONSUMER_CHECK_HEADERS=ON
            run_scene_file deb
            build_with_pkg_config deb
            "${sudo_cmd[@]}" dpkg -r lockbox-dev > /dev/null
            deb_installed=0
            [ ! -e /usr/include/lockbox/lockbox.h ] || fail "deb: headers left behind after dpkg -r"
            step_end deb
            ;;
        *) fail "unknown step '$step' (expected static shared subdir fetch deb)" ;;
    esac
done

for h in "${hashes[@]}"; do
    [ "$h" = "${hashes[0]}" ] || fail "the builds disagree: ${hashes[*]}"
done
echo
echo "check-consumer: ${#hashes[@]} consumer builds ($steps) print ${hashes[0]:-no hash}"
