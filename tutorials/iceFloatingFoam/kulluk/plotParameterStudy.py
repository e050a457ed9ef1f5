#!/usr/bin/env python3
"""iceFloatingFoam/kulluk: the parameter study's table, CSV and PNG.

    python3 plotParameterStudy.py --runs parameterStudyRuns \
        --csv parameterStudy.csv --png parameterStudy.png
    python3 plotParameterStudy.py --csv parameterStudy.csv --png parameterStudy.png

With --runs: reads every run folder <h>_<c>_<seed>[_coupled] (see
parameterStudy), computes the statistics of the horizontal ice load
|F_h| = sqrt(Fx^2 + Fy^2) of postProcessing/iceLoad/0/iceLoad.dat over the
run's own window from its first floe-structure contact to its end, and
writes the CSV. Without --runs: reads the CSV. Then prints the table and
draws the PNG: mean and maximum |F_h| against thickness, one curve per
concentration (DEM-only runs, averaged over the seeds), the coupled runs as
open markers, with the field-record context of the Kulluk (method.md
section 8): the design ice thickness 1.2 m and loads of order 1 MN in
managed broken ice (Wright 1999/2000, Kulluk stationkeeping in pack ice;
no numeric table of the records was retrievable, so only the order of
magnitude is marked).
"""
import argparse
import csv
import datetime
import glob
import os
import re
import subprocess
import sys

import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt     # noqa: E402

MN = 1e6
FIELDS = ["solver", "drag", "thickness_m", "concentration", "seed", "floes",
          "meanFloeArea_m2", "endTime_s", "windowStart_s", "windowEnd_s",
          "meanFh_MN", "stdFh_MN", "maxFh_MN", "meanFx_MN", "contactSteps", "steps"]


def table(path):
    return np.array([list(map(float, l.split())) for l in open(path)
                     if l.strip() and not l.startswith("#")])


def run_row(d):
    m = re.match(r"([0-9.]+)_([0-9.]+)_([0-9]+)(_coupled)?$", os.path.basename(d))
    if not m or not os.path.isfile(os.path.join(d, "postProcessing/iceLoad/0/iceLoad.dat")):
        return None
    L = table(os.path.join(d, "postProcessing/iceLoad/0/iceLoad.dat"))
    # the ice field's report (a coupled run uses its DEM-only twin's field)
    log = open(os.path.join(re.sub(r"_coupled$", "", d), "log.createIceField")).read()
    floes = re.search(r"^\s*floes\s+(\d+)", log, re.M).group(1)
    area = re.search(r"floe area \[m2\]\s+total\s+\S+\s+mean\s+(\S+)", log).group(1)
    coupled = bool(m.group(4))
    row = {"solver": "iceFloatingFoam" if coupled else "iceFloatingFoam -noFlow",
           "drag": "resolved" if coupled else "empirical",
           "thickness_m": m.group(1), "concentration": m.group(2), "seed": m.group(3),
           "floes": floes, "meanFloeArea_m2": f"{float(area):.1f}",
           "endTime_s": f"{L[-1, 0]:g}", "contactSteps": int((L[:, 7] > 0).sum()),
           "steps": len(L)}
    contact = L[:, 7] > 0
    if contact.any():
        t1 = L[contact, 0].min()
        w = L[L[:, 0] >= t1]
        Fh = np.hypot(w[:, 1], w[:, 2])
        row.update(windowStart_s=f"{t1:g}", windowEnd_s=f"{L[-1, 0]:g}",
                   meanFh_MN=f"{Fh.mean()/MN:.5f}", stdFh_MN=f"{Fh.std()/MN:.5f}",
                   maxFh_MN=f"{Fh.max()/MN:.5f}", meanFx_MN=f"{w[:, 1].mean()/MN:.5f}")
    else:
        row.update(windowStart_s="", windowEnd_s="", meanFh_MN="0", stdFh_MN="0",
                   maxFh_MN="0", meanFx_MN="0")
    return row


