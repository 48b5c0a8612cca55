#!/usr/bin/env python3
"""Fail when a binary calls a `core::core_arch` intrinsic as a function.

The hot loops (the fits' batched solve, the face-map kernel, the flight integrator) are written
once over lane types and compiled inside `#[target_feature(enable = "avx2")]` and
`#[target_feature(enable = "avx512f")]` entry points. A lane operation is `#[inline(always)]`
and the intrinsic it calls (`_mm256_mul_pd`, `_mm512_add_pd`, ...) can only be inlined into a
function compiled with that feature: inside a closure, an iterator adaptor or a generic callback
(which do not inherit `#[target_feature]`) it stays an out-of-line function, and every vector
multiply becomes a call with its operands spilled to the stack. The code still gives the same
bits, so no test of results sees it; only the machine code does. This check reads the machine
code (`objdump -d`) and counts every `call` whose target is in `core::core_arch`.

One target is allowed: the CPU feature detection's `_xgetbv` (std_detect reads the XCR0
register once, not in a loop).

Usage: no_outlined_intrinsics.py [--warn-only] BINARY [BINARY ...]
Prints the count per calling function and exits 1 if any call is found (0 with `--warn-only`,
after a loud warning); prints a summary and exits 0 otherwise. Exits 2 when objdump is missing
or a binary cannot be read (a check that cannot run must not pass).
"""

import collections
import re
import shutil
import subprocess
import sys

ALLOWED = ("_xgetbv",)
FUNCTION = re.compile(r"^[0-9a-f]+ <(.*)>:$")
CALL = re.compile(r"\bcall\S*\s+[0-9a-f]+ <(.*)>")


def outlined_calls(binary):
    """(calling function, called intrinsic) -> count, and the number of instructions read."""
    out = subprocess.run(
        ["objdump", "-d", "-C", "--no-show-raw-insn", binary],
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    calls = collections.Counter()
    current = "?"
    lines = 0
    for line in out.splitlines():
        m = FUNCTION.match(line)
        if m:
            current = m.group(1)
            continue
        lines += 1
        c = CALL.search(line)
        if c and "core_arch" in c.group(1) and not any(a in c.group(1) for a in ALLOWED):
            target = c.group(1).split("+")[0]
            calls[(current, target)] += 1
    return calls, lines


def main(argv):
    warn_only = "--warn-only" in argv
    argv = [a for a in argv if a != "--warn-only"]
    if len(argv) < 2:
        print(__doc__.strip().splitlines()[-6], file=sys.stderr)
        return 2
    if shutil.which("objdump") is None:
        print("no_outlined_intrinsics: objdump is not installed (binutils)", file=sys.stderr)
        return 2
    failed = False
    for binary in argv[1:]:
        try:
            calls, lines = outlined_calls(binary)
        except (subprocess.CalledProcessError, OSError) as e:
            print(f"no_outlined_intrinsics: cannot read {binary}: {e}", file=sys.stderr)
            return 2
        if lines < 1000:
            print(f"no_outlined_intrinsics: {binary} holds only {lines} instructions", file=sys.stderr)
            return 2
        total = sum(calls.values())
        if total:
            failed = True
            print(f"{binary}: {total} calls into core::core_arch (out-of-line intrinsics):")
            by_caller = collections.Counter()
            for (caller, _), n in calls.items():
                by_caller[caller] += n
            for caller, n in by_caller.most_common(15):
                targets = sorted({t for (c, t) in calls if c == caller})
                print(f"  {n:6d} in {caller[:160]}")
                print(f"         -> {', '.join(t.split('::')[-1] for t in targets)[:160]}")
        else:
            print(f"{binary}: no call into core::core_arch ({lines} instructions read)")
    if failed and warn_only:
        print("WARNING: out-of-line intrinsics found (--warn-only: not failing)", file=sys.stderr)
        return 0
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
