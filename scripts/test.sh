#!/usr/bin/env bash
# Build lockbox in Release and run every test (heavy ones included).
#   scripts/test.sh
# Installs missing Debian packages first (scripts/install-deps.sh), then runs the `release`
# workflow preset: configure, build with 2 jobs, ctest. Exits non-zero on any failure.
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

bash scripts/install-deps.sh
cmake --workflow --preset release
