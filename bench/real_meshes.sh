#!/usr/bin/env bash
# The real-mesh table of the README: every mesh of ../shared/meshes/ flattened (by default into
# pieces where it does not come within tolerance whole), one fresh process each, timed, every
# written part checked by the independent metrics (../shared/bench/metrics.py). One line per
# mesh on standard output: its parts (pieces), those within 1 % (E_S and E_C as the metrics
# measure them, no flipped triangle, no overlap), the worst part's E_S and E_C, flipped
# triangles and self-overlapping parts over all parts, crest-line cuts and their length, and
# the section curves' length (each section is a seam of the two pieces it separates, counted
# once).
#
# Usage: bench/real_meshes.sh OUT [TIMEOUT_SECONDS] [MESH...]
#   OUT              folder for the runs (OUT/NAME/ per mesh)
#   TIMEOUT_SECONDS  a run still going after this is stopped and listed as such (default 300)
#   MESH             mesh files (default: every ../shared/meshes/*.obj)
# FLATCUT_ARGS adds options to every run (`--repair --units m` for the long sleeve, `--seams
# whole` for the part kept whole); FLATCUT names the binary (default target/release/flatcut).
set -u
here=$(cd "$(dirname "$0")/.." && pwd)
out=${1:?usage: bench/real_meshes.sh OUT [TIMEOUT_SECONDS] [MESH...]}
limit=${2:-300}
shift $(( $# >= 2 ? 2 : 1 ))
meshes=("$@")
[ ${#meshes[@]} -eq 0 ] && meshes=("$here"/../shared/meshes/*.obj)
flatcut=${FLATCUT:-"$here/target/release/flatcut"}
mkdir -p "$out"
printf '%-34s %5s %8s %6s %6s %9s %9s %7s %7s %5s %10s %11s\n' mesh exit seconds parts within \
  worst_E_S worst_E_C flipped overlap cuts cut_length section_len
for mesh in "${meshes[@]}"; do
  name=$(basename "$mesh" .obj)
  dir="$out/$name"
  rm -rf "$dir"
  start=$(date +%s.%N)
  # shellcheck disable=SC2086
  timeout "$limit" "$flatcut" flatten "$mesh" -o "$dir" ${FLATCUT_ARGS:-} >"$out/$name.log" 2>&1
  code=$?
  seconds=$(echo "$(date +%s.%N) - $start" | bc)
  if [ ! -f "$dir/report.json" ]; then
    printf '%-34s %5s %8.1f %s\n' "$name" "$code" "$seconds" "$(tail -1 "$out/$name.log" | cut -c1-120)"
    continue
  fi
  python3 - "$dir" "$here/../shared/bench" "$code" "$seconds" "$name" <<'PY'
import json, os, sys
folder, bench, code, seconds, name = sys.argv[1:]
sys.path.insert(0, bench)
import metrics
report = json.load(open(os.path.join(folder, "report.json")))
within = flipped = overlapping = missing = cuts = 0
worst_s = worst_c = cut_length = section = 0.0
for part in report["parts"]:
    stem = os.path.join(folder, part["name"])
    section += sum(s["length"] for s in part["seams"] if s["kind"] == "section") / 2
    cuts += len(part["cuts"])
    cut_length += part["total_cut_length"]
    if not os.path.exists(stem + ".pattern.obj"):
        missing += 1
        continue
    m = metrics.evaluate_files(stem + ".mesh.obj", stem + ".pattern.obj")
    worst_s, worst_c = max(worst_s, m["E_S"]), max(worst_c, m["E_C"])
    flipped += m["flipped"]
    overlapping += bool(m.get("boundary_self_intersection"))
    within += m["E_S"] <= 0.01 and m["E_C"] <= 0.01 and m["flipped"] == 0 \
        and not m.get("boundary_self_intersection")
print("%-34s %5s %8.1f %6d %6d %8.3f%% %8.3f%% %7d %7d %5d %10.4g %11.4g%s" % (
    name, code, float(seconds), len(report["parts"]), within, 100 * worst_s, 100 * worst_c,
    flipped, overlapping, cuts, cut_length, section,
    " (%d without a pattern)" % missing if missing else ""))
PY
done
