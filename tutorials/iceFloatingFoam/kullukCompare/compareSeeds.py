#!/usr/bin/env python3
# -----------------------------------------------------------------------------
# iceDEM tutorial iceFloatingFoam/kullukCompare: the comparison over seeds.
#
#   python3 compareSeeds.py --out DIR RESULTS_DIR...
#
# Each RESULTS_DIR is the results/ folder of one seed (Allrun.compare -seed S
# -dir seedS writes results/seedS/compare.csv). For the mean horizontal ice
# load and the largest line tension it writes DIR/compareSeeds.csv:
#   per seed and variant: the run's mean and its 95 % half-width (batch means);
#   per variant: the mean over the seeds and its 95 % interval across seeds
#     (Student t with seeds - 1 degrees of freedom: the seeds are independent
#     ice fields, so this interval holds the field-to-field spread);
#   per pair of variants: the mean of the per-seed differences and its 95 %
#     interval (paired: the variants share each seed's mesh and ice field, so
#     the field-to-field spread cancels in the difference).
# The same table is printed.
# -----------------------------------------------------------------------------
import argparse
import csv
import math
import os
import sys

VARIANTS = ("oneWay", "twoWay", "empirical")
QUANTITIES = ("iceLoad", "maxTension")
PAIRS = (("twoWay", "oneWay"), ("empirical", "oneWay"), ("twoWay", "empirical"))

# Two-sided 95 % Student t quantiles t_{dof, 0.975}
T975 = {1: 12.706, 2: 4.303, 3: 3.182, 4: 2.776, 5: 2.571, 6: 2.447, 7: 2.365,
        8: 2.306, 9: 2.262, 10: 2.228}


def tQuantile(dof):
    if dof in T975:
        return T975[dof]
    return 1.96 + 2.4/dof     # close enough beyond 10 (error < 1 %)


def meanInterval(x):
    n = len(x)
    m = sum(x)/n
    if n < 2:
        return m, float("nan")
    s = math.sqrt(sum((v - m)**2 for v in x)/(n - 1))
    return m, tQuantile(n - 1)*s/math.sqrt(n)


def readCompare(path):
    table = {}
    with open(path) as f:
        rows = [l for l in f if not l.startswith("#")]
    for r in csv.DictReader(rows):
        table[(r["variant"], r["quantity"])] = (float(r["mean"]),
                                                 float(r["halfWidth95"]))
    return table


def main():
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("--out", required=True)
    p.add_argument("dirs", nargs="+")
    a = p.parse_args()

    seeds = []
    for d in a.dirs:
        f = os.path.join(d, "compare.csv")
        if not os.path.isfile(f):
            sys.exit(f"compareSeeds.py: no {f} (run Allrun.compare for that seed first)")
        seeds.append((os.path.basename(os.path.normpath(d)), readCompare(f)))
    for name, t in seeds:
        for v in VARIANTS:
            for q in QUANTITIES:
                if (v, q) not in t:
                    sys.exit(f"compareSeeds.py: {name}: no {v} {q} in compare.csv")

    os.makedirs(a.out, exist_ok=True)
    out = os.path.join(a.out, "compareSeeds.csv")
    lines = ["kind,quantity,variant,seed,mean,halfWidth95,seeds"]
    print(f"{len(seeds)} seeds: " + " ".join(n for n, _ in seeds))
    for q in QUANTITIES:
        print(f"\n{q} [kN]: per seed, mean +- 95 % half-width of the run")
        print("seed".ljust(12) + "".join(v.rjust(22) for v in VARIANTS))
        for name, t in seeds:
            row = name.ljust(12)
            for v in VARIANTS:
                m, h = t[(v, q)]
                row += f"{m/1e3:14.1f} +- {h/1e3:5.1f}"
                lines.append(f"run,{q},{v},{name},{m:.6g},{h:.6g},1")
            print(row)
        row = "over seeds".ljust(12)
        for v in VARIANTS:
            m, h = meanInterval([t[(v, q)][0] for _, t in seeds])
            row += f"{m/1e3:14.1f} +- {h/1e3:5.1f}"
            lines.append(f"acrossSeeds,{q},{v},,{m:.6g},{h:.6g},{len(seeds)}")
        print(row)
        for x, y in PAIRS:
            d = [t[(x, q)][0] - t[(y, q)][0] for _, t in seeds]
            m, h = meanInterval(d)
            lines.append(f"pairedDifference,{q},{x}-{y},,{m:.6g},{h:.6g},{len(seeds)}")
            print(f"  {x} - {y}: {m/1e3:+.1f} +- {h/1e3:.1f} kN (paired over the seeds)")
    with open(out, "w") as f:
        f.write("\n".join(lines) + "\n")
    print(f"\nwritten: {out}")


if __name__ == "__main__":
    main()
