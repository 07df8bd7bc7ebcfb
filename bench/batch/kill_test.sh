#!/usr/bin/env bash
# Kill test of `flatcut batch`: a batch of COUNT parts is run once uninterrupted (folder A), then
# again into folder B, killed at a random moment (SIGKILL, SIGTERM or SIGINT to the batch process
# alone, in turn) and rerun until it completes. Afterwards no worker may be left running, and B
# must hold exactly A's files with A's bytes.
#
#   bench/batch/kill_test.sh [KILLS=20] [COUNT=40] [BIN=target/release/flatcut]
#
# Prints one line per kill (signal, delay, parts done so far) and a summary; exits 1 when B
# differs from A or a worker outlived its batch.
set -euo pipefail
kills=${1:-20}
count=${2:-40}
here=$(cd "$(dirname "$0")/../.." && pwd)
bin=${3:-$here/target/release/flatcut}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$here/bench/batch/make_batch.sh" "$work/batch" "$count" > /dev/null
batch=("$bin" batch --manifest "$work/batch/parts.csv" --jobs 2)

started=$(date +%s.%N)
"${batch[@]}" -o "$work/a" 2> /dev/null || true
seconds=$(echo "$(date +%s.%N) - $started" | bc)
echo "uninterrupted: $count parts in $seconds s"

signals=(KILL TERM INT)
for ((k = 0; k < kills; k++)); do
    signal=${signals[$((k % 3))]}
    delay=$(awk -v seed="$k" -v limit="$seconds" 'BEGIN { srand(seed); printf "%.2f", rand() * limit }')
    "${batch[@]}" -o "$work/b" 2> /dev/null &
    pid=$!
    sleep "$delay"
    kill -s "$signal" "$pid" 2> /dev/null || true
    code=0
    wait "$pid" || code=$?
    sleep 0.3
    if pgrep -f "$bin batch-part" > /dev/null; then
        echo "kill $k: a worker outlived its batch"
        exit 1
    fi
    done_parts=$(grep -l '"status": "ok"' "$work"/b/parts/*/batch-part.json 2> /dev/null | wc -l)
    echo "kill $k: SIG$signal after $delay s: exit $code, $done_parts of $count parts done"
done

reruns=0
until "${batch[@]}" -o "$work/b" 2> "$work/rerun.log"; do
    reruns=$((reruns + 1))
    if [ "$reruns" -gt 3 ]; then
        echo "the batch does not complete:"; tail -5 "$work/rerun.log"; exit 1
    fi
done
redone=$(grep -vc 'skipped\|part(s):' "$work/rerun.log" || true)
if diff -r "$work/a" "$work/b" > "$work/diff.log"; then
    echo "after $kills kills, the final rerun redid $redone part(s); B is byte-identical to A"
else
    echo "B differs from A:"; head -20 "$work/diff.log"; exit 1
fi
