#!/usr/bin/env python3
"""Rebound measurements made by LIGGGHTS 3.8, for the diagnosis (issue 22).

Runs benches/liggghts/diagnosis/rebound.in at every drop height of the rebound experiment of a
[diagnosis] study or template (Young's modulus from its calibration; restitution and SJKR
cohesion as given here, which is what the other engine "hides") and writes the true rebound
ratios as CSV (experiment, condition, truth), which `arachis synth STUDY --truth CSV` turns
into noisy replicates. LIGGGHTS is installed by scripts/install-liggghts.sh when missing.

Usage: liggghts-rebound-truth.py STUDY OUT.csv [--restitution E] [--cohesion-j-m3 K]
"""
import argparse
import math
import os
import subprocess
import sys
import tempfile
import tomllib

# Standard gravity, m/s² (the rig's impact speed is √(2gh)).
GRAVITY_M_S2 = 9.80665
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DECK = os.path.join(ROOT, "benches", "liggghts", "diagnosis", "rebound.in")


def rebound_ratio(work, youngs, e, cohesion, v):
    out = os.path.join(work, "ratio.txt")
    cmd = ["liggghts", "-in", DECK, "-log", "none", "-var", "youngs", repr(youngs),
           "-var", "e", repr(e), "-var", "cohesion", repr(cohesion), "-var", "v", repr(v),
           "-var", "out", out]
    run = subprocess.run(cmd, cwd=work, capture_output=True, text=True)
    if run.returncode != 0 or not os.path.exists(out):
        sys.exit(f"LIGGGHTS failed at v = {v} m/s:\n{run.stdout[-2000:]}{run.stderr[-2000:]}")
    with open(out) as f:
        name, value = f.read().split()
    os.remove(out)
    return float(value)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("study")
    p.add_argument("out")
    p.add_argument("--restitution", type=float, default=None,
                   help="pod-steel restitution (default: the study's calibration)")
    p.add_argument("--cohesion-j-m3", type=float, default=0.0)
    a = p.parse_args()
    subprocess.run([os.path.join(ROOT, "scripts", "install-liggghts.sh")], check=True)
    with open(a.study, "rb") as f:
        study = tomllib.load(f)["diagnosis"]
    youngs = study["calibration"]["youngs_modulus_pa"]
    e = a.restitution if a.restitution is not None else study["calibration"]["restitution"]
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for experiment in study["experiment"]:
            if experiment["kind"] != "rebound":
                continue
            for point in experiment["point"]:
                h = point["condition"]
                v = math.sqrt(2.0 * GRAVITY_M_S2 * h)
                rows.append((h, rebound_ratio(work, youngs, e, a.cohesion_j_m3, v)))
    if not rows:
        sys.exit(f"{a.study} has no rebound experiment")
    tmp = a.out + ".part"
    with open(tmp, "w") as f:
        f.write(f"# LIGGGHTS 3.8, {os.path.relpath(DECK, ROOT)}: E {youngs} Pa, "
                f"e {e}, SJKR cohesion {a.cohesion_j_m3} J/m3\n")
        f.write("experiment,condition,truth\n")
        for h, ratio in rows:
            f.write(f"rebound,{h!r},{ratio!r}\n")
    os.replace(tmp, a.out)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
