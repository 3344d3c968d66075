#!/usr/bin/env python3
"""Compares the JSON outputs of two runs of the shipped cases, figure by figure.

Usage: scripts/diff_outputs.py REFERENCE_DIR NEW_DIR [--rel 1e-12]
Each DIR holds one folder per case (as `strainwave run CASE --out DIR/<stem>` writes it). For every case folder of
NEW_DIR, each result.json, backlash.json, contact.json, dynamics.json and reconcile.json of REFERENCE_DIR's folder
of that name is compared with its namesake in NEW_DIR: the same keys, the same strings, numbers equal to a relative tolerance (default 1e-12: a refactor moves no
figure). Timings and rates, peak memory, the tool's version and the paths a run was given (`case_file`, the case file
or output it ran) are left out. Exits 1 on the first
case with a difference, after listing every difference of it (at most 40).
"""
import json
import math
import sys
from pathlib import Path

FILES = ["result.json", "backlash.json", "contact.json", "dynamics.json", "reconcile.json"]
IGNORED_KEYS = {"timings_s", "peak_rss_bytes", "version", "case_file", "setup_s", "influence_s", "contact_s", "check_s",
                "real_time_factor", "factor_s"}


def differences(a, b, path, rel, out, dirs):
    """Appends to `out` every difference of a (in the reference run) and b; `dirs`: the two runs' folders, which
    paths in strings may name."""
    if isinstance(a, dict) and isinstance(b, dict):
        for k in sorted(set(a) | set(b)):
            if k in IGNORED_KEYS or k.endswith("_per_s"):  # timings and rates
                continue
            if k not in a or k not in b:
                out.append(f"{path}.{k}: only in {'new' if k not in a else 'reference'}")
            else:
                differences(a[k], b[k], f"{path}.{k}", rel, out, dirs)
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            out.append(f"{path}: {len(a)} items, now {len(b)}")
        for i, (x, y) in enumerate(zip(a, b)):
            differences(x, y, f"{path}[{i}]", rel, out, dirs)
    elif isinstance(a, (int, float)) and isinstance(b, (int, float)) and not isinstance(a, bool):
        if a == b or (math.isnan(a) and math.isnan(b)):
            return
        if abs(a - b) > rel * max(abs(a), abs(b)):
            out.append(f"{path}: {a!r} -> {b!r}")
    elif isinstance(a, str) and isinstance(b, str):
        if a.replace(str(dirs[0]), "DIR") != b.replace(str(dirs[1]), "DIR"):  # the paths the runs were given
            out.append(f"{path}: {a!r} -> {b!r}")
    elif a != b:
        out.append(f"{path}: {a!r} -> {b!r}")


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--rel")]
    rel = 1e-12
    for a in sys.argv[1:]:
        if a.startswith("--rel"):
            rel = float(a.split("=", 1)[1])
    if len(args) != 2:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    ref, new = Path(args[0]), Path(args[1])
    compared = 0
    failed = False
    for f in sorted(ref.glob("*/*.json")):
        if f.name not in FILES or not (new / f.parent.name).is_dir():
            continue
        g = new / f.parent.name / f.name
        if not g.exists():
            print(f"{g}: missing")
            failed = True
            continue
        out = []
        differences(json.loads(f.read_text()), json.loads(g.read_text()), f.parent.name + "/" + f.name, rel, out, (ref, new))
        compared += 1
        for line in out[:40]:
            print(line)
        failed |= bool(out)
    print(f"{compared} files compared, {'differences found' if failed else 'no figure moved'} (relative tolerance {rel:g})")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
