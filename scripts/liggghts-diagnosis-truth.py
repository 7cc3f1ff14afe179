#!/usr/bin/env python3
"""Rebound, press and roll measurements made by LIGGGHTS 3.8, for the diagnosis (issue 22).

Runs the decks of benches/liggghts/diagnosis/ at every condition of the rebound, press and
roll experiments of a [diagnosis] study or template (Young's modulus from its calibration;
restitution, SJKR cohesion and EPSD rolling resistance as given here, which is what the other
engine "hides") and
writes the true values as CSV (experiment, condition, truth), which
`arachis synth STUDY --truth CSV` turns into noisy replicates. Each run mirrors its rig
(host/src/rigs/rebound.rs, press.rs): the rebound starts at first touch; the press starts at
rest at the Hertz overlap of its load and settles for 25 small-oscillation periods, 30 steps
each; the roll starts at the Hertz overlap of the weight, rolling without slip, and runs 0.2 s
at 60 steps per small-oscillation period. Other experiments are refused. LIGGGHTS is installed by scripts/install-liggghts.sh when
missing.

Usage: liggghts-diagnosis-truth.py STUDY OUT.csv [--restitution E] [--cohesion-j-m3 K]
                                  [--epsd-rolling-friction MU]
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
# The rigs' sphere and floor (host/src/rigs/single_sphere.rs).
RADIUS_M = 0.004
DENSITY_KG_M3 = 582.36
POD_POISSON = 0.386
STEEL_YOUNGS_PA = 2.05e11
STEEL_POISSON = 0.3
# The press rig's settling: steps per small-oscillation period, and periods.
STEPS_PER_PERIOD = 30
PERIODS = 25
# The roll rig's time before the speed is read, s, and steps per small-oscillation period.
ROLL_TIME_S = 0.2
ROLL_STEPS_PER_PERIOD = 60
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DECKS = os.path.join(ROOT, "benches", "liggghts", "diagnosis")


def liggghts(work, deck, **variables):
    """Run DECK with -var NAME VALUE for each keyword; the one number it writes."""
    out = os.path.join(work, "value.txt")
    cmd = ["liggghts", "-in", os.path.join(DECKS, deck), "-log", "none", "-var", "out", out]
    for name, value in variables.items():
        cmd += ["-var", name, repr(value)]
    run = subprocess.run(cmd, cwd=work, capture_output=True, text=True)
    if run.returncode != 0 or not os.path.exists(out):
        sys.exit(f"LIGGGHTS failed ({deck}, {variables}):\n{run.stdout[-2000:]}{run.stderr[-2000:]}")
    with open(out) as f:
        _, value = f.read().split()
    os.remove(out)
    return float(value)


def rebound(work, youngs, e, cohesion, height_m):
    v = math.sqrt(2.0 * GRAVITY_M_S2 * height_m)
    return liggghts(work, "rebound.in", youngs=youngs, e=e, cohesion=cohesion, v=v)


def mass_kg():
    return 4.0 / 3.0 * math.pi * RADIUS_M**3 * DENSITY_KG_M3


def resting(youngs, load_n):
    """Hertz overlap under load_n (m) and the period of small normal oscillations there (s)."""
    e_star = 1.0 / ((1.0 - POD_POISSON**2) / youngs + (1.0 - STEEL_POISSON**2) / STEEL_YOUNGS_PA)
    alpha0 = (3.0 * load_n / (4.0 * e_star * math.sqrt(RADIUS_M))) ** (2.0 / 3.0)
    k = 2.0 * e_star * math.sqrt(RADIUS_M * alpha0)
    return alpha0, 2.0 * math.pi * math.sqrt(mass_kg() / k)


def press(work, youngs, cohesion, load_n):
    alpha0, period = resting(youngs, load_n)
    return liggghts(work, "press.in", youngs=youngs, cohesion=cohesion, g=load_n / mass_kg(),
                    z0=RADIUS_M - alpha0, dt=period / STEPS_PER_PERIOD,
                    steps=STEPS_PER_PERIOD * PERIODS)


def roll(work, youngs, e, mu_r, v0):
    alpha0, period = resting(youngs, mass_kg() * GRAVITY_M_S2)
    dt = period / ROLL_STEPS_PER_PERIOD
    return liggghts(work, "roll.in", youngs=youngs, e=e, mu_r=mu_r, v0=v0,
                    w0=v0 / (RADIUS_M - 0.5 * alpha0), z0=RADIUS_M - alpha0, dt=dt,
                    steps=round(ROLL_TIME_S / dt))


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("study")
    p.add_argument("out")
    p.add_argument("--restitution", type=float, default=None,
                   help="pod-steel restitution (default: the study's calibration)")
    p.add_argument("--cohesion-j-m3", type=float, default=0.0)
    p.add_argument("--epsd-rolling-friction", type=float, default=0.0)
    a = p.parse_args()
    subprocess.run([os.path.join(ROOT, "scripts", "install-liggghts.sh")], check=True)
    with open(a.study, "rb") as f:
        study = tomllib.load(f)["diagnosis"]
    youngs = study["calibration"]["youngs_modulus_pa"]
    e = a.restitution if a.restitution is not None else study["calibration"]["restitution"]
    rows = []
    k = a.cohesion_j_m3
    mu_r = a.epsd_rolling_friction
    with tempfile.TemporaryDirectory() as work:
        for experiment in study["experiment"]:
            kind = experiment["kind"]
            for point in experiment["point"]:
                x = point["condition"]
                if kind == "rebound":
                    rows.append((kind, x, rebound(work, youngs, e, k, x)))
                elif kind == "press":
                    rows.append((kind, x, press(work, youngs, k, x)))
                elif kind == "roll":
                    rows.append((kind, x, roll(work, youngs, e, mu_r, x)))
                else:
                    sys.exit(f"{a.study}: no LIGGGHTS deck for the {kind} rig "
                             "(rebound, press, roll)")
    tmp = a.out + ".part"
    with open(tmp, "w") as f:
        f.write(f"# LIGGGHTS 3.8, {os.path.relpath(DECKS, ROOT)}: E {youngs} Pa, "
                f"e {e}, SJKR cohesion {k} J/m3, EPSD2 rolling friction {mu_r}\n")
        f.write("experiment,condition,truth\n")
        for kind, x, truth in rows:
            f.write(f"{kind},{x!r},{truth!r}\n")
    os.replace(tmp, a.out)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
