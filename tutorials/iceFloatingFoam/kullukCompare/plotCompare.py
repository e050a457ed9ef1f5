#!/usr/bin/env python3
# -----------------------------------------------------------------------------
# iceDEM tutorial iceFloatingFoam/kullukCompare: tables and figures of the
# comparison one-way / two-way / empirical (Allrun.compare runs it).
#
#   python3 plotCompare.py --out DIR --transient T [--depth D] VARIANT_DIR...
#
# (also ../kullukPack/runCoupled's figures: the same outputs of the pack)
#
# Reads, per variant folder (oneWay, twoWay, empirical):
#   postProcessing/iceLoadStatistics/*/series.dat   loads and tensions per step
#   postProcessing/iceLoadStatistics/*/statistics.dat   (cross-check)
#   postProcessing/flowProbes/*/U                   the current at the probes
#   postProcessing/flowSlices/<t>/UMean_*.raw       the mean current on the slices
# Writes to DIR:
#   compare.csv  per variant and quantity: samples, mean, 95 % half-width
#                (batch means, 20 batches, Student t, as iceLoadStatistics),
#                std, max, lag-1 autocorrelation of the batch means
#   flow.csv     per variant and probe: mean and 95 % half-width of Ux, Uy
#                and of the horizontal speed |U_h|
#   loads.png    mean horizontal ice load, driving force and line tensions
#                with their intervals; the load's running mean
#   topView.png  the floes at the last common write time, coloured by speed
#                (../kulluk/plotKulluk.py)
#   flow.png     |U_h| of UMean under the ice (z = -D, default 1.55 m) and on the
#                section y = 0.1 m, one-way and two-way and their difference;
#                the probes along the drift line with intervals
# Statistics over the samples at times > T, the same window for every
# variant (iceLoadStatistics's 'transient T' of the runs).
#
# License GPL-3.0-or-later.
# -----------------------------------------------------------------------------
import argparse
import glob
import math
import os
import re
import sys

import numpy as np

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import matplotlib.tri as mtri

BATCHES = 20
# Student t, two-sided 95 %, 19 degrees of freedom (BATCHES - 1)
T95_19 = 2.093
LABEL = {"oneWay": "one-way (resolved)", "twoWay": "two-way (resolved, twoWay)",
         "empirical": "empirical"}
COLOUR = {"oneWay": "tab:blue", "twoWay": "tab:red", "empirical": "tab:green"}


def batchMeans(x):
    """Mean of all samples, 95 % half-width and lag-1 of the batch means,
    samples used by the batches: the newest BATCHES*b samples in BATCHES
    batches (as iceLoadStatistics and core/statistics/SeriesStatistics.C)."""
    n = len(x)
    b = n // BATCHES
    if b == 0:
        return float("nan"), float("nan"), float("nan"), 0
    y = np.asarray(x[n - b*BATCHES:], dtype=float).reshape(BATCHES, b).mean(axis=1)
    mean = float(np.mean(x))
    d = y - y.mean()
    half = T95_19*y.std(ddof=1)/math.sqrt(BATCHES)
    lag1 = float(np.sum(d[1:]*d[:-1])/np.sum(d*d)) if np.sum(d*d) > 0 else 0.0
    return float(mean), float(half), lag1, b*BATCHES


def timeDirs(case, name):
    """postProcessing/<name>/<start time>/ folders in time order (a restart
    makes a new one)."""
    dirs = glob.glob(os.path.join(case, "postProcessing", name, "*"))
    dirs = [d for d in dirs if re.match(r"^[-+0-9.eE]+$", os.path.basename(d))]
    return sorted(dirs, key=lambda d: float(os.path.basename(d)))


def readSeries(case):
    """series.dat of every segment, later segments replacing the rows of the
    times they repeat (a restart from a write time)."""
    names, rows = None, {}
    segments = timeDirs(case, "iceLoadStatistics")
    for d in segments:
        with open(os.path.join(d, "series.dat")) as f:
            for line in f:
                if line.startswith("# time"):
                    names = line[2:].split()
                elif line.strip() and not line.startswith("#"):
                    v = [float(s) for s in line.split()]
                    rows[v[0]] = v
    if names is None:
        sys.exit("plotCompare.py: no series.dat in %s" % case)
    t = sorted(rows)
    return names, np.array([rows[k] for k in t]), len(segments)


