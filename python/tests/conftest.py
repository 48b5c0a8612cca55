"""Shared set-up: the repository, the `smash` binary to compare with, and a shipped world made
by the CLI's own `smash synth`."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
from pathlib import Path

import pandas as pd
import pytest

ROOT = Path(__file__).resolve().parents[2]


def _find_binary() -> Path:
    """The `smash` binary: $SMASH_BIN, else the one cargo built in this repository's target
    folder ($CARGO_TARGET_DIR or target/, debug profile, which `cargo test` builds), else built
    here with `cargo build -p smash-cli`."""
    given = os.environ.get("SMASH_BIN")
    if given:
        return Path(given)
    target = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    candidate = target / "debug" / "smash"
    if not candidate.exists():
        cargo = shutil.which("cargo")
        if cargo is None:
            pytest.skip("no smash binary and no cargo to build it")
        subprocess.run([cargo, "build", "-p", "smash-cli"], cwd=ROOT, check=True)
    return candidate


@pytest.fixture(scope="session")
def smash_bin() -> Path:
    return _find_binary()


class Cli:
    """Runs the `smash` binary in the repository root."""

    def __init__(self, binary: Path) -> None:
        self.binary = binary

    def run(self, *args: str, ok: bool = True) -> subprocess.CompletedProcess:
        p = subprocess.run(
            [str(self.binary), *map(str, args)], cwd=ROOT, capture_output=True, text=True
        )
        if ok and p.returncode != 0:
            raise AssertionError(f"smash {' '.join(map(str, args))} failed: {p.stderr}")
        return p

    def json(self, *args: str) -> dict:
        return json.loads(self.run(*args, "--json").stdout)

    def error(self, *args: str) -> str:
        """The CLI's one-line error (without `error: `)."""
        p = self.run(*args, ok=False)
        assert p.returncode != 0, f"smash {args} succeeded"
        lines = [l for l in p.stderr.splitlines() if l.startswith("error: ")]
        assert len(lines) == 1, p.stderr
        return lines[0][len("error: "):]


@pytest.fixture(scope="session")
def cli(smash_bin: Path) -> Cli:
    return Cli(smash_bin)


@pytest.fixture(scope="session")
def paper_world(cli: Cli, tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The shipped paper world's shots (configs/synth/paper_world.toml), made by the CLI."""
    out = tmp_path_factory.mktemp("world") / "paper_world.csv"
    cli.run("synth", "--config", "configs/synth/paper_world.toml", "--out", out)
    return out


def read_cli_csv(path: Path) -> pd.DataFrame:
    from smash_golf import _read_csv  # the same reader the package uses

    return _read_csv(Path(path).read_bytes())

