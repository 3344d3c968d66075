#!/usr/bin/env bash
# Runs the fuzz targets one after another, single process, at the lowest priority:
#   run.sh BUILD_DIR SEED_DIR WORK_DIR SECONDS [TARGET...]
#     (TARGET: case recording fem_result neutral_curve backlash_result contact_result)
# WORK_DIR/corpus/TARGET collects the inputs that reached new code, WORK_DIR/TARGET.log libFuzzer's output, and a
# crashing input is written as WORK_DIR/crash-* (libFuzzer then stops that target).
set -uo pipefail
build=${1:?usage: run.sh BUILD_DIR SEED_DIR WORK_DIR SECONDS [TARGET...]}
seeds=${2:?}; work=${3:?}; seconds=${4:?}; shift 4
targets=("$@")
[[ ${#targets[@]} -gt 0 ]] || targets=(case recording fem_result neutral_curve backlash_result contact_result)
mkdir -p "$work"
# The readers of the tool's outputs take a file: each input is written to $TMPDIR first. On tmpfs that costs microseconds; on
# ext4 it held them to ~250 runs/s here.
if [[ -z ${TMPDIR:-} && -w /dev/shm ]]; then export TMPDIR=/dev/shm; fi
work=$(cd "$work" && pwd)
for t in "${targets[@]}"; do
  mkdir -p "$work/corpus/$t"
  # 8 KiB bounds the recordings (their seeds are 2 KiB); the other formats' seeds are smaller.
  (cd "$work" && nice -n 19 "$build/fuzz_$t" -max_total_time="$seconds" -timeout=10 -max_len=8192 -print_final_stats=1 \
     -artifact_prefix="$work/" "$work/corpus/$t" "$seeds/$t" >"$work/$t.log" 2>&1)
  echo "$t: exit $? ($(grep -c . "$work/$t.log") log lines; $(ls "$work/corpus/$t" | wc -l) corpus inputs)"
done
