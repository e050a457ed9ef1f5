#!/usr/bin/env python3
# -----------------------------------------------------------------------------
# iceFloatingFoam/kullukPack: the study's CSV and figures from the finished
# points (the folders with a file 'done') of runStudy or domainConvergence.
#
#   python3 plotStudy.py --dir studyRuns [--transient 300] [--convergence]
#                        [--runs results/studyFull_study_runs.csv]
#                        [--against results/studyPerPair_study_runs.csv]
#                        [--markdown FILE] [--hullMarkdown FILE]
#                        [--pointsMarkdown FILE]
#
# --against CSV: DIR/against.txt, each run against the same point of
# another study_runs.csv (writeAgainst; README "Outputs").
# --runs CSV: rows of a study_runs.csv written before (a study that ran on
# several machines or sessions whose point folders are gone): every row whose
# point has no finished folder in DIR is taken as it is; a finished folder
# replaces its row. Rows of another transient are refused.
#
# Per run, from postProcessing/iceLoadStatistics/<start>/series.dat of every
# session (a resumed run has one folder per session; the samples of a
# session after the next one's start are replaced by the next one's):
#   the horizontal ice load Fh = |(Fx, Fy)| and the largest line tension of
#   each sample after the transient: mean, std (n - 1), max, P99 (linear
#   interpolation, Hyndman & Fan type 7, as numpy); the 95 % interval of the
#   mean by 20 batch means (as iceLoadStatistics); the force balance: the
#   mean of (F + W) along the mean driving force D against |mean D|, with
#   the batch-means half-width of (F + W - D).d / |mean D|.
#   Speed: floe-steps per second and contacts per step (its sessions weighted
#   by their DEM steps) from speed.txt, and
#   the commits its sessions ran from (commits, joined by '+'; "unknown"
#   where speed.txt has none); the multi-rate step K (bodyForceInterval in
#   the point's parameters; 1 where it is absent: the runs before the entry)
#   and the contacts' damping (normalDamping; perContact where it is absent:
#   the only one before the entry); the stretches run at the fallback step
#   after a stop (fallbackStretches, and fallbackTime: the simulated seconds
#   they cover; from fallback.txt, 0 where the point has none).
#   At the hull (bodies.dat at the write times after the transient): the
#   mean number of floes whose centre is inside the waterline circle (35 m:
#   under the hull), and of floes within 60 m of the axis whose top is
#   below the water (pushed down the cone or under the hull), and of all
#   floes within 60 m; the mean x velocity of all floes (packSpeedX: a
#   jammed pack is at rest, a pack in free drift moves at about 0.4 m/s).
#   From postProcessing/iceClearance/ (the points run since the function
#   object exists): the net floes whose centre crossed the plane through the
#   hull's axis normal to the drift after the transient, inside the 35 m
#   waterline circle (clearUnder: under the hull) and out to 60 m
#   (clearAround), the floes among them pushed under the water near the hull
#   (clearSubmerged), their ice volumes [m3] and the hours counted.
#   From postProcessing/iceLoad/ (every output step after the transient):
#   the mean vertical ice load on the hull Fz_mean with its batch-means
#   half-width (upward, > 0: the cone pushes floes down; a fully submerged
#   floe of area A and thickness h lifts with A h (rho_w - rho_i) g) and the
#   mean number of floe-hull contacts.
# Across seeds (one row per thickness and concentration): the mean of each
# statistic over the seeds and its 95 % interval t_{n-1} s/sqrt(n).
# Writes DIR/study_runs.csv, DIR/study.csv, DIR/study.png,
# DIR/forceBalance.png, DIR/trends.csv (per concentration with three or more
# thicknesses: the exponent b of mean |F_h| ~ h^b, the least-squares slope of
# the logarithms over every run, with its 95 % interval); --markdown FILE: the table of every run (the
# kullukPack README's "Results so far"); --hullMarkdown FILE: what happens at the
# hull, one row per thickness and concentration (means over the seeds: |F_h|,
# F_z, F_z/|F_h|, F_z in lifts of fully submerged floes, floe-hull contacts,
# floes within 60 m, pushed down, under the hull; the floes that passed under
# and beside the hull and were pushed under the water, and the hours counted,
# from iceClearance (sums over the seeds); the README's "What happens at the hull"); --pointsMarkdown FILE: study.csv as a table, one row per
# thickness and concentration (the means over the seeds with their 95 %
# t-intervals across the seeds) (with --convergence: DIR/convergence.csv and
# DIR/convergence.png, the mean load against the domain's length and width).
# -----------------------------------------------------------------------------
import argparse
import glob
import math
import os
import re
import sys

import numpy as np

# two-sided 95 % Student t quantiles t_{nu, 0.975}
T975 = {1: 12.706, 2: 4.303, 3: 3.182, 4: 2.776, 5: 2.571, 6: 2.447, 7: 2.365,
        8: 2.306, 9: 2.262, 10: 2.228, 15: 2.131, 19: 2.093, 20: 2.086, 29: 2.045}


