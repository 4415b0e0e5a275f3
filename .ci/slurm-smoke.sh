#!/usr/bin/env bash
# Slurm smoke test of the sweep engine: install Debian's slurm-wlm, start munged, slurmctld and
# slurmd on this host with the minimal config in sweeps/slurm/, submit sweeps/smoke.toml as a
# job array over 2 shards, wait, check that the dataset is complete, and stop the daemons by
# their pid files. Needs root (apt-get, daemons). Standalone: bash .ci/slurm-smoke.sh
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
SHARDS=${SHARDS:-2}
SPEC=${SPEC:-sweeps/smoke.toml}

echo "== slurm-wlm"
if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    apt-get install -y -qq --no-install-recommends slurm-wlm munge >/dev/null
fi
slurmctld -V

echo "== ehlmap"
cargo build --release --quiet
EHLMAP=$ROOT/target/release/ehlmap

WORK=$(mktemp -d /tmp/ehlmap-slurm.XXXXXX)
chmod 755 "$WORK"
mkdir -p "$WORK"/{munge,state,spool,log,out}
stop() {
    # Stop the daemons by their pid files, newest first.
    for pidfile in "$WORK/slurmd.pid" "$WORK/slurmctld.pid" "$WORK/munge/munged.pid"; do
        if [[ -s $pidfile ]]; then
            pid=$(cat "$pidfile")
            kill "$pid" 2>/dev/null || true
            for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
        fi
    done
}
trap stop EXIT

echo "== munged"
dd if=/dev/urandom of="$WORK/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$WORK/munge/munge.key"
chmod 700 "$WORK/munge"
munged --force --key-file="$WORK/munge/munge.key" --socket="$WORK/munge/munge.socket.2" \
    --pid-file="$WORK/munge/munged.pid" --log-file="$WORK/log/munged.log" \
    --seed-file="$WORK/munge/munged.seed"
for _ in $(seq 50); do [[ -S $WORK/munge/munge.socket.2 ]] && break; sleep 0.1; done
chmod 755 "$WORK/munge"

echo "== slurmctld, slurmd"
HOST=$(hostname -s)
CPUS=$(nproc)
sed -e "s|@HOST@|$HOST|g" -e "s|@CPUS@|$CPUS|g" -e "s|@WORK@|$WORK|g" \
    -e "s|@CTLD_PORT@|${CTLD_PORT:-16817}|g" -e "s|@SLURMD_PORT@|${SLURMD_PORT:-16818}|g" \
    sweeps/slurm/slurm.conf.in >"$WORK/slurm.conf"
export SLURM_CONF=$WORK/slurm.conf
slurmctld -c
slurmd
ready=
for _ in $(seq 100); do
    state=$(sinfo -h -N -o '%T' 2>/dev/null | head -1 || true)
    if [[ $state == idle* ]]; then ready=1; break; fi
    sleep 0.2
done
if [[ -z $ready ]]; then
    echo "the node did not become idle (state: ${state:-none})"
    tail -n 20 "$WORK"/log/*.log
    exit 1
fi
sinfo

echo "== sweep array ($SHARDS shards of $SPEC)"
cd "$WORK"
sbatch --wait --array=0-$((SHARDS - 1)) --output="$WORK/log/array-%A_%a.out" \
    "$ROOT/sweeps/slurm/smoke-array.sbatch" "$EHLMAP" "$ROOT/$SPEC" "$WORK/out" || {
    echo "the array failed"
    cat "$WORK"/log/array-*.out || true
    exit 1
}
cat "$WORK"/log/array-*.out
cd "$ROOT"

# complete SPEC OUT: every planned case of SPEC is stored in OUT/<name>/, which holds only parts.
complete() {
    local spec=$1 out=$2 name plan total missing
    name=$(sed -n 's/^name *= *"\(.*\)".*/\1/p' "$spec" | head -1)
    ls -l "$out/$name"
    if ls -A "$out/$name" | grep -qv '^part-[0-9]*of[0-9]*-[0-9]*\.parquet$'; then
        echo "foreign files in the dataset directory $out/$name"
        return 1
    fi
    plan=$("$EHLMAP" sweep "$spec" --out "$out" --dry-run)
    total=$(grep -vc '^#' <<<"$plan")
    missing=$(grep -v '^#' <<<"$plan" | grep -c ' false$' || true)
    echo "$out/$name: $total cases planned, $missing missing"
    [[ $total -gt 0 && $missing -eq 0 ]]
}

echo "== dataset"
name=$(sed -n 's/^name *= *"\(.*\)".*/\1/p' "$SPEC" | head -1)
parts=$(ls "$WORK/out/$name" | grep -c "^part-[0-9]*of$SHARDS-[0-9]*\.parquet$" || true)
if [[ $parts -lt 1 || $parts -gt $SHARDS ]]; then
    echo "expected up to $SHARDS part files (one per non-empty shard), found $parts"
    exit 1
fi
complete "$SPEC" "$WORK/out" || { echo "the dataset is incomplete"; exit 1; }

echo "== sweeps/slurm/submit-nightly.sh (array of nightly.sbatch on $SPEC, then the fit report)"
# Capture, then print: `tee /dev/stderr` would truncate a log file that stderr points to.
submitted=$(OUT=$WORK/out2 SPEC=$SPEC EHLMAP=$EHLMAP DATASET=$WORK/out2/$name REPORT=$WORK/report \
    sweeps/slurm/submit-nightly.sh)
echo "$submitted"
jobs=$(sed -n 's/^jobs: //p' <<<"$submitted")
for _ in $(seq 600); do
    left=$(squeue -h -j "${jobs// /,}" 2>/dev/null | wc -l)
    [[ $left -eq 0 ]] && break
    sleep 0.5
done
[[ $left -eq 0 ]] || { echo "jobs $jobs still queued"; squeue; exit 1; }
cat "$WORK"/out2/logs/*.log
complete "$SPEC" "$WORK/out2" || { echo "the nightly array left the dataset incomplete"; exit 1; }
if [[ $jobs == *" "* && ! -s $WORK/report/report.md ]]; then
    echo "the fit report job wrote no $WORK/report/report.md"
    exit 1
fi

stop
trap - EXIT
rm -rf "$WORK"
echo "slurm smoke: OK"
