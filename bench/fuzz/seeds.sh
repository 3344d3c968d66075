#!/usr/bin/env bash
# Seed corpora for the fuzz targets, from the project's own files: seeds.sh OUT_DIR [FEM_DIR]
#   OUT_DIR/case           cases/*.toml
#   OUT_DIR/recording      cases/recordings/*.csv cut to their first 40 lines (the rows repeat one shape; short
#                          inputs keep libFuzzer fast)
#   OUT_DIR/fem_result     FEM_DIR/result.json          (FEM_DIR: the --out folder of `strainwave fem`)
#   OUT_DIR/neutral_curve  FEM_DIR/neutral_curve.csv when present, else 12 rows in the format neutral_curve_csv() writes
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
out=${1:?usage: seeds.sh OUT_DIR [FEM_DIR]}
fem=${2:-}
mkdir -p "$out"/{case,recording,fem_result,neutral_curve}
cp "$root"/cases/*.toml "$out/case/"
for f in "$root"/cases/recordings/*.csv; do head -n 40 "$f" > "$out/recording/$(basename "$f")"; done
if [[ -n $fem && -f $fem/result.json ]]; then cp "$fem/result.json" "$out/fem_result/"; fi
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