def t975(nu):
    if nu in T975:
        return T975[nu]
    k = max(x for x in T975 if x <= nu)
    return T975[k]


BATCHES = 20
WATERLINE_RADIUS = 35.0   # [m] the Kulluk's 70 m waterline (structureDict)
NEAR_RADIUS = 60.0        # [m] around the axis: the cone and the ice at it
# the lift of a fully submerged floe, A h (rho_w - rho_i) g: the densities of
# the tutorial's constant/iceDEMProperties (materials ice, water)
ICE_DENSITY = 900.0       # [kg/m3]
WATER_DENSITY = 1025.0    # [kg/m3]
GRAVITY = 9.81            # [m/s2]


def readParameters(d):
    p = {}
    for line in open(os.path.join(d, "parameters")):
        k, v = line.split(None, 1)
        p[k] = v.strip()
    return p


def sessionFiles(d, pattern):
    """The file of every session of the run in d, postProcessing/<object>/<start
    time>/<file> (pattern: "<object>/*/<file>"), by start time: [(start, path)]"""
    return sorted((float(f.split("/")[-2]), f)
                  for f in glob.glob(os.path.join(d, "postProcessing", pattern)))


def readSeries(d):
    header, parts = None, []
    for _, f in sessionFiles(d, "iceLoadStatistics/*/series.dat"):
        names = None
        rows = []
        for line in open(f):
            if line.startswith("# time"):
                names = line[1:].split()
            elif not line.startswith("#") and line.strip():
                rows.append([float(x) for x in line.split()])
        if rows:
            header = names
            parts.append(np.array(rows))
    if not parts:
        return None, None
    out = []
    for i, a in enumerate(parts):
        if i + 1 < len(parts):
            a = a[a[:, 0] <= parts[i + 1][0, 0] - 1e-9]
        out.append(a)
    return header, np.vstack(out)


def readIceLoad(d):
    """postProcessing/iceLoad/*/iceLoad.dat of every session (the ice load
    on the structure per output step: time Fx Fy Fz Mx My Mz contacts), later
    sessions replacing the rows they repeat, as readSeries."""
    rows = {}
    for _, f in sessionFiles(d, "iceLoad/*/iceLoad.dat"):
        for line in open(f):
            if not line.startswith("#") and line.strip():
                v = [float(x) for x in line.split()]
                rows[v[0]] = v
    return np.array([rows[t] for t in sorted(rows)]) if rows else None


def clearanceCounts(d, tStart):
    """The net floes (and ice volume) that passed the hull after tStart,
    under it and around it, and of those the floes pushed under the water
    near it, from postProcessing/iceClearance/<start>/clearance.dat of every
    session (cumulative from each session's start: a session's rows up to
    the next one's start, where the next one's counts begin), and the hours
    they cover. NaN without the files (points run before the function
    object)."""
    files = sessionFiles(d, "iceClearance/*/clearance.dat")
    keys = ["clearUnder", "clearAround", "clearSubmerged", "clearVolumeUnder",
            "clearVolumeAround", "clearHours"]
    out = dict.fromkeys(keys, float("nan"))
    if not files:
        return out
    total = np.zeros(5)
    seconds = 0.0
    for k, (start, f) in enumerate(files):
        end = files[k + 1][0] if k + 1 < len(files) else math.inf
        rows = [[float(x) for x in l.split()[:6]] for l in open(f)
                if not l.startswith("#") and l.strip()]
        rows = [r for r in rows if r[0] <= end]
        if not rows or rows[-1][0] <= tStart:
            continue
        before = [r for r in rows if r[0] <= tStart]
        base = np.array(before[-1][1:6]) if before else np.zeros(5)
        total += np.array(rows[-1][1:6]) - base
        seconds += rows[-1][0] - max(start, tStart)
    out.update(zip(keys, list(total) + [seconds/3600.0]))
    return out


def batchHalfWidth(x, k=BATCHES):
    n = len(x)
    b = n // k
    if b < 1:
        return float("nan")
    m = x[n - k*b:].reshape(k, b).mean(axis=1)
    return t975(k - 1)*m.std(ddof=1)/math.sqrt(k)


def stats(x):
    return dict(mean=x.mean(), std=x.std(ddof=1), max=x.max(),
                p99=np.percentile(x, 99), hw=batchHalfWidth(x))


