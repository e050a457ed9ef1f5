#!/usr/bin/env python3
"""iceFloatingFoam/kulluk: plots and the comparison table of the variants.

    python3 plotKulluk.py [--out DIR] [--time T] [VARIANT ...]

VARIANT: case folders (default: coupled empirical). Reads from each
    postProcessing/iceLoad/0/iceLoad.dat      time Fx Fy Fz Mx My Mz contacts
    postProcessing/hullMotion/0/motion.dat    time x y z roll pitch yaw vx ...
    postProcessing/mooring/0/tensions.dat     time T0 ... T11
    postProcessing/iceDEM/0/bodies.dat        time id x y z vx vy vz ... q
    constant/iceField                         the floe outlines at t = 0
and writes to DIR (default plots/):
    iceLoad.png      Fx, Fy and the horizontal load |F_h| of all variants
    hullMotion.png   the Kulluk's offset (surge x, sway y) and yaw
    mooring.png      the tensions of the 12 lines, per variant
    topView.png      the floes around the hull at time T (default: the last
                     time written to bodies.dat by every variant)
and prints the table: mean, standard deviation and maximum of the horizontal
ice load |F_h| = sqrt(Fx^2 + Fy^2) per variant, and the ratio of the first
variant to the second. The statistics are taken over the same window for
every variant: from the first step with a floe-structure contact in any
variant to the end of the shortest run (before it the load is exactly 0).
"""
import argparse
import os
import re
import sys

import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt                      # noqa: E402
from matplotlib.collections import PolyCollection    # noqa: E402

MN = 1e6


def table(path):
    """Rows of a whitespace-separated file, '#' lines skipped."""
    rows = [list(map(float, l.split())) for l in open(path)
            if l.strip() and not l.startswith("#")]
    return np.array(rows)


def ice_load(case):
    return table(os.path.join(case, "postProcessing/iceLoad/0/iceLoad.dat"))


def load_statistics(loads, names):
    """Statistics of |F_h| over the common window (see the module doc)."""
    firsts = [L[L[:, 7] > 0, 0].min() for L in loads if (L[:, 7] > 0).any()]
    tEnd = min(L[-1, 0] for L in loads)
    t1 = min(firsts) if firsts else None
    stats = []
    for L, name in zip(loads, names):
        contact = L[L[:, 7] > 0, 0]
        s = {"variant": name, "t1": t1, "tEnd": tEnd,
             "firstContact": contact.min() if contact.size else None,
             "contactSteps": int((L[:, 7] > 0).sum()), "steps": len(L)}
        if t1 is not None:
            w = L[(L[:, 0] >= t1) & (L[:, 0] <= tEnd)]
            Fh = np.hypot(w[:, 1], w[:, 2])
            s.update(mean=Fh.mean(), std=Fh.std(), max=Fh.max(),
                     meanFx=w[:, 1].mean(), n=len(w))
        stats.append(s)
    return stats


def print_table(stats, out=sys.stdout):
    t1 = stats[0]["t1"]
    p = lambda *a: print(*a, file=out)                 # noqa: E731
    if t1 is None:
        p("No floe reached the Kulluk in any variant: the ice load is zero.")
        return
    p("Ice load on the Kulluk: horizontal |F_h| = sqrt(Fx^2 + Fy^2) [MN],")
    p(f"over t = {t1:g} ... {stats[0]['tEnd']:g} s (from the first ice contact on)")
    p(f"{'variant':<12}{'mean':>10}{'std':>10}{'max':>10}{'mean Fx':>10}"
      f"{'first contact':>15}{'contact steps':>15}")
    for s in stats:
        fc = f"{s['firstContact']:g} s" if s["firstContact"] is not None else "none"
        p(f"{s['variant']:<12}{s['mean']/MN:10.3f}{s['std']/MN:10.3f}"
          f"{s['max']/MN:10.3f}{s['meanFx']/MN:10.3f}{fc:>15}"
          f"{s['contactSteps']:>9d} of {s['steps']}")
    if len(stats) >= 2:
        a, b = stats[0], stats[1]
        r = lambda x, y: f"{x/y:10.3f}" if y > 0 else f"{'-':>10}"  # noqa: E731
        p(f"{'ratio ' + a['variant'][:1] + '/' + b['variant'][:1]:<12}"
          f"{r(a['mean'], b['mean'])}{r(a['std'], b['std'])}"
          f"{r(a['max'], b['max'])}{r(a['meanFx'], b['meanFx'])}"
          f"   ({a['variant']} / {b['variant']})")


def plot_loads(cases, names, loads, out):
    fig, ax = plt.subplots(3, 1, figsize=(9, 8), sharex=True)
    for L, name in zip(loads, names):
        ax[0].plot(L[:, 0], L[:, 1]/MN, lw=0.8, label=name)
        ax[1].plot(L[:, 0], L[:, 2]/MN, lw=0.8, label=name)
        ax[2].plot(L[:, 0], np.hypot(L[:, 1], L[:, 2])/MN, lw=0.8, label=name)
    for a, lab in zip(ax, ["$F_x$ [MN]", "$F_y$ [MN]", "$|F_h|$ [MN]"]):
        a.set_ylabel(lab)
        a.grid(alpha=0.3)
    ax[0].legend()
    ax[0].set_title("Ice load on the Kulluk (averaged over each coupling step)")
    ax[2].set_xlabel("time [s]")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "iceLoad.png"), dpi=120)
    plt.close(fig)


