#!/usr/bin/env python3
"""The architecture's rules, held by the suite (docs/architecture.md):

- layers: every include under vantage/ runs to the file's own layer or one below it, as
  vantage/layers.txt writes the layers down;
- folders: a folder within a stage's (vantage/gain/models/, vantage/experiment/detail/, ...)
  holds the files of one layer, so that the folders read as the layers, and no file sits beside a
  folder of its own name (gain/metrics.hpp beside gain/metrics/);
- sizes: no source file of the library, the CLI or the bindings reaches 500 lines, and the
  decision's entry point (vantage/planner/planner.cpp) stays under 200.

Run as `layers_test.py REPO`. It first checks itself on a small tree with one include up a
layer, so that a checker that cannot fail does not pass.
"""
import fnmatch
import pathlib
import re
import sys
import tempfile

INCLUDE = re.compile(r'^\s*#\s*include\s+"vantage/([^"]+)"', re.M)
MAX_LINES = 500
ENTRY_POINT = ("vantage/planner/planner.cpp", 200)
SIZED = ("vantage", "apps", "python/src")


def read_layers(path):
    """[(name, [patterns])], bottom first."""
    layers = []
    for line in path.read_text().splitlines():
        line = line.split("#", 1)[0].strip()
        if not line:
            continue
        name, _, patterns = line.partition(":")
        if not patterns.split():
            raise SystemExit(f"{path}: layer '{name}' has no pattern")
        layers.append((name.strip(), patterns.split()))
    return layers


def layer_of(relative, layers):
    """(rank, name) of the layer whose longest pattern matches `relative`, or None."""
    best = None
    for rank, (name, patterns) in enumerate(layers):
        for pattern in patterns:
            if fnmatch.fnmatchcase(relative, pattern):
                if best is None or len(pattern) > best[0]:
                    best = (len(pattern), rank, name)
    return None if best is None else best[1:]


def layer_violations(root):
    """Every include under root/vantage that runs up a layer, and every file in no layer."""
    layers = read_layers(root / "vantage" / "layers.txt")
    problems = []
    for path in sorted((root / "vantage").rglob("*")):
        if path.suffix not in (".hpp", ".cpp", ".h"):
            continue
        relative = path.relative_to(root / "vantage").as_posix()
        mine = layer_of(relative, layers)
        if mine is None:
            problems.append(f"vantage/{relative}: in no layer of vantage/layers.txt")
            continue
        for included in INCLUDE.findall(path.read_text()):
            theirs = layer_of(included, layers)
            if theirs is None:
                problems.append(f"vantage/{relative}: includes vantage/{included}, in no layer")
            elif theirs[0] > mine[0]:
                problems.append(f"vantage/{relative} ({mine[1]}) includes vantage/{included} "
                                f"({theirs[1]}), a higher layer")
    return problems


def folder_violations(root):
    """Every folder within a stage's that spans layers, and every file named as a folder beside it."""
    layers = read_layers(root / "vantage" / "layers.txt")
    problems = []
    spans = {}
    for path in sorted((root / "vantage").rglob("*")):
        relative = path.relative_to(root / "vantage")
        if path.is_dir():
            if path.with_suffix(".hpp").exists() or path.with_suffix(".cpp").exists():
                problems.append(f"vantage/{relative.as_posix()}/ has a file of its name beside it")
            continue
        if path.suffix not in (".hpp", ".cpp", ".h") or len(relative.parts) < 3:
            continue
        mine = layer_of(relative.as_posix(), layers)
        if mine is not None:
            spans.setdefault("/".join(relative.parts[:2]), set()).add(mine[1])
    for folder, names in sorted(spans.items()):
        if len(names) > 1:
            problems.append(f"vantage/{folder}/ spans the layers {', '.join(sorted(names))}")
    return problems


def size_violations(root):
    problems = []
    for top in SIZED:
        for path in sorted((root / top).rglob("*")):
            if path.suffix not in (".hpp", ".cpp", ".h"):
                continue
            lines = len(path.read_text().splitlines())
            relative = path.relative_to(root).as_posix()
            limit = ENTRY_POINT[1] if relative == ENTRY_POINT[0] else MAX_LINES
            if lines >= limit:
                problems.append(f"{relative}: {lines} lines, at most {limit - 1}")
    return problems


def self_check():
    """The checker finds an include up a layer and a file in no layer, and passes a clean tree."""
    with tempfile.TemporaryDirectory() as tmp:
        root = pathlib.Path(tmp)
        (root / "vantage" / "low").mkdir(parents=True)
        (root / "vantage" / "high").mkdir()
        (root / "vantage" / "layers.txt").write_text("low: low/*\nhigh: high/*\n")
        (root / "vantage" / "high" / "h.hpp").write_text('#include "vantage/low/l.hpp"\n')
        (root / "vantage" / "low" / "l.hpp").write_text("// nothing\n")
        assert layer_violations(root) == [], layer_violations(root)
        (root / "vantage" / "low" / "l.hpp").write_text('#include "vantage/high/h.hpp"\n')
        (root / "vantage" / "other.hpp").write_text("\n")
        found = layer_violations(root)
        assert any("includes vantage/high/h.hpp (high), a higher layer" in p for p in found), found
        assert any("other.hpp: in no layer" in p for p in found), found
        assert folder_violations(root) == [], folder_violations(root)
        (root / "vantage" / "layers.txt").write_text("low: low/*\nhigh: high/* low/sub/h*\n")
        (root / "vantage" / "low" / "sub").mkdir()
        (root / "vantage" / "low" / "sub" / "l.hpp").write_text("\n")
        (root / "vantage" / "low" / "sub" / "h.hpp").write_text("\n")
        (root / "vantage" / "low" / "sub.hpp").write_text("\n")
        found = folder_violations(root)
        assert any("low/sub/ spans the layers high, low" in p for p in found), found
        assert any("low/sub/ has a file of its name" in p for p in found), found


def main():
    root = pathlib.Path(sys.argv[1]).resolve()
    self_check()
    checks = {"layers": layer_violations(root), "folders": folder_violations(root),
              "sizes": size_violations(root)}
    failed = 0
    for name, problems in checks.items():
        for problem in problems:
            print(f"FAIL ({name}): {problem}")
        failed += 1 if problems else 0
    print(f"{len(checks) - failed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
