#!/usr/bin/env python3
"""Write a sphere study for the LIGGGHTS cross-checks (scripts/cross-check-*.sh).

The shipped seed-000 study (testdata/peanut-pods-saline/study.toml) with its pods replaced by
spheres of one radius (the pod material, DESIGN §8) and both pairs in the given LIGGGHTS
conventions. With --spheres N, its quick and full modes hold N spheres in a cylinder whose
diameter makes the fill about as deep as it is wide (D³ = 4·N·V/(0.6π), V a sphere's volume,
0.6 the packing fraction), as the seed's 900 pods fill its 200 mm cylinder.

Usage: sphere-study.py SOURCE TARGET [--radius-mm R] [--rolling-convention C]
                       [--friction-convention C] [--spheres N]
"""
import argparse
import math
import sys

PACKING = 0.6


def replace_value(text, key, value):
    i = text.index(key + " = ")
    j = text.index("\n", i)
    return text[:i] + f"{key} = {value}" + text[j:]


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("source")
    p.add_argument("target")
    p.add_argument("--radius-mm", type=float, default=4.0)
    p.add_argument("--rolling-convention", default="liggghts-cdt")
    p.add_argument("--friction-convention", default="liggghts")
    p.add_argument("--spheres", type=int)
    a = p.parse_args()
    text = open(a.source).read()
    start, end = text.index("[pods]"), text.index("# Contact pairs.")
    text = text[:start] + f'[spheres]\nmaterial = "pod"\nradius_mm = {a.radius_mm}\n\n' + text[end:]
    for pair in ("pod-pod", "pod-steel"):
        header = f'[pairs."{pair}"]\n'
        text = text.replace(
            header,
            header + f'rolling_convention = "{a.rolling_convention}"\n'
            f'friction_convention = "{a.friction_convention}"\n',
            1,
        )
    note = f"study: spheres of R {a.radius_mm} mm, {a.rolling_convention}/{a.friction_convention}"
    if a.spheres is not None:
        volume = 4.0 / 3.0 * math.pi * a.radius_mm**3
        diameter = (4.0 * a.spheres * volume / (PACKING * math.pi)) ** (1.0 / 3.0)
        text = replace_value(text, "cylinder_diameter_mm", f"{diameter:.1f}")
        text = replace_value(text, "cylinder_height_mm", f"{1.5 * diameter:.1f}")
        # The quick mode is the pile of N spheres; the full mode the same: nothing rescales.
        for mode in ("[plan.modes.quick]", "[plan.modes.full]"):
            at = text.index(mode)
            text = text[:at] + replace_value(text[at:], "pods", a.spheres)
        note += f"; {a.spheres} spheres, cylinder {diameter:.1f} mm"
    open(a.target, "w").write(text)
    print(note, file=sys.stderr)


if __name__ == "__main__":
    main()
