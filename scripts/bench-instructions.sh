#!/usr/bin/env bash
# Instructions per particle-step of the DESIGN §8 bench bed (`arachis pour`, 2 000 spheres,
# one thread), counted by valgrind's callgrind: an exact count that the machine's load does
# not move, so two builds can be compared on a shared, noisy machine where wall times scatter
# by ±10 %. Instructions are not time (a spill and a division both count one), so a change is
# confirmed by timing as well; the count says where the instructions go, stage by stage.
# Installs valgrind from the Debian archive when it is missing. Prints one JSON line:
#
#   {"particles":2000,"steps":20000,"scalar":"fixed","instructions":…,
#    "per_particle_step":…,"stages":{"contact_scan":…,"integration":…,
#    "neighbour_rebuild":…,"other":…},"digest":"…","binary":"…"}
#
# Stage figures are per particle-step, inclusive of what each stage calls.
#
# --liggghts also counts LIGGGHTS 3.8 on the same bed (the deck of bench-vs-liggghts.sh,
# installed from the Debian archive when missing), alongside on the other core, and adds
#
#   "liggghts":{"instructions":…,"per_particle_step":…,"liggghts_vs_arachis":…}
#
# where the last is LIGGGHTS' count over ours: on 2026-12-07 it was 0.615 in fixed point,
# the same as the measured ratio of the two engines' speeds, so the count stands in for the
# speed ratio on a machine too loaded to time (core/API_NOTES.md, "LIGGGHTS' instructions
# beside ours").
#
# Usage: scripts/bench-instructions.sh [--f64] [--liggghts] [--steps N] [--particles N]
#        [--binary PATH]
# (about 6 minutes for the default 20 000 steps in fixed point; --binary compares an older
# build without rebuilding).
set -euo pipefail
cd "$(dirname "$0")/.."

steps=20000
particles=2000
scalar_flag=""
binary=""
liggghts=0
while [ $# -gt 0 ]; do
    case "$1" in
        --f64) scalar_flag="--f64"; shift ;;
        --liggghts) liggghts=1; shift ;;
        --steps) steps="$2"; shift 2 ;;
        --particles) particles="$2"; shift 2 ;;
        --binary) binary="$2"; shift 2 ;;
        *) echo "bench-instructions.sh: unknown argument $1" >&2; exit 2 ;;
    esac
done

if ! command -v valgrind >/dev/null 2>&1; then
    echo "bench-instructions.sh: installing valgrind from the Debian archive" >&2
    DEBIAN_FRONTEND=noninteractive apt-get install -y -q valgrind >&2
fi
if [ -z "$binary" ]; then
    cargo build --release -q -p arachis >&2
    binary=target/release/arachis
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
if [ "$liggghts" = 1 ]; then
    bash scripts/install-liggghts.sh
    deck="$PWD/benches/liggghts/bench_bed.in"
    (cd "$work" && valgrind --tool=callgrind --callgrind-out-file="$work/lg.out" \
        liggghts -in "$deck" -log none -var particles "$particles" -var steps "$steps" \
        -var final "$work/final.txt" >"$work/liggghts.log" 2>&1) &
    liggghts_pid=$!
fi
valgrind --tool=callgrind --callgrind-out-file="$work/cg.out" \
    "$binary" pour --threads 1 --particles "$particles" --steps "$steps" $scalar_flag \
    >"$work/pour.json" 2>"$work/valgrind.log"
if [ "$liggghts" = 1 ]; then
    wait "$liggghts_pid" || { cat "$work/liggghts.log" >&2; exit 1; }
fi

python3 - "$work/cg.out" "$work/pour.json" "$particles" "$steps" "$binary" "$work/lg.out" <<'EOF'
import json, os, re, subprocess, sys
out, pour, particles, steps, binary, lg = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), sys.argv[5], sys.argv[6]
run = json.load(open(pour))
# Inclusive counts per function from callgrind_annotate (one line per function).
text = subprocess.run(["callgrind_annotate", "--inclusive=yes", out],
                      capture_output=True, text=True, check=True).stdout
total = None
inclusive = {}
for line in text.splitlines():
    m = re.match(r"^\s*([\d,]+) \(\s*[\d.]+%\)\s+(.*)$", line)
    if not m:
        continue
    count, name = int(m.group(1).replace(",", "")), m.group(2)
    if "PROGRAM TOTALS" in name:
        total = count
        continue
    # A function's whole inclusive count is the line that names its binary; lines without
    # it are the shares of code inlined from other files.
    if name.endswith("]") and " [" in name:
        inclusive[name] = max(inclusive.get(name, 0), count)
stages = {
    "contact_scan": r"narrow_phase::ContactPart<S>::scan \[",
    "integration": r"integration::IntegratePart<S,_>::integrate \[",
    "neighbour_rebuild": r"neighbour_list::NeighbourList<S>::rebuild \[",
}
per = particles * steps
result = {}
for stage, pattern in stages.items():
    result[stage] = round(sum(c for n, c in inclusive.items() if re.search(pattern, n)) / per, 1)
result["other"] = round(total / per - sum(result.values()), 1)
line = {
    "particles": particles, "steps": steps, "scalar": run.get("scalar"),
    "instructions": total, "per_particle_step": round(total / per, 1),
    "stages": result, "digest": run.get("digest"), "binary": binary,
}
if os.path.exists(lg):
    text = subprocess.run(["callgrind_annotate", lg], capture_output=True, text=True,
                          check=True).stdout
    m = re.search(r"^\s*([\d,]+) \(\s*[\d.]+%\)\s+PROGRAM TOTALS", text, re.M)
    lg_total = int(m.group(1).replace(",", ""))
    line["liggghts"] = {
        "instructions": lg_total, "per_particle_step": round(lg_total / per, 1),
        "liggghts_vs_arachis": round(lg_total / total, 3),
    }
print(json.dumps(line))
EOF
