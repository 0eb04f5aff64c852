#!/usr/bin/env python3
"""Jumbo (unity) build plan for tests/cross/run.sh.

Splits the given .cpp files into as few unity translation units as possible such that putting
them into one TU cannot change what any of them means. Pasting several .cpp files into one TU
makes each file's file-local names visible to the files after it, which can

  * fail to compile (two files define the same anonymous-namespace helper), or worse,
  * compile and silently change meaning (a later file's call now also sees an earlier file's
    helper as an overload candidate, or an earlier file's `using namespace` or macro).

The engine code is not edited for this. Instead each file is scanned (comments, string and
character literals removed) for
  I(F): the names it gives file-local effect at namespace scope: everything declared in an
        anonymous namespace, `static` functions and variables, namespace-scope const/constexpr
        variables (internal linkage), namespace-scope class/enum definitions and type aliases,
        and macro names it #defines;
  T(F): every identifier its own text uses;
  D(F): the namespaces it pulls in with a namespace-scope `using namespace`.
Two files F and G may share a TU only if I(F) and T(G) are disjoint and I(G) and T(F) are
disjoint (the check is symmetric, so the order inside a TU does not matter for it). Inside a TU
the files are ordered so that every file's D includes the D of every file before it (a later
file then sees no using-directive it does not already have itself); files whose D sets do not
form such a chain go to different TUs. Assignment is first-fit in sorted path order, so the
plan depends only on the file contents.

The check is deliberately conservative (a shared identifier token is enough to separate two
files). Headers are included once per TU, as in any unity build; they are include-guarded and
define no file-local names of their own in a way that depends on the including file.

Project headers (quoted includes) count too: a header's file-local names belong to the files
that include it when the other file does not, its using-directives to every includer, and a
class defined differently by two project headers (an ODR clash that separate TUs get away
with) keeps the files that include one of them apart from those that include the other.

Usage: unity.py --root DIR --out DIR [--report] [-I DIR]... FILE...
  Writes DIR/unity_<n>.cpp (each #including its files by absolute path) and prints the
  generated paths, one per line. --report prints the plan and every conflict found to stderr.
"""
import argparse
import os
import re
import sys

IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
KEYWORDS = {
    "alignas", "alignof", "auto", "bool", "break", "case", "catch", "char", "class", "concept",
    "const", "consteval", "constexpr", "constinit", "const_cast", "continue", "decltype",
    "default", "delete", "do", "double", "dynamic_cast", "else", "enum", "explicit", "export",
    "extern", "false", "float", "for", "friend", "goto", "if", "inline", "int", "long",
    "mutable", "namespace", "new", "noexcept", "nullptr", "operator", "private", "protected",
    "public", "register", "reinterpret_cast", "requires", "return", "short", "signed", "sizeof",
    "static", "static_assert", "static_cast", "struct", "switch", "template", "this",
    "thread_local", "throw", "true", "try", "typedef", "typeid", "typename", "union",
    "unsigned", "using", "virtual", "void", "volatile", "while", "final", "override",
}


