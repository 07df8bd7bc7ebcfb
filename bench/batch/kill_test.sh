#!/usr/bin/env bash
# Kill test of `flatcut batch`: a batch of COUNT parts is run once uninterrupted (folder A); then,
# KILLS times, again into a fresh folder B, killed at a random moment (SIGKILL, SIGTERM or SIGINT
# to the batch process alone, in turn) and rerun. After each kill no worker may be left running,
# the rerun must skip exactly the parts whose records say finished and redo the rest, and B must
# then hold exactly A's files with A's bytes.
#
#   bench/batch/kill_test.sh [KILLS=20] [COUNT=40] [BIN=target/release/flatcut]
#
# Prints one line per kill (signal, delay, parts finished, parts redone) and a summary; exits 1
# when B differs from A, the rerun redoes a finished part, or a worker outlived its batch.
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
total_redone=0
for ((k = 0; k < kills; k++)); do
    signal=${signals[$((k % 3))]}
    delay=$(awk -v seed="$k" -v limit="$seconds" 'BEGIN { srand(seed); printf "%.2f", rand() * limit }')
    rm -rf "$work/b"
    "${batch[@]}" -o "$work/b" 2> /dev/null &
    pid=$!
    sleep "$delay"
    kill -s "$signal" "$pid" 2> /dev/null || true
    code=0
    wait "$pid" 2> /dev/null || code=$?
    # A worker replacing its folder's files when the signal comes finishes that first (a few
    # renames and its record).
    sleep 1
    if pgrep -f "$bin batch-part" > /dev/null; then
        echo "kill $k: a worker outlived its batch:"; pgrep -af "$bin batch-part"
        exit 1
    fi
    finished=$(grep -l '"status": "ok"' "$work"/b/parts/*/batch-part.json 2> /dev/null | wc -l)
    "${batch[@]}" -o "$work/b" 2> "$work/rerun.log" || { echo "kill $k: the rerun failed"; exit 1; }
    skipped=$(grep -c 'skipped' "$work/rerun.log" || true)
    redone=$((count - skipped))
    total_redone=$((total_redone + redone))
    if [ "$skipped" -ne "$finished" ]; then
        echo "kill $k: $finished parts were finished but the rerun skipped $skipped"; exit 1
    fi
    if ! diff -r "$work/a" "$work/b" > "$work/diff.log"; then
        echo "kill $k: the resumed batch differs from the uninterrupted one:"; head "$work/diff.log"; exit 1
    fi
    echo "kill $k: SIG$signal after $delay s: exit $code, $finished of $count parts finished; the rerun redid $redone, byte-identical to A"
done
echo "$kills kills: every rerun redid only the unfinished parts ($total_redone in all) and ended byte-identical to the uninterrupted batch; no worker outlived its batch"
