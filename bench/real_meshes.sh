#!/usr/bin/env bash
# The real-mesh table of the README: every mesh of ../shared/meshes/ flattened with the default
# options, one fresh process each, timed, then each written part checked by the independent
# metrics (../shared/bench/metrics.py). One line per part on standard output.
#
# Usage: bench/real_meshes.sh OUT [TIMEOUT_SECONDS] [MESH...]
#   OUT              folder for the runs (OUT/NAME/ per mesh)
#   TIMEOUT_SECONDS  a run still going after this is stopped and listed as such (default 300)
#   MESH             mesh files (default: every ../shared/meshes/*.obj)
set -u
here=$(cd "$(dirname "$0")/.." && pwd)
out=${1:?usage: bench/real_meshes.sh OUT [TIMEOUT_SECONDS] [MESH...]}
limit=${2:-300}
shift $(( $# >= 2 ? 2 : 1 ))
meshes=("$@")
[ ${#meshes[@]} -eq 0 ] && meshes=("$here"/../shared/meshes/*.obj)
flatcut="$here/target/release/flatcut"
metrics="$here/../shared/bench/metrics.py"
mkdir -p "$out"
printf '%-34s %5s %8s %9s %9s %7s %6s %5s %10s %6s %11s\n' part exit seconds E_S E_C flipped overlap cuts cut_length seams seam_length
for mesh in "${meshes[@]}"; do
  name=$(basename "$mesh" .obj)
  dir="$out/$name"
  rm -rf "$dir"
  start=$(date +%s.%N)
  timeout "$limit" "$flatcut" flatten "$mesh" -o "$dir" >"$out/$name.log" 2>&1
  code=$?
  seconds=$(echo "$(date +%s.%N) - $start" | bc)
  if [ ! -f "$dir/report.json" ]; then
    printf '%-34s %5s %8.1f %s\n' "$name" "$code" "$seconds" "$(tail -1 "$out/$name.log" | cut -c1-120)"
    continue
  fi
  python3 - "$dir" "$metrics" "$code" "$seconds" "$name" <<'PY'
import json, subprocess, sys, os
folder, metrics, code, seconds, name = sys.argv[1:]
report = json.load(open(os.path.join(folder, "report.json")))
for part in report["parts"]:
    stem = os.path.join(folder, part["name"])
    if not os.path.exists(stem + ".pattern.obj"):
        print("%-34s %5s %8.1f  no pattern written" % (part["name"], code, float(seconds)))
        continue
    m = json.loads(subprocess.run(["python3", metrics, stem + ".mesh.obj", stem + ".pattern.obj"],
                                  capture_output=True, text=True, check=True).stdout)
    e = m
    print("%-34s %5s %8.1f %8.3f%% %8.3f%% %7d %6s %5d %10.4g %6d %11.4g" % (
        part["name"], code, float(seconds), 100 * e["E_S"], 100 * e["E_C"],
        e["flipped"], e.get("boundary_self_intersection", "?"),
        len(part["cuts"]), part["total_cut_length"],
        len(part["seams"]), sum(seam["length"] for seam in part["seams"])))
PY
done