def hullCounts(d, tStart, floes, pieces=0):
    """Mean over the write times after the transient of the floes (ids below
    'floes': the structure's pieces follow them) whose centre is inside the
    waterline circle (under the hull: only a submerged floe gets there), and
    of the floes within NEAR_RADIUS of the axis whose top is below the water
    (centre below -h/2: pushed down the cone or under the hull; a floating
    floe's centre is at about -0.38 h). Floes inserted by an inflow (ids
    after the pieces') count."""
    files = sessionFiles(d, "iceDEM/*/bodies.dat")
    if not files:
        return float("nan"), float("nan"), float("nan"), float("nan")
    # every session's file (a restart writes postProcessing/iceDEM/<start>/),
    # an earlier session's rows kept only before the next one's start, as
    # readSeries (what a stopped session wrote past its last restart point
    # was run again)
    rows = {}
    for k, (_, f) in enumerate(files):
        end = files[k + 1][0] if k + 1 < len(files) else math.inf
        for line in open(f):
            if not line.startswith("#") and line.strip():
                v = line.split()
                if float(v[0]) < end:
                    rows[(float(v[0]), int(v[1]))] = v
    h = float(readParameters(d)["thickness"])
    under, down, near, vx = {}, {}, {}, []
    for key in sorted(rows):
        v = rows[key]
        t, i = key
        if t <= tStart or floes <= i < floes + pieces or (not pieces and i >= floes):
            continue
        x, y, z = float(v[2]), float(v[3]), float(v[4])
        vx.append(float(v[5]))
        r = math.hypot(x, y)
        under.setdefault(t, 0)
        down.setdefault(t, 0)
        near.setdefault(t, 0)
        if r < NEAR_RADIUS:
            near[t] += 1
        if r < WATERLINE_RADIUS:
            under[t] += 1
        if r < NEAR_RADIUS and z < -0.5*h:
            down[t] += 1
    if not under:
        return float("nan"), float("nan"), float("nan"), float("nan")
    return (np.mean(list(under.values())), np.mean(list(down.values())),
            np.mean(list(near.values())), np.mean(vx))


def fallbackStretches(d):
    """The stretches the point ran at its fallback step (runStudy
    -fallbackDeltaT) and the simulated seconds they cover, from its
    fallback.txt (a line 'from until deltaT K (message)' per stretch; a
    '# the stretch resumed at A s: to B s' line moves the last one's end);
    0 and 0 where the point has none."""
    stretches = []
    path = os.path.join(d, "fallback.txt")
    if os.path.exists(path):
        for line in open(path):
            m = re.match(r"# the stretch resumed at \S+ s: to (\S+) s", line)
            if m and stretches:
                stretches[-1][1] = float(m.group(1))
            elif line.strip() and not line.startswith("#"):
                v = line.split()
                stretches.append([float(v[0]), float(v[1])])
    return len(stretches), sum(b - a for a, b in stretches)


def analyseRun(d, transient):
    header, X = readSeries(d)
    if X is None:
        return None
    c = {n: i for i, n in enumerate(header)}
    steady = X[:, 0] > transient
    if steady.sum() < 2*BATCHES:
        return None
    S = X[steady]
    Fh = S[:, c["Fh"]]
    T = S[:, [i for n, i in c.items() if ".T" in n]]
    Tmax = T.max(axis=1) if T.shape[1] else np.zeros(len(S))
    D = S[:, [c["Dx"], c["Dy"]]]
    L = S[:, [c["Fx"], c["Fy"]]] + S[:, [c["Wx"], c["Wy"]]]
    dm = D.mean(axis=0)
    drive = np.hypot(*dm)
    e = dm/drive
    load = (L @ e).mean()
    hwRatio = batchHalfWidth((L - D) @ e)/drive
    p = readParameters(d)
    r = dict(dir=os.path.basename(d), length=float(p["length"]), width=float(p["width"]),
             thickness=float(p["thickness"]), concentration=float(p["concentration"]),
             seed=int(p["seed"]), deltaT=float(p["deltaT"]),
             bodyForceInterval=int(p.get("bodyForceInterval", 1)),
             normalDamping=p.get("normalDamping", "perContact"), floeArea=float(p["floeArea"]),
             steadyFrom=transient, steadyTo=S[-1, 0], samples=len(S))
    for k, v in stats(Fh).items():
        r["Fh_" + k] = v
    for k, v in stats(Tmax).items():
        r["Tmax_" + k] = v
    r.update(load=load, drive=drive, ratio=load/drive, ratioHalfWidth=hwRatio)
    # the trend within the run: the first and the second half of the window
    half = len(S)//2
    r.update(Fh_half1=Fh[:half].mean(), Fh_half2=Fh[half:].mean(),
             drive_half1=np.hypot(*D[:half].mean(axis=0)),
             drive_half2=np.hypot(*D[half:].mean(axis=0)))
    r["finished"] = int(os.path.isfile(os.path.join(d, "done")))
    r["domain"] = p.get("domain", "periodic")
    r["startVelocity"] = p.get("startVelocity", "current")
    sp = os.path.join(d, "speed.txt")
    if os.path.exists(sp):
        rows = [l.split() for l in open(sp) if not l.startswith("#")]
        steps = sum(float(x[1]) for x in rows)
        wall = sum(float(x[2]) for x in rows)
        r["floes"] = int(rows[-1][0])
        r["floeStepsPerSecond"] = int(rows[-1][0])*steps/wall if wall > 0 else float("nan")
        # weighted by the sessions' steps: a resumed point has several,
        # and one that resumes a finished run has none
        r["contactsPerStep"] = (sum(float(x[4])*float(x[1]) for x in rows)/steps
                                if steps > 0 else float("nan"))
        r["wallTime"] = wall
        commits = []
        for x in rows:
            c = x[6] if len(x) > 6 else "unknown"
            if c not in commits:
                commits.append(c)
        r["commits"] = "+".join(commits)
    r["fallbackStretches"], r["fallbackTime"] = fallbackStretches(d)
    floes = r.get("floes") or int([l.split()[1] for l in open(os.path.join(d, "log.createIceField"))
                                    if l.split()[:1] == ["floes"]][-1])
    # the structure's pieces have the ids floes .. floes + pieces - 1 (the
    # solver adds them after the field); floes inserted by an inflow come after
    pieces = 0
    for line in open(os.path.join(d, "log.iceFloatingFoam")):
        m = re.search(r"convex piece\(s\), (\d+) segment\(s\)", line)
        if m:
            pieces = int(m.group(1))
            break
    r.setdefault("floes", floes)
    r["floesUnderHull"], r["floesPushedDown"], r["floesNearHull"], r["packSpeedX"] = \
        hullCounts(d, transient, floes, pieces)
    # the floes that passed the hull, under and around it (iceClearance)
    r.update(clearanceCounts(d, transient))
    # the vertical ice load on the hull (upward: the cone pushes floes down)
    # and the floe-hull contacts, every output step after the transient
    A = readIceLoad(d)
    w = A[:, 0] > transient if A is not None else None
    if A is not None and w.sum() >= 2*BATCHES:
        r["Fz_mean"], r["Fz_hw"] = A[w, 3].mean(), batchHalfWidth(A[w, 3])
        r["hullContacts_mean"] = A[w, 7].mean()
    else:
        r["Fz_mean"] = r["Fz_hw"] = r["hullContacts_mean"] = float("nan")
    return r


