#!/usr/bin/env bash
# Fetches and unpacks Debian's zstd source package for the WebAssembly build's replay decoder
# (cmake/LockboxWasmDependencies.cmake), the same version as the installed libzstd-dev when
# there is one, so the browser and the native build decompress with the same zstd release.
# Prints the unpacked source directory. Needs a deb-src entry for the Debian archive
# (scripts/install-deps.sh --web adds it); runs as any user.
#
# Usage: scripts/fetch-zstd-source.sh DEST_DIR
set -euo pipefail
dest="${1:?usage: fetch-zstd-source.sh DEST_DIR}"
mkdir -p "$dest"
cd "$dest"
for d in zstd-src; do
    if [ -f "$d/lib/zstd.h" ]; then
        echo "$PWD/$d"
        exit 0
    fi
done
version=$(dpkg-query -W -f='${Version}' libzstd-dev 2> /dev/null || true)
spec=libzstd${version:+=$version}
echo "fetch-zstd-source: apt-get source $spec" >&2
apt-get source --download-only "$spec" >&2
dsc=$(ls -1 libzstd_*.dsc | head -n 1)
rm -rf zstd-src
dpkg-source -x "$dsc" zstd-src >&2
echo "$PWD/zstd-src"
