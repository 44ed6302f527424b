"""Shared fixtures: the CLI binary and the source tree, as ctest passes them in the environment."""

import contextlib
import importlib
import json
import os
import pathlib
import subprocess
import sys

import pytest


def _env_path(name):
    value = os.environ.get(name)
    if not value:
        pytest.fail(f"{name} is not set; run the suite through ctest (python.*)")
    return pathlib.Path(value)


@pytest.fixture(scope="session")
def vantage_bin():
    """The `vantage` command-line tool of the same build."""
    return _env_path("VANTAGE_BIN")


@pytest.fixture(scope="session")
def source_dir():
    return _env_path("VANTAGE_SOURCE_DIR")


def cli_error(vantage_bin, *args):
    """The one line `vantage ARGS` prints on stderr when it fails, without its prefix."""
    run = subprocess.run([str(vantage_bin), *args], capture_output=True, text=True)
    assert run.returncode != 0, f"vantage {' '.join(args)} succeeded"
    lines = run.stderr.splitlines()
    assert len(lines) == 1, run.stderr
    prefix = "vantage: error: "
    assert lines[0].startswith(prefix), lines[0]
    return lines[0][len(prefix):]


@pytest.fixture(scope="session")
def own_scans(tmp_path_factory, vantage_bin, source_dir):
    """The own-scans example made by its own script, in a scratch copy, and `vantage plan --json`
    with its defaults (the survival reading, the swept search; the bindings' defaults too) run on
    it: (folder, the CLI's plan.json as a dict, the CLI's results folder)."""
    folder = tmp_path_factory.mktemp("own-scans")
    example = source_dir / "examples" / "own-scans"
    subprocess.run([str(example / "make-data.sh"), str(folder), str(vantage_bin)], check=True,
                   capture_output=True)
    out = folder / "cli-results"
    run = subprocess.run([str(vantage_bin), "plan", str(folder), "--json", "--out", str(out)],
                         check=True, capture_output=True, text=True)
    return folder, json.loads(run.stdout), out


@contextlib.contextmanager
def tree_modules(folder, *names):
    """The modules `names` of one of the tree's folders (scripts/, examples/python/), imported
    with the folder on the path while in the block (a script imports its neighbours so)."""
    sys.path.insert(0, str(folder))
    try:
        yield tuple(importlib.import_module(name) for name in names)
    finally:
        sys.path.remove(str(folder))


@pytest.fixture(scope="module")
def plot_bench(source_dir):
    """scripts/plot_bench.py as a module (the summaries' tests)."""
    with tree_modules(source_dir / "scripts", "plot_bench") as (module,):
        yield module
