#!/usr/bin/env bash
# Throughput of `flatcut batch` with --jobs 1 and --jobs 2 on a generated batch of COUNT parts
# (bench/batch/make_batch.sh), each into a fresh folder, and the peak memory of the whole batch
# (the batch process and its workers: the processes of BIN, summed, sampled every 0.1 s).
#
#   bench/batch/throughput.sh [COUNT=120] [BIN=target/release/flatcut] [JOBS="1 2"]
set -euo pipefail
count=${1:-120}
here=$(cd "$(dirname "$0")/../.." && pwd)
bin=${2:-$here/target/release/flatcut}
jobs_list=${3:-1 2}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$here/bench/batch/make_batch.sh" "$work/batch" "$count" > /dev/null

# Peak of the summed resident memory (MiB) of the processes of `bin` until PID ends.
peak_memory() {
    local pid=$1 peak=0 now
    while kill -0 "$pid" 2> /dev/null; do
        now=$(pgrep -f "^$bin " | xargs -r ps -o rss= -p | awk '{ sum += $1 } END { print int(sum / 1024) }')
        [ "$now" -gt "$peak" ] && peak=$now
        sleep 0.1
    done
    echo "$peak"
}

echo "| jobs | parts | seconds | parts/s | speed-up | peak memory (MiB) | statuses |"
echo "| --- | --- | --- | --- | --- | --- | --- |"
first=
for jobs in $jobs_list; do
    started=$(date +%s.%N)
    "$bin" batch --manifest "$work/batch/parts.csv" -o "$work/out-$jobs" --jobs "$jobs" 2> "$work/log-$jobs" &
    pid=$!
    peak=$(peak_memory "$pid")
    wait "$pid" || true
    seconds=$(echo "$(date +%s.%N) - $started" | bc -l)
    rate=$(echo "$count / $seconds" | bc -l)
    first=${first:-$seconds}
    speedup=$(echo "$first / $seconds" | bc -l)
    statuses=$(tail -1 "$work/log-$jobs" | sed 's/.*part(s): //; s/; summary.*//')
    printf '| %s | %s | %.1f | %.2f | %.2f | %s | %s |\n' "$jobs" "$count" "$seconds" "$rate" "$speedup" "$peak" "$statuses"
done
if diff -r "$work/out-1" "$work/out-2" > /dev/null 2>&1; then
    echo "outputs of --jobs 1 and --jobs 2: byte-identical"
fi
