#!/usr/bin/env python3
"""No cycle of calls (or data references) between the source files of a target, nor between their
folders: file A uses file B when A's object file leaves a symbol undefined (nm type U) that B's
object file defines (T, D, B, R and the other global definitions). Static functions are not seen,
which is fine: what must have no cycle is the use of one file by another.

The object files are those CMake compiles for TARGET (default touchdown_objects, the library) into
a folder TARGET.dir somewhere under BUILD_DIR; CMake mirrors the source tree there
(CMakeFiles/touchdown_objects.dir/lib/sim/sim.c.o is lib/sim/sim.c). Only sources under PREFIX
(default lib/) count. The folder of a file is its first two path parts (lib/sim).

Usage: call_cycles.py BUILD_DIR [--nm NM] [--target TARGET] [--prefix PREFIX]
                      [--level files|folders|both]
         exit 1 and each cycle (its members and one concrete path, with the symbols) if any;
         exit 2 when no object file of TARGET is found
       call_cycles.py --self-check CC NM
         the check itself: compiles fixtures/call_cycles/ with CC into a layout like CMake's and
         expects its cycles (one of three files, one of two folders) and no other
"""
import os
import subprocess
import sys

sys.dont_write_bytecode = True  # never write __pycache__ into the source tree
import graph  # noqa: E402  (tests/style/graph.py, next to this script)

OBJECT_SUFFIXES = (".o", ".obj")
# nm's kinds of a global symbol: used but not defined here (U; w and v are weak references), or
# defined here (text, data, bss, read-only, common, small data, weak definitions, GNU unique, ifunc)
USED = frozenset("Uwv")
DEFINED = frozenset("TDBRCGSVWui")


def cmake_source_dir(build):
    """The source tree of a CMake build (CMakeCache.txt's CMAKE_HOME_DIRECTORY), or None."""
    try:
        with open(os.path.join(build, "CMakeCache.txt")) as cache:
            for line in cache:
                if line.startswith("CMAKE_HOME_DIRECTORY:"):
                    return line.split("=", 1)[1].strip()
    except OSError:
        pass
    return None


def object_files(build, target, prefix):
    """{source path: object path} of TARGET's objects under BUILD_DIR whose source is under PREFIX.
    Raises SystemExit(2) when the target's folder is missing or found twice."""
    homes = []
    for here, dirs, _ in os.walk(build):
        dirs.sort()
        if os.path.basename(here) == target + ".dir":
            homes.append(here)
            dirs[:] = []
    if len(homes) != 1:
        sys.stderr.write("call_cycles: %s folder(s) %s.dir under %s (want one)%s\n"
                         % (len(homes) or "no", target, build,
                            "".join("\n  " + h for h in homes)))
        raise SystemExit(2)
    source_dir = cmake_source_dir(build)
    objects = {}
    for here, dirs, files in os.walk(homes[0]):
        dirs.sort()
        for name in files:
            for suffix in OBJECT_SUFFIXES:
                if name.endswith(suffix):
                    path = os.path.join(here, name)
                    source = os.path.relpath(path, homes[0])[: -len(suffix)]
                    # an object left by a source since moved or removed is not the target's
                    gone = source_dir and not os.path.exists(os.path.join(source_dir, source))
                    if source.startswith(prefix.rstrip("/") + "/") and not gone:
                        objects[source] = path
    if not objects:
        sys.stderr.write("call_cycles: no object file of a source under %s in %s\n"
                         % (prefix, homes[0]))
        raise SystemExit(2)
    return objects


def symbols(nm, path):
    """(defined, undefined): the sets of global symbols an object file defines and uses."""
    text = subprocess.run([nm, "-P", "-g", path], check=True, stdout=subprocess.PIPE,
                          universal_newlines=True).stdout
    defined, undefined = set(), set()
    for line in text.splitlines():
        fields = line.split()
        if len(fields) < 2:
            continue
        name, kind = fields[0], fields[1]
        if kind in USED:
            undefined.add(name)
        elif kind in DEFINED:
            defined.add(name)
    return defined, undefined


def call_graph(objects, nm):
    table = {source: symbols(nm, path) for source, path in objects.items()}
    definer = {}
    for source, (defined, _) in table.items():
        for name in defined:
            definer.setdefault(name, []).append(source)
    files = {source: {} for source in table}
    for source, (_, undefined) in table.items():
        for name in undefined:
            for other in definer.get(name, []):
                graph.add_edge(files, source, other, name)
    return files


