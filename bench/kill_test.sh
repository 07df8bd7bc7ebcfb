#!/usr/bin/env bash
# Kill test of the output folder: a complete run A is in OUT; run B (other parts, other options)
# is started into OUT and sent SIGINT or SIGTERM at a random moment, N times. After each kill the
# folder must hold exactly run A's files or exactly run B's (every file and its bytes, the
# manifest included, no staging folder, the user's own file kept), nothing else.
#
#   bench/kill_test.sh [N=50] [BIN=target/debug/flatcut]
#
# Odd kills land anywhere (mostly while flattening and nesting), even ones near the end (writing
# and replacing). Prints one line per kill (signal, delay, exit code, which run the folder holds) and a summary;
# exits 1 if any kill left anything else.
set -euo pipefail
n=${1:-50}
here=$(cd "$(dirname "$0")/.." && pwd)
bin=${2:-$here/target/debug/flatcut}
samples=$here/samples
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
out=$work/out

# No stock: the nesting search stops on the wall clock under load and its layouts would differ
# between reruns; flattening is deterministic (the script checks that run B repeats exactly).
# Run A's cone_ring files are not in run B: they must go when B completes.
run_a=("$bin" run "$samples/cone_frustum.toml" "$samples/cone_ring.obj" -o "$out" --no-timings)
run_b=("$bin" run "$samples/cone_frustum.toml" "$samples/saddle.obj" "$samples/hemisphere.obj" -o "$out" --dxf-chord 0.02 --no-timings)

# Every entry under OUT (folders too, hidden ones included) with the hash of every file.
snapshot() {
    (cd "$out" && find . -mindepth 1 | sort | while read -r entry; do
        if [ -f "$entry" ]; then echo "$entry $(sha256sum < "$entry" | cut -d' ' -f1)"; else echo "$entry/"; fi
    done)
}

fresh_a() {
    rm -rf "$out"
    mkdir -p "$out"
    echo "the user's own notes" > "$out/notes.txt"
    "${run_a[@]}" 2>/dev/null
}

fresh_a
snapshot > "$work/a.txt"
start=$(date +%s.%N)
"${run_b[@]}" 2>/dev/null
seconds_b=$(echo "$(date +%s.%N) - $start" | bc)
snapshot > "$work/b.txt"
fresh_a
"${run_b[@]}" 2>/dev/null
snapshot | cmp -s - "$work/b.txt" || { echo "run B is not repeatable"; exit 1; }
cmp -s "$work/a.txt" "$work/b.txt" && { echo "runs A and B must differ"; exit 1; }
echo "run B takes ${seconds_b} s; killing it $n times at random moments (odd kills in [0, 1.1 x that], even ones in [0.85, 1.05 x that])"

held_a=0 held_b=0 mixed=0
for i in $(seq 1 "$n"); do
    fresh_a
    signal=$([ $((i % 2)) -eq 0 ] && echo INT || echo TERM)
    # Odd kills anywhere in the run; even ones near its end, where it writes and replaces files.
    if [ $((i % 2)) -eq 1 ]; then
        delay=$(echo "scale=3; $seconds_b * 1.1 * $RANDOM / 32767" | bc)
    else
        delay=$(echo "scale=3; $seconds_b * (0.85 + 0.2 * $RANDOM / 32767)" | bc)
    fi
    # exec: the signal goes to flatcut itself, not to a subshell around it.
    (exec "${run_b[@]}" 2>/dev/null) &
    pid=$!
    sleep "$delay"
    kill -s "$signal" "$pid" 2>/dev/null || true
    code=0
    wait "$pid" || code=$?
    snapshot > "$work/now.txt"
    if cmp -s "$work/now.txt" "$work/a.txt"; then
        held=previous; held_a=$((held_a + 1))
    elif cmp -s "$work/now.txt" "$work/b.txt"; then
        held=new; held_b=$((held_b + 1))
    else
        held=MIXED; mixed=$((mixed + 1))
        diff "$work/a.txt" "$work/now.txt" | head -20 || true
    fi
    printf 'kill %2d: SIG%-4s after %6.3f s, exit %3d: folder holds the %s run\n' "$i" "$signal" "$delay" "$code" "$held"
done
echo "kills: $n; previous complete run: $held_a; new complete run: $held_b; anything else: $mixed"
[ "$mixed" -eq 0 ]
