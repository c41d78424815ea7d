#!/usr/bin/env python3
"""No cycle of #include lines between the files of lib/, tools/ and include/touchdown/, nor between
their folders (lib/util, lib/model, ..., tools/<family>, include/touchdown): a layer includes only
what lies below it, so that each part can be read, tested and replaced on its own.

A quoted include "X" of file F names the first of DIR(F)/X, lib/X (F in lib/), tools/X (F in
tools/), include/X that exists; an include that names none of them (a system or third-party
header) is no edge. Includes inside #if blocks count: every configuration must be free of cycles.
The folder of a file is its first two path parts (lib/sim for lib/sim/parts/dae.c, tools for
tools/main.c).

Usage: include_cycles.py SOURCE_DIR [--level files|folders|both]
         exit 1 and each cycle (its members and one concrete path, with the include lines) if any
       include_cycles.py --self-check
         the check itself, on fixtures/include_cycles/ (two file cycles, one folder cycle)
"""
import os
import re
import sys

sys.dont_write_bytecode = True  # never write __pycache__ into the source tree
import graph  # noqa: E402  (tests/style/graph.py, next to this script)

INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')
TOPS = ("lib", "tools", "include/touchdown")


def sources(src):
    """The .c and .h files under lib/, tools/ and include/touchdown/, relative to src, sorted."""
    found = []
    for top in TOPS:
        for here, dirs, files in os.walk(os.path.join(src, top)):
            dirs.sort()
            for name in files:
                if name.endswith((".c", ".h")):
                    found.append(os.path.relpath(os.path.join(here, name), src))
    return sorted(found)


def resolve(src, including, name):
    """The file (relative to src) that the quoted include NAME of INCLUDING names, or None."""
    roots = [os.path.dirname(including)]
    top = including.split(os.sep)[0]
    if top in ("lib", "tools"):
        roots.append(top)
    roots.append("include")
    for root in roots:
        path = os.path.normpath(os.path.join(root, name))
        if os.path.isfile(os.path.join(src, path)):
            return path
    return None


def include_graph(src):
    files = {}
    for path in sources(src):
        files.setdefault(path, {})
        with open(os.path.join(src, path), encoding="utf-8", errors="replace") as f:
            for number, line in enumerate(f, 1):
                m = INCLUDE.match(line)
                if not m:
                    continue
                target = resolve(src, path, m.group(1))
                if target is not None:
                    graph.add_edge(files, path, target, "%s:%d" % (path, number))
    return files


def folder_of(path):
    parts = path.split(os.sep)
    return os.sep.join(parts[:2]) if len(parts) > 2 else parts[0]


def check(src, level, out):
    """Number of cycles at LEVEL, each reported on out."""
    files = include_graph(src)
    n = 0
    if level in ("files", "both"):
        n += graph.report(files, "files (#include)", out)
    if level in ("folders", "both"):
        n += graph.report(graph.folder_graph(files, folder_of), "folders (#include)", out)
    return n


def self_check():
    """fixtures/include_cycles/: lib/a/one.h -> lib/a/two.h -> lib/a/one.h (a cycle of files in
    one folder), lib/a/x.c -> lib/b/y.h -> lib/a/z.h (no cycle of files, but one of folders
    a <-> b), tools/t.c -> tools/t.h -> tools/t.c's header (include/touchdown/p.h, no cycle) and
    include/touchdown/p.h <-> include/touchdown/q.h (a cycle among the public headers)."""
    import io
    here = os.path.dirname(os.path.abspath(__file__))
    src = os.path.join(here, "fixtures", "include_cycles")
    want = {
        "files": "cycle between files (#include) (2): include/touchdown/p.h, include/touchdown/q.h\n"
                 "  include/touchdown/p.h -> include/touchdown/q.h: include/touchdown/p.h:3\n"
                 "  include/touchdown/q.h -> include/touchdown/p.h: include/touchdown/q.h:3\n"
                 "cycle between files (#include) (2): lib/a/one.h, lib/a/two.h\n"
                 "  lib/a/one.h -> lib/a/two.h: lib/a/one.h:3\n"
                 "  lib/a/two.h -> lib/a/one.h: lib/a/two.h:3\n",
        "folders": "cycle between folders (#include) (2): lib/a, lib/b\n"
                   "  lib/a -> lib/b: lib/a/x.c -> lib/b/y.h (lib/a/x.c:1)\n"
                   "  lib/b -> lib/a: lib/b/y.h -> lib/a/z.h (lib/b/y.h:3)\n",
    }
    for level in ("files", "folders"):
        out = io.StringIO()
        n = check(src, level, out)
        if n == 0 or out.getvalue() != want[level]:
            print("FAIL: at level %s the check reported (%d cycles)\n%s\ninstead of\n%s"
                  % (level, n, out.getvalue(), want[level]))
            return 1
    print("ok:   the check reports the fixtures' two cycles of files and one of folders, "
          "and no other")
    return 0


def main(argv):
    if argv[1:] == ["--self-check"]:
        return self_check()
    if len(argv) not in (2, 4) or (len(argv) == 4 and (argv[2] != "--level" or
                                                      argv[3] not in ("files", "folders", "both"))):
        print(__doc__.strip().split("\n\n")[-1])
        return 2
    src, level = argv[1], argv[3] if len(argv) == 4 else "both"
    n = check(src, level, sys.stdout)
    if n:
        print("%d include cycle(s) at level %s" % (n, level))
        return 1
    print("ok:   no include cycle between %s of lib/, tools/ and include/touchdown/"
          % ("files or folders" if level == "both" else level))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
