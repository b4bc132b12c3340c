#!/usr/bin/env python3
"""Fails on a source path named in src/ or tests/ that does not exist.

Usage: scripts/check_comment_paths.py [ROOT]
Every "src/LAYER/NAME.hpp|cpp" and every "LAYER/NAME.hpp|cpp" whose LAYER is a folder of src/ (in
comments, strings or includes of src/ and tests/) must name a file of ROOT/src. Prints each
offence as 'FILE:LINE: names PATH, which does not exist', then a count; exit status 1 when there is
any, else 0. (A comment pointing at a moved header sends the reader nowhere.) Likewise every
"docs/NAME.md §N" must name a file of ROOT/docs with a heading "## N.", and a comment cites the
model as docs/model.md, not as "MODEL.md". In every text file of src/, tests/, bench/ and
scripts/ (sources, scripts, YAML, Markdown; comments and strings alike), a section of the model
is cited as "docs/model.md §N", never by the old name "MODEL.md" followed by a section sign, and
each N of "docs/model.md §N" (and of a list that follows it: "§2 and §7", "§2/§7", "§2, §7")
must be a heading "## N." of ROOT/docs/model.md.
"""
import os
import re
import sys


def main(argv):
    root = argv[0] if argv else "."
    src = os.path.join(root, "src")
    layers = sorted(d for d in os.listdir(src) if os.path.isdir(os.path.join(src, d)))
    section = re.compile(r'(?<![\w/.-])docs/([A-Za-z0-9_-]+\.md) §(\d+)')
    bare_model = re.compile(r'(?<![\w/.-])MODEL\.md')
    headings = {}

    def has_section(doc, number):
        if doc not in headings:
            try:
                with open(os.path.join(root, "docs", doc), encoding="utf-8") as f:
                    headings[doc] = {m.group(1) for m in re.finditer(r'^## (\d+)\.', f.read(), re.M)}
            except OSError:
                headings[doc] = None
        return headings[doc] is not None and number in headings[doc]

    pattern = re.compile(r'(?<![\w/.-])(?:src/)?((?:%s)/[A-Za-z0-9_]+\.(?:hpp|cpp))\b' % "|".join(map(re.escape, layers)))
    bad = 0
    for top in ("src", "tests", "bench"):
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
                        for m in section.finditer(line):
                            if not has_section(m.group(1), m.group(2)):
                                print(f"{os.path.relpath(path, root)}:{lineno}: names {m.group(0)}, which does not exist")
                                bad += 1
                        comment = line[line.index("//"):] if "//" in line else ""
                        if bare_model.search(comment):  # (strings and other files: check_model_citations)
                            print(f"{os.path.relpath(path, root)}:{lineno}: cites MODEL.md; cite docs/model.md §N")
                            bad += 1
    bad += check_model_citations(root, has_section)
    print(f"{bad} path(s) or citation(s) that do not hold")
    return 1 if bad else 0


TEXT_SUFFIXES = (".hpp", ".cpp", ".h", ".py", ".sh", ".yaml", ".yml", ".md", ".txt", ".cmake", ".gp", ".in")


def check_model_citations(root, has_section):
    """The model's sections cited by their file, docs/model.md; each cited section exists."""
    old_name = re.compile(r'(?<![\w/.-])MODEL\.md ?§')
    cited = re.compile(r'(?<![\w/.-])docs/model\.md §(\d+)((?:(?:,| and| or|/|–| to) ?§\d+)*)')
    bad = 0
    for top in ("src", "tests", "bench", "scripts"):
        for folder, dirs, files in os.walk(os.path.join(root, top)):
            dirs.sort()
            for name in sorted(files):
                if not name.endswith(TEXT_SUFFIXES):
                    continue
                path = os.path.join(folder, name)
                rel = os.path.relpath(path, root)
                covered = top != "scripts" and name.endswith((".hpp", ".cpp"))
                try:
                    with open(path, encoding="utf-8") as f:
                        lines = f.readlines()
                except (OSError, UnicodeDecodeError):
                    continue
                for lineno, line in enumerate(lines, 1):
                    comment = line[line.index("//"):] if "//" in line else ""
                    if old_name.search(line) and not (covered and re.search(r'(?<![\w/.-])MODEL\.md', comment)):
                        print(f"{rel}:{lineno}: cites the model as MODEL.md; cite docs/model.md §N")
                        bad += 1
                    for m in cited.finditer(line):
                        # The first number of a C++ file of src/, tests/ or bench/ is main's to check.
                        first = [] if covered else [m.group(1)]
                        for number in first + re.findall(r'§(\d+)', m.group(2)):
                            if not has_section("model.md", number):
                                print(f"{rel}:{lineno}: cites docs/model.md §{number}, which docs/model.md does not have")
                                bad += 1
    return bad


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
