#!/usr/bin/env python3
"""Fails on a source path named in src/ or tests/ that does not exist.

Usage: scripts/check_comment_paths.py [ROOT]
Every "src/LAYER/NAME.hpp|cpp" and every "LAYER/NAME.hpp|cpp" whose LAYER is a folder of src/ (in
comments, strings or includes of src/ and tests/) must name a file of ROOT/src. Prints each
offence as 'FILE:LINE: names PATH, which does not exist', then a count; exit status 1 when there is
any, else 0. (A comment pointing at a moved header sends the reader nowhere.)
"""
import os
import re
import sys


def main(argv):
    root = argv[0] if argv else "."
    src = os.path.join(root, "src")
    layers = sorted(d for d in os.listdir(src) if os.path.isdir(os.path.join(src, d)))
    pattern = re.compile(r'(?<![\w/.-])(?:src/)?((?:%s)/[A-Za-z0-9_]+\.(?:hpp|cpp))\b' % "|".join(map(re.escape, layers)))
    bad = 0
    for top in ("src", "tests"):
        for folder, _, files in os.walk(os.path.join(root, top)):
            for name in sorted(files):
                if not name.endswith((".hpp", ".cpp")):
                    continue
                path = os.path.join(folder, name)
                with open(path, encoding="utf-8") as f:
                    for lineno, line in enumerate(f, 1):
                        for m in pattern.finditer(line):
                            if not os.path.exists(os.path.join(src, m.group(1))):
                                print(f"{os.path.relpath(path, root)}:{lineno}: names {m.group(0)}, which does not exist")
                                bad += 1
    print(f"{bad} path(s) named that do not exist")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
