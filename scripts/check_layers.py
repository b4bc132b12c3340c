#!/usr/bin/env python3
"""Fails on an include that runs against the layers of src/.

Usage: scripts/check_layers.py [SRC_DIR] [--rules FILE]
  SRC_DIR  the source tree (default: src)
  --rules  the layers, one per line, lowest first; folders on one line share a layer; '#'
           starts a comment (default: SRC_DIR/layers.txt)
A file in folder F may include "G/x.hpp" only when G's layer is not above F's; a folder that no
layer names is an error too. There are no exceptions. Prints every offence as 'FILE:LINE: includes G/x.hpp (layer F -> G)',
then a count; exit status 1 when there is any, else 0.
"""
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')


def words_per_line(path):
    with open(path) as f:
        for line in f:
            words = line.split("#")[0].split()
            if words:
                yield words


def main(argv):
    src, rules = "src", None
    args = list(argv)
    while args:
        a = args.pop(0)
        if a == "--rules" and args:
            rules = args.pop(0)
        elif a.startswith("-"):
            print(__doc__, file=sys.stderr)
            return 2
        else:
            src = a
    rules = rules or os.path.join(src, "layers.txt")

    rank = {}
    for r, names in enumerate(words_per_line(rules)):
        for name in names:
            rank[name] = r

    offences, unplaced = [], set()
    for root, dirs, files in os.walk(src):
        dirs.sort()
        for name in sorted(files):
            path = os.path.join(root, name)
            rel = os.path.relpath(path, src)
            if os.sep not in rel:
                continue  # files at the top of src/ (the rules) belong to no folder
            folder = rel.split(os.sep)[0]
            if folder not in rank:
                unplaced.add(folder)
                continue
            with open(path, errors="replace") as f:
                for ln, text in enumerate(f, 1):
                    m = INCLUDE.match(text)
                    if not m:
                        continue
                    target = m.group(1)
                    to = target.split("/")[0] if "/" in target else folder
                    if to not in rank or rank[to] <= rank[folder]:
                        continue
                    offences.append(f"{os.path.join(src, rel)}:{ln}: includes {target} (layer {folder} -> {to})")
    for line in offences:
        print(line)
    for folder in sorted(unplaced):
        print(f"{src}/{folder}/: folder on no layer")
    print(f"{len(offences)} upward include(s), {len(unplaced)} unplaced folder(s)")
    return 1 if offences or unplaced else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