def readRuns(path, transient):
    """The rows of a study_runs.csv as analyseRun gives them (numbers as float,
    the seed, samples, floes and finished as int, the rest as text)."""
    ints = {"seed", "samples", "floes", "finished", "bodyForceInterval", "fallbackStretches"}
    texts = {"dir", "domain", "startVelocity", "commits", "normalDamping"}   # "7e27389" is a float
    lines = [l.rstrip("\n").split(",") for l in open(path) if l.strip()]
    keys, rows = lines[0], []
    for n, v in enumerate(lines[1:], start=2):
        if len(v) != len(keys):
            sys.exit(f"plotStudy: {path} line {n}: {len(v)} fields, the header has {len(keys)}")
        r = {}
        for k, x in zip(keys, v):
            if k in texts:
                r[k] = x
                continue
            try:
                r[k] = int(float(x)) if k in ints else float(x)
            except ValueError:
                r[k] = x
        r.setdefault("normalDamping", "perContact")   # rows from before the column
        if r.get("steadyFrom") != transient:
            sys.exit(f"plotStudy: {path} line {n} ({r.get('dir')}): transient "
                     f"{r.get('steadyFrom')} s, this analysis uses {transient} s")
        rows.append(r)
    return rows


def writeCsv(path, rows, keys):
    with open(path, "w") as f:
        f.write(",".join(keys) + "\n")
        for r in rows:
            f.write(",".join(("%.6g" % r[k]) if isinstance(r[k], float) else str(r[k])
                             for k in keys) + "\n")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--dir", required=True)
    ap.add_argument("--transient", type=float, default=300.0)
    ap.add_argument("--convergence", action="store_true")
    ap.add_argument("--unfinished", action="store_true",
                    help="also the points still running or stopped (column finished = 0)")
    ap.add_argument("--runs", help="a study_runs.csv of points analysed before; a finished "
                    "folder in DIR replaces its row")
    ap.add_argument("--against", help="a study_runs.csv of the same points run otherwise "
                    "(another step, damping, code): DIR/against.txt, point by point")
    ap.add_argument("--markdown", help="write the table of every run (markdown) to this file")
    ap.add_argument("--hullMarkdown", help="write what happens at the hull, one row per "
                    "thickness and concentration (markdown), to this file")
    ap.add_argument("--pointsMarkdown", help="write the statistics across seeds, one row per "
                    "thickness and concentration (markdown), to this file")
    a = ap.parse_args()
    runs = []
    for d in sorted(glob.glob(os.path.join(a.dir, "*"))):
        if os.path.isfile(os.path.join(d, "done")) or \
                (a.unfinished and os.path.isfile(os.path.join(d, "parameters"))):
            r = analyseRun(d, a.transient)
            if r is None:
                print(f"plotStudy: {d}: too few steady samples, left out")
            else:
                runs.append(r)
    if a.runs:
        here = {r["dir"] for r in runs}
        kept = [r for r in readRuns(a.runs, a.transient) if r["dir"] not in here]
        print(f"plotStudy: {len(kept)} runs taken from {a.runs}")
        runs = sorted(runs + kept, key=lambda r: r["dir"])
    if not runs:
        print(f"plotStudy: no finished point in {a.dir}")
        return 0
    keys = []   # every run's columns (rows written before a column existed lack it)
    for r in runs:
        keys += [k for k in r if k not in keys]
    for r in runs:
        for k in keys:
            r.setdefault(k, float("nan"))
    writeCsv(os.path.join(a.dir, "study_runs.csv"), runs, keys)
    print(f"plotStudy: {len(runs)} runs ({sum(r['finished'] for r in runs)} finished)"
          f" -> {a.dir}/study_runs.csv")
    print("run                      |Fh| mean +- hw [MN]   P99    max  | Tmax mean  P99 [MN] | "
          "balance ratio +- hw | floe-steps/s contacts/step")
    for r in runs:
        print(f"{r['dir']:24s} {r['Fh_mean']/1e6:7.3f} +- {r['Fh_hw']/1e6:6.3f} "
              f"{r['Fh_p99']/1e6:6.3f} {r['Fh_max']/1e6:6.3f} | {r['Tmax_mean']/1e6:6.3f} "
              f"{r['Tmax_p99']/1e6:6.3f} | {r['ratio']:7.4f} +- {r['ratioHalfWidth']:6.4f} | "
              f"{r.get('floeStepsPerSecond', float('nan')):9.0f} {r.get('contactsPerStep', float('nan')):8.1f}")

    if a.against:
        writeAgainst(os.path.join(a.dir, "against.txt"), runs, a.against, a.transient)
        print(f"plotStudy: the runs against {a.against} -> {a.dir}/against.txt")
    if a.markdown:
        writeMarkdown(a.markdown, runs)
        print(f"plotStudy: the table of {len(runs)} runs -> {a.markdown}")
    if a.hullMarkdown:
        writeHullMarkdown(a.hullMarkdown, runs)
        print(f"plotStudy: what happens at the hull -> {a.hullMarkdown}")
    if a.convergence:
        return convergence(a, runs)

    # across seeds
    agg = []
    qs = ["Fh_mean", "Fh_std", "Fh_max", "Fh_p99", "Tmax_mean", "Tmax_std", "Tmax_max",
          "Tmax_p99", "ratio", "Fz_mean"]
    for (h, cc), rs in byPoint(runs):
        row = dict(thickness=h, concentration=cc, seeds=len(rs))
        for q in qs:
            v = np.array([r[q] for r in rs])
            row[q] = v.mean()
            row[q + "_ci"] = t975(len(v) - 1)*v.std(ddof=1)/math.sqrt(len(v)) \
                if len(v) > 1 else float("nan")
        agg.append(row)
    writeCsv(os.path.join(a.dir, "study.csv"), agg, list(agg[0].keys()))
    print(f"plotStudy: {len(agg)} points -> {a.dir}/study.csv")
    if a.pointsMarkdown:
        writePointsMarkdown(a.pointsMarkdown, agg)
        print(f"plotStudy: the statistics across seeds -> {a.pointsMarkdown}")
    trends = thicknessExponents(runs)
    if trends:
        writeCsv(os.path.join(a.dir, "trends.csv"), trends, list(trends[0].keys()))
        for t in trends:
            print(f"plotStudy: c = {t['concentration']:g}: mean |F_h| ~ h^{t['exponent']:.2f}"
                  f" +- {t['exponent_ci']:.2f} ({t['runs']} runs, h = {t['thicknesses']})")
        print(f"plotStudy: the thickness exponents -> {a.dir}/trends.csv")
    figures(a.dir, runs, agg)
    return 0


