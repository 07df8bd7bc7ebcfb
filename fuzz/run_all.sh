#!/usr/bin/env bash
# Fuzzes every reader for SECONDS each (default 600), JOBS targets at once (default 1), seeding
# each target's corpus from the repository's samples, with libFuzzer's limits: no input may take
# over 10 s (a hang) or allocate over 2 GiB. Prints, per target, the executions, the time and
# whether it found a crash (the crashing input is then in fuzz/artifacts/TARGET/).
#
#   fuzz/run_all.sh [SECONDS=600] [JOBS=1] [TARGET...]
#
# Needs the nightly toolchain and cargo-fuzz (`cargo install cargo-fuzz`).
set -uo pipefail
seconds=${1:-600}
jobs=${2:-1}
shift $(( $# > 2 ? 2 : $# ))
here=$(cd "$(dirname "$0")" && pwd)
samples=$here/../samples
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(obj stl ply step part_toml cut_sidecar esicup_json pattern_file batch_manifest)

seed() {
    local target=$1 corpus=$here/corpus/$1
    mkdir -p "$corpus"
    case $target in
        obj) cp "$samples"/*.obj "$corpus"/ ;;
        stl) find "$samples" -name '*.stl' -exec cp {} "$corpus"/ \; ;;
        step) cp "$samples"/*.step "$corpus"/ ;;
        part_toml) cp "$samples"/*.toml "$corpus"/ ;;
        esicup_json) cp "$samples"/nesting/*.json "$corpus"/ 2>/dev/null ;;
        cut_sidecar) printf '{"seams": [[[0, -100, 0], [0, -50, 100]]], "no_cut_regions": [{"center": [0, 0, 100], "radius": 20}]}' > "$corpus/sidecar.json" ;;
        pattern_file) find "$samples" -name '*.pattern.json' -exec cp {} "$corpus"/ \; ;;
        batch_manifest) printf 'input,name,quantity,material,thickness\nparts/a.obj,a,2,steel,1.5\n' > "$corpus/parts.csv" ;;
        ply) printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n' > "$corpus/triangle.ply" ;;
    esac
}

cd "$here" || exit 1
cargo +nightly fuzz build -O || exit 1
run() {
    local target=$1
    seed "$target"
    mkdir -p "artifacts/$target"
    local log=artifacts/$target.log
    cargo +nightly fuzz run -O "$target" "corpus/$target" -- \
        -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048 \
        -print_final_stats=1 > "$log" 2>&1
    local status=$?
    local executions
    executions=$(grep -m1 'stat::number_of_executed_units' "$log" | awk '{print $2}')
    if [ $status -eq 0 ]; then
        echo "$target: ${executions:-?} executions in $seconds s, no crash"
    else
        echo "$target: CRASH after ${executions:-?} executions (exit $status): see fuzz/$log and fuzz/artifacts/$target/"
    fi
}
export -f run seed
export here samples seconds
printf '%s\n' "${targets[@]}" | xargs -P "$jobs" -I{} bash -c 'run {}'