def plot_motion(cases, names, out):
    fig, ax = plt.subplots(3, 1, figsize=(9, 7), sharex=True)
    for case, name in zip(cases, names):
        M = table(os.path.join(case, "postProcessing/hullMotion/0/motion.dat"))
        ax[0].plot(M[:, 0], M[:, 1] - M[0, 1], label=name)
        ax[1].plot(M[:, 0], M[:, 2] - M[0, 2], label=name)
        ax[2].plot(M[:, 0], M[:, 6], label=name)
    for a, lab in zip(ax, ["surge offset x [m]", "sway offset y [m]", "yaw [deg]"]):
        a.set_ylabel(lab)
        a.grid(alpha=0.3)
    ax[0].legend()
    ax[0].set_title("Kulluk motion (offset from the first step)")
    ax[2].set_xlabel("time [s]")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "hullMotion.png"), dpi=120)
    plt.close(fig)


def plot_mooring(cases, names, out):
    fig, ax = plt.subplots(len(cases), 1, figsize=(9, 3.2*len(cases)),
                           sharex=True, squeeze=False)
    for a, case, name in zip(ax[:, 0], cases, names):
        T = table(os.path.join(case, "postProcessing/mooring/0/tensions.dat"))
        for i in range(1, T.shape[1]):
            a.plot(T[:, 0], T[:, i]/MN, lw=0.8, label=f"line {i-1}")
        a.set_ylabel("tension [MN]")
        a.set_title(f"{name}: mooring line tensions")
        a.grid(alpha=0.3)
    ax[0, 0].legend(ncol=6, fontsize=7)
    ax[-1, 0].set_xlabel("time [s]")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "mooring.png"), dpi=120)
    plt.close(fig)


def floe_outlines(case):
    """Outlines of the prism floes of constant/iceField, in file order."""
    text = open(os.path.join(case, "constant/iceField")).read()
    out = []
    for m in re.finditer(r"outline\s*\(((?:\s*\([^()]*\))+)\s*\)\s*;", text):
        pts = re.findall(r"\(\s*([-+0-9.eE]+)\s+([-+0-9.eE]+)\s*\)", m.group(1))
        out.append(np.array([[float(x), float(y)] for x, y in pts]))
    return out


def quat_matrix(q):
    w, x, y, z = q
    return np.array([
        [1 - 2*(y*y + z*z), 2*(x*y - w*z), 2*(x*z + w*y)],
        [2*(x*y + w*z), 1 - 2*(x*x + z*z), 2*(y*z - w*x)],
        [2*(x*z - w*y), 2*(y*z + w*x), 1 - 2*(x*x + y*y)]])


def hull_polygon(case, diameter, t):
    """The 24-gon of the given corner diameter at the hull's pose at t."""
    M = table(os.path.join(case, "postProcessing/hullMotion/0/motion.dat"))
    k = np.argmin(abs(M[:, 0] - t))
    a = np.radians(M[k, 6]) + 2*np.pi*np.arange(25)/24
    return (M[k, 1] + 0.5*diameter*np.cos(a), M[k, 2] + 0.5*diameter*np.sin(a))


def plot_top_view(cases, names, out, time=None):
    B = {c: table(os.path.join(c, "postProcessing/iceDEM/0/bodies.dat")) for c in cases}
    if time is None:
        time = min(b[:, 0].max() for b in B.values())
    fig, ax = plt.subplots(1, len(cases), figsize=(6.5*len(cases), 6), squeeze=False)
    for a, case, name in zip(ax[0], cases, names):
        outlines = floe_outlines(case)
        b = B[case]
        t = b[np.argmin(abs(b[:, 0] - time)), 0]
        b0 = b[b[:, 0] == b[0, 0]]
        bt = b[b[:, 0] == t]
        polys, speed = [], []
        for k, outline in enumerate(outlines):
            r0, rt = b0[b0[:, 1] == k], bt[bt[:, 1] == k]
            if not len(r0) or not len(rt):
                continue
            R = quat_matrix(rt[0, 11:15])
            local = np.c_[outline - r0[0, 2:4], np.zeros(len(outline))]
            world = local @ R.T + rt[0, 2:5]
            polys.append(world[:, :2])
            speed.append(np.hypot(rt[0, 5], rt[0, 6]))
        pc = PolyCollection(polys, array=np.array(speed), cmap="viridis",
                            edgecolor="k", linewidths=0.3)
        pc.set_clim(0, 0.45)
        a.add_collection(pc)
        for d, style in ((70, "r-"), (81, "r--")):
            a.plot(*hull_polygon(case, d, t), style, lw=1.2)
        a.set_aspect("equal")
        a.set_xlim(-160, 120)
        a.set_ylim(-120, 120)
        a.set_title(f"{name}: t = {t:g} s (red: waterline 70 m, deck 81 m)")
        a.set_xlabel("x [m] (current and drift along +x)")
        a.set_ylabel("y [m]")
        fig.colorbar(pc, ax=a, label="floe speed [m/s]", shrink=0.8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "topView.png"), dpi=110)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("variants", nargs="*", default=["coupled", "empirical"])
    ap.add_argument("--out", default="plots")
    ap.add_argument("--time", type=float, default=None)
    args = ap.parse_args()
    cases = [v for v in args.variants if os.path.isdir(v)]
    if not cases:
        sys.exit("plotKulluk.py: none of the case folders exists: "
                 + " ".join(args.variants))
    names = [os.path.basename(os.path.normpath(c)) for c in cases]
    os.makedirs(args.out, exist_ok=True)
    loads = [ice_load(c) for c in cases]
    plot_loads(cases, names, loads, args.out)
    plot_motion(cases, names, args.out)
    plot_mooring(cases, names, args.out)
    plot_top_view(cases, names, args.out, args.time)
    print_table(load_statistics(loads, names))
    print("Plots: " + " ".join(os.path.join(args.out, f) for f in
          ("iceLoad.png", "hullMotion.png", "mooring.png", "topView.png")))


if __name__ == "__main__":
    main()
