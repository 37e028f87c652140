#!/usr/bin/env bash
# Grid speed on the OpenFOAM motorBike geometry: leaf cells of the balanced grid per second of
# refinement + balance + cut tests + region selection (one core), plus cells, seconds and peak
# memory of the whole run. Prints one JSON line per run.
# Usage: benchmark/Hex_meshing_3/grid_speed.sh [path/to/hexmesh]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
hexmesh="${1:-$here/../../build/tools/hexmesh/hexmesh}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
src=""
for f in "$here/../../../shared/data/motorBike.obj.gz" \
         /usr/share/doc/openfoam-examples/examples/resources/geometry/motorBike.obj.gz; do
  [ -f "$f" ] && { src="$f"; break; }
done
[ -n "$src" ] || { echo "motorBike.obj.gz not found (install openfoam-examples)" >&2; exit 1; }
gunzip -c "$src" > "$work/motorBike.obj"
run() {
  local name="$1"; shift
  "$hexmesh" "$work/motorBike.obj" -o "$work/mb.vtu" --force -q --report "$work/r.json" "$@"
  /usr/bin/python3 - "$work/r.json" "$name" "$*" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
print(json.dumps({"run": sys.argv[2], "options": sys.argv[3], "cells": j["counts"]["cells"],
                  "leaf_cells": j["grid"]["leaf_cells"], "grid_seconds": round(j["grid"]["seconds"], 3),
                  "leaf_cells_per_second": round(j["grid"]["leaf_cells_per_second"]),
                  "seconds": {k: round(v, 3) for k, v in j["seconds"].items()},
                  "peak_memory_mib": round(j["peak_memory_mib"], 1)}))
PY
}
run issue2 --box -5,-4,0,15,4,8 --size 1 --surface-size 0.03125 --region seed:3.0001,3.0001,0.43
run fine_surface --box -5,-4,0,15,4,8 --size 1 --surface-size 0.0078125 \
    --refine-box -1,-0.7,0,8,0.7,2.5:0.0625 --region seed:3.0001,3.0001,0.43
