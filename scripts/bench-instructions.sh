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
# Usage: scripts/bench-instructions.sh [--f64] [--steps N] [--particles N] [--binary PATH]
# (about 6 minutes for the default 20 000 steps in fixed point; --binary compares an older
# build without rebuilding).
set -euo pipefail
cd "$(dirname "$0")/.."

steps=20000
particles=2000
scalar_flag=""
binary=""
while [ $# -gt 0 ]; do
    case "$1" in
        --f64) scalar_flag="--f64"; shift ;;
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
valgrind --tool=callgrind --callgrind-out-file="$work/cg.out" \
    "$binary" pour --threads 1 --particles "$particles" --steps "$steps" $scalar_flag \
    >"$work/pour.json" 2>"$work/valgrind.log"

python3 - "$work/cg.out" "$work/pour.json" "$particles" "$steps" "$binary" <<'EOF'
import json, re, subprocess, sys
out, pour, particles, steps, binary = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), sys.argv[5]
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
print(json.dumps({
    "particles": particles, "steps": steps, "scalar": run.get("scalar"),
    "instructions": total, "per_particle_step": round(total / per, 1),
    "stages": result, "digest": run.get("digest"), "binary": binary,
}))
EOF