def folder_of(path):
    parts = path.split("/")
    return "/".join(parts[:2]) if len(parts) > 2 else parts[0]


def check(build, nm, target, prefix, level, out):
    files = call_graph(object_files(build, target, prefix), nm)
    n = 0
    if level in ("files", "both"):
        n += graph.report(files, "files (calls)", out)
    if level in ("folders", "both"):
        n += graph.report(graph.folder_graph(files, folder_of), "folders (calls)", out)
    return n, len(files)


SELF_CHECK_WANT = {
    "files": "cycle between files (calls) (3): lib/a/flight.c, lib/a/modes.c, lib/a/section.c\n"
             "  lib/a/flight.c -> lib/a/modes.c: fx_mode_step\n"
             "  lib/a/modes.c -> lib/a/section.c: fx_section_cross\n"
             "  lib/a/section.c -> lib/a/flight.c: fx_flight_at\n"
             "  also lib/a/section.c -> lib/a/modes.c: fx_mode_step\n",
    "folders": "cycle between folders (calls) (2): lib/a, lib/b\n"
               "  lib/a -> lib/b: lib/a/user.c -> lib/b/table.c (fx_table)\n"
               "  lib/b -> lib/a: lib/b/table.c -> lib/a/leaf.c (fx_leaf_value)\n",
}


def self_check(cc, nm):
    """fixtures/call_cycles/: flight.c -> modes.c -> section.c -> flight.c (a cycle of files in one
    folder, through functions, with one more edge inside it: section.c -> modes.c); a/user.c -> b/table.c (data) -> a/leaf.c (no cycle of files, but
    one of folders); lib/a/leaf.c and lib/b/table.c both define a static fx_hidden (no edge); an
    object of another target (other.dir) that would close more cycles is not read."""
    import io
    import tempfile
    here = os.path.dirname(os.path.abspath(__file__))
    fixtures = os.path.join(here, "fixtures", "call_cycles")
    with tempfile.TemporaryDirectory() as build:
        for target, source in [("touchdown_objects", s) for s in
                               ("lib/a/flight.c", "lib/a/modes.c", "lib/a/section.c",
                                "lib/a/user.c", "lib/a/leaf.c", "lib/b/table.c")] + \
                              [("other", "lib/b/decoy.c")]:
            obj = os.path.join(build, "CMakeFiles", target + ".dir", source + ".o")
            os.makedirs(os.path.dirname(obj), exist_ok=True)
            subprocess.run([cc, "-std=c99", "-O0", "-c", os.path.join(fixtures, source), "-o", obj],
                           check=True)
        for level in ("files", "folders"):
            out = io.StringIO()
            n, nodes = check(build, nm, "touchdown_objects", "lib", level, out)
            if nodes != 6 or n == 0 or out.getvalue() != SELF_CHECK_WANT[level]:
                print("FAIL: at level %s the check read %d files and reported (%d cycles)\n%s\n"
                      "instead of\n%s" % (level, nodes, n, out.getvalue(), SELF_CHECK_WANT[level]))
                return 1
    print("ok:   the check reports the fixtures' cycle of three files and of two folders, "
          "and no other")
    return 0


def main(argv):
    args = argv[1:]
    if args[:1] == ["--self-check"]:
        if len(args) != 3:
            print("usage: call_cycles.py --self-check CC NM")
            return 2
        return self_check(args[1], args[2])
    if not args or args[0].startswith("--"):
        print(__doc__.strip().split("\n\n")[-1])
        return 2
    build, options = args[0], {"--nm": "nm", "--target": "touchdown_objects", "--prefix": "lib",
                               "--level": "both"}
    rest = args[1:]
    while rest:
        if len(rest) < 2 or rest[0] not in options:
            print(__doc__.strip().split("\n\n")[-1])
            return 2
        options[rest[0]] = rest[1]
        rest = rest[2:]
    level = options["--level"]
    if level not in ("files", "folders", "both"):
        print("call_cycles: --level is files, folders or both, not %s" % level)
        return 2
    n, nodes = check(build, options["--nm"], options["--target"], options["--prefix"], level,
                     sys.stdout)
    if n:
        print("%d call cycle(s) at level %s among %d files of %s/" % (n, level, nodes,
                                                                    options["--prefix"]))
        return 1
    print("ok:   no call cycle between %s of the %d files of %s/ in %s"
          % ("files or folders" if level == "both" else level, nodes, options["--prefix"],
             options["--target"]))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
