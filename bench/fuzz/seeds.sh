#!/usr/bin/env bash
# Seed corpora for the fuzz targets, from the project's own files: seeds.sh OUT_DIR [FEM_DIR]
#   OUT_DIR/case           cases/*.toml
#   OUT_DIR/recording      cases/recordings/*.csv cut to their first 40 lines (the rows repeat one shape; short
#                          inputs keep libFuzzer fast)
#   OUT_DIR/fem_result     FEM_DIR/result.json, its lists cut short (FEM_DIR: the --out folder of `strainwave fem`
#                          or `strainwave run`)
#   OUT_DIR/backlash_result, OUT_DIR/contact_result   FEM_DIR/backlash.json, FEM_DIR/contact.json the same, when there
#   OUT_DIR/neutral_curve  FEM_DIR/neutral_curve.csv when present, else 12 rows in the format neutral_curve_csv() writes
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
out=${1:?usage: seeds.sh OUT_DIR [FEM_DIR]}
fem=${2:-}
mkdir -p "$out"/{case,recording,fem_result,neutral_curve,backlash_result,contact_result}
cp "$root"/cases/*.toml "$out/case/"
for f in "$root"/cases/recordings/*.csv; do head -n 40 "$f" > "$out/recording/$(basename "$f")"; done
# The outputs run to 10-800 kB, past the 8 KiB run.sh gives an input: each list is cut to its first two and last two
# elements and the file written without indentation (still a file of the same shape; a torque-twist list stays a
# rising branch).
for name in result backlash contact; do
  if [[ -n $fem && -f $fem/$name.json ]]; then
    dir=${name}_result; [[ $name == result ]] && dir=fem_result
    python3 - "$fem/$name.json" "$out/$dir/$name.json" <<'PY'
import json, sys
def cut(v):
    if isinstance(v, dict):
        return {k: cut(x) for k, x in v.items()}
    if isinstance(v, list):
        v = v if len(v) <= 4 else v[:2] + v[-2:]
        return [cut(x) for x in v]
    return v
json.dump(cut(json.load(open(sys.argv[1]))), open(sys.argv[2], "w"), separators=(",", ":"))
PY
  fi
done
if [[ -n $fem && -f $fem/neutral_curve.csv ]]; then
  cp "$fem/neutral_curve.csv" "$out/neutral_curve/"
else
  python3 - "$out/neutral_curve/neutral_curve.csv" <<'PY'
import math, sys
with open(sys.argv[1], "w") as f:
    f.write("# neutral circle radius_mm 25.4, z_mm 30\n")
    f.write("phi_rad,w_wg_m,v_wg_m,mu_wg_rad,w_comb_m,v_comb_m,mu_comb_rad\n")
    for k in range(0, 360, 30):
        p = math.radians(k)
        c, s = math.cos(2 * p), math.sin(2 * p)
        f.write("%.9f,%.9e,%.9e,%.9e,%.9e,%.9e,%.9e\n" % (p, 1e-4 * c, -5e-5 * s, 1e-3 * s, 1.1e-4 * c, -5.5e-5 * s, 1.1e-3 * s))
PY
fi