def writeAgainst(path, runs, otherPath, transient):
    """The runs against the same points (dir) of another study_runs.csv:
    mean |F_h| with each run's 95 % batch-means half-width, the relative
    difference, and the difference over the root-sum-square of the two
    half-widths (|z| > 1: outside the 95 % interval of the difference of two
    independent runs); the DEM steps' fallback stretches and the wall times
    (comparable only where both ran on one machine); last, the mean relative
    difference over the points with its 95 % Student t interval."""
    other = {r["dir"]: r for r in readRuns(otherPath, transient)}
    lines = [f"# {len(runs)} runs against {otherPath}: mean |F_h| +- 95 % half-width [MN] "
             "this vs other, this/other - 1, z = difference / rss(half-widths),",
             "# fallback stretches (simulated s at the fallback step), wall time [s] this / other",
             "# (the same machine only: machines differ by up to 2x)"]
    rel, worst = [], 0.0
    for r in sorted(runs, key=lambda r: (r["seed"], r["dir"])):
        o = other.get(r["dir"])
        if o is None:
            lines.append(f"{r['dir']:14s} not in {otherPath}")
            continue
        fa, ha, fb, hb = (r["Fh_mean"]/1e6, r["Fh_hw"]/1e6, o["Fh_mean"]/1e6, o["Fh_hw"]/1e6)
        z = (fa - fb)/math.hypot(ha, hb)
        worst = max(worst, abs(z))
        rel.append(fa/fb - 1)
        lines.append(f"{r['dir']:14s} {fa:.3f} +- {ha:.3f} vs {fb:.3f} +- {hb:.3f} "
                     f"{100*(fa/fb - 1):+6.1f} %  z {z:+.2f}   fallback "
                     f"{r.get('fallbackStretches', 0)} ({r.get('fallbackTime', 0):g} s)   wall "
                     f"{r.get('wallTime', float('nan')):.1f} / {o.get('wallTime', float('nan')):.1f}")
    if len(rel) > 1:
        m, sd = float(np.mean(rel)), float(np.std(rel, ddof=1))
        lines.append(f"{len(rel)} points: this/other - 1 = {100*m:+.1f} +- "
                     f"{100*t975(len(rel) - 1)*sd/math.sqrt(len(rel)):.1f} % (95 %, t), "
                     f"worst |z| {worst:.2f}")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def byPoint(runs):
    """The runs grouped by thickness and concentration (the seeds of a
    point), in order: [((h, c), [runs]), ...]"""
    groups = {}
    for r in runs:
        groups.setdefault((r["thickness"], r["concentration"]), []).append(r)
    return sorted(groups.items())


