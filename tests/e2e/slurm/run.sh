#!/usr/bin/env bash
# A real Slurm run (docs/sharding.md, "Slurm"): starts a single-node cluster in a temporary folder
# (cluster.sh: munged, slurmctld, slurmd on 127.0.0.1, stopped in all cases), then runs
# scripts/vt-slurm, the command the docs give users: the shards as a job array, the merge as a job
# that depends on it. Checks, byte for byte against the single-process build: an image, an atlas
# (three layers, wrapping textures), a shard killed once and resubmitted alone by vt-slurm, and a
# shard that fails for good, reported with the command that reruns just it, which is then run.
# Exit 77 (skipped, with the reason) only when the daemons cannot run here.
#   run.sh VT_SLURM VT_TILES VT_MERGE VT_SYNTH_IMAGE VT_ATLAS VT_SAMPLE_SCENE
set -euo pipefail
[ $# -eq 6 ] || { echo "usage: run.sh VT_SLURM VT_TILES VT_MERGE VT_SYNTH_IMAGE VT_ATLAS VT_SAMPLE_SCENE" >&2; exit 2; }
VT_SLURM=$1 VT_TILES=$2 VT_MERGE=$3 VT_SYNTH_IMAGE=$4 VT_ATLAS=$5 VT_SAMPLE_SCENE=$6
here=$(cd "$(dirname "$0")" && pwd)

for cmd in munged slurmctld slurmd sbatch squeue sinfo scancel; do
  command -v $cmd >/dev/null || {
    echo "SKIP: '$cmd' is not installed (scripts/setup installs slurmctld slurmd slurm-client munge)"
    exit 77
  }
done
[ "$(id -u)" = 0 ] || { echo "SKIP: the test cluster's daemons run as root (SlurmUser=root): not root"; exit 77; }

work=$(mktemp -d "${TMPDIR:-/tmp}/vt-slurm-test.XXXXXX")
CLUSTER=$work/cluster
source "$here/cluster.sh"
finish() {
  local rc=$?
  cluster_stop
  if [ $rc -ne 0 ] && [ $rc -ne 77 ]; then
    echo "FAILED ($rc): the logs" >&2
    tail -n 20 "$CLUSTER"/log/*.log "$work"/*/*.log 2>/dev/null >&2 || true
  fi
  [ -n "${VT_KEEP_TEST:-}" ] || rm -rf "$work" # VT_KEEP_TEST=1: keep it to debug
  exit $rc
}
trap finish EXIT
trap 'exit 130' INT TERM
if ! cluster_start; then
  echo "SKIP: the Slurm daemons cannot run here (see above)"
  exit 77
fi
echo "ok a single-node cluster is up: $(sinfo -h -o '%P %D %T %c')"
cd "$work"
# check WHAT COMMAND...: prints "ok WHAT", or fails the test
check() {
  local what=$1
  shift
  if "$@"; then echo "ok $what"; else echo "FAILED: $what" >&2; exit 1; fi
}
slurm() { "$VT_SLURM" --poll 0.5 --vt-tiles "${tiles:-$VT_TILES}" --vt-merge "$VT_MERGE" -q "$@"; }

# an image: 4 shards, the seams the merge makes
"$VT_SYNTH_IMAGE" in.tif --format tiff --size 2500x1900 --channels 3 --tile 128
"$VT_TILES" in.tif -o single.vts --tile-size 128 -j2 -q
slurm in.tif -o image.vts -n 4 -- --tile-size 128
check "image: 4 shards on Slurm equal the single build" cmp single.vts image.vts

# an atlas: 4 shards of the sample scene (diffuse with alpha, normal, alpha mask; textures that wrap)
"$VT_SAMPLE_SCENE" --shrink 4 -q scene
"$VT_ATLAS" scene/scene.obj -o atlas.json --tile-size 64 --border 2 --wrap split -q
"$VT_TILES" --layout atlas.json -o atlas-single.vts -j2 -q
slurm --layout atlas.json -o atlas.vts -n 4 -c 2 --merge-cpus 2
check "atlas: 4 shards on Slurm equal the single build" cmp atlas-single.vts atlas.vts

# a vt-tiles that dies once while building shard 3 (as a killed task or a lost node: no output),
# and one that always fails it; every run is logged
cat >flaky <<SH
#!/bin/bash
prev= i=
for a in "\$@"; do [ "\$prev" = --shard ] && i=\${a%/*}; prev=\$a; done
echo "\$i" >>"\$RUNS"
if [ "\$i" = 3 ] && { [ "\${FAIL:-once}" = always ] || [ ! -e "\$RUNS.failed" ]; }; then
  touch "\$RUNS.failed"
  kill -9 \$\$
fi
exec "$VT_TILES" "\$@"
SH
chmod +x flaky
runs() { sort -n "$RUNS" | uniq -c | awk '{print $2 ":" $1}' | paste -sd' '; }

export RUNS=$work/runs1
tiles=./flaky slurm in.tif -o retried.vts -n 4 -r 1 -d retried.shards -- --tile-size 128
echo "runs per shard: $(runs)"
check "shard 3 failed once and was resubmitted alone" [ "$(runs)" = "1:1 2:1 3:2 4:1" ]
check "the retried build equals the single build" cmp single.vts retried.vts

export RUNS=$work/runs2
set +e
FAIL=always tiles=./flaky slurm in.tif -o failed.vts -n 4 -r 0 -d failed.shards -- --tile-size 128 2>err.txt
rc=$?
set -e
echo "exit $rc; runs per shard: $(runs)"
check "vt-slurm exits 1" [ $rc = 1 ]
check "the failure is reported" grep -q '^vt-slurm: shards 3 of 4 failed' err.txt
check "nothing written" test ! -e failed.vts
rerun=$(grep -A1 'rerun just them' err.txt | tail -1)
eval "$rerun"
echo "after the rerun: $(runs)"
check "the printed command reran shard 3 alone" [ "$(runs)" = "1:1 2:1 3:2 4:1" ]
check "the rerun build equals the single build" cmp single.vts failed.vts
# the comparison can fail: another build is told apart
"$VT_TILES" in.tif -o other.vts --tile-size 128 --quality 80 -j2 -q
differs() { ! cmp -s "$1" "$2"; }
check "a different build differs" differs single.vts other.vts
