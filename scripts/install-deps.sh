#!/usr/bin/env bash
# Install the Debian packages lockbox needs to build, test, benchmark and run its demo.
#
# Usage: scripts/install-deps.sh [--cross] [--web]
#   --cross  also install the cross toolchains (i686, aarch64, s390x, riscv64, armhf, ppc64el),
#            qemu-user, LLVM's libc++ and Emscripten, used to check that a step produces the
#            same bits on other architectures, standard libraries and WebAssembly
#            (tests/cross/run.sh).
#   --web    also install what the browser build and its tests need: Emscripten (with node),
#            headless Chromium, and Debian's zstd source package (a deb-src entry for the
#            Debian archive already configured is added, and dpkg-dev unpacks the source).
#
# Does nothing (one line of output, no apt-get update) when everything is already installed.
set -euo pipefail

# Always installed. One package per line, with what needs it.
PACKAGES=(
    build-essential     # g++ 12, make, libc headers: the default toolchain
    cmake               # build system (CMakePresets.json needs >= 3.25)
    ninja-build         # generator used by every preset
    clang               # second compiler, to check the code builds and hashes the same with it
    clang-format        # the formatting check (scripts/check-format.sh) run by CI
    doxygen             # the public API documentation check (scripts/check-docs.sh) run by CI
    libclang-rt-14-dev  # libFuzzer and the sanitizer runtimes for clang (the sanitize preset)
    googletest          # GoogleTest / GoogleMock sources (tests/)
    libgtest-dev        # GTest::gtest, GTest::gtest_main (tests/)
    libgmock-dev        # GTest::gmock (tests/)
    libbenchmark-dev    # benchmark::benchmark (bench/)
    pkg-config          # scripts/check-consumer.sh builds the consumer sample through lockbox.pc
    libxxhash-dev       # lockbox_dep::xxhash: state hashing in core/
    libcereal-dev       # lockbox_dep::cereal: snapshot serialization in core/
    libzstd-dev         # lockbox_dep::zstd: replay file compression
    libenet-dev         # lockbox_dep::enet: UDP transport for netcode samples
    libsodium-dev       # lockbox_dep::sodium: signing and checking admission tokens (tools/admission, lockbox_server, lockbox_token)
    libcpp-httplib-dev  # lockbox_dep::httplib: /healthz, /readyz and /metrics of lockbox_server (tools/server)
    rapidjson-dev       # lockbox_dep::rapidjson: JSON reading and writing of scene files (scenefile/)
    libbox2d-dev        # lockbox_dep::box2d_float: float Box2D, differential tests and benchmarks only
    python3-matplotlib  # plotting benchmark / drift results
    valgrind            # memcheck and callgrind instruction counts
    libglfw3-dev        # GLFW window and OpenGL context: the testbed (samples/testbed, optional)
    libimgui-dev        # Dear ImGui 1.86 with GLFW/OpenGL2 backends: the testbed (pulls libstb-dev)
    libstb-dev          # stb_image_write / stb_image: the testbed's PNG screenshots and their check
    libgl1-mesa-dri     # Mesa software OpenGL, so the testbed renders under Xvfb
    xvfb                # xvfb-run: virtual X server for the testbed smoke test (ctest -L testbed)
    xauth               # needed by xvfb-run
)

# Installed with --cross: other architectures for cross-machine determinism checks.
CROSS_PACKAGES=(
    g++-i686-linux-gnu     # 32-bit x86 cross compiler (links -static, runs natively)
    g++-aarch64-linux-gnu  # 64-bit ARM cross compiler (run with qemu-aarch64 -L /usr/aarch64-linux-gnu)
    g++-s390x-linux-gnu    # big-endian s390x cross compiler (run with qemu-s390x -L /usr/s390x-linux-gnu)
    g++-riscv64-linux-gnu      # 64-bit RISC-V cross compiler (run with qemu-riscv64 -L /usr/riscv64-linux-gnu)
    g++-arm-linux-gnueabihf    # 32-bit ARM (armhf) cross compiler (run with qemu-arm -L /usr/arm-linux-gnueabihf)
    g++-powerpc64le-linux-gnu  # little-endian POWER cross compiler (qemu-ppc64le -L /usr/powerpc64le-linux-gnu)
    qemu-user              # qemu-aarch64, qemu-s390x, qemu-riscv64, qemu-arm, qemu-ppc64le user-mode emulators
    libc++-dev             # LLVM's C++ standard library: the clang + libc++ cell
    libc++abi-dev          # its ABI library (linked by -stdlib=libc++)
    emscripten             # em++ (clang 14 for wasm32, prebuilt system libraries) and node: the wasm32 cells
)

