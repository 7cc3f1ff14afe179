#!/usr/bin/env bash
# The repose angle by cylinder lifting on a pile of spheres, Arachis beside LIGGGHTS 3.8, over
# several placement seeds (issue 18: mean angles within 1°).
#
# The study (scripts/sphere-study.py) is the shipped seed-000 study with its pods replaced by
# spheres of R 4 mm (the pod material, DESIGN §8) and both pairs in LIGGGHTS' conventions
# (rolling_convention = "liggghts-cdt", friction_convention = "liggghts"; pod-pod e, μs, μr
# held at the centres of seed 000's ranges), written into a temporary folder. Its quick mode
# holds --spheres spheres, in a cylinder whose diameter makes the fill about as deep as it is
# wide, as the seed's 900 pods fill its 200 mm cylinder.
#
# For each seed k = 1..--seeds:
#   Arachis:  arachis simulate --study S --seed k --json repose   (its angle);
#   LIGGGHTS: arachis export liggghts S --seed k (the same particles, time step and stages),
#             liggghts -in in.repose, then arachis lab repose-pile final.dump, the rig's own
#             photographs applied to LIGGGHTS' final positions.
# Prints per-seed angles and a table: each engine's mean, SD and SE, the difference of means,
# its 2·SE, and whether |difference| <= 1° and within 2·SE; with --json, one JSON line too.
# LIGGGHTS is installed from the Debian archive when missing (scripts/install-liggghts.sh).
#
# Usage: scripts/cross-check-repose.sh [--seeds N] [--spheres N] [--json]
set -euo pipefail
cd "$(dirname "$0")/.."

seeds=8
spheres=1500
json=0
while [ $# -gt 0 ]; do
    case "$1" in
        --seeds) seeds="$2"; shift 2 ;;
        --spheres) spheres="$2"; shift 2 ;;
        --json) json=1; shift ;;
        *) echo "cross-check-repose.sh: unknown argument $1" >&2; exit 2 ;;
    esac
done

scripts/install-liggghts.sh
cargo build --release -q -p arachis >&2
arachis=$PWD/target/release/arachis
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
load_before=$(cut -d' ' -f1-3 /proc/loadavg)
start=$(date +%s)

scripts/sphere-study.py testdata/peanut-pods-saline/study.toml "$work/study.toml" \
    --spheres "$spheres"

: > "$work/angles.txt"
for k in $(seq "$seeds"); do
    "$arachis" simulate --study "$work/study.toml" --mode quick --seed "$k" --json repose \
        > "$work/arachis_$k.json"
    a=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["observation"]["value"])' \
        "$work/arachis_$k.json")
    deck="$work/deck_$k"
    "$arachis" export liggghts "$work/study.toml" --mode quick --seed "$k" --out "$deck" > /dev/null
    (cd "$deck" && liggghts -in in.repose -log none > liggghts.out 2>&1) \
        || { tail -20 "$deck/liggghts.out" >&2; exit 1; }
    atoms=$(awk 'f { print; exit } /^ITEM: NUMBER OF ATOMS/ { f = 1 }' "$deck/final.dump")
    if [ "$atoms" != "$spheres" ]; then
        echo "LIGGGHTS lost spheres on seed $k: $atoms of $spheres left" >&2
        exit 1
    fi
    l=$("$arachis" lab --json repose-pile "$deck/final.dump" |
        python3 -c 'import json,sys; print(json.load(sys.stdin)["angle_deg"])')
    echo "$k $a $l" >> "$work/angles.txt"
    echo "seed $k: Arachis $a°, LIGGGHTS $l°" >&2
done
end=$(date +%s)
load_after=$(cut -d' ' -f1-3 /proc/loadavg)

python3 - "$work/angles.txt" "$spheres" "$json" "$((end - start))" "$load_before" "$load_after" <<'EOF'
import json, math, statistics, sys
path, n, as_json, seconds, before, after = sys.argv[1:7]
rows = [list(map(float, l.split())) for l in open(path) if l.strip()]
arachis = [r[1] for r in rows]
liggghts = [r[2] for r in rows]
TOLERANCE_DEG = 1.0
def stats(xs):
    mean = statistics.fmean(xs)
    sd = statistics.stdev(xs) if len(xs) > 1 else 0.0
    return mean, sd, sd / math.sqrt(len(xs))
(ma, sa, ea), (ml, sl, el) = stats(arachis), stats(liggghts)
diff = ma - ml
two_se = 2.0 * math.hypot(ea, el)
print(f"Repose by cylinder lifting: {n} spheres of R 4 mm, {len(rows)} seeds per engine; "
      "LIGGGHTS 3.8 with limitForce on; both engines' piles photographed by the rig's extraction")
print("seed  Arachis deg  LIGGGHTS deg")
for r in rows:
    print(f"{int(r[0]):4d}  {r[1]:11.3f}  {r[2]:12.3f}")
print(f"{'engine':9s} {'mean':>8s} {'SD':>7s} {'SE':>7s}")
print(f"{'Arachis':9s} {ma:8.3f} {sa:7.3f} {ea:7.3f}")
print(f"{'LIGGGHTS':9s} {ml:8.3f} {sl:7.3f} {el:7.3f}")
ok = abs(diff) <= TOLERANCE_DEG
within = abs(diff) <= two_se
print(f"difference {diff:+.3f} deg, 2·SE {two_se:.3f} deg; |diff| <= {TOLERANCE_DEG}°: "
      f"{'yes' if ok else 'NO'}; within 2·SE: {'yes' if within else 'no'}")
print(f"wall time {seconds} s; load average before {before}, after {after}")
if as_json == "1":
    print(json.dumps({"spheres": int(n), "seeds": len(rows), "arachis_deg": arachis,
                      "liggghts_deg": liggghts, "arachis_mean_deg": ma, "liggghts_mean_deg": ml,
                      "difference_deg": diff, "two_se_deg": two_se,
                      "within_tolerance": ok, "within_two_se": within}))
EOF