def readStatistics(case):
    """The last rows of the last segment's statistics.dat: {quantity: row}."""
    segments = timeDirs(case, "iceLoadStatistics")
    out = {}
    with open(os.path.join(segments[-1], "statistics.dat")) as f:
        last = {}
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            s = line.split()
            last[s[1]] = s
    for q, s in last.items():
        out[q] = {"samples": int(s[2]), "mean": float(s[4]), "halfWidth": float(s[8])}
    return out


def readProbes(case):
    """Probe locations and U per probe: (points, times, U[t, probe, 3])."""
    points, rows = [], {}
    for d in timeDirs(case, "flowProbes"):
        with open(os.path.join(d, "U")) as f:
            for line in f:
                m = re.match(r"#\s*Probe\s+(\d+)\s+\(([^)]*)\)", line)
                if m:
                    p = [float(s) for s in m.group(2).split()]
                    if int(m.group(1)) >= len(points):
                        points.append(p)
                    continue
                if line.startswith("#") or not line.strip():
                    continue
                t = float(line.split()[0])
                vec = re.findall(r"\(([^)]*)\)", line)
                rows[t] = [[float(s) for s in v.split()] for v in vec]
    t = np.array(sorted(rows))
    return np.array(points), t, np.array([rows[k] for k in t])


