#!/usr/bin/env bash
# Throughput of Arachis against LIGGGHTS 3.8 on the DESIGN §8 bench bed (2 000 spheres,
# 20 000 steps of 2e-5 s, insertion and settling included), measured one after the other on
# this machine, and printed as one JSON line:
#
#   {"liggghts_particle_steps_per_second":…, "fixed_particle_steps_per_second":…,
#    "fixed_vs_liggghts":…, "f64_particle_steps_per_second":…, "f64_vs_liggghts":…,
#    "threads":N, "fixed_threaded_particle_steps_per_second":…, "threaded_vs_one_thread":…, …}
#
# Rates are particles × steps / wall seconds. LIGGGHTS' figure is its own "Loop time" (the run
# without its set-up, which favours LIGGGHTS); Arachis' is `arachis pour`'s wall clock over the
# whole run, insertion included. Each engine runs `--repeat` times (default 3), alternating, and
# the median of each is reported, with the load average before and after. Targets (issue 16):
# fixed ≥ 1.0× LIGGGHTS on one thread, f64 ≥ 2×, fixed on N threads ≥ 1.8× one thread (N = 2).
#
# The deck is benches/liggghts/bench_bed.in. Its neighbour skin, 1 mm, was LIGGGHTS' fastest of
# 0.5, 1 and 2 mm on this bed (2026-11-25: 5.32, 4.91, 5.03 s loop time).
#
# Usage: scripts/bench-vs-liggghts.sh [--repeat N] [--threads N] [--particles N] [--steps N]
# LIGGGHTS is installed from the Debian archive (package liggghts) when missing.
set -euo pipefail
cd "$(dirname "$0")/.."

repeat=3
threads=2
particles=2000
steps=20000
while [ $# -gt 0 ]; do
    case "$1" in
        --repeat) repeat="$2"; shift 2 ;;
        --threads) threads="$2"; shift 2 ;;
        --particles) particles="$2"; shift 2 ;;
        --steps) steps="$2"; shift 2 ;;
        *) echo "bench-vs-liggghts.sh: unknown argument $1" >&2; exit 2 ;;
    esac
done

scripts/install-liggghts.sh

cargo build --release -q -p arachis >&2
arachis=target/release/arachis
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

load() { cut -d' ' -f1 /proc/loadavg; }
median() { sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }
field() { sed -n "s/.*\"$1\":\([^,}]*\).*/\1/p" | tr -d '"'; }

run_liggghts() {
    (cd "$work" && liggghts -in "$OLDPWD/benches/liggghts/bench_bed.in" -log none \
        -var particles "$particles" -var steps "$steps" -var final "$work/final.txt") \
        > "$work/liggghts.out" 2>&1 || { cat "$work/liggghts.out" >&2; exit 1; }
    local loop
    loop=$(sed -n 's/^Loop time of \([0-9.e+-]*\) on.*/\1/p' "$work/liggghts.out" | tail -1)
    [ -n "$loop" ] || { echo "no loop time in LIGGGHTS output" >&2; exit 1; }
    awk -v p="$particles" -v s="$steps" -v t="$loop" 'BEGIN { printf "%.6e\n", p * s / t }'
}

# 95th percentile of z + R of LIGGGHTS' final state, m (the bed height of `arachis pour`).
liggghts_bed_height() {
    awk 'f { print $5 + $2 } /^ITEM: ATOMS/ { f = 1 }' "$work/final.txt" | sort -g |
        awk '{a[NR]=$1} END { i = int(0.95 * NR + 0.999999); if (i < 1) i = 1; print a[i] }'
}

run_arachis() { # extra args...
    "$arachis" pour --particles "$particles" --steps "$steps" --dt 2e-5 "$@" 2>/dev/null
}

load_before=$(load)
: > "$work/lg"; : > "$work/fx"; : > "$work/f64"; : > "$work/fxn"
for _ in $(seq "$repeat"); do
    run_liggghts >> "$work/lg"
    run_arachis --threads 1 > "$work/fx.json"
    field particle_steps_per_second < "$work/fx.json" >> "$work/fx"
    run_arachis --threads 1 --f64 > "$work/f64.json"
    field particle_steps_per_second < "$work/f64.json" >> "$work/f64"
    run_arachis --threads "$threads" > "$work/fxn.json"
    field particle_steps_per_second < "$work/fxn.json" >> "$work/fxn"
    if [ "$(field digest < "$work/fxn.json")" != "$(field digest < "$work/fx.json")" ]; then
        echo "fixed-point digest differs between 1 and $threads threads" >&2
        exit 1
    fi
done
load_after=$(load)

lg=$(median < "$work/lg"); fx=$(median < "$work/fx"); f64=$(median < "$work/f64")
fxn=$(median < "$work/fxn")
awk -v lg="$lg" -v fx="$fx" -v f64="$f64" -v fxn="$fxn" -v n="$threads" -v r="$repeat" \
    -v p="$particles" -v s="$steps" -v l0="$load_before" -v l1="$load_after" \
    -v hl="$(liggghts_bed_height)" -v hf="$(field bed_height_m < "$work/fx.json")" \
    -v h64="$(field bed_height_m < "$work/f64.json")" -v d="$(field digest < "$work/fx.json")" \
    -v cpu="$(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -1)" 'BEGIN {
    printf "{\"particles\":%d,\"steps\":%d,\"repeat\":%d,", p, s, r
    printf "\"liggghts_particle_steps_per_second\":%.4g,", lg
    printf "\"fixed_particle_steps_per_second\":%.4g,\"fixed_vs_liggghts\":%.3f,", fx, fx / lg
    printf "\"f64_particle_steps_per_second\":%.4g,\"f64_vs_liggghts\":%.3f,", f64, f64 / lg
    printf "\"threads\":%d,\"fixed_threaded_particle_steps_per_second\":%.4g,", n, fxn
    printf "\"threaded_vs_one_thread\":%.3f,\"fixed_digest\":\"%s\",", fxn / fx, d
    printf "\"bed_height_m\":{\"liggghts\":%.5f,\"fixed\":%.5f,\"f64\":%.5f},", hl, hf, h64
    printf "\"load_average\":[%s,%s],\"cpu\":\"%s\"}\n", l0, l1, cpu
}'
