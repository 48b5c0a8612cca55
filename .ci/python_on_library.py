#!/usr/bin/env python3
"""Fail when the Python package goes through the command line instead of the library.

The package binds the library's application layer (`smash::app`): its keyword arguments fill a
command's settings and its reports come back as Python objects. Going up through the CLI again
(an argument list parsed by clap, a `--json` report parsed from text) would make every option
cost a change in four places, which is what the application layer removed. Checked:

- `python/Cargo.toml` has no dependency on the command line's package (`smash-cli`) or on clap;
- the compiled half (`python/src/*.rs`) names no `smash_cli` item, parses no command line
  (`try_parse_from`, `parse_from`) and reads no JSON text (`serde_json::from_str`,
  `from_slice`, `from_reader`);
- the Python half (`python/smash_golf/*.py`) builds no command line (a string starting with
  `--` put into a list, or a helper named `_args`/`_flag`/`argv`) and parses no JSON text
  (`json.loads`, `json.load`).

Prints every place found and exits 1, else prints a summary and exits 0. `--self-test` checks
the checker on small files written to a temporary directory.
"""

import os
import re
import sys
import tempfile

RUST_BANNED = [
    (re.compile(r"\bsmash_cli\b"), "names the command line's crate"),
    (re.compile(r"\btry_parse_from\b|\bparse_from\b"), "parses a command line"),
    (re.compile(r"serde_json::(from_str|from_slice|from_reader)"), "parses JSON text"),
]

PY_BANNED = [
    (re.compile(r"\bjson\.loads?\("), "parses JSON text"),
    (re.compile(r"\bdef (_args|_flag|argv)\b|\bargv\b"), "builds a command line"),
    (re.compile(r"""["']--[a-z][a-z0-9-]*["']\s*[,\]]"""), "puts a command-line flag in a list"),
]


def dependencies(cargo_toml):
    """The names of the `[dependencies]` table's entries."""
    names, table = [], None
    with open(cargo_toml, encoding="utf-8") as f:
        for line in f:
            s = line.strip()
            if s.startswith("["):
                table = s.strip("[]").strip()
                continue
            if table in ("dependencies", "build-dependencies") and "=" in s and not s.startswith("#"):
                names.append(s.split("=", 1)[0].strip().strip('"'))
    return names


def scan(path, banned, strip_comment):
    found = []
    with open(path, encoding="utf-8") as f:
        for n, line in enumerate(f, 1):
            code = strip_comment(line)
            for pattern, what in banned:
                if pattern.search(code):
                    found.append(f"{path}:{n}: {what}: {line.strip()}")
    return found


def rust_code(line):
    return line.split("//", 1)[0]


def python_code(line):
    s = line.lstrip()
    return "" if s.startswith("#") else line


def check(root):
    problems = []
    cargo = os.path.join(root, "python", "Cargo.toml")
    for dep in dependencies(cargo):
        if dep in ("smash-cli", "clap"):
            problems.append(f"{cargo}: depends on {dep}")
    for sub, ext, banned, strip in [
        (os.path.join("python", "src"), ".rs", RUST_BANNED, rust_code),
        (os.path.join("python", "smash_golf"), ".py", PY_BANNED, python_code),
    ]:
        d = os.path.join(root, sub)
        for name in sorted(os.listdir(d)):
            if name.endswith(ext):
                problems += scan(os.path.join(d, name), banned, strip)
    return problems


def self_test():
    with tempfile.TemporaryDirectory() as root:
        os.makedirs(os.path.join(root, "python", "src"))
        os.makedirs(os.path.join(root, "python", "smash_golf"))

        def write(rel, text):
            with open(os.path.join(root, rel), "w", encoding="utf-8") as f:
                f.write(text)

        write("python/Cargo.toml", '[dependencies]\nsmash = { path = ".." }\n')
        write("python/src/lib.rs", "// smash_cli was here once\nuse smash::app;\n")
        write("python/smash_golf/__init__.py", "# json.loads in a comment\nx = {'alpha': 1}\n")
        assert check(root) == [], check(root)
        write("python/Cargo.toml", '[dependencies]\nsmash-cli = { path = "../cli" }\n')
        write("python/src/lib.rs", "let r: V = serde_json::from_str(&s)?;\n")
        write("python/smash_golf/__init__.py", "args = ['--alpha', '0.1']\nout = json.loads(t)\n")
        got = check(root)
        assert len(got) == 4, got
    print("python_on_library: self-test passed")


def main():
    if "--self-test" in sys.argv[1:]:
        self_test()
        return 0
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    problems = check(root)
    for p in problems:
        print(p)
    if problems:
        return 1
    print("python_on_library: the Python package binds the library (no CLI, no argv, no JSON text)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