def readSlice(case, field, surface):
    """The last time's raw slice: x y z Ux Uy Uz per face."""
    dirs = timeDirs(case, "flowSlices")
    if not dirs:
        return None
    f = os.path.join(dirs[-1], "%s_%s.raw" % (field, surface))
    if not os.path.isfile(f):
        return None
    return np.loadtxt(f, comments="#"), float(os.path.basename(dirs[-1]))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", required=True)
    ap.add_argument("--transient", type=float, required=True)
    ap.add_argument("--depth", type=float, default=1.55,
                    help="depth [m] of the slice and probes under the ice (the runs' own)")
    ap.add_argument("variants", nargs="+")
    a = ap.parse_args()
    base = os.path.dirname(os.path.abspath(a.variants[0])) if os.path.isdir(a.variants[0]) else None
    cases = {}
    for v in a.variants:
        c = v if os.path.isdir(v) else os.path.join(os.getcwd(), v)
        if not os.path.isdir(c):
            sys.exit("plotCompare.py: no folder %s" % c)
        cases[os.path.basename(os.path.normpath(c))] = c
    os.makedirs(a.out, exist_ok=True)

    # ---- loads
    loadRows, series = [], {}
    for v, c in cases.items():
        names, s, nSeg = readSeries(c)
        col = {n: i for i, n in enumerate(names)}
        w = s[:, 0] > a.transient
        series[v] = (s, col)
        Fx, Fy = s[w, col["Fx"]], s[w, col["Fy"]]
        Dx, Dy = s[w, col["Dx"]], s[w, col["Dy"]]
        tensions = [n for n in names if re.match(r".*\.T\d+$", n)]
        q = {"iceLoad": s[w, col["Fh"]], "iceLoadFx": Fx, "iceLoadFy": Fy,
             "driveFx": Dx, "driveFy": Dy,
             "balanceFx": Fx + s[w, col["Wx"]] - Dx}
        T = s[w][:, [col[n] for n in tensions]]
        for i, n in enumerate(tensions):
            q[n] = T[:, i]
        q["maxTension"] = T.max(axis=1) if len(tensions) else np.array([])
        for n, x in q.items():
            mean, half, lag1, used = batchMeans(x)
            loadRows.append((v, n, len(x), mean, half,
                             float(np.std(x, ddof=1)) if len(x) > 1 else float("nan"),
                             float(np.max(x)) if len(x) else float("nan"), lag1,
                             int(lag1 > 1.6448536/math.sqrt(BATCHES))))
        # cross-check with the function object's own statistics (a run
        # without restart: the same samples)
        if nSeg == 1:
            st = readStatistics(c)
            mine = [r for r in loadRows if r[0] == v and r[1] == "iceLoad"][0]
            fo = st.get("iceLoad")
            if fo and fo["samples"] == mine[2] and (
                    abs(fo["mean"] - mine[3]) > 1e-6*max(1.0, abs(mine[3]))
                    or abs(fo["halfWidth"] - mine[4]) > 1e-3*max(1.0, abs(mine[4]))):
                sys.exit("plotCompare.py: %s: iceLoad mean %g +- %g differs from "
                         "statistics.dat's %g +- %g"
                         % (v, mine[3], mine[4], fo["mean"], fo["halfWidth"]))
            if fo:
                print("%s: iceLoadStatistics: %d samples, mean %.6g N, half-width %.4g N "
                      "(this script: %d samples, %.6g, %.4g)"
                      % (v, fo["samples"], fo["mean"], fo["halfWidth"], mine[2], mine[3], mine[4]))
    with open(os.path.join(a.out, "compare.csv"), "w") as f:
        f.write("# kullukCompare: statistics over t > %g s; batch means of %d batches, "
                "95 %% half-width (Student t); forces [N]\n" % (a.transient, BATCHES))
        f.write("# balanceFx = Fx on the hull + Fx on the walls - driving Fx on the floes "
                "(zero in the mean in a steady state)\n")
        f.write("variant,quantity,samples,mean,halfWidth95,std,max,lag1,correlated\n")
        for r in loadRows:
            f.write("%s,%s,%d,%.6g,%.4g,%.4g,%.6g,%.3f,%d\n" % r)

    def stat(v, n):
        r = [r for r in loadRows if r[0] == v and r[1] == n][0]
        return r[3], r[4]

    # ---- the flow at the probes
    flowRows, probes = [], {}
    for v, c in cases.items():
        pts, t, U = readProbes(c)
        w = t > a.transient
        probes[v] = (pts, t, U)
        for i, p in enumerate(pts):
            if np.any(np.abs(U[:, i, :]) > 1e100):
                continue    # outside the mesh ('Not Found': OpenFOAM writes vGreat)
            ux, uy = U[w, i, 0], U[w, i, 1]
            sp = np.hypot(ux, uy)
            row = [v, i, p[0], p[1], p[2], int(w.sum())]
            for x in (ux, uy, sp):
                mean, half, _, _ = batchMeans(x)
                row += [mean, half]
            flowRows.append(row)
    with open(os.path.join(a.out, "flow.csv"), "w") as f:
        f.write("# kullukCompare: the current at the probes over t > %g s; batch means of %d "
                "batches, 95 %% half-width; [m/s]\n" % (a.transient, BATCHES))
        f.write("variant,probe,x,y,z,samples,Ux,Ux_hw95,Uy,Uy_hw95,Uh,Uh_hw95\n")
        for r in flowRows:
            f.write("%s,%d,%g,%g,%g,%d,%.6g,%.3g,%.6g,%.3g,%.6g,%.3g\n" % tuple(r))

    # ---- loads.png
    vs = list(cases)
    fig, ax = plt.subplots(2, 2, figsize=(13, 9))
    x = np.arange(len(vs))
    for k, (n, title) in enumerate((("iceLoad", "mean horizontal ice load |F_h| [MN]"),
                                    ("driveFx", "mean driving force on the floes, x [MN]"))):
        m = [stat(v, n)[0]/1e6 for v in vs]
        h = [stat(v, n)[1]/1e6 for v in vs]
        ax[0, k].bar(x, m, yerr=h, capsize=6, color=[COLOUR.get(v, "grey") for v in vs])
        ax[0, k].set_xticks(x)
        ax[0, k].set_xticklabels([LABEL.get(v, v) for v in vs], fontsize=8)
        ax[0, k].set_title(title + ", 95 % intervals", fontsize=10)
    tn = [r[1] for r in loadRows if r[0] == vs[0] and re.match(r".*\.T\d+$", r[1])]
    width = 0.8/len(vs)
    for j, v in enumerate(vs):
        m = [(stat(v, n)[0] - 1.5e6)/1e3 for n in tn]
        h = [stat(v, n)[1]/1e3 for n in tn]
        ax[1, 0].bar(np.arange(len(tn)) + (j - (len(vs) - 1)/2)*width, m, width, yerr=h,
                     capsize=2, color=COLOUR.get(v, "grey"), label=LABEL.get(v, v))
    ax[1, 0].set_xticks(np.arange(len(tn)))
    ax[1, 0].set_xticklabels([n.split(".")[-1] for n in tn])
    ax[1, 0].set_title("mean line tension minus the 1.5 MN pretension [kN], 95 % intervals",
                       fontsize=10)
    ax[1, 0].legend(fontsize=8)
    for v in vs:
        s, col = series[v]
        t, Fh = s[:, 0], s[:, col["Fh"]]
        ax[1, 1].plot(t, Fh/1e6, color=COLOUR.get(v, "grey"), lw=0.4, alpha=0.35)
        # running mean over 20 s
        n = 40
        if len(Fh) > n:
            rm = np.convolve(Fh, np.ones(n)/n, mode="valid")
            ax[1, 1].plot(t[n - 1:], rm/1e6, color=COLOUR.get(v, "grey"), lw=1.5,
                          label=LABEL.get(v, v) + " (20 s mean)")
    ax[1, 1].axvline(a.transient, color="k", ls=":", lw=1)
    ax[1, 1].set_xlabel("t [s]")
    ax[1, 1].set_ylabel("|F_h| [MN]")
    ax[1, 1].set_title("horizontal ice load (statistics from the dotted line on)", fontsize=10)
    ax[1, 1].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "loads.png"), dpi=110)
    plt.close(fig)

    # ---- flow.png
    have = [v for v in ("oneWay", "twoWay") if v in cases]
    slices = {}
    for v in have:
        for s in ("underIce", "section"):
            r = readSlice(cases[v], "UMean", s)
            if r is not None:
                slices[(v, s)] = r
    fig = plt.figure(figsize=(15, 13))
    gs = fig.add_gridspec(3, 3, height_ratios=[1.1, 0.8, 1.0])
    vmax = 0.36   # the colour range of |U_h| [m/s]; slower is clipped to its bottom

    def hullRadius(z):
        """The hull's radius at depth z <= 0 (structureDict of ../kulluk:
        35 m at the waterline, the 46 m waist 3 m above the 11 m keel, the
        52 m keel flare), for masking the triangles across the hull."""
        return np.interp(z, [-11.0, -8.0, 0.0], [26.0, 23.0, 35.0], left=0.0, right=35.0)

    def triangulate(pts, s):
        X = pts[:, 0]
        Y = pts[:, 1] if s == "underIce" else pts[:, 2]
        keep = (X > -330) & (X < 250) & ((np.abs(Y) < 160) if s == "underIce" else (Y > -50))
        tri = mtri.Triangulation(X[keep], Y[keep])
        cx = X[keep][tri.triangles].mean(axis=1)
        cy = Y[keep][tri.triangles].mean(axis=1)
        if s == "underIce":
            inside = np.hypot(cx, cy) < hullRadius(-a.depth)
        else:
            inside = (np.abs(cx) < hullRadius(cy)) & (cy > -11.0)
        tri.set_mask(inside)
        return tri, keep

    for k, s in enumerate(("underIce", "section")):
        for j, v in enumerate(have + ["diff"]):
            axk = fig.add_subplot(gs[k, j])
            if v == "diff":
                if ("oneWay", s) not in slices or ("twoWay", s) not in slices:
                    axk.set_axis_off()
                    continue
                # two-way's |U_h| interpolated to one-way's points (the meshes
                # moved with the hulls, whose offsets differ by centimetres)
                d1, _ = slices[("oneWay", s)]
                d2, _ = slices[("twoWay", s)]
                tri2, keep2 = triangulate(d2, s)
                f2 = mtri.LinearTriInterpolator(tri2, np.hypot(d2[keep2, 3], d2[keep2, 4]))
                pts = d1
                X1 = d1[:, 0]
                Y1 = d1[:, 1] if s == "underIce" else d1[:, 2]
                val = np.ma.filled(f2(X1, Y1), np.nan) - np.hypot(d1[:, 3], d1[:, 4])
                val = np.nan_to_num(val)
                cmap, lev = "RdBu_r", np.linspace(-0.06, 0.06, 25)
                title = "two-way minus one-way"
            else:
                if (v, s) not in slices:
                    axk.set_axis_off()
                    continue
                pts, tEnd = slices[(v, s)]
                val = np.hypot(pts[:, 3], pts[:, 4])
                cmap, lev = "viridis", np.linspace(0.10, vmax, 27)
                title = LABEL[v]
            tri, keep = triangulate(pts, s)
            cf = axk.tricontourf(tri, np.clip(val[keep], lev[0], lev[-1] - 1e-9*(lev[-1] - lev[0])),
                                levels=lev, cmap=cmap)
            fig.colorbar(cf, ax=axk, shrink=0.8,
                         label="|U_h| [m/s]" if v != "diff" else "difference of |U_h| [m/s]")
            if s == "underIce":
                axk.add_patch(plt.Circle((0, 0), 35, fill=False, color="w" if v != "diff" else "k"))
                axk.set_aspect("equal")
                axk.set_ylabel("y [m]")
                axk.set_title("%s\nUMean at z = -%g m (0.5 m under the floes)" % (title, a.depth),
                              fontsize=9)
            else:
                axk.set_ylabel("z [m]")
                axk.set_title("%s\nUMean on the section y = 0.1 m" % title, fontsize=9)
            axk.set_xlabel("x [m] (drift: +x)")
    axp = fig.add_subplot(gs[2, :2])
    for v in cases:
        rows = [r for r in flowRows if r[0] == v and abs(r[3]) < 1e-9 and abs(r[4] + a.depth) < 1e-9]
        rows.sort(key=lambda r: r[2])
        axp.errorbar([r[2] for r in rows], [r[10] for r in rows], yerr=[r[11] for r in rows],
                     marker="o", ms=3, capsize=3, color=COLOUR.get(v, "grey"), label=LABEL.get(v, v))
    axp.axvline(-35, color="k", lw=0.8, ls=":")
    axp.set_xlabel("x [m] on the drift line y = 0, z = -%g m (hull waterline at x = -35 m)"
                   % a.depth)
    axp.set_ylabel("mean |U_h| [m/s]")
    axp.set_title("the current in front of the hull, mean over t > %g s with 95 %% intervals"
                  % a.transient, fontsize=10)
    axp.legend(fontsize=8)
    axq = fig.add_subplot(gs[2, 2])
    axq.axis("off")
    lines = ["lateral current Uy [m/s] (deflection), mean +- 95 %:"]
    for r in flowRows:
        if abs(r[3]) > 1 or r[4] < -2:
            lines.append("%-9s (%g, %g, %g): Uy %+.4f +- %.4f, |U_h| %.4f" %
                         (r[0], r[2], r[3], r[4], r[8], r[9], r[10]))
    axq.text(0, 1, "\n".join(lines), va="top", family="monospace", fontsize=6.5)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "flow.png"), dpi=100)
    plt.close(fig)

    # ---- the floes around the hull at the last common write time of the
    # first DEM output segment (../kulluk/plotKulluk.py's top view)
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "kulluk"))
    import plotKulluk
    plotKulluk.plot_top_view(list(cases.values()), [LABEL.get(v, v) for v in cases], a.out)

    # ---- two-way: the momentum exchange of the log (fluid source impulse
    # = - floes' drag impulse per flow step, and the impulse no cell took)
    for v, c in cases.items():
        log = os.path.join(c, "log.iceFloatingFoam")
        if v != "twoWay" or not os.path.isfile(log):
            continue
        imb, drag, lost = [], np.zeros(3), np.zeros(3)
        vec = r"\(([-+0-9.eE]+) ([-+0-9.eE]+) ([-+0-9.eE]+)\)"
        for line in open(log):
            m = re.search(r"floes' drag impulse " + vec + r" N s, fluid source impulse .*"
                          r"relative imbalance ([-+0-9.eE]+), lost \(no cell\) " + vec, line)
            if m:
                g = [float(x) for x in m.groups()]
                drag += g[0:3]
                imb.append(abs(g[3]))
                lost += g[4:7]
        if imb:
            print("%s: %d coupling steps (log lines) with drag returned to the flow: largest relative imbalance "
                  "%.3g; floes' drag impulse in all (%.4g %.4g %.4g) N s, lost (no cell) "
                  "(%.3g %.3g %.3g) N s" % ((v, len(imb), max(imb)) + tuple(drag) + tuple(lost)))

    # ---- the table on stdout
    print("statistics over t > %g s (95 %% half-widths, batch means of %d batches)"
          % (a.transient, BATCHES))
    print("%-10s %22s %22s %22s %22s" % ("variant", "|F_h| [MN]", "drive Fx [MN]",
                                          "max tension [MN]", "balance Fx [MN]"))
    for v in vs:
        print("%-10s" % v + "".join("   %9.4f +- %7.4f" % (stat(v, n)[0]/1e6, stat(v, n)[1]/1e6)
                                    for n in ("iceLoad", "driveFx", "maxTension", "balanceFx")))


if __name__ == "__main__":
    main()
