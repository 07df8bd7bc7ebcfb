#!/usr/bin/env bash
# The performance table: every mesh flattened by flatcut (fast; paper too below 5k triangles),
# each run in a fresh process (peak memory is per run), every pattern re-measured by
# ../shared/bench/metrics.py, then the libigl peers on the same mesh (one at a time, never in
# parallel with our runs). Prints Markdown rows; files go to OUT_DIR.
#
#   bench/run_table.sh OUT_DIR MESH.obj...
#   (PEERS=arap by default, PEERS= for none; REPEATS=3 peer runs, median; MAX_SECONDS=300 per run)
#
# Meshes: python3 ../shared/bench/gen_meshes.py /tmp/bench_meshes
# Peers need: pip install -r ../shared/bench/requirements.txt
set -euo pipefail
out=$1
shift
here=$(cd "$(dirname "$0")/.." && pwd)
shared=${SHARED_BENCH:-$here/../shared/bench}
peers=${PEERS-arap}
mkdir -p "$out"
(cd "$here" && cargo build --release --example bench_table >&2)
bin=${CARGO_TARGET_DIR:-$here/target}/release/examples/bench_table
"$bin" --header
for mesh in "$@"; do
    name=$(basename "$mesh" .obj)
    triangles=$(grep -c '^f ' "$mesh")
    solvers=fast
    if [ "$triangles" -lt 5000 ]; then solvers="fast paper"; fi
    for solver in $solvers; do
        "$bin" "$mesh" "$solver" "$out/$name.$solver" 2>>"$out/log.txt"
        python3 "$shared/metrics.py" "$out/$name.$solver.mesh.obj" "$out/$name.$solver.pattern.obj" \
            >"$out/$name.$solver.metrics.json"
    done
    if [ -n "$peers" ]; then
        /usr/bin/time -f "%M" -o "$out/$name.peers.rss" \
            python3 "$shared/peer_flatten.py" "$mesh" --out-dir "$out" --peers "$peers" \
            --repeats "${REPEATS:-3}" --max-seconds "${MAX_SECONDS:-300}" \
            >"$out/$name.peers.jsonl" 2>>"$out/log.txt"
        python3 - "$out/$name.peers.jsonl" "$out/$name.peers.rss" <<'PY'
import json, sys
rss = open(sys.argv[2]).read().split()[-1]
for line in open(sys.argv[1]):
    peer = json.loads(line)
    if not peer.get("ok"):
        print(f"| {peer['mesh']} | {peer.get('faces', '')} | {peer['peer']} (failed) | | | | | | | |")
        continue
    raw = peer["raw"]
    print(f"| {peer['mesh']} | {peer['faces']} | {peer['peer']} (libigl) | {peer['seconds']:.3f} | "
          f"{int(rss) / 1024:.0f}* | {100 * raw['E_S']:.3f} | {100 * raw['E_C']:.3f} | {raw['flipped']} | "
          f"{peer.get('iterations', '')} | {'capped' if peer.get('capped') else 'converged' if peer.get('converged') else ''} |")
PY
    fi
done
# Independent check: metrics.py's figures for every flatcut pattern.
for metrics in "$out"/*.metrics.json; do
    python3 - "$metrics" <<'PY'
import json, sys
m = json.load(open(sys.argv[1]))
m = m.get("raw", m)
print(f"<!-- metrics.py {sys.argv[1].rsplit('/', 1)[-1]}: E_S {100 * m['E_S']:.3f} % "
      f"E_C {100 * m['E_C']:.3f} % flipped {m['flipped']} -->")
PY
done
