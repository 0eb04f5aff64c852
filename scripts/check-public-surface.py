#!/usr/bin/env python3
"""Checks the public surface of core/: what a user sees through #include <lockbox/lockbox.h>.

Parses the umbrella header with clang (its AST, so access specifiers, nested classes and
macros are read the way the compiler reads them) and fails when b2World, b2Body, b2Fixture,
b2Contact, b2Joint or a class derived from one of them has a public non-static data member in a
public header of core/, or when such a header defines a type of the rollback frames'
book-keeping (epochs, structure changes, frame caches and restore counts, a *_detail namespace).
Prints the number of public headers of core/ as well.

  scripts/check-public-surface.py     (no build needed: lockbox/Version.h is generated here)
Needs clang++ (Debian package clang, installed by scripts/install-deps.sh).
"""
import pathlib
import re
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
GUARDED = {"b2World", "b2Body", "b2Fixture", "b2Contact", "b2Joint"}
# Book-keeping that belongs to the engine: a user saves and restores frames through the opaque
# b2WorldFrame, and never sees how the world tracks them. (A sync test's summary of which restore
# paths ran, SyncTestFrameRestores, is a result the caller reads, not book-keeping.)
INTERNAL_NAME = re.compile(r"Epoch|Structure|FrameCache|FrameBook|FrameData|FrameRestoreCounts|Serial|_detail::")


def dump_ast() -> list[str]:
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        # The generated version header, with any numbers: only the declarations matter here.
        (tmp / "lockbox").mkdir()
        template = (ROOT / "cmake/Version.h.in").read_text()
        (tmp / "lockbox/Version.h").write_text(re.sub(r"@\w+@", "0", template))
        (tmp / "tu.cpp").write_text("#include <lockbox/lockbox.h>\n")
        # The text dump: clang 14's JSON dumper crashes on some of the templates lockbox.h includes.
        cmd = ["clang++", "-std=c++20", "-fsyntax-only", f"-I{tmp}", f"-I{ROOT / 'core/include'}",
               f"-I{ROOT / 'fixed/include'}", "-Xclang", "-ast-dump", "-Xclang",
               "-ast-dump-filter=lockbox::", str(tmp / "tu.cpp")]
        out = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT)
    if out.returncode != 0:
        sys.exit(f"check-public-surface: clang++ could not parse lockbox.h:\n{out.stderr[-4000:]}")
    return out.stdout.splitlines()


TREE_PREFIX = re.compile(r"^((?:[| ] )*)[|`]-")
LOCATION = re.compile(r"<(?!line:|col:)([^:<>, ]+):\d+:\d+")
RECORD = re.compile(r"^CXXRecordDecl .* (class|struct) (\w+) definition$")
BASE = re.compile(r"^(public|protected|private)(?: virtual)? '([^']+)'")
ACCESS = re.compile(r"^AccessSpecDecl .* (public|protected|private)$")
FIELD = re.compile(r"^FieldDecl .*? col:\d+(?: implicit)?(?: referenced)? (\w+) '")


def nodes(lines):
    """Yields (depth, text, file) per AST line. Clang prints a location's file only when it
    differs from the previous location's, so the current file is carried along."""
    file = ""
    qualified = ""
    for line in lines:
        if line.startswith("Dumping "):
            qualified = line[len("Dumping "):].rstrip(":")
            continue
        m = TREE_PREFIX.match(line)
        depth = len(m.group(1)) // 2 + 1 if m else 0
        text = line[m.end():] if m else line
        for loc in LOCATION.finditer(text):
            file = loc.group(1)
        yield depth, text, file, qualified if depth == 0 else ""


NAMESPACE = re.compile(r"^NamespaceDecl .* (\w+)$")


def records(lines):
    """Class and struct definitions: name, qualified name, file, tag, base names and direct
    children."""
    found = []
    scopes = []  # (depth, qualified name, record or None)
    for depth, text, file, dumped in nodes(lines):
        while scopes and scopes[-1][0] >= depth:
            scopes.pop()
        if scopes and scopes[-1][0] == depth - 1 and scopes[-1][2] is not None:
            scopes[-1][2]["children"].append(text)
        outer = scopes[-1][1] if scopes else dumped.rpartition("::")[0]
        if m := NAMESPACE.match(text):
            scopes.append((depth, f"{outer}::{m.group(1)}" if outer else m.group(1), None))
        elif m := RECORD.match(text):
            qualified = f"{outer}::{m.group(2)}" if outer else m.group(2)
            rec = {"tag": m.group(1), "name": m.group(2), "qualified": qualified, "file": file,
                   "children": []}
            found.append(rec)
            scopes.append((depth, qualified, rec))
    for rec in found:
        rec["bases"] = [b.group(2).split("::")[-1] for b in map(BASE.match, rec["children"]) if b]
    return found


def display(file: str) -> str:
    path = pathlib.Path(file)
    try:
        return str(path.resolve().relative_to(ROOT))
    except ValueError:
        return file


def public_header(file: str) -> bool:
    path = pathlib.Path(file)
    if not path.is_absolute():
        path = ROOT / path
    try:
        rel = path.resolve().relative_to(ROOT)
    except ValueError:
        return False
    return rel.parts[:2] == ("core", "include")


def main():
    if len(sys.argv) > 1:
        print(f"check-public-surface: unknown argument '{sys.argv[1]}' (it takes none)", file=sys.stderr)
        return 2
    recs = records(dump_ast())

    guarded = set(GUARDED)
    changed = True
    while changed:  # classes derived from a guarded one (the joints) are guarded too
        changed = False
        for rec in recs:
            if rec["name"] not in guarded and any(b in guarded for b in rec["bases"]):
                guarded.add(rec["name"])
                changed = True

    problems = set()
    for rec in recs:
        if not public_header(rec["file"]):
            continue
        name = rec["name"]
        if INTERNAL_NAME.search(rec["qualified"]):
            problems.add(f"{display(rec['file'])}: type {rec['qualified']} is engine book-keeping")
        if name not in guarded:
            continue
        access = "private" if rec["tag"] == "class" else "public"
        for child in rec["children"]:
            if m := ACCESS.match(child):
                access = m.group(1)
            elif (m := FIELD.match(child)) and access == "public":
                problems.add(f"{display(rec['file'])}: {name}::{m.group(1)} is a public data member")

    headers = sorted((ROOT / "core/include").rglob("*.h"))
    print(f"check-public-surface: {len(headers)} public headers in core/include, "
          f"{len(guarded)} guarded classes")
    for p in sorted(problems):
        print(p)
    if problems:
        print(f"check-public-surface: {len(problems)} problem(s)")
        return 1
    print("check-public-surface: no public data members or engine book-keeping types")
    return 0


if __name__ == "__main__":
    sys.exit(main())
