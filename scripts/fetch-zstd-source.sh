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
# The installed version first. A mirror may list a source it no longer serves (a security
# update's, say): then the other versions apt lists, then whatever it picks. The decoder of any
# zstd release reads every frame, so another Debian revision only changes which patches it has.
specs=()
if [ -n "$version" ]; then specs+=("libzstd=$version"); fi
while read -r listed; do
    if [ -n "$listed" ] && [ "$listed" != "$version" ]; then specs+=("libzstd=$listed"); fi
done < <(apt-cache showsrc libzstd 2> /dev/null | sed -n 's/^Version: //p' | sort -r -V)
specs+=(libzstd)
fetched=""
for spec in "${specs[@]}"; do
    echo "fetch-zstd-source: apt-get source $spec" >&2
    rm -f libzstd_*
    if apt-get source --download-only "$spec" >&2; then
        fetched=$spec
        break
    fi
    echo "fetch-zstd-source: $spec could not be fetched" >&2
done
if [ -z "$fetched" ]; then
    echo "fetch-zstd-source: no libzstd source package could be fetched" >&2
    exit 1
fi
if [ -n "$version" ] && [ "$fetched" != "libzstd=$version" ]; then
    echo "fetch-zstd-source: note: the decoder is built from $fetched, the installed libzstd-dev is $version" >&2
fi
dsc=$(ls -1 libzstd_*.dsc | head -n 1)
rm -rf zstd-src
dpkg-source -x "$dsc" zstd-src >&2
echo "$PWD/zstd-src"
