#!/usr/bin/env bash
# lockbox in the browser: builds the WebAssembly package and the web page (the `wasm` preset)
# and runs their tests, or serves the page locally.
#
# Usage: scripts/web.sh [test]        install what is missing (scripts/install-deps.sh --web),
#                                     build the native helper of the tests (release preset) and
#                                     the wasm preset, run the tests labelled `web` (node,
#                                     npm pack, headless Chromium)
#        scripts/web.sh serve [PORT]  build the wasm preset and serve the page on
#                                     http://127.0.0.1:PORT/ (default 8000) until Ctrl-C
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
cmd="${1:-test}"

bash scripts/install-deps.sh --web
launcher=()
if command -v ccache > /dev/null 2>&1; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi

case "$cmd" in
    test)
        # The native half of the node tests (snapshots crossing both ways, the joint rig, a
        # divergent replay) comes from the release build.
        [ -f build/release/CMakeCache.txt ] || cmake --preset release "${launcher[@]}"
        cmake --build --preset release --target lockbox_web_native
        cmake --workflow --preset wasm
        ;;
    serve)
        port="${2:-8000}"
        [ -f build/wasm/CMakeCache.txt ] || cmake --preset wasm
        cmake --build --preset wasm
        echo "web: open http://127.0.0.1:$port/ (Ctrl-C stops the server)"
        exec python3 -m http.server "$port" --bind 127.0.0.1 --directory build/wasm/web/page
        ;;
    *)
        echo "usage: scripts/web.sh [test | serve [PORT]]" >&2
        exit 2
        ;;
esac