def markdownHeader(header):
    """A markdown table's header and its rule, one cell per column (an
    escaped \\| inside a cell is not a column)."""
    return [header, "|" + "---|"*header.replace("\\|", "").strip("|").count("|") + "---|"]


def writeLines(path, option, lines):
    """The lines of a markdown table into path (option names it in the error)."""
    try:
        with open(path, "w") as f:
            f.write("\n".join(lines) + "\n")
    except OSError as e:
        sys.exit(f"plotStudy: {option} {path}: {e.strerror}")


def writePointsMarkdown(path, agg):
    """study.csv as a table: per thickness and concentration the means over
    the seeds of each run's statistics, ± their 95 % t-interval across the
    seeds (n/a with one seed)."""
    def pm(r, k, scale=1e-6, fmt="{:.3f}"):
        v, ci = r[k]*scale, r[k + "_ci"]*scale
        return fmt.format(v) + (" ± " + fmt.format(ci) if ci == ci else " ± n/a")
    lines = markdownHeader("| h [m] | c | seeds | mean \\|F_h\\| [MN] | std [MN] | P99 [MN] | max [MN] "
                           "| largest line tension: mean [MN] | its max [MN] | load/drive |")
    for r in agg:
        lines.append(
            f"| {r['thickness']:g} | {r['concentration']*100:.0f} % | {r['seeds']} "
            f"| **{pm(r, 'Fh_mean')}** | {pm(r, 'Fh_std')} | {pm(r, 'Fh_p99', fmt='{:.2f}')} "
            f"| {pm(r, 'Fh_max', fmt='{:.2f}')} | {pm(r, 'Tmax_mean')} "
            f"| {pm(r, 'Tmax_max')} | {pm(r, 'ratio', 1.0, '{:.2f}')} |")
    writeLines(path, "--pointsMarkdown", lines)


def thicknessExponents(runs, quantity="Fh_mean"):
    """Per concentration with at least three thicknesses: the exponent b of
    quantity ~ h^b, the least-squares slope of log(quantity) on log(h) over
    every run (the seeds as replicates), with its 95 % interval
    t_{n-2} se(b). A description of the grid's trend, not a law."""
    out = []
    for c in sorted({r["concentration"] for r in runs}):
        rs = [r for r in runs if r["concentration"] == c and r[quantity] > 0]
        hs = sorted({r["thickness"] for r in rs})
        if len(hs) < 3:
            continue
        x = np.log([r["thickness"] for r in rs])
        y = np.log([r[quantity] for r in rs])
        n = len(x)
        sxx = ((x - x.mean())**2).sum()
        b = ((x - x.mean())*(y - y.mean())).sum()/sxx
        resid = y - y.mean() - b*(x - x.mean())
        se = math.sqrt((resid**2).sum()/(n - 2)/sxx)
        out.append(dict(concentration=c, runs=n, thicknesses=" ".join(f"{h:g}" for h in hs),
                        exponent=b, exponent_ci=t975(n - 2)*se))
    return out


