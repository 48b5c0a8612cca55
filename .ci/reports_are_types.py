#!/usr/bin/env python3
"""Fail when a JSON report is built as a `json!` tree instead of serialised from its type.

Every command's `--json` is the serde form of its report type (a view model filled once with
its verdicts, `src/report/views.rs` and the reports beside it), so the JSON, the text and the
HTML read one value and `docs/json.md` describes types, not hand-built trees. Checked: no
`json!` macro in the code of the library (`src/`), the command line (`cli/src/`) or the Python
module (`python/src/`); comments and strings do not count.

Prints every place found and exits 1, else prints a summary and exits 0. `--self-test` checks
the checker on a small file written to a temporary directory.
"""

import os
import re
import sys
import tempfile

from rust_source import code_only

MACRO = re.compile(r"\bjson!\s*[\(\[\{]")


def check(root, dirs=("src", os.path.join("cli", "src"), os.path.join("python", "src"))):
    found, files = [], 0
    for d in dirs:
        for base, _, names in os.walk(os.path.join(root, d)):
            for name in sorted(names):
                if not name.endswith(".rs"):
                    continue
                path = os.path.join(base, name)
                files += 1
                with open(path, encoding="utf-8") as f:
                    code = code_only(f.read())
                for n, line in enumerate(code.split("\n"), 1):
                    if MACRO.search(line):
                        found.append(f"{path}:{n}: a report built with json!")
    return found, files


def self_test():
    with tempfile.TemporaryDirectory() as root:
        os.makedirs(os.path.join(root, "src"))
        path = os.path.join(root, "src", "a.rs")
        with open(path, "w", encoding="utf-8") as f:
            f.write('// json!({"a": 1}) in a comment\nlet s = "json!({})";\n')
        assert check(root, ("src",))[0] == []
        with open(path, "a", encoding="utf-8") as f:
            f.write('let v = serde_json::json!({"a": 1});\n')
        got = check(root, ("src",))[0]
        assert len(got) == 1 and got[0].endswith(":3: a report built with json!"), got
    print("reports_are_types: self-test passed")


def main():
    if "--self-test" in sys.argv[1:]:
        self_test()
        return 0
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    found, files = check(root)
    for p in found:
        print(p)
    if found:
        return 1
    print(f"reports_are_types: no json! tree in {files} Rust files; every report is a type")
    return 0


if __name__ == "__main__":
    sys.exit(main())
