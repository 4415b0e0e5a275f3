#!/usr/bin/env bash
# Submit the nightly sweep array and, after it succeeds, the fit report on its dataset.
#   sweeps/slurm/submit-nightly.sh            (from the checkout, after cargo build --release)
# Same environment settings as nightly.sbatch (EHLMAP, SPEC, OUT); DATASET defaults to
# $OUT/nightly-line, REPORT to $OUT/nightly-line-report; job logs go to $OUT/logs/.
# Prints the job ids; the last line is "jobs: ARRAY_ID [FIT_ID]".
set -euo pipefail
cd "$(dirname "$0")/../.."
export EHLMAP=${EHLMAP:-$PWD/target/release/ehlmap}
export SPEC=${SPEC:-sweeps/nightly-line.toml}
export OUT=${OUT:-outputs}
DATASET=${DATASET:-$OUT/nightly-line}
REPORT=${REPORT:-$OUT/nightly-line-report}
mkdir -p "$OUT/logs"
array=$(sbatch --parsable --export=ALL --output="$OUT/logs/nightly-%A_%a.log" sweeps/slurm/nightly.sbatch)
array=${array%%;*}
echo "sweep array: job $array"
if "$EHLMAP" fit --help >/dev/null 2>&1; then
    fit=$(sbatch --parsable --dependency="afterok:$array" --job-name=ehlmap-fit \
        --output="$OUT/logs/fit-%j.log" --wrap "\"$EHLMAP\" fit \"$DATASET\" --out \"$REPORT\"")
    fit=${fit%%;*}
    echo "fit report: job $fit (after $array), into $REPORT"
    echo "jobs: $array $fit"
else
    echo "this ehlmap build has no fit command: no report job submitted"
    echo "jobs: $array"
fi
