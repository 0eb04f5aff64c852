#!/usr/bin/env bash
# Checks that every public declaration of lockbox's installed headers is documented: runs
# Doxygen with docs/Doxyfile (warnings as errors) and prints each warning as file:line: text.
#   scripts/check-docs.sh               check only; Doxygen's output goes to a temporary folder
#   scripts/check-docs.sh --html DIR    also build the HTML API reference into DIR (e.g. build/doxygen)
# Needs doxygen (Debian package doxygen, installed by scripts/install-deps.sh). Writes nothing
# into the source tree.
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

html_dir=""
while [ "$#" -gt 0 ]; do
    case "$1" in
        --html)
            [ "$#" -ge 2 ] || { echo "check-docs.sh: --html needs a folder" >&2; exit 2; }
            html_dir="$2"
            shift 2
            ;;
        *) echo "check-docs.sh: unknown argument '$1' (expected --html DIR)" >&2; exit 2 ;;
    esac
done

if ! command -v doxygen >/dev/null 2>&1; then
    echo "check-docs: doxygen not found (apt-get install doxygen, or scripts/install-deps.sh)" >&2
    exit 1
fi

out_dir="$(mktemp -d)"
trap 'rm -rf "$out_dir"' EXIT

# A header's opening comment must start with `/// @file`, or Doxygen hands it to the next
# declaration (usually the namespace) instead of the file.
no_file_doc=()
while IFS= read -r header; do
    if [ "$(sed -n 2p "$header")" != "/// @file" ]; then
        no_file_doc+=("$header")
    fi
done < <(git ls-files 'fixed/include/*.h' 'core/include/*.h' 'replay/include/*.h' 'net/include/*.h' \
    'scenefile/include/*.h' | grep -v '/detail/')

# Doxygen needs one output format to run; XML into the temporary folder is the cheapest.
overrides=("OUTPUT_DIRECTORY=$out_dir" "GENERATE_XML=YES" "XML_PROGRAMLISTING=NO")
if [ -n "$html_dir" ]; then
    mkdir -p "$html_dir"
    overrides+=("GENERATE_HTML=YES" "HTML_OUTPUT=$(cd "$html_dir" && pwd)")
fi

# WARN_AS_ERROR=FAIL_ON_WARNINGS: Doxygen reports every warning, then exits non-zero.
rc=0
{ cat docs/Doxyfile; printf '%s\n' "${overrides[@]}"; } | doxygen - >"$out_dir/log" 2>"$out_dir/warnings" || rc=$?

# The same declaration is reported once per class that inherits it; print each warning once,
# with paths relative to the repository.
mapfile -t warnings < <(sed "s|^$repo_root/||" "$out_dir/warnings" | awk 'NF && !seen[$0]++')
for header in "${no_file_doc[@]}"; do
    warnings+=("$header:2: line 2 is not '/// @file' (after #pragma once, the header's comment opens with it)")
done
if [ "$rc" -ne 0 ] || [ "${#warnings[@]}" -ne 0 ]; then
    printf '%s\n' "${warnings[@]}" >&2
    echo "check-docs: ${#warnings[@]} warning(s): document the public declarations above (///, see docs/Doxyfile)" >&2
    exit 1
fi
echo "check-docs: every public declaration of the installed headers is documented"
if [ -n "$html_dir" ]; then
    echo "check-docs: HTML reference in $html_dir/index.html"
fi
