#!/usr/bin/env python3
"""Layering check (issue 18): each emoface library uses only the libraries docs/architecture.md allows.

Usage: scripts/check_layering.py [SOURCE_DIR]      (exit 0 clean, 1 violations, 2 bad table)
       scripts/check_layering.py --self-test       (checks the checker on a made-up tree)

Reads the table between <!-- layering:begin --> and <!-- layering:end --> in docs/architecture.md and
checks, for every libs/<lib>:
  1. every '#include "emoface/<other>/..."' (or <...>) in libs/<lib>/{src,include} names an allowed library;
  2. every emoface::<other> in libs/<lib>/CMakeLists.txt is allowed;
  3. every included library is linked directly or reachable through PUBLIC_DEPS of linked libraries;
  4. the allowed graph is acyclic and covers every directory in libs/.
"""
import os
import re
import sys
import tempfile

INCLUDE_RE = re.compile(r'^\s*#\s*include\s*[<"]emoface/([a-z_]+)/')
DEP_RE = re.compile(r"emoface::([a-z_]+)")
SOURCE_EXT = (".hpp", ".h", ".cpp", ".cc", ".in", ".inl")


def read_table(doc_path):
    """{library: set(allowed)} from the marked table; raises ValueError with file:line on a bad row."""
    allowed = {}
    inside = False
    with open(doc_path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            if "layering:begin" in line:
                inside = True
                continue
            if "layering:end" in line:
                inside = False
                continue
            if not inside or not line.startswith("|") or line.startswith("|---"):
                continue
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if cells[0] == "library":
                continue
            if len(cells) < 2 or not re.fullmatch(r"[a-z_]+", cells[0]):
                raise ValueError(f"{doc_path}:{number}: bad layering row: {line.strip()}")
            deps = set() if cells[1] in ("—", "-", "") else {d.strip() for d in cells[1].split(",")}
            for d in deps:
                if not re.fullmatch(r"[a-z_]+", d):
                    raise ValueError(f"{doc_path}:{number}: bad library name '{d}'")
            if cells[0] in allowed:
                raise ValueError(f"{doc_path}:{number}: library '{cells[0]}' listed twice")
            allowed[cells[0]] = deps
    if not allowed:
        raise ValueError(f"{doc_path}: no layering table between the markers")
    return allowed


def cmake_deps(cmake_path):
    """(public, private) emoface dependencies of the emoface_add_library call in a CMakeLists.txt."""
    with open(cmake_path, encoding="utf-8") as f:
        text = re.sub(r"#[^\n]*", "", f.read())
    m = re.search(r"emoface_add_library\s*\((.*?)\)", text, re.S)
    if not m:  # a target made otherwise (capi, python): every emoface::x it names is a private link
        return set(), set(), set(DEP_RE.findall(text))
    public, private, section = set(), set(), None
    for token in m.group(1).split():
        if token in ("SOURCES", "PUBLIC_DEPS", "PRIVATE_DEPS", "FIND_DEPENDENCIES"):
            section = token
            continue
        dep = DEP_RE.fullmatch(token)
        if dep and section == "PUBLIC_DEPS":
            public.add(dep.group(1))
        elif dep and section == "PRIVATE_DEPS":
            private.add(dep.group(1))
    # Any other emoface::x in the file (target_link_libraries, ...) counts as a private link.
    other = set(DEP_RE.findall(text)) - public - private
    return public, private, other


def check(root):
    """Returns (violations, error) for the tree at root."""
    doc = os.path.join(root, "docs", "architecture.md")
    try:
        allowed = read_table(doc)
    except (OSError, ValueError) as e:
        return [], str(e)
    libs_dir = os.path.join(root, "libs")
    libs = sorted(d for d in os.listdir(libs_dir) if os.path.isdir(os.path.join(libs_dir, d)))
    problems = []
    for lib in libs:
        if lib not in allowed:
            problems.append(f"{doc}: library '{lib}' (libs/{lib}) has no row in the layering table")
    for lib, deps in allowed.items():
        for d in deps:
            if d not in allowed:
                problems.append(f"{doc}: '{lib}' may use unknown library '{d}'")
    # 4. acyclic
    state = {}

    def visit(node, path):
        if state.get(node) == 1:
            problems.append(f"{doc}: layering cycle: {' -> '.join(path + [node])}")
            return
        if state.get(node) == 2:
            return
        state[node] = 1
        for d in sorted(allowed.get(node, ())):
            if d != "core" or node != "core":
                visit(d, path + [node])
        state[node] = 2

    for lib in sorted(allowed):
        visit(lib, [])

    public_of, linked_of = {}, {}
    for lib in libs:
        cm = os.path.join(libs_dir, lib, "CMakeLists.txt")
        public, private, other = cmake_deps(cm) if os.path.exists(cm) else (set(), set(), set())
        public.discard(lib), private.discard(lib), other.discard(lib)
        public_of[lib] = public
        linked_of[lib] = public | private | other
        ok = allowed.get(lib, set()) | {"core"}
        for dep in sorted(linked_of[lib]):  # 2.
            if dep not in ok:
                problems.append(f"{cm}: {lib} links emoface::{dep}, which docs/architecture.md "
                                f"does not allow (allowed: {', '.join(sorted(ok))})")

    def reachable(lib):
        seen, todo = set(), list(linked_of.get(lib, ()))
        while todo:
            d = todo.pop()
            if d in seen:
                continue
            seen.add(d)
            todo.extend(public_of.get(d, ()))
        return seen

    for lib in libs:
        ok = allowed.get(lib, set()) | {"core"}
        declared = reachable(lib)
        for sub in ("src", "include"):
            base = os.path.join(libs_dir, lib, sub)
            for dirpath, _, files in os.walk(base):
                for name in sorted(files):
                    if not name.endswith(SOURCE_EXT):
                        continue
                    path = os.path.join(dirpath, name)
                    with open(path, encoding="utf-8", errors="replace") as f:
                        for number, line in enumerate(f, 1):
                            m = INCLUDE_RE.match(line)
                            if not m or m.group(1) == lib:
                                continue
                            used = m.group(1)
                            rel = os.path.relpath(path, root)
                            if used not in ok:  # 1.
                                problems.append(f"{rel}:{number}: {lib} includes emoface/{used}/, "
                                                f"which docs/architecture.md does not allow")
                            elif used not in declared:
                                problems.append(f"{rel}:{number}: {lib} includes emoface/{used}/ "
                                                f"but its CMake target does not link it")  # 3.
    return problems, None


def self_test():
    """The checker must catch each kind of violation on a small made-up tree."""
    def tree(table, libs):
        root = tempfile.mkdtemp(prefix="layering_selftest_")
        os.makedirs(os.path.join(root, "docs"))
        with open(os.path.join(root, "docs", "architecture.md"), "w") as f:
            f.write("<!-- layering:begin -->\n| library | may use (emoface) |\n|---|---|\n")
            for lib, deps in table.items():
                f.write(f"| {lib} | {', '.join(deps) if deps else '—'} |\n")
            f.write("<!-- layering:end -->\n")
        for lib, (cmake, include) in libs.items():
            d = os.path.join(root, "libs", lib, "src")
            os.makedirs(d)
            with open(os.path.join(root, "libs", lib, "CMakeLists.txt"), "w") as f:
                f.write(f"emoface_add_library({lib}\n  SOURCES src/a.cpp\n  {cmake})\n")
            with open(os.path.join(d, "a.cpp"), "w") as f:
                f.write("".join(f'#include "emoface/{i}/x.hpp"\n' for i in include))
        return root

    table = {"core": [], "a": ["core"], "b": ["core", "a"]}
    cases = [
        ("clean", table, {"core": ("", []), "a": ("PUBLIC_DEPS emoface::core", ["core"]),
                          "b": ("PUBLIC_DEPS emoface::a", ["a", "core"])}, 0),
        ("upward include", table, {"core": ("", []), "a": ("PUBLIC_DEPS emoface::core", ["b"]),
                                   "b": ("PUBLIC_DEPS emoface::a", [])}, 1),
        ("upward link", table, {"core": ("", []), "a": ("PUBLIC_DEPS emoface::b", []),
                                "b": ("PUBLIC_DEPS emoface::a", [])}, 1),
        ("undeclared use", table, {"core": ("", []), "a": ("PUBLIC_DEPS emoface::core", []),
                                   "b": ("PUBLIC_DEPS emoface::core", ["a"])}, 1),
        ("missing row", {"core": [], "a": ["core"]},
         {"core": ("", []), "a": ("", []), "b": ("", [])}, 1),
        ("cycle", {"core": [], "a": ["core", "b"], "b": ["core", "a"]},
         {"core": ("", []), "a": ("", []), "b": ("", [])}, 1),
    ]
    failed = 0
    for name, tab, libs, expect in cases:
        problems, error = check(tree(tab, libs))
        got = 1 if (problems or error) else 0
        if got != expect:
            print(f"self-test '{name}': expected {'violations' if expect else 'clean'}, got "
                  f"{problems or error or 'clean'}")
            failed += 1
    print(f"check_layering self-test: {len(cases) - failed}/{len(cases)} cases behave")
    return 1 if failed else 0


def main(argv):
    if len(argv) > 1 and argv[1] == "--self-test":
        return self_test()
    root = argv[1] if len(argv) > 1 else os.path.join(os.path.dirname(__file__), "..")
    problems, error = check(os.path.abspath(root))
    if error:
        print(f"check_layering: {error}", file=sys.stderr)
        return 2
    for p in problems:
        print(p)
    if problems:
        print(f"check_layering: {len(problems)} violation(s)", file=sys.stderr)
        return 1
    print("check_layering: every library uses only what docs/architecture.md allows")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
