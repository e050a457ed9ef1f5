#!/usr/bin/env python3
# -----------------------------------------------------------------------------
# iceFloatingFoam/kullukPack: the free-drift velocity of a point's pack, from
# the solver's own models (run by caseFunctions' freeDriftVelocity).
#
#   python3 freeDrift.py CASE
#
# CASE is a copy of a point (constant/ with its iceField, system/) whose
# controlDict runs iceFloatingFoam -noFlow for one DEM step with
# iceLoadStatistics (transient 0). For a trial velocity u, every floe of
# constant/iceField gets the velocity u (no spin), one DEM step is run and
# the horizontal driving force on all floes, D(u) = sum of wind and water
# drag (series.dat's Dx Dy: the sum over the free floes, contacts not
# included), is read back. The pack's free drift is the u where D(u) = 0:
# the pack translating as one piece then gains no momentum. A dense pack
# moves together, so this, not the mean of each floe's own free drift, is
# the velocity it starts at.
#
# D is smooth in u except where u equals the current (the water drag's
# derivative vanishes there), so Newton's method (Jacobian by forward
# differences of du) starts from u0 = U_w + 0.02 (U_a - U_w): the current
# plus 2 % of the relative wind, the order of the wind factor of free drift
# (method.md section 8). Only the start: the iteration stops when the step
# is below tol (1e-4 m/s), at most 12 iterations, and then reports the
# residual |D| against the drive on the pack held at the current, |D(U_w)|.
# Prints the velocity "(ux uy 0)" on stdout, the iterations on stderr.
# -----------------------------------------------------------------------------
import glob
import math
import os
import re
import shutil
import subprocess
import sys

du = 1e-3       # [m/s] forward-difference step of the Jacobian
tol = 1e-4      # [m/s] Newton step at which the iteration stops
maxIter = 12


def entry(path, key):
    """The vector of foamDictionary's -entry KEY -value in PATH"""
    out = subprocess.run(["foamDictionary", "-entry", key, "-value", path],
                         check=True, capture_output=True, text=True).stdout
    v = [float(x) for x in out.strip().strip("()").split()]
    if len(v) != 3 or not all(math.isfinite(x) for x in v):
        sys.exit(f"freeDrift.py: {path}: {key} is not a finite vector: {out}")
    return v


def drive(case, u, log):
    """D(u): the horizontal driving force on the pack moving at u"""
    field = os.path.join(case, "constant", "iceField")
    text = open(field).read()
    text, n = re.subn(r"(\n\s*velocity\s+)\([^)]*\);",
                      lambda m: f"{m.group(1)}({u[0]:.12g} {u[1]:.12g} 0);", text)
    if n == 0:
        sys.exit(f"freeDrift.py: no velocity entry in {field}")
    open(field, "w").write(text)
    # every output of a previous trial goes (startFrom latestTime)
    shutil.rmtree(os.path.join(case, "postProcessing"), ignore_errors=True)
    for d in glob.glob(os.path.join(case, "*")):
        name = os.path.basename(d)
        if os.path.isdir(d) and re.fullmatch(r"[0-9.e+-]+", name) and name != "0":
            shutil.rmtree(d)
    with open(os.path.join(case, log), "w") as f:
        r = subprocess.run(["iceFloatingFoam", "-noFlow"], cwd=case, stdout=f,
                           stderr=subprocess.STDOUT,
                           env=dict(os.environ, OMP_NUM_THREADS="1"))
    if r.returncode != 0:
        sys.exit(f"freeDrift.py: iceFloatingFoam -noFlow failed in {case} (see {log})")
    series = glob.glob(os.path.join(case, "postProcessing", "iceLoadStatistics",
                                    "*", "series.dat"))
    rows = [l.split() for l in open(series[0]) if l.strip() and not l.startswith("#")]
    head = [l for l in open(series[0]) if l.startswith("# time")][0].split()[1:]
    last = rows[-1]
    return [float(last[head.index("Dx")]), float(last[head.index("Dy")])]


def main():
    case = sys.argv[1]
    props = os.path.join(case, "constant", "iceDEMProperties")
    Uw = entry(props, "drag/current")
    Ua = entry(props, "wind/velocity")
    D0 = drive(case, Uw[:2], "log.iceFloatingFoam.current")
    scale = math.hypot(*D0)
    print(f"pack at the current ({Uw[0]:g} {Uw[1]:g}): drive ({D0[0]:.6g} {D0[1]:.6g}) N",
          file=sys.stderr)
    u = [Uw[i] + 0.02*(Ua[i] - Uw[i]) for i in range(2)]
    for it in range(1, maxIter + 1):
        D = drive(case, u, "log.iceFloatingFoam")
        Dx = drive(case, [u[0] + du, u[1]], "log.iceFloatingFoam.dx")
        Dy = drive(case, [u[0], u[1] + du], "log.iceFloatingFoam.dy")
        J = [[(Dx[0] - D[0])/du, (Dy[0] - D[0])/du],
             [(Dx[1] - D[1])/du, (Dy[1] - D[1])/du]]
        det = J[0][0]*J[1][1] - J[0][1]*J[1][0]
        if not math.isfinite(det) or det == 0:
            sys.exit(f"freeDrift.py: singular Jacobian at u = {u}")
        step = [(J[1][1]*D[0] - J[0][1]*D[1])/det,
                (-J[1][0]*D[0] + J[0][0]*D[1])/det]
        u = [u[0] - step[0], u[1] - step[1]]
        print(f"iteration {it}: drive ({D[0]:.6g} {D[1]:.6g}) N, "
              f"step ({-step[0]:.3g} {-step[1]:.3g}) m/s, u = ({u[0]:.6f} {u[1]:.6f})",
              file=sys.stderr)
        if math.hypot(*step) < tol:
            break
    else:
        sys.exit(f"freeDrift.py: no convergence in {maxIter} iterations ({case})")
    D = drive(case, u, "log.iceFloatingFoam")
    print(f"free drift ({u[0]:.6f} {u[1]:.6f}) m/s: residual drive "
          f"({D[0]:.4g} {D[1]:.4g}) N = {math.hypot(*D)/scale:.2e} of the drive "
          f"on the pack held at the current", file=sys.stderr)
    print(f"({u[0]:.6f} {u[1]:.6f} 0)")


if __name__ == "__main__":
    main()
