#!/usr/bin/env python3
"""Turns the C++ blocks of the project's Markdown files into sources the build compiles.

Conventions (README.md "Docs"):
  ```cpp   a block that compiles. The blocks of one Markdown file form one translation unit, in
           order: `#include` and `using namespace` lines go to the top of the file, the rest of
           each block into one function body, each block in a scope nested in the previous one
           (a later block sees the earlier blocks' names and may reuse them).
  ```c++   a synopsis: declarations excerpted from a header, shown for reading, not compiled.
  <!-- snippet-setup
  code -->   right before a ```cpp block: code the block needs but the reader does not (the
             variables a fragment assumes), placed just before it in the same scope.
  <!-- snippet-scope: namespace -->   right before a ```cpp block: the block is declarations at
             namespace scope (after the includes) instead of statements.

Each generated line carries a #line directive back to the Markdown file, so a compiler error
names the document and its line.

Usage: extract_snippets.py OUT_DIR ROOT FILE.md...   (writes OUT_DIR/<stem>.cpp per file with
blocks; a file is rewritten only when its text changes; prints the paths written or kept)
"""
import os
import re
import sys

FENCE = re.compile(r"^```(\S*)\s*$")
SETUP_OPEN = "<!-- snippet-setup"
SCOPE_NAMESPACE = "<!-- snippet-scope: namespace -->"


def blocks(lines):
    """Yields (language, first_line_number, block_lines, setup_lines, setup_line_number, namespace)."""
    i = 0
    pending_setup, setup_line, namespace = None, 0, False
    while i < len(lines):
        line = lines[i]
        if line.startswith(SETUP_OPEN):
            setup_line = i + 2
            body = []
            rest = line[len(SETUP_OPEN):]
            if "-->" in rest:
                raise SystemExit(f"line {i + 1}: put the setup code on the lines after '{SETUP_OPEN}'")
            i += 1
            while i < len(lines) and "-->" not in lines[i]:
                body.append(lines[i])
                i += 1
            if i == len(lines):
                raise SystemExit(f"line {setup_line - 1}: snippet-setup comment is not closed")
            before = lines[i].split("-->")[0]
            if before.strip():
                body.append(before)
            pending_setup = body
            i += 1
            continue
        if line.strip() == SCOPE_NAMESPACE:
            namespace = True
            i += 1
            continue
        m = FENCE.match(line)
        if m:
            language = m.group(1)
            start = i + 2
            body = []
            i += 1
            while i < len(lines) and not lines[i].startswith("```"):
                body.append(lines[i])
                i += 1
            i += 1
            if language == "cpp":
                yield start, body, pending_setup or [], setup_line, namespace
            pending_setup, namespace = None, False
            continue
        if line.strip():
            # A setup or scope comment applies to the very next block only.
            pending_setup, namespace = None, False
        i += 1


def translate(md_path, shown_name):
    with open(md_path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    head, namespace_parts, body_parts = [], [], []
    depth = 0
    for start, body, setup, setup_line, namespace in blocks(lines):
        chunk = []
        numbered = [(setup_line + n, text) for n, text in enumerate(setup)]
        numbered += [(start + n, text) for n, text in enumerate(body)]
        for n, text in numbered:
            stripped = text.strip()
            placed = head if stripped.startswith(("#include", "using namespace")) else chunk
            placed.append(f'#line {n} "{shown_name}"\n{text}')
        target = namespace_parts if namespace else body_parts
        if namespace:
            target.append("\n".join(chunk))
        else:
            target.append("{\n" + "\n".join(chunk))
            depth += 1
    if not head and not namespace_parts and not body_parts:
        return None
    out = [f"// Generated from {shown_name} by tests/docs/extract_snippets.py: do not edit.",
           "#include <cstdio>", "#include <memory>", "#include <string>", "#include <vector>"]
    out.extend(head)
    out.extend(namespace_parts)
    if body_parts:
        out.append("[[maybe_unused]] static void DocumentSnippets() {")
        out.extend(body_parts)
        out.append("}" * depth)
        out.append("}")
    return "\n".join(out) + "\n"


def main():
    if len(sys.argv) < 3:
        raise SystemExit(__doc__)
    out_dir, root = sys.argv[1], sys.argv[2]
    os.makedirs(out_dir, exist_ok=True)
    for md in sys.argv[3:]:
        shown = os.path.relpath(md, root)
        try:
            text = translate(md, shown)
        except SystemExit as e:
            raise SystemExit(f"{shown}: {e}")
        if text is None:
            continue
        stem = shown.replace(os.sep, "_").replace(".md", "")
        path = os.path.join(out_dir, f"{stem}.cpp")
        old = None
        if os.path.exists(path):
            with open(path, encoding="utf-8") as f:
                old = f.read()
        if old != text:
            with open(path, "w", encoding="utf-8") as f:
                f.write(text)
        print(path)


if __name__ == "__main__":
    main()