def write_csv(rows, path, args):
    try:
        commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"],
                                capture_output=True, text=True).stdout.strip()
    except OSError:
        commit = ""
    with open(path, "w", newline="") as f:
        f.write("# iceDEM tutorials/iceFloatingFoam/kulluk/parameterStudy: ice load on the"
                " moored Kulluk\n")
        f.write(f"# written {datetime.date.today()} (git {commit or 'unknown'});"
                " the case files of the tutorial with these changes:\n")
        f.write("#   ice field x -150..60 m, y -120..120 m, exclusion circle r = 45 m,"
                " meanFloeArea 225 m2, drift/current 0.3 m/s along x,\n")
        f.write(f"#   endTime {args.endTime} s, DEM deltaT {args.deltaT} s, drag subdivision 0;"
                " coupled runs on the reduced mesh (Allrun -reduced)\n")
        f.write("# statistics of |F_h| = sqrt(Fx^2+Fy^2) over windowStart (first ice"
                " contact) ... windowEnd\n")
        w = csv.DictWriter(f, fieldnames=FIELDS)
        w.writeheader()
        for r in rows:
            w.writerow(r)


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(l for l in f if not l.startswith("#")))


def print_table(rows):
    print("Ice load on the Kulluk against thickness and concentration: |F_h| [MN]"
          " from the first contact on")
    print(f"{'solver':<26}{'h [m]':>6}{'c':>6}{'seed':>6}{'floes':>7}"
          f"{'mean':>9}{'std':>9}{'max':>9}")
    for r in rows:
        print(f"{r['solver']:<26}{float(r['thickness_m']):6.1f}"
              f"{float(r['concentration']):6.2f}{r['seed']:>6}{r['floes']:>7}"
              f"{float(r['meanFh_MN']):9.3f}{float(r['stdFh_MN']):9.3f}"
              f"{float(r['maxFh_MN']):9.3f}")


def plot(rows, png):
    fig, ax = plt.subplots(1, 2, figsize=(12, 5))
    dem = [r for r in rows if r["drag"] == "empirical"]
    cpl = [r for r in rows if r["drag"] == "resolved"]
    cs = sorted({float(r["concentration"]) for r in rows})
    colours = dict(zip(cs, plt.cm.viridis(np.linspace(0.1, 0.85, len(cs)))))
    for a, key, title in ((ax[0], "meanFh_MN", "mean"), (ax[1], "maxFh_MN", "maximum")):
        for c in cs:
            sel = [r for r in dem if float(r["concentration"]) == c]
            hs = sorted({float(r["thickness_m"]) for r in sel})
            y = [np.mean([float(r[key]) for r in sel if float(r["thickness_m"]) == h])
                 for h in hs]
            a.plot(hs, y, "o-", color=colours[c],
                   label=f"c = {c:.0%}, DEM only (empirical drag)")
            selc = [r for r in cpl if float(r["concentration"]) == c]
            if selc:
                a.plot([float(r["thickness_m"]) for r in selc], [float(r[key]) for r in selc],
                       "s", mfc="none", mec=colours[c], ms=9, mew=1.5,
                       label=f"c = {c:.0%}, coupled (resolved drag)")
        a.axvline(1.2, color="grey", ls=":", lw=1.2)
        a.text(1.21, 0.62, "design ice 1.2 m", rotation=90, transform=a.get_xaxis_transform(),
               va="bottom", fontsize=8, color="grey")
        a.axhline(1.0, color="firebrick", ls="--", lw=1.2)
        a.text(0.02, 0.93, "field records: order 1 MN in managed broken ice\n"
               "(Wright 1999/2000, as in method.md section 8)",
               transform=a.get_yaxis_transform(), fontsize=8, color="firebrick", va="top")
        a.set_yscale("log")
        a.set_ylim(top=1.5)
        a.set_xlabel("ice thickness h [m]")
        a.set_ylabel(f"{title} horizontal ice load |F_h| [MN]")
        a.set_title(f"{title} |F_h| on the moored Kulluk")
        a.grid(alpha=0.3, which="both")
    ax[0].legend(fontsize=7, loc="center right")
    fig.tight_layout()
    fig.savefig(png, dpi=120)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--runs")
    ap.add_argument("--csv", default="parameterStudy.csv")
    ap.add_argument("--png", default="parameterStudy.png")
    ap.add_argument("--endTime", default="?")
    ap.add_argument("--deltaT", default="?")
    args = ap.parse_args()
    if args.runs:
        rows = [r for r in (run_row(d) for d in sorted(glob.glob(os.path.join(args.runs, "*"))))
                if r]
        if not rows:
            sys.exit(f"plotParameterStudy.py: no finished run in {args.runs}")
        rows.sort(key=lambda r: (r["drag"], float(r["concentration"]),
                                 float(r["thickness_m"]), int(r["seed"])))
        write_csv(rows, args.csv, args)
    rows = read_csv(args.csv)
    print_table(rows)
    plot(rows, args.png)
    print(f"Wrote {args.csv} and {args.png}")


if __name__ == "__main__":
    main()