def writeMarkdown(path, runs):
    """The table of every run, thinnest ice and lowest concentration first."""
    def num(r, k, scale=1.0, fmt="{:.3f}"):
        v = r.get(k, float("nan"))
        if not isinstance(v, (int, float)) or v != v:
            return "n/a"
        return fmt.format(v*scale)
    lines = markdownHeader("| h [m] | c | seed | floes | DEM step [s]; K; damping | commit(s) "
                           "| mean \\|F_h\\| ± 95 % [MN] | P99 [MN] | max [MN] "
                           "| largest line tension: mean / max [MN] | load/drive ± 95 % "
                           "| pack drift [m/s] | F_z [MN] | contacts per step |")
    for r in sorted(runs, key=lambda r: (r["thickness"], r["concentration"], r["seed"])):
        lines.append(
            f"| {r['thickness']:g} | {r['concentration']*100:.0f} % | {r['seed']} "
            f"| {r['floes']} | {r['deltaT']:g}; {num(r, 'bodyForceInterval', fmt='{:.0f}')}; "
            f"{r.get('normalDamping', 'perContact')} "
            f"| {r.get('commits', 'unknown')} "
            f"| **{num(r, 'Fh_mean', 1e-6)} ± {num(r, 'Fh_hw', 1e-6)}** "
            f"| {num(r, 'Fh_p99', 1e-6, '{:.2f}')} | {num(r, 'Fh_max', 1e-6, '{:.2f}')} "
            f"| {num(r, 'Tmax_mean', 1e-6)} / {num(r, 'Tmax_max', 1e-6)} "
            f"| {num(r, 'ratio', fmt='{:.2f}')} ± {num(r, 'ratioHalfWidth', fmt='{:.2f}')} "
            f"| {num(r, 'packSpeedX')} | {num(r, 'Fz_mean', 1e-6, '{:.2f}')} "
            f"| {num(r, 'contactsPerStep', fmt='{:,.0f}')} |")
    writeLines(path, "--markdown", lines)


def writeHullMarkdown(path, runs):
    """What happens at the hull, one row per thickness and concentration: the
    means over the seeds of the horizontal and vertical ice loads, F_z in
    lifts of a fully submerged floe of the point's mean area, the floe-hull
    contacts (every output step), the floes near, pushed down and under
    the hull (bodies.dat snapshots, hullCounts) and the flux at the hull
    (iceClearance, clearanceCounts): the floes that passed under the hull,
    beside it (35-60 m from the axis) and, of those, pushed under the water
    near it: the sums over the seeds, and the hours they cover."""
    def mean(rs, k, scale=1.0, fmt="{:.3f}"):
        v = [r.get(k, float("nan")) for r in rs]
        v = [x for x in v if isinstance(x, (int, float))]
        if not v or any(x != x for x in v):
            return "n/a"
        return fmt.format(scale*sum(v)/len(v))

    def total(rs, k, fmt="{:.0f}"):
        # the sum over the seeds that counted (runs before iceClearance: NaN)
        v = [r.get(k, float("nan")) for r in rs]
        v = [x for x in v if isinstance(x, (int, float)) and x == x]
        return fmt.format(sum(v)) if v else "n/a"
    lines = markdownHeader("| h [m] | c | seeds | mean \\|F_h\\| [MN] | mean F_z [MN] | F_z / \\|F_h\\| "
                           "| F_z in submerged-floe lifts | floe-hull contacts | floes within 60 m "
                           "| pushed down | under the hull | passed under the hull | passed beside it "
                           "| of those pushed under the water | hours counted |")
    for (h, c), rs in byPoint(runs):
        rs = [dict(r, FzOverFh=r["Fz_mean"]/r["Fh_mean"],
                   lifts=r["Fz_mean"]/(r["floeArea"]*h*(WATER_DENSITY - ICE_DENSITY)*GRAVITY))
              for r in rs]
        lines.append(
            f"| {h:g} | {c*100:.0f} % | {len(rs)} | {mean(rs, 'Fh_mean', 1e-6)} "
            f"| {mean(rs, 'Fz_mean', 1e-6, '{:.2f}')} | {mean(rs, 'FzOverFh', fmt='{:.1f}')} "
            f"| {mean(rs, 'lifts', fmt='{:.1f}')} | {mean(rs, 'hullContacts_mean', fmt='{:.1f}')} "
            f"| {mean(rs, 'floesNearHull', fmt='{:.1f}')} | {mean(rs, 'floesPushedDown', fmt='{:.2f}')} "
            f"| {mean(rs, 'floesUnderHull', fmt='{:.2f}')} | {total(rs, 'clearUnder')} "
            f"| {total(rs, 'clearAround')} | {total(rs, 'clearSubmerged')} "
            f"| {total(rs, 'clearHours', '{:.2f}')} |")
    writeLines(path, "--hullMarkdown", lines)


