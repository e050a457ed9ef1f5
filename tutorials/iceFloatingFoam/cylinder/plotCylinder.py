#!/usr/bin/env python3
"""iceFloatingFoam/cylinder: the ice load on the fixed cylinder.

    python3 plotCylinder.py [--out plots]

Reads postProcessing/iceLoad/0/iceLoad.dat (time Fx Fy Fz Mx My Mz contacts),
postProcessing/iceDEM/0/bodies.dat and constant/iceField; writes
    plots/iceLoad.png   Fx (along the drift) and Fy against time
    plots/topView.png   the floes at three times
and prints the mean, standard deviation and maximum of Fx and |Fy| from the
first contact on, and the number of steps with contact.
"""
import argparse
import os
import re

import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt                      # noqa: E402
from matplotlib.collections import PolyCollection    # noqa: E402

KN = 1e3
D = 10.0      # cylinder diameter across flats [m] (structureDict)


def table(path):
    return np.array([list(map(float, l.split())) for l in open(path)
                     if l.strip() and not l.startswith("#")])


def outlines():
    text = open("constant/iceField").read()
    res = []
    for m in re.finditer(r"outline\s*\(((?:\s*\([^()]*\))+)\s*\)\s*;", text):
        pts = re.findall(r"\(\s*([-+0-9.eE]+)\s+([-+0-9.eE]+)\s*\)", m.group(1))
        res.append(np.array([[float(x), float(y)] for x, y in pts]))
    return res


def rotation(q):
    w, x, y, z = q
    return np.array([
        [1 - 2*(y*y + z*z), 2*(x*y - w*z), 2*(x*z + w*y)],
        [2*(x*y + w*z), 1 - 2*(x*x + z*z), 2*(y*z - w*x)],
        [2*(x*z - w*y), 2*(y*z + w*x), 1 - 2*(x*x + y*y)]])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", default="plots")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)

    L = table("postProcessing/iceLoad/0/iceLoad.dat")
    fig, ax = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    ax[0].plot(L[:, 0], L[:, 1]/KN, lw=0.8)
    ax[1].plot(L[:, 0], L[:, 2]/KN, lw=0.8)
    ax[0].set_ylabel("$F_x$ (drift) [kN]")
    ax[1].set_ylabel("$F_y$ [kN]")
    ax[1].set_xlabel("time [s]")
    ax[0].set_title("Ice load on the fixed 10 m cylinder (averaged over each 0.5 s step)")
    for a in ax:
        a.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "iceLoad.png"), dpi=120)
    plt.close(fig)

    B = table("postProcessing/iceDEM/0/bodies.dat")
    times = np.unique(B[:, 0])
    shots = [times[len(times)//4], times[len(times)//2], times[-1]]
    b0 = B[B[:, 0] == times[0]]
    shapes = outlines()
    fig, ax = plt.subplots(len(shots), 1, figsize=(7, 2.9*len(shots)))
    a24 = np.pi/24 + 2*np.pi*np.arange(25)/24
    rc = 0.5*D/np.cos(np.pi/24)
    for a, t in zip(ax, shots):
        bt = B[B[:, 0] == t]
        polys = []
        for k, o in enumerate(shapes):
            r0, rt = b0[b0[:, 1] == k], bt[bt[:, 1] == k]
            if not len(r0) or not len(rt):
                continue
            local = np.c_[o - r0[0, 2:4], np.zeros(len(o))]
            polys.append((local @ rotation(rt[0, 11:15]).T + rt[0, 2:5])[:, :2])
        a.add_collection(PolyCollection(polys, facecolor="aliceblue",
                                        edgecolor="steelblue", linewidths=0.5))
        a.fill(rc*np.cos(a24), rc*np.sin(a24), color="dimgray")
        a.set_aspect("equal")
        a.set_xlim(-60, 60)
        a.set_ylim(-35, 35)
        a.set_title(f"t = {t:g} s")
        a.set_ylabel("y [m]")
    ax[-1].set_xlabel("x [m] (drift along +x)")
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "topView.png"), dpi=110)
    plt.close(fig)

    contact = L[:, 7] > 0
    if not contact.any():
        print("No floe reached the cylinder: the ice load is zero.")
        return
    t1 = L[contact, 0].min()
    w = L[L[:, 0] >= t1]
    print(f"Ice load on the cylinder from the first contact (t = {t1:g} s) to "
          f"t = {L[-1, 0]:g} s [kN]:")
    print(f"{'':8}{'mean':>10}{'std':>10}{'max':>10}")
    print(f"{'Fx':<8}{w[:, 1].mean()/KN:10.2f}{w[:, 1].std()/KN:10.2f}{w[:, 1].max()/KN:10.2f}")
    ay = abs(w[:, 2])
    print(f"{'|Fy|':<8}{ay.mean()/KN:10.2f}{ay.std()/KN:10.2f}{ay.max()/KN:10.2f}")
    print(f"steps with ice on the cylinder: {int(contact.sum())} of {len(L)}")
    print("Plots: " + os.path.join(args.out, "iceLoad.png") + " "
          + os.path.join(args.out, "topView.png"))


if __name__ == "__main__":
    main()
