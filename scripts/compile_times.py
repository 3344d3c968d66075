#!/usr/bin/env python3
"""Where a build's time goes: compiles every translation unit of a configured build folder one at a time (from its
compile_commands.json, into a scratch object file) and prints the slowest, the total and the total per folder.

    scripts/compile_times.py build [--tool] [--top 25]

--tool keeps the units the `strainwave` binary is made of (leaves out tests/ and bench/). One unit at a time on an
otherwise quiet machine: the figures are each unit's own wall time, not a parallel build's.
"""
import argparse
import json
import os
import shlex
import subprocess
import sys
import tempfile
import time
from collections import defaultdict


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("build", help="a configured CMake build folder (CMAKE_EXPORT_COMPILE_COMMANDS=ON)")
    ap.add_argument("--tool", action="store_true", help="only the units of the strainwave binary (no tests/, bench/)")
    ap.add_argument("--top", type=int, default=25, help="how many of the slowest units to list")
    a = ap.parse_args()

    db_path = os.path.join(a.build, "compile_commands.json")
    try:
        with open(db_path) as f:
            units = json.load(f)
    except (OSError, ValueError) as e:
        sys.exit(f"compile_times.py: {db_path}: {e}; configure the build with CMAKE_EXPORT_COMPILE_COMMANDS=ON")
    source = os.path.abspath(os.path.join(a.build, ".."))
    try:
        with open(os.path.join(a.build, "CMakeCache.txt")) as f:
            for line in f:
                if line.startswith("CMAKE_HOME_DIRECTORY:INTERNAL="):
                    source = line.split("=", 1)[1].strip()
    except OSError:
        pass
    rows = []
    with tempfile.TemporaryDirectory() as scratch:
        for u in units:
            rel = os.path.relpath(u["file"], source)
            if a.tool and rel.split(os.sep)[0] in ("tests", "bench"):
                continue
            args = shlex.split(u["command"]) if "command" in u else list(u["arguments"])
            if "-o" in args:
                args[args.index("-o") + 1] = os.path.join(scratch, "unit.o")
            start = time.monotonic()
            done = subprocess.run(args, cwd=u["directory"], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
            seconds = time.monotonic() - start
            if done.returncode != 0:
                sys.exit(f"compile_times.py: {rel} did not compile:\n{done.stderr.decode(errors='replace')}")
            rows.append((seconds, rel))
            print(f"{seconds:7.1f} s  {rel}", file=sys.stderr, flush=True)
    rows.sort(reverse=True)
    total = sum(s for s, _ in rows)
    per_folder = defaultdict(float)
    for s, rel in rows:
        per_folder[os.path.dirname(rel) or "."] += s
    print(f"{len(rows)} units, {total:.0f} s one at a time")
    print(f"slowest {min(a.top, len(rows))}:")
    for s, rel in rows[: a.top]:
        print(f"  {s:7.1f} s  {100 * s / total:5.1f} %  {rel}")
    print("per folder:")
    for folder, s in sorted(per_folder.items(), key=lambda kv: -kv[1]):
        print(f"  {s:7.1f} s  {100 * s / total:5.1f} %  {folder}")


if __name__ == "__main__":
    main()
