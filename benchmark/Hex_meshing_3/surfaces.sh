#!/usr/bin/env bash
# Meshes every test surface (the repository's test data, and ../shared/data when present) with
# hexmesh's default settings and prints one JSON line per file: cells, seconds, peak memory,
# min scaled Jacobian, and checkMesh's verdicts (-allTopology, and the checks -allGeometry adds).
# Usage: benchmark/Hex_meshing_3/surfaces.sh [path/to/hexmesh] [extra hexmesh options]
set -uo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
hexmesh="${1:-$here/../../build/tools/hexmesh/hexmesh}"
shift || true
export WM_PROJECT_DIR=/usr/share/openfoam
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
files=$(ls "$here"/../../test/Hex_meshing_3/data/*.off)
if [ -d "$here/../../../shared/data" ]; then files=$(ls "$here"/../../../shared/data/*.off); fi
for f in $files; do
  name=$(basename "$f" .off)
  rm -rf "$work/case"
  "$hexmesh" "$f" -o "$work/case" -q --report "$work/r.json" "$@" 2> "$work/err"
  rc=$?
  topo=$(checkMesh -case "$work/case" -allTopology 2>&1 | grep -E "Mesh OK|Failed [0-9]+ mesh" || echo "no mesh")
  geo=$(checkMesh -case "$work/case" -allGeometry -allTopology 2>&1 | grep -E '^ \*\*\*' | sed 's/^ *//' | tr '\n' ';')
  /usr/bin/python3 - "$work/r.json" "$name" "$rc" "$topo" "$geo" "$work/err" <<'PY'
import json, sys, os
rep, name, rc, topo, geo, err = sys.argv[1:]
out = {"file": name, "exit": int(rc)}
if int(rc) == 0 and os.path.exists(rep):
    j = json.load(open(rep))
    out.update({"cells": j["counts"]["cells"], "hanging_nodes": j["counts"]["hanging_nodes"],
                "seconds": round(j["seconds"]["total"], 3), "peak_memory_mib": round(j["peak_memory_mib"], 1),
                "min_scaled_jacobian": j["quality"]["scaled_jacobian"]["min"],
                "max_non_orthogonality": round(j["quality"]["non_orthogonality"]["max"], 2),
                "inside_test": "exact" if j["input_summary"]["exact_inside_test"] else "winding number",
                "checkMesh_allTopology": topo, "checkMesh_allGeometry_flags": geo})
else:
    out["error"] = open(err).read().strip()[-300:]
print(json.dumps(out))
PY
  rm -f "$work/r.json"
done
