# Environment for Emscripten's em++ and for node running its output; sourced by the scripts
# that build or run WebAssembly (tests/cross/run.sh, tests/web/, scripts/web.sh), so no
# developer has to set anything in their own shell.
#
# Usage: . scripts/emscripten-env.sh [PRIVATE_CACHE_DIR]
#
# - NODE_PATH: em++ runs a JavaScript optimizer (when it links at -O2 and above) that needs
#   Debian's acorn module, which lives in /usr/share/nodejs, outside node's default path.
# - EM_CACHE: Debian ships Emscripten's system libraries prebuilt in a frozen cache that
#   nothing writes, so it is used as it is. An Emscripten whose cache is not frozen and not
#   writable by this user (a shared install) gets PRIVATE_CACHE_DIR instead, when given.
export NODE_PATH="/usr/share/nodejs${NODE_PATH:+:$NODE_PATH}"
if [ -n "${1:-}" ] && [ -z "${EM_CACHE:-}" ] && command -v em-config > /dev/null 2>&1; then
    lockbox_em_cache=$(em-config CACHE 2> /dev/null || true)
    if [ "$(em-config FROZEN_CACHE 2> /dev/null || true)" != True ] && [ -n "$lockbox_em_cache" ] &&
        [ ! -w "$lockbox_em_cache" ]; then
        mkdir -p "$1" && export EM_CACHE="$1"
    fi
    unset lockbox_em_cache
fi
