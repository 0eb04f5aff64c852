#!/usr/bin/env bash
# Build and run the lockbox demo (Release). Arguments are passed to the demo.
#   scripts/demo.sh [demo arguments...]
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

bash scripts/install-deps.sh
cmake --preset release
cmake --build --preset release --target lockbox_demo
exec "$repo_root/build/release/samples/lockbox_demo" "$@"
