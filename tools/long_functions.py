#!/usr/bin/env python3
"""Lists the C++ functions longer than a limit (default 80 lines): free functions,
methods defined in a class body (at any depth of classes and namespaces),
constructors with initializer lists, operators; a lambda or a local class counts
as part of the function that holds it. A function's length runs from the first
line of its signature (after any `template <...>` line) to its closing brace.

Usage: tools/long_functions.py [--limit N] [--check] [--allow FILE] [PATH...]
  PATH...     files or folders to scan (default: src python/src), *.cpp and *.hpp
  --check     exit 1 if a function over the limit is not in the allow-list
  --allow F   allow-list: one `path:function` a line (`#` starts a comment);
              entries that are no longer over the limit are reported as stale
Run from the repository root."""
import argparse
import os
import re
import sys

OPENS_SCOPE = re.compile(r"\b(namespace|class|struct|union|enum)\b")
# A function head ends with its parameter list, then optional qualifiers, a
# trailing return type, or a constructor's initializer list.
FUNCTION_END = re.compile(
    r"\)\s*(const|volatile|override|final|noexcept(\s*\([^()]*\))?|mutable|&&?|\s)*"
    r"(->\s*[^{};]+)?$")
INITIALIZER_LIST = re.compile(r"\)\s*(noexcept\s*)?:\s*[^;]*[)}]$")
INITIALIZER_OPEN = re.compile(r"\)\s*(noexcept\s*)?:(?!:)\s*[^;]*\w$")
CONTROL = re.compile(r"^\s*(if|for|while|switch|do|else|try|catch)\b")


def strip(text):
    """Comments, string and character literals and preprocessor lines blanked,
    newlines kept (so line numbers stay)."""
    out, i, n = [], 0, len(text)
    at_line_start = True
    while i < n:
        c = text[i]
        if at_line_start and c == "#":
            while i < n and text[i] != "\n":  # a directive, with its continuations
                if text[i] == "\\" and i + 1 < n and text[i + 1] == "\n":
                    out.append("\n")
                    i += 2
                    continue
                i += 1
            continue
        if c == "\n":
            at_line_start = True
            out.append(c)
            i += 1
            continue
        if not c.isspace():
            at_line_start = False
        if text.startswith("//", i):
            while i < n and text[i] != "\n":
                i += 1
        elif text.startswith("/*", i):
            end = text.find("*/", i + 2)
            end = n if end < 0 else end + 2
            out.append("\n" * text.count("\n", i, end))
            i = end
        elif c == "R" and i + 1 < n and text[i + 1] == '"' and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            delim_end = text.find("(", i + 2)
            delim = text[i + 2:delim_end]
            end = text.find(")" + delim + '"', delim_end)
            end = n if end < 0 else end + len(delim) + 2
            out.append('""' + "\n" * text.count("\n", i, end))
            i = end
        elif c == '"' or (c == "'" and not (i > 0 and text[i - 1].isalnum())):
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            out.append(c + c)
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def head_start(head_chars):
    """Index into the head where the signature starts: after access specifiers
    and template parameter lists."""
    text = "".join(ch for ch, _ in head_chars)
    k = 0
    while True:
        m = re.match(r"\s*(public|private|protected)\s*:(?!:)", text[k:])
        if m:
            k += m.end()
            continue
        m = re.match(r"\s*template\s*<", text[k:])
        if m:
            depth, j = 1, k + m.end()
            while j < len(text) and depth:
                depth += {"<": 1, ">": -1}.get(text[j], 0)
                j += 1
            k = j
            continue
        break
    while k < len(text) and text[k].isspace():
        k += 1
    return k


def functions(path):
    """(first line, last line, signature) of every function defined in the file."""
    text = strip(open(path, encoding="utf-8", errors="replace").read())
    stack = []  # per open brace: "scope" (namespace/class/extern), "function" or "block"
    head = []  # (char, line) since the last ; { } at the current level
    line = 1
    found = []
    for c in text:
        if c == "\n":
            line += 1
        if c == "{":
            inside_function = any(kind[0] == "function" for kind in stack)
            h = "".join(ch for ch, _ in head).strip()
            if inside_function:
                stack.append(("block",))
            elif INITIALIZER_OPEN.search(h):  # `S() : a_{1}`: a member's braces, the head goes on
                stack.append(("initializer", head))
                continue
            elif OPENS_SCOPE.search(h) and "(" not in h.split("{")[0] or h.startswith("extern"):
                stack.append(("scope",))
            elif (FUNCTION_END.search(h) or INITIALIZER_LIST.search(h)) and not CONTROL.match(h) \
                    and "=" not in h.split("(")[0]:
                k = head_start(head)
                first = head[k][1] if k < len(head) else line
                signature = " ".join("".join(ch for ch, _ in head[k:]).split())
                stack.append(("function", first, signature))
            else:
                stack.append(("block",))
            head = []
        elif c == "}":
            if stack:
                kind = stack.pop()
                if kind[0] == "function":
                    found.append((kind[1], line, kind[2]))
                if kind[0] == "initializer":
                    head = kind[1] + [("{", line), ("}", line)]
                    continue
            head = []
        elif c == ";":
            head = []
        else:
            head.append((c, line))
    return found


def name_of(signature):
    """The function's qualified name: the identifier before the parameter list."""
    m = re.search(r"((?:[\w~]+::)*(?:operator\s*[^\s(]+|[\w~]+))\s*\(", signature)
    return m.group(1) if m else signature[:60]


def sources(paths):
    for p in paths:
        if os.path.isfile(p):
            yield p
        for root, _, files in os.walk(p):
            for f in sorted(files):
                if f.endswith((".cpp", ".hpp")):
                    yield os.path.join(root, f)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("paths", nargs="*", default=["src", "python/src"])
    ap.add_argument("--limit", type=int, default=80)
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--allow")
    args = ap.parse_args()
    allowed = set()
    if args.allow:
        for raw in open(args.allow, encoding="utf-8"):
            entry = raw.split("#")[0].strip()
            if entry:
                allowed.add(entry)
    long_ones, unexpected, seen = 0, 0, set()
    for path in sorted(set(sources(args.paths))):
        for first, last, signature in functions(path):
            length = last - first + 1
            if length <= args.limit:
                continue
            key = "%s:%s" % (path, name_of(signature))
            seen.add(key)
            long_ones += 1
            mark = " (allowed)" if key in allowed else ""
            unexpected += not mark
            print("%s:%d: %d lines: %s%s" % (path, first, length, name_of(signature), mark))
    for key in sorted(allowed - seen):
        print("stale allow-list entry (no longer over %d lines): %s" % (args.limit, key))
    print("%d functions longer than %d lines, %d not allowed" % (long_ones, args.limit, unexpected))
    return 1 if args.check and unexpected else 0


if __name__ == "__main__":
    sys.exit(main())
