#!/usr/bin/env python3
"""Fails on a relative link of README.md or docs/*.md that leads nowhere.

Usage: scripts/check_doc_links.py [ROOT]
Each [text](target) whose target is not a URL must name an existing file, and a #anchor in it a
heading of that Markdown file (GitHub's rule: lower case, punctuation dropped, spaces to '-').
Prints 'FILE: link TARGET: why' per offence, then a count; exit status 1 when there is any.
"""
import os
import re
import sys


def anchors(path):
    out, fence = set(), False
    with open(path, encoding="utf-8") as f:
        for line in f:
            if line.startswith("```"):
                fence = not fence
            m = re.match(r"^#{1,6} (.*)", line)
            if m and not fence:
                out.add(re.sub(r"[^\w\- ]", "", m.group(1).strip().lower()).replace(" ", "-"))
    return out


def main(argv):
    root = argv[0] if argv else "."
    files = ["README.md"] + sorted(os.path.join("docs", x) for x in os.listdir(os.path.join(root, "docs")) if x.endswith(".md"))
    bad = 0
    for f in files:
        with open(os.path.join(root, f), encoding="utf-8") as fh:
            text = fh.read()
        for m in re.finditer(r"\]\(([^)\s]+)\)", text):
            target = m.group(1)
            if re.match(r"^[a-z]+://", target) or target.startswith("mailto:"):
                continue
            path, _, anchor = target.partition("#")
            full = os.path.normpath(os.path.join(root, os.path.dirname(f), path)) if path else os.path.join(root, f)
            why = None
            if not os.path.exists(full):
                why = "no such file"
            elif anchor and full.endswith(".md") and anchor not in anchors(full):
                why = "no such heading"
            if why:
                print(f"{f}: link {target}: {why}")
                bad += 1
    print(f"{bad} broken link(s)")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
