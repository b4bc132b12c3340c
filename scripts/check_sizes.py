#!/usr/bin/env python3
"""Fails on a source file or a function that has grown past what one reads at once.

Usage: scripts/check_sizes.py [SRC_DIR] [--max-file N] [--max-function N]
  SRC_DIR         the source tree (default: src)
  --max-file      most lines a .cpp/.hpp file may have (default: 600)
  --max-function  most lines of code a function may have, signature to closing brace, blank
                  lines and lines of comment only not counted (default: 80)
A function is a brace block opened at namespace or class scope after a parenthesised parameter
list: free functions, member functions in or out of their class, templates, constructors (their
initialiser lists included) and function-like macros such as PYBIND11_MODULE. A lambda given to a
variable at namespace scope is not one. ALLOWED names the data tables that may be longer: a table
is one entry a line, and cutting it in parts would only scatter it.
Prints every offence as 'FILE:LINE: ...', then a count; exit status 1 when there is any, else 0.
"""
import os
import re
import sys

# (file relative to SRC_DIR, function name): data tables, one entry a line.
ALLOWED = {
    ("python/module.cpp", "PYBIND11_MODULE"),  # the pybind11 binding table
    ("scene/scene_keys.cpp", "make_table"),  # the scene key table
}

SCOPE_WORDS = re.compile(r"\b(namespace|class|struct|union|enum)\b")
NOT_FUNCTION = re.compile(r"\b(if|for|while|switch|catch|do|else|return)\b")


def blank_out(text):
    """The text with comments blanked, and string and character literals and preprocessor lines
    emptied but for their first character (newlines kept): braces and parentheses in them do not
    count, and a line that holds only a comment is blank."""
    out = []
    i, n = 0, len(text)
    at_line_start = True
    while i < n:
        c = text[i]
        if at_line_start and c == "#" or (at_line_start and c in " \t" and text[i:].lstrip(" \t").startswith("#")):
            j = i
            while j < n:  # a directive, continued by a backslash at the end of a line
                k = text.find("\n", j)
                if k < 0:
                    k = n
                if k > 0 and text[k - 1] == "\\":
                    j = k + 1
                    continue
                break
            out.append("#" + re.sub(r"[^\n]", " ", text[i + 1:k]))  # still a line of code
            i = k
            continue
        if text.startswith("//", i):
            k = text.find("\n", i)
            k = n if k < 0 else k
            out.append(" " * (k - i))
            i = k
            continue
        if text.startswith("/*", i):
            k = text.find("*/", i + 2)
            k = n if k < 0 else k + 2
            out.append(re.sub(r"[^\n]", " ", text[i:k]))
            i = k
            continue
        raw = re.match(r'R"([^(\s]*)\(', text[i:i + 20])
        if raw and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            end = text.find(")" + raw.group(1) + '"', i)
            k = n if end < 0 else end + len(raw.group(1)) + 2
            out.append("R" + re.sub(r"[^\n]", " ", text[i + 1:k]))
            i = k
            continue
        if c in "\"'":
            if c == "'" and i > 0 and text[i - 1].isalnum() and i + 1 < n and text[i + 1].isalnum():
                out.append(" ")  # a digit separator, 1'000
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            out.append(c + " " * (min(j + 1, n) - i - 1))
            i = j + 1
            continue
        out.append(c)
        at_line_start = c == "\n" or (at_line_start and c in " \t")
        i += 1
    return "".join(out)


def function_name(header):
    """The name a function header declares, e.g. 'EventIntegrator<Junctions>::advance'."""
    h = re.sub(r"\s+", " ", header).strip()
    h = re.sub(r"^template\s*<.*?>\s*(?=[A-Za-z_])", "", h)  # the outer template parameters
    m = re.search(r"operator\s*(\(\)|[^\s(]+)\s*\(", h)
    if m:
        head = h[:m.end() - 1]
    else:
        depth, cut = 0, len(h)
        for k, ch in enumerate(h):
            if ch == "<":
                depth += 1
            elif ch == ">":
                depth -= 1
            elif ch == "(" and depth <= 0:
                cut = k
                break
        head = h[:cut]
    # The last word of the head at template depth 0: the qualified name, without the return type.
    head = head.strip()
    depth, k = 0, len(head)
    while k > 0:
        ch = head[k - 1]
        if ch == ">":
            depth += 1
        elif ch == "<":
            depth -= 1
        elif ch.isspace() and depth == 0 and not head[:k].rstrip().endswith("operator"):
            break
        k -= 1
    return head[k:]