def figures(d, runs, agg):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    cs = sorted(set(r["concentration"] for r in agg))
    fig, ax = plt.subplots(2, 2, figsize=(11, 8))
    panels = [("Fh_mean", "mean |F_h| [MN]", ax[0, 0]), ("Fh_p99", "P99 and max |F_h| [MN]", ax[0, 1]),
              ("Tmax_mean", "mean largest line tension [MN]", ax[1, 0]),
              ("Tmax_p99", "P99 and max of the largest line tension [MN]", ax[1, 1])]
    for q, label, a_ in panels:
        for c in cs:
            rs = [r for r in agg if r["concentration"] == c]
            h = [r["thickness"] for r in rs]
            y = np.array([r[q] for r in rs])/1e6
            e = np.nan_to_num(np.array([r[q + "_ci"] for r in rs])/1e6)
            l = a_.errorbar(h, y, yerr=e, marker="o", capsize=3, label=f"c = {c*100:.0f} %")
            if q.endswith("p99"):
                m = np.array([r[q.replace("p99", "max")] for r in rs])/1e6
                a_.plot(h, m, "x--", color=l[0].get_color(), alpha=0.6)
        a_.set_xlabel("ice thickness h [m]")
        a_.set_ylabel(label)
        a_.grid(alpha=0.3)
    ax[0, 0].axhline(1.0, color="k", ls=":", label="field: order 1 MN, managed broken ice")
    ax[0, 1].axhline(1.0, color="k", ls=":")
    # the loads are one to two orders below the field's: a log axis shows
    # their trends beside it
    ax[0, 0].set_yscale("log")
    ax[0, 1].set_yscale("log")
    for a_ in (ax[1, 0], ax[1, 1]):
        a_.axhspan(5, 10, color="r", alpha=0.1, label="mooring capacity, order 5-10 MN")
        a_.axhline(1.5, color="gray", ls="--", lw=0.8, label="pretension 1.5 MN (assumed)")
    ax[0, 0].legend(fontsize=8)
    ax[1, 0].legend(fontsize=8)
    fig.suptitle("Kulluk in a periodic pack, design wind 55 km/h + current 0.3 m/s, DEM only; "
                 "error bars: 95 % CI across seeds; x: max", fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(d, "study.png"), dpi=110)
    plt.close(fig)

    fig, a_ = plt.subplots(figsize=(10, 4))
    x = np.arange(len(runs))
    a_.errorbar(x, [r["ratio"] for r in runs], yerr=[r["ratioHalfWidth"] for r in runs],
                fmt="o", capsize=3)
    a_.axhline(1, color="k", lw=0.8)
    a_.axhspan(0.95, 1.05, color="g", alpha=0.1, label="within 5 %")
    a_.set_xticks(x)
    a_.set_xticklabels([r["dir"] for r in runs], rotation=70, fontsize=7)
    a_.set_ylabel("mean hull load / mean driving force")
    a_.set_title("Force balance of every run (95 % batch-means interval)")
    a_.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(d, "forceBalance.png"), dpi=110)
    plt.close(fig)
    print(f"plotStudy: {d}/study.png, {d}/forceBalance.png")


def convergence(a, runs):
    keys = ["dir", "domain", "startVelocity", "finished", "length", "width", "deltaT", "seed",
            "floes", "steadyFrom", "steadyTo", "Fh_mean", "Fh_hw", "Fh_std",
            "Fh_p99", "Fh_max", "Tmax_mean", "drive", "ratio", "ratioHalfWidth", "packSpeedX",
            "Fh_half1", "Fh_half2", "drive_half1", "drive_half2",
            "floesUnderHull", "floesPushedDown", "floesNearHull",
            "floeStepsPerSecond", "contactsPerStep", "wallTime"]
    for r in runs:
        for k in keys:
            r.setdefault(k, float("nan"))
    writeCsv(os.path.join(a.dir, "convergence.csv"), runs, keys)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
    for r in runs:
        lab = f"dt {r['deltaT']:g}, seed {r['seed']}"
        ax[0].errorbar(r["length"], r["Fh_mean"]/1e6, yerr=r["Fh_hw"]/1e6, fmt="o", capsize=3)
        ax[0].annotate(f"W {r['width']:.0f}\n{lab}", (r["length"], r["Fh_mean"]/1e6), fontsize=6)
        ax[1].errorbar(r["width"], r["Fh_mean"]/1e6, yerr=r["Fh_hw"]/1e6, fmt="o", capsize=3)
        ax[1].annotate(f"L {r['length']:.0f}\n{lab}", (r["width"], r["Fh_mean"]/1e6), fontsize=6)
    ax[0].set_xlabel("periodic length along the drift L [m]")
    ax[1].set_xlabel("periodic width across the drift W [m]")
    for a_ in ax:
        a_.set_ylabel("mean |F_h| [MN] (95 % batch-means CI)")
        a_.grid(alpha=0.3)
    fig.suptitle("Domain convergence at the design point (1.2 m, 80 %), design wind + current")
    fig.tight_layout()
    fig.savefig(os.path.join(a.dir, "convergence.png"), dpi=110)
    print(f"plotStudy: {a.dir}/convergence.csv, {a.dir}/convergence.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
