#!/usr/bin/env python3
"""The tool reads result files only through the library's read API (touchdown/result.h): no file
under tools/ includes an HDF5 header (hdf5.h, hdf5_hl.h, H5*.h) or names an HDF5 function, constant
or type (H5*, hid_t, herr_t, hsize_t, ...). The names the file format uses are then declared in one
place, the library's output schema, and a change of the format cannot leave the tool behind.

Comments and string literals are not code: a comment may say "HDF5" and a message may name a file
kind. An include inside #if counts (every configuration is checked).

Usage: tools_results.py SOURCE_DIR
         exit 1 and one line per offending line (FILE:LINE: what it uses) if any
       tools_results.py --self-check
         the check itself, on fixtures/tools_results/ (two offending files, one clean one)
"""
import os
import re
import sys

HEADER = re.compile(r'^\s*#\s*include\s*[<"]((?:hdf5[A-Za-z0-9_]*|H5[A-Za-z0-9_]*)\.h)[>"]')
NAME = re.compile(r"\b(H5[A-Za-z0-9_]*|h(?:id|err|size|ssize|addr|tri|bool)_t)\b")
# a comment, a string or character literal, or anything else, in the order they come
LEXEME = re.compile(r'/\*.*?\*/|//[^\n]*|"(?:\\.|[^"\\\n])*"|\'(?:\\.|[^\'\\\n])*\'|[^/"\']+|.',
                    re.S)


def code_only(text):
    """text with comments and literals blanked, line breaks kept (so line numbers stay)."""
    def blank(m):
        s = m.group(0)
        if s.startswith(("/*", "//", '"', "'")):
            return re.sub(r"[^\n]", " ", s)
        return s
    return LEXEME.sub(blank, text)


def findings(src):
    """One line "FILE:LINE: what" per offending line of SRC/tools/**.{c,h}, sorted by file."""
    found = []
    for here, dirs, files in os.walk(os.path.join(src, "tools")):
        dirs.sort()
        for name in sorted(files):
            if not name.endswith((".c", ".h")):
                continue
            path = os.path.join(here, name)
            rel = os.path.relpath(path, src)
            with open(path, encoding="utf-8", errors="replace") as f:
                text = f.read()
            raw = text.split("\n")
            for number, line in enumerate(code_only(text).split("\n"), 1):
                m = HEADER.match(raw[number - 1])
                if m:
                    found.append("%s:%d: includes %s" % (rel, number, m.group(1)))
                    continue
                names = sorted(set(NAME.findall(line)))
                if names:
                    found.append("%s:%d: uses %s" % (rel, number, ", ".join(names)))
    return sorted(found, key=lambda s: (s.split(":")[0], int(s.split(":")[1])))


def self_check():
    here = os.path.dirname(os.path.abspath(__file__))
    got = findings(os.path.join(here, "fixtures", "tools_results"))
    want = ["tools/plot/reader.c:2: includes hdf5.h",
            "tools/plot/reader.c:8: uses H5F_ACC_RDONLY, H5Fopen, H5P_DEFAULT, hid_t",
            "tools/plot/reader.c:9: uses H5Fclose",
            "tools/scales.h:4: includes hdf5_hl.h"]
    if got != want:
        print("FAIL: the check reported\n%s\ninstead of\n%s" % ("\n".join(got), "\n".join(want)))
        return 1
    print("ok:   the check reports the fixtures' HDF5 includes and calls, not the names in "
          "comments and strings")
    return 0


def main(argv):
    if argv[1:] == ["--self-check"]:
        return self_check()
    if len(argv) != 2 or argv[1].startswith("--"):
        print(__doc__.strip().split("\n\n")[-1])
        return 2
    found = findings(argv[1])
    for line in found:
        print(line)
    if found:
        print("%d line(s) of %d file(s) under tools/ use HDF5 directly: read results through "
              "touchdown/result.h" % (len(found), len({f.split(":")[0] for f in found})))
        return 1
    print("ok:   no file under tools/ uses HDF5 directly")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