def strip_source(text):
    """Removes comments and the contents of string/character literals; returns (code, macros)
    where macros are the names #defined, and preprocessor lines are blanked."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            i = n if j < 0 else j + 2
            out.append(" ")
        elif c == 'R' and text.startswith('R"', i):
            m = re.match(r'R"([^(]*)\(', text[i:])
            end = text.find(")" + m.group(1) + '"', i) if m else -1
            i = n if end < 0 else end + len(m.group(1)) + 2
            out.append('""')
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            # A digit separator (1'000) is not a character literal.
            if c == "'" and i > 0 and text[i - 1].isalnum():
                out.append(" ")
                i += 1
                continue
            out.append(c + c)
            i = j + 1
        else:
            out.append(c)
            i += 1
    code = "".join(out)
    macros = set()
    lines = []
    for line in code.split("\n"):
        m = re.match(r"\s*#\s*(define|undef)\s+([A-Za-z_]\w*)", line)
        if m:
            macros.add(m.group(2))
        lines.append("" if line.lstrip().startswith("#") else line)
    return "\n".join(lines), macros


def tokens(code):
    return re.findall(r"[A-Za-z_]\w*|::|\S", code)


def skip_angles(toks, i):
    """toks[i] == '<': index just past the matching '>'."""
    depth = 0
    while i < len(toks):
        if toks[i] == "<":
            depth += 1
        elif toks[i] == ">":
            depth -= 1
            if depth == 0:
                return i + 1
        i += 1
    return i


def declared_name(decl):
    """Name introduced by one namespace-scope declaration (token list, a body replaced by
    "{}"), whether it has internal linkage by itself, and whether it names a type (a class or
    enumeration definition, a type alias). None for member definitions (X::f), forward
    declarations and declarations that introduce nothing new."""
    d = list(decl)
    while d and d[0] == "template":
        d = d[skip_angles(d, 1):] if len(d) > 1 and d[1] == "<" else d[1:]
    if not d:
        return None, False, False
    if d[0] in ("struct", "class", "union", "enum"):
        if "{}" not in d:
            return None, False, False  # forward declaration
        k = 1
        if k < len(d) and d[k] in ("class", "struct"):
            k += 1
        # An export macro (`class LOCKBOX_API b2World`) stands between the key and the name.
        while k + 1 < len(d) and re.fullmatch(r"[A-Z][A-Z0-9_]*_API", d[k]) and IDENT.fullmatch(d[k + 1]):
            k += 1
        if k >= len(d) or not IDENT.fullmatch(d[k]):
            return None, True, True
        # `struct Outer::Inner {...}` defines a nested class declared inside Outer: its name is
        # the whole qualified one (two files defining different nested classes of one class do
        # not clash).
        name = d[k]
        while k + 2 < len(d) and d[k + 1] == "::" and IDENT.fullmatch(d[k + 2]):
            k += 2
            name += "::" + d[k]
        return name, True, True
    if d[0] == "using":
        if len(d) > 2 and d[2] == "=":
            return d[1], True, True
        return None, False, False  # using-declaration / using-directive: handled elsewhere
    if d[0] == "typedef":
        names = [t for t in d if IDENT.fullmatch(t) and t not in KEYWORDS]
        return (names[-1] if names else None), True, True
    if d[0] in ("static_assert", "extern"):
        return None, False, False
    internal = "static" in d[:3] or (("const" in d or "constexpr" in d) and "inline" not in d)
    if "operator" in d:
        k = d.index("operator")
        if k > 0 and d[k - 1] == "::":
            return None, False, False  # a member operator
        return "operator" + (d[k + 1] if k + 1 < len(d) else ""), "static" in d[:3], False
    depth = 0
    for k, t in enumerate(d):
        if t in "([{":
            if t == "(" and depth == 0 and k > 0 and IDENT.fullmatch(d[k - 1]):
                if k > 1 and d[k - 2] == "::":
                    return None, False, False  # definition of a member or of a qualified name
                if d[k - 1] in KEYWORDS:
                    return None, False, False
                # A function: `static` decides; const in its return type does not.
                return d[k - 1], "static" in d[:3], False
            depth += 1
        elif t in ")]}":
            depth -= 1
        elif depth == 0 and t in ("=", ";"):
            break
    # A variable: the last identifier before '=', '{', '[' or the end.
    names = []
    depth = 0
    for k, t in enumerate(d):
        if depth == 0 and t in ("=", "{", "["):
            break
        if t in "(<":
            depth += 1
        elif t in ")>":
            depth -= 1
        elif depth == 0 and IDENT.fullmatch(t) and t not in KEYWORDS:
            names.append((k, t))
    if not names:
        return None, False, False
    k, name = names[-1]
    if k > 0 and d[k - 1] == "::":
        return None, False, False
    return name, internal, False


def scan(path):
    """(L, T, D, C, Y) of one file: L its file-local names except types (anonymous namespace,
    static, const variables, macros), T, D as in the module comment, C the qualified names of
    the classes and enumerations it defines at namespace scope, Y the names of the types it
    defines or aliases at namespace scope outside anonymous namespaces. I = L | Y for a .cpp
    file; for a header only L counts (its types are the same in every TU)."""
    with open(path, encoding="utf-8") as f:
        code, macros = strip_source(f.read())
    toks = tokens(code)
    used = {t for t in toks if IDENT.fullmatch(t)}
    local = set(macros)
    directives = set()
    classes = set()
    types = set()

    def note(name, internal, is_type, anon):
        if name and is_type and not anon:
            types.add(name)
        elif name and (internal or anon):
            local.add(name)

    # Scope stack entries: ("ns", anonymous, name) for namespaces, ("other",) for other braces.
    stack = []
    decl = []
    i = 0
    while i < len(toks):
        t = toks[i]
        at_ns = all(s[0] == "ns" for s in stack)
        anon = any(s[0] == "ns" and s[1] for s in stack)
        if not at_ns:
            if t == "{":
                stack.append(("other",))
            elif t == "}":
                stack.pop()
            i += 1
            continue
        if t == "namespace" and not decl:
            j = i + 1
            name = []
            while j < len(toks) and toks[j] not in ("{", "=", ";"):
                name.append(toks[j])
                j += 1
            if j < len(toks) and toks[j] == "{":
                stack.append(("ns", not name, "".join(name) or "(anonymous)"))
                i = j + 1
                continue
            if j < len(toks) and toks[j] == "=" and name:
                local.add(name[0])  # namespace alias
        if t == "using" and not decl and i + 1 < len(toks) and toks[i + 1] == "namespace":
            j = i + 2
            name = []
            while j < len(toks) and toks[j] != ";":
                name.append(toks[j])
                j += 1
            directives.add("".join(name))
            i = j + 1
            continue
        if t == "}" and not decl:
            stack.pop()
            i += 1
            continue
        if t == ";":
            note(*declared_name(decl), anon)
            decl = []
            i += 1
            continue
        if t == "{":
            # Body of a function, class or initializer: the declaration ends with the body,
            # except for a brace initializer of a variable (followed by ';' or ',').
            name, internal, is_type = declared_name(decl + ["{}"])
            note(name, internal, is_type, anon)
            depth = 0
            j = i
            while j < len(toks):
                if toks[j] == "{":
                    depth += 1
                elif toks[j] == "}":
                    depth -= 1
                    if depth == 0:
                        break
                j += 1
            i = j + 1
            is_class = decl and decl[0] in ("struct", "class", "union", "enum")
            if is_class and name:
                classes.add("::".join([e[2] for e in stack] + [name]))
            if is_class or (i < len(toks) and toks[i] in (";", ",")) or "=" in decl:
                # class body or brace initializer: the declaration goes on to its ';'
                decl.append("{}")
                continue
            decl = []
            continue
        decl.append(t)
        i += 1
    return local, used, directives, classes, types


INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"', re.M)


def header_closure(path, include_dirs, cache):
    """The project headers (quoted includes found in include_dirs or beside the includer) that
    path includes, directly or not."""
    seen = set()
    todo = [path]
    while todo:
        cur = todo.pop()
        if cur not in cache:
            with open(cur, encoding="utf-8") as f:
                names = INCLUDE.findall(f.read())
            found = []
            for name in names:
                for d in [os.path.dirname(cur)] + include_dirs:
                    cand = os.path.normpath(os.path.join(d, name))
                    if os.path.isfile(cand):
                        found.append(cand)
                        break
            cache[cur] = found
        for h in cache[cur]:
            if h not in seen:
                seen.add(h)
                todo.append(h)
    return seen


def plan(files, include_dirs, report):
    info = {}
    for f in files:
        local, used, directives, classes, types = scan(f)
        info[f] = (local | types, used, directives, classes)
    cache = {}
    closure = {f: header_closure(f, include_dirs, cache) for f in files}
    headers = sorted(set().union(*closure.values()))
    header_info = {h: scan(h) for h in headers}
    header_classes = {h: header_info[h][3] for h in headers}
    # A header's using-directives act on everything after it in the TU: count them as the
    # includer's own.
    for f in files:
        for h in closure[f]:
            info[f][2].update(header_info[h][2])
    # A class defined differently by two headers (or by a header and a .cpp) is an ODR clash
    # that separate TUs tolerate but one TU rejects: such includers must stay apart.
    definers = {}
    for h in headers:
        for c in header_classes[h]:
            definers.setdefault(c, set()).add(h)
    for f in files:
        for c in info[f][3]:
            definers.setdefault(c, set()).add(f)
    clashing = {c: hs for c, hs in definers.items() if len(hs) > 1}
    defines = {f: {c for c, hs in clashing.items() if hs & (closure[f] | {f})} for f in files}
    via = {f: {c: sorted(hs & (closure[f] | {f})) for c, hs in clashing.items()} for f in files}

    def conflicts(f, g):
        (i_f, t_f, _, _), (i_g, t_g, _, _) = info[f], info[g]
        # File-local names of headers that only one of the two includes count as that file's.
        i_f = i_f.union(*(header_info[h][0] for h in closure[f] - closure[g]))
        i_g = i_g.union(*(header_info[h][0] for h in closure[g] - closure[f]))
        names = (i_f & t_g) | (i_g & t_f)
        for c in defines[f] & defines[g]:
            if via[f][c] != via[g][c]:
                names.add(c + " (two definitions)")
        return sorted(names)

    # Files with fewer using-directives first, so that each TU's directive sets form a chain.
    order = sorted(files, key=lambda f: (len(info[f][2]), f))
    units = []
    split = {}
    for f in order:
        placed = False
        for unit in units:
            if any(not info[g][2] <= info[f][2] for g in unit):
                continue
            clash = [(g, conflicts(f, g)) for g in unit]
            clash = [(g, c) for g, c in clash if c]
            if clash:
                split.setdefault(f, []).extend(clash)
                continue
            unit.append(f)
            placed = True
            break
        if not placed:
            units.append([f])
    if report:
        for c, hs in sorted(clashing.items()):
            print(f"unity: {c} is defined differently in {' and '.join(os.path.relpath(h) for h in sorted(hs))}"
                  ": files that include one stay apart from files that include the other", file=sys.stderr)
        for f, clash in split.items():
            names = sorted({n for _, ns in clash for n in ns})
            print(f"unity: {os.path.relpath(f)} kept apart from {len(clash)} file(s) by: "
                  f"{', '.join(names)}", file=sys.stderr)
        for n, unit in enumerate(units):
            print(f"unity: TU {n}: {len(unit)} files: "
                  f"{' '.join(os.path.relpath(f) for f in unit)}", file=sys.stderr)
    return units


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--root", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--report", action="store_true")
    ap.add_argument("-I", dest="include", action="append", default=[],
                    help="include directory searched for quoted includes")
    ap.add_argument("files", nargs="+")
    a = ap.parse_args()
    os.chdir(a.root)
    files = [os.path.abspath(f) for f in a.files]
    os.makedirs(a.out, exist_ok=True)
    include_dirs = [os.path.abspath(d) for d in a.include]
    for n, unit in enumerate(plan(files, include_dirs, a.report)):
        path = os.path.join(a.out, f"unity_{n}.cpp")
        with open(path, "w", encoding="utf-8") as out:
            out.write("// Generated by tests/cross/unity.py: one jumbo translation unit.\n")
            for f in unit:
                out.write(f'#include "{f}"\n')
        print(path)


if __name__ == "__main__":
    main()
