#!/usr/bin/env bash
# Throughput of `attenuvis vg` on 1 and 2 MPI processes against one process
# with one and with two threads, measured in the same run in alternating
# rounds (the machine may be shared: compare the minima of the same round
# set).  Prints one line per configuration: the pass's wall time (the first
# process's, which ends after the exact reduction, i.e. with the slowest
# share), pairs per second overall and per process, and the speed-up over one
# process on one thread; checks that every CSV is byte-identical.
# usage: mpi_scaling.sh [ATTENUVIS] [CITY_RINGS] [SPACING] [ROUNDS]
set -euo pipefail
attenuvis=${1:-build/apps/attenuvis}
rings=${2:-1}
spacing=${3:-2.5}
rounds=${4:-3}
attenuvis=$(realpath "$attenuvis")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
"$attenuvis" scene city --rings "$rings" --out city.obj >/dev/null
vg=(vg city.obj --spacing "$spacing" --conditions clear,fog:advection,rain:8 --quiet --allow-large)
configs=("1 process, 1 thread|$attenuvis ${vg[*]} --threads 1"
         "1 process, 2 threads|$attenuvis ${vg[*]} --threads 2"
         "mpirun -np 1 (1 core)|mpirun -np 1 $attenuvis ${vg[*]}"
         "mpirun -np 2 (1 core each)|mpirun -np 2 $attenuvis ${vg[*]}"
         "mpirun -np 2 --bind-to none|mpirun -np 2 --bind-to none $attenuvis ${vg[*]}")
echo "city --rings $rings --spacing $spacing m, $rounds rounds, $(nproc) cores, load before: $(cut -d' ' -f1-3 /proc/loadavg)"
for round in $(seq "$rounds"); do
  for c in "${!configs[@]}"; do
    command=${configs[$c]#*|}
    /usr/bin/time -o "cpu.$c.$round" -f "%U %S %e" $command --out "scores.$c.csv" --summary "summary.$c.$round.json"
  done
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
/usr/bin/python3 - "$rounds" "${configs[@]}" <<'PY'
import json, sys, statistics
rounds = int(sys.argv[1]); names = [c.split("|")[0] for c in sys.argv[2:]]
rows = []
for c, name in enumerate(names):
    runs = [json.load(open(f"summary.{c}.{r}.json")) for r in range(1, rounds + 1)]
    t = [s["time_s"]["visibility"] for s in runs]
    cpu = [sum(map(float, open(f"cpu.{c}.{r}").read().split()[:2])) for r in range(1, rounds + 1)]
    rows.append((name, min(t), statistics.median(t), runs[0], min(cpu)))
base = rows[0][1]
s = rows[0][3]
print(f"{s['nodes']} nodes, {s['pairs']['considered']} pairs: {s['pairs']['cast']} cast, "
      f"{s['pairs']['culled_in_sight']} culled in sight, {s['pairs']['culled_blocked']} culled blocked")
base_cpu = rows[0][4]
for name, best, median, s, cpu in rows:
    procs = 2 if "np 2" in name else 1
    total = s["pairs"]["considered"]
    print(f"{name:28s} pass: min {best:6.3f} s, median {median:6.3f} s, {total / best / 1e6:5.1f} M pairs/s "
          f"({total / best / 1e6 / procs:5.1f} per process), speed-up {base / best:.2f}x; "
          f"whole run CPU {cpu:6.2f} s = {total / cpu / 1e6:5.1f} M pairs per CPU second, "
          f"{base_cpu / cpu:.2f} of one process's efficiency")
PY
for f in scores.*.csv; do cmp scores.0.csv "$f"; done
echo "every CSV byte-identical to the one-process run"
