"""Scores dam-break fronts the way `runnel validate dambreak` does (surge_front.cpp): the surge
distance s = x - L against Koshizuka & Oka (1996), error |s_sim - s_exp| / s_exp at every measured
t* = t sqrt(g/L) whose front lies inside the 4 L tank, the front linearly interpolated in t*.

    python dambreak_front.py REFERENCE.csv pysph OUTPUT_DIR NAME   (PySPH's dam_break_2d output)
    python dambreak_front.py REFERENCE.csv runnel FRONT.csv NAME   (runnel validate's front.csv)

Prints one JSON line: the mean and worst error and the front at each measured time. The surge is
the front particle's displacement since t = 0 in both codes, so the column's own width L and how
each code places its particles against the wall do not enter.
"""
import csv
import glob
import json
import re
import sys

import numpy as np

G = 9.81
L = 1.0  # both codes' column width, m
TANK = 4.0  # L


def reference(path):
    with open(path) as f:
        rows = csv.DictReader(line for line in f if not line.startswith("#"))
        return [(float(r["t_star"]), float(r["x_over_L"])) for r in rows]


def pysph_front(out_dir):
    from pysph.solver.utils import load

    files = glob.glob(out_dir + "/*_[0-9]*.npz")
    files.sort(key=lambda f: int(re.search(r"_(\d+)\.npz$", f).group(1)))
    t, x = [], []
    for f in files:
        data = load(f)
        t.append(data["solver_data"]["t"] * np.sqrt(G / L))
        x.append(data["arrays"]["fluid"].get("x").max() / L)
    return np.array(t), np.array(x) - x[0]


def runnel_front(front_csv):
    t, x = np.loadtxt(front_csv, delimiter=",", unpack=True, comments=("#", "t"))
    return t, x - x[0]


def main():
    ref_path, code, source, name = sys.argv[1:5]
    t, surge = pysph_front(source) if code == "pysph" else runnel_front(source)
    points = []
    for t_exp, x_exp in reference(ref_path):
        if x_exp - 1.0 <= 0 or x_exp >= TANK or t_exp < t[0] or t_exp > t[-1]:
            continue
        s = float(np.interp(t_exp, t, surge))
        points.append({"t_star": t_exp, "experiment": x_exp, "simulated": round(1.0 + s, 4),
                       "error": abs(s - (x_exp - 1.0)) / (x_exp - 1.0)})
    errors = [p["error"] for p in points]
    print(json.dumps({"code": name, "mean_error": float(np.mean(errors)),
                      "worst_error": max(errors), "points": len(points),
                      "t_star_reached": round(float(t[-1]), 3), "front": points}))


if __name__ == "__main__":
    main()