def matching_brace(code, i):
    """Index of the brace closing the one at code[i] (len(code) when unclosed)."""
    depth = 0
    for j in range(i, len(code)):
        if code[j] == "{":
            depth += 1
        elif code[j] == "}":
            depth -= 1
            if depth == 0:
                return j
    return len(code)


def functions(text):
    """(name, first line, lines of code) of each function defined in `text`, outermost only."""
    code = blank_out(text)
    line_of = [0] * (len(code) + 1)
    line = 1
    for k, ch in enumerate(code):
        line_of[k] = line
        if ch == "\n":
            line += 1
    line_of[len(code)] = line
    found = []
    stack = []  # 'scope' (namespace, class, extern block) or 'other'
    start = 0  # where the text before the next brace begins
    i, n = 0, len(code)
    while i < n:
        ch = code[i]
        if ch in ";":
            start = i + 1
        elif ch == "}":
            if stack:
                stack.pop()
            start = i + 1
        elif ch == "{":
            header = code[start:i]
            at_scope = all(s == "scope" for s in stack)
            label = re.sub(r"^\s*(public|private|protected)\s*:", "", header)
            if not at_scope:
                stack.append("other")
                start = i + 1
            elif SCOPE_WORDS.search(label) and "(" not in label.split("{")[0] or re.match(r"\s*extern\s*$", label):
                stack.append("scope")
                start = i + 1
            elif "(" in label and ")" in label and not NOT_FUNCTION.search(label.split("(")[0]) and "=" not in label.split("(")[0].replace("operator", "").replace("==", ""):
                # A constructor's initialiser list may hold braces (x_{1}, a lambda inside an
                # argument list): they belong to the header.
                in_init_list = re.search(r"\)\s*(noexcept\s*)?:[^:]", label)
                open_parens = label.count("(") - label.count(")")
                if in_init_list and (open_parens > 0 or re.search(r"[\w>]\s*$", label)):
                    i = matching_brace(code, i) + 1
                    continue
                # The body: to its matching brace.
                j = matching_brace(code, i)
                first = start + (len(header) - len(header.lstrip()))
                last = min(j, n)
                code_lines = sum(1 for ln in code[first:last + 1].split("\n") if ln.strip())
                found.append((function_name(label), line_of[first], code_lines))
                i = j + 1
                start = i
                continue
            else:
                stack.append("other")
                start = i + 1
        i += 1
    return found


def main(argv):
    src, max_file, max_function = "src", 600, 80
    args = list(argv)
    while args:
        a = args.pop(0)
        if a == "--max-file" and args:
            max_file = int(args.pop(0))
        elif a == "--max-function" and args:
            max_function = int(args.pop(0))
        elif a.startswith("-"):
            print(__doc__, file=sys.stderr)
            return 2
        else:
            src = a
    offences = []
    for root, dirs, files in os.walk(src):
        dirs.sort()
        for name in sorted(files):
            if not name.endswith((".cpp", ".hpp", ".h", ".cc")):
                continue
            path = os.path.join(root, name)
            rel = os.path.relpath(path, src).replace(os.sep, "/")
            with open(path, encoding="utf-8", errors="replace") as f:
                text = f.read()
            lines = text.count("\n") + (0 if text.endswith("\n") or not text else 1)
            if lines > max_file:
                offences.append(f"{path}:1: file of {lines} lines (at most {max_file})")
            for fn, first, length in functions(text):
                if length > max_function and (rel, fn.split("::")[-1]) not in ALLOWED and (rel, fn) not in ALLOWED:
                    offences.append(f"{path}:{first}: {fn} has {length} lines of code (at most {max_function})")
    for o in offences:
        print(o)
    print(f"{len(offences)} file(s) or function(s) over the limits")
    return 1 if offences else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