# Installed with --web: the WebAssembly build (web/), its node tests and the headless browser
# test of the page (tests/web/).
WEB_PACKAGES=(
    emscripten             # em++ and node: the wasm preset and the JavaScript API tests
    chromium               # headless browser for the web page test (tests/web/page_test.js)
    npm                    # npm pack of the package folder (tests/web/npm_pack.cmake)
    dpkg-dev               # dpkg-source: unpacks Debian's zstd source package for the browser's decoder
)

want_cross=0
want_web=0
for arg in "$@"; do
    case "$arg" in
        --cross) want_cross=1 ;;
        --web) want_web=1 ;;
        -h|--help)
            sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//'
            exit 0
            ;;
        *)
            echo "install-deps.sh: unknown argument '$arg' (expected --cross or --web)" >&2
            exit 2
            ;;
    esac
done

wanted=("${PACKAGES[@]}")
if [ "$want_cross" -eq 1 ]; then
    wanted+=("${CROSS_PACKAGES[@]}")
fi
if [ "$want_web" -eq 1 ]; then
    wanted+=("${WEB_PACKAGES[@]}")
fi

if [ "$(id -u)" -eq 0 ]; then
    SUDO=()
elif command -v sudo >/dev/null 2>&1; then
    SUDO=(sudo)
else
    SUDO=(false)
fi

# --web: the browser's zstd decoder is compiled from Debian's own zstd source package, which
# apt-get source fetches only when the archive's deb-src entries are configured. Add them for
# the Debian archive this machine already uses (deb822 or one-line format), once.
if [ "$want_web" -eq 1 ] && ! apt-cache showsrc libzstd 2> /dev/null | grep -q '^Package: libzstd'; then
    src_list=""
    if [ -f /etc/apt/sources.list.d/debian.sources ]; then
        src_list=/etc/apt/sources.list.d/lockbox-deb-src.sources
        sed 's/^Types: deb$/Types: deb-src/' /etc/apt/sources.list.d/debian.sources > /tmp/lockbox-deb-src.$$
    elif [ -f /etc/apt/sources.list ]; then
        src_list=/etc/apt/sources.list.d/lockbox-deb-src.list
        sed -n 's/^deb \(.*debian.*\)$/deb-src \1/p' /etc/apt/sources.list > /tmp/lockbox-deb-src.$$
    fi
    if [ -z "$src_list" ] || [ ! -s /tmp/lockbox-deb-src.$$ ]; then
        echo "install-deps: no Debian archive entry found to add deb-src for (needed by --web)" >&2
        exit 1
    fi
    echo "install-deps: adding deb-src entries ($src_list) for Debian's zstd source package"
    "${SUDO[@]}" cp /tmp/lockbox-deb-src.$$ "$src_list"
    rm -f /tmp/lockbox-deb-src.$$
    "${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -qq
fi

missing=()
for pkg in "${wanted[@]}"; do
    # A node from NodeSource bundles npm and conflicts with Debian's npm package.
    if [ "$pkg" = npm ] && command -v npm > /dev/null 2>&1; then
        continue
    fi
    status=$(dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null || true)
    if [ "$status" != "install ok installed" ]; then
        missing+=("$pkg")
    fi
done

if [ "${#missing[@]}" -eq 0 ]; then
    echo "install-deps: all ${#wanted[@]} packages already installed"
    exit 0
fi

echo "install-deps: installing ${missing[*]}"

if [ "${SUDO[*]}" = false ]; then
    echo "install-deps: missing packages (${missing[*]}) and not root, and sudo is not available." >&2
    echo "install-deps: run as root: apt-get install ${missing[*]}" >&2
    exit 1
fi

export DEBIAN_FRONTEND=noninteractive
"${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -qq
"${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive \
    apt-get install -y -qq --no-install-recommends "${missing[@]}"
