#!/usr/bin/env bash
# The house's one rule, checked on the code: a folder includes only folders on the floors below it (the pipeline's
# order), never a folder beside or above it, and each folder is one CMake library named after it (sw_<folder>), so no
# split library can hide a cycle. Prints every offending include and exits 1; exits 0 when the house is sound.
# Run by ctest (house.layers); by hand: bash scripts/check_layers.sh
set -euo pipefail
cd "$(dirname "$0")/.."

# Floors from the ground up; folders on one floor may not include each other.
floors=(
  "common"
  "gear generator"
  "mesh"
  "kinematics fem"
  "contact"
  "design dynamics"
  "reconcile datasheet"
  "io"
  "app"
)
declare -A floor_of
for i in "${!floors[@]}"; do
  for f in ${floors[$i]}; do floor_of[$f]=$i; done
done

bad=0
for folder in "${!floor_of[@]}"; do
  own=${floor_of[$folder]}
  while IFS= read -r line; do
    file=${line%%:*}
    target=$(sed -E 's/.*#include "([a-z_]+)\/.*/\1/' <<<"$line")
    [ "$target" = "$folder" ] && continue
    if [ -z "${floor_of[$target]+x}" ]; then
      echo "$file: includes $target/, a folder outside the pipeline"; bad=1
    elif [ "${floor_of[$target]}" -ge "$own" ]; then
      echo "$file: includes $target/ (floor ${floor_of[$target]}) from $folder/ (floor $own): an arrow up or sideways"
      bad=1
    fi
  done < <(grep -HE '^#include "[a-z_]+/' "$folder"/*.hpp "$folder"/*.cpp 2>/dev/null || true)
  # One library per folder, named after it (app also builds the executable from main.cpp).
  libs=$(grep -cE '^add_library\(sw_[a-z_]+( |$)' "$folder/CMakeLists.txt" || true)
  if [ "$libs" != 1 ] || ! grep -qE "^add_library\(sw_$folder( |$)" "$folder/CMakeLists.txt"; then
    echo "$folder/CMakeLists.txt: must define exactly one library, sw_$folder (found $libs)"; bad=1
  fi
done
for dir in */; do
  d=${dir%/}
  if [ -f "$d/CMakeLists.txt" ] && ls "$d"/*.cpp >/dev/null 2>&1 && [ -z "${floor_of[$d]+x}" ] &&
     [[ ! " tests bench build " =~ " $d " ]]; then
    echo "$d/: a folder of code on no floor of the house (add it to scripts/check_layers.sh)"; bad=1
  fi
done
# Inside a folder, a header and its source are one unit (x.hpp + x.cpp); the units' includes of each other must not
# run in a circle (a loop the floors cannot see). Prints the circle and fails.
for folder in "${!floor_of[@]}"; do
  loop=$(grep -HE "^#include \"$folder/[a-z_0-9]+\.hpp\"" "$folder"/*.hpp "$folder"/*.cpp 2>/dev/null |
    sed -E "s|^$folder/([a-z_0-9]+)\.(hpp\|cpp):#include \"$folder/([a-z_0-9]+)\.hpp\".*|\1 \3|" |
    awk -v folder="$folder" '$1 != $2 { edge[$1] = edge[$1] " " $2; node[$1]; node[$2] }
      function visit(u,    n, i, v, next_of) {
        state[u] = 1; stack[++depth] = u
        n = split(edge[u], next_of, " ")
        for (i = 1; i <= n; i++) {
          v = next_of[i]
          if (state[v] == 1) { path = v; for (j = depth; stack[j] != v; j--) path = stack[j] " -> " path
                               found = v " -> " path; return 1 }
          if (!state[v] && visit(v)) return 1
        }
        state[u] = 2; depth--; return 0
      }
      END { for (u in node) if (!state[u] && visit(u)) { print found; exit } }')
  if [ -n "$loop" ]; then echo "$folder/: units include each other in a circle: $loop"; bad=1; fi
done
[ $bad = 0 ] && echo "house: ${#floor_of[@]} folders on ${#floors[@]} floors, no arrow up the pipeline, no circle inside a folder"
exit $bad
