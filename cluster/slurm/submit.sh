#!/usr/bin/env bash
# Submits a flatcut batch as a Slurm array of SHARDS tasks and the fan-in nest after it; prints
# the two job ids.
#
#   cluster/slurm/submit.sh MANIFEST OUT SHARDS "--sheet 3000x1500"
#
# FLATCUT (the flatcut program), FLATCUT_OPTIONS (options of every part, e.g. "--tolerance
# 0.01") and NEST_OPTIONS (e.g. "--seed 7 --work 2000000") are passed on from the environment.
set -euo pipefail
manifest=$(realpath "${1:?usage: submit.sh MANIFEST OUT SHARDS STOCK}")
out=$(realpath -m "${2:?}")
shards=${3:?}
stock=${4:?}
here=$(cd "$(dirname "$0")" && pwd)
array=$(sbatch --parsable --array="1-$shards" \
    --export="ALL,MANIFEST=$manifest,OUT=$out" "$here/batch.sbatch")
nest=$(sbatch --parsable --dependency="afterany:$array" \
    --export="ALL,OUT=$out,STOCK=$stock" "$here/nest.sbatch")
echo "$array $nest"
