#!/usr/bin/env python3
"""List Rust functions longer than 120 lines and files longer than 600 lines that do not state
why in a `//! Size:` line of their header.

Run by .ci/run as a gate: exits 1 when anything is listed. Braces are counted outside comments, strings, raw
strings and char literals; a function runs from its `fn` line to its closing brace.

Usage: python3 .ci/function_length.py [--max-fn 120] [--max-file 600] [ROOT ...]
"""
import argparse
import os
import re
import sys

from rust_source import code_only

FN = re.compile(r"\bfn\s+([A-Za-z_][A-Za-z0-9_]*)")


def functions(text):
    """(name, first line, line count) of every function with a body."""
    code = code_only(text)
    found = []
    for m in FN.finditer(code):
        # The body starts at the first `{` after the signature, unless a `;` comes first
        # (a trait method or extern declaration without a body).
        j = m.end()
        depth_paren = 0
        while j < len(code):
            ch = code[j]
            if ch in "([<":
                depth_paren += 1
            elif ch in ")]>":
                depth_paren -= 1
            elif ch == ";" and depth_paren <= 0:
                j = -1
                break
            elif ch == "{" and depth_paren <= 0:
                break
            j += 1
        if j < 0 or j >= len(code):
            continue
        depth, k = 0, j
        while k < len(code):
            if code[k] == "{":
                depth += 1
            elif code[k] == "}":
                depth -= 1
                if depth == 0:
                    break
            k += 1
        first = code.count("\n", 0, m.start()) + 1
        last = code.count("\n", 0, k) + 1
        found.append((m.group(1), first, last - first + 1))
    return found


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--max-fn", type=int, default=120)
    ap.add_argument("--max-file", type=int, default=600)
    ap.add_argument("roots", nargs="*", default=["src", "cli/src"])
    a = ap.parse_args()
    os.chdir(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    long_fns, long_files = [], []
    for root in a.roots:
        for dirpath, _, names in os.walk(root):
            for name in sorted(names):
                if not name.endswith(".rs"):
                    continue
                path = os.path.join(dirpath, name)
                text = open(path, encoding="utf-8").read()
                n_lines = text.count("\n")
                header = "\n".join(l for l in text.splitlines()[:40] if l.startswith("//!"))
                if n_lines > a.max_file and "//! Size:" not in header:
                    long_files.append((n_lines, path))
                for fname, first, count in functions(text):
                    if count > a.max_fn:
                        long_fns.append((count, f"{path}:{first}", fname))
    for count, where, fname in sorted(long_fns, reverse=True):
        print(f"function {fname} ({where}): {count} lines > {a.max_fn}")
    for n_lines, path in sorted(long_files, reverse=True):
        print(f"file {path}: {n_lines} lines > {a.max_file} without a `//! Size:` reason")
    print(f"{len(long_fns)} long function(s), {len(long_files)} long file(s) without a reason")
    return 1 if long_fns or long_files else 0


if __name__ == "__main__":
    sys.exit(main())
