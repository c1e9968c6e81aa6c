#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""One-sided check of a scadprofile module against the exact drawn region.

    scad_sided.py MODULE.scad --d PATHDATA --fit inside|outside|middle --tol T
                  [--height H] [--scale K] [--evenodd]

PATHDATA (absolute M, L, H, V, C, A, Z only) is the drawn fill; it is made a
dense polygon (every curve cut into 4096 pieces) in the module's frame:
x' = K x, y' = K (H - y) (K: output units per user unit, 25.4/96 for a px
document written in mm). The module's polygon (NAME_points / NAME_paths)
is compared with it by Clipper (pyclipper): for `inside` nothing of the
module may lie outside the region grown by T/50 and nothing of the region
outside the module grown by T (plus T/50); `outside` the other way round;
`middle` T both ways. Prints what it measured; exit 0 when it holds, 1 when
not, 2 on bad input.
"""
import math
import re
import sys

import pyclipper

SCALE = 2 ** 30


def module_polygon(text):
    pts = re.search(r"function \w+_points\(\) = \[(.*?)\];", text, re.S)
    paths = re.search(r"function \w+_paths\(\) = \[(.*?)\];", text, re.S)
    xy = [tuple(map(float, p)) for p in re.findall(r"\[([-0-9.e+]+),([-0-9.e+]+)\]", pts.group(1))]
    idx = [list(map(int, re.findall(r"\d+", p))) for p in re.findall(r"\[([0-9,\s]*)\]", paths.group(1))]
    return [[xy[i] for i in q] for q in idx]


def arc_points(x0, y0, rx, ry, phi, large, sweep, x1, y1, n):
    # SVG 1.1 F.6.5: end points to centre
    c, s = math.cos(phi), math.sin(phi)
    dx, dy = (x0 - x1) / 2, (y0 - y1) / 2
    xp, yp = c * dx + s * dy, -s * dx + c * dy
    lam = (xp / rx) ** 2 + (yp / ry) ** 2
    if lam > 1:
        rx, ry = rx * math.sqrt(lam), ry * math.sqrt(lam)
    num = rx * rx * ry * ry - rx * rx * yp * yp - ry * ry * xp * xp
    k = math.sqrt(max(0.0, num / (rx * rx * yp * yp + ry * ry * xp * xp)))
    if large == sweep:
        k = -k
    cxp, cyp = k * rx * yp / ry, -k * ry * xp / rx
    cx = c * cxp - s * cyp + (x0 + x1) / 2
    cy = s * cxp + c * cyp + (y0 + y1) / 2

    def ang(ux, uy, vx, vy):
        return math.atan2(ux * vy - uy * vx, ux * vx + uy * vy)
    t1 = ang(1, 0, (xp - cxp) / rx, (yp - cyp) / ry)
    dt = ang((xp - cxp) / rx, (yp - cyp) / ry, (-xp - cxp) / rx, (-yp - cyp) / ry)
    if not sweep and dt > 0:
        dt -= 2 * math.pi
    elif sweep and dt < 0:
        dt += 2 * math.pi
    out = []
    for i in range(1, n + 1):
        t = t1 + dt * i / n
        out.append((cx + c * rx * math.cos(t) - s * ry * math.sin(t),
                    cy + s * rx * math.cos(t) + c * ry * math.sin(t)))
    out[-1] = (x1, y1)
    return out


def dense(d, n=4096):
    toks = re.findall(r"[MLHVCAZ]|-?[0-9.]+(?:e[-+]?[0-9]+)?", d)
    subs, cur, i, pos, start = [], [], 0, (0.0, 0.0), (0.0, 0.0)
    num = lambda: float(toks[i])
    while i < len(toks):
        cmd = toks[i]; i += 1
        if cmd == "M":
            if cur:
                subs.append(cur)
            pos = start = (float(toks[i]), float(toks[i + 1])); i += 2
            cur = [pos]
        elif cmd == "L":
            pos = (float(toks[i]), float(toks[i + 1])); i += 2; cur.append(pos)
        elif cmd == "H":
            pos = (float(toks[i]), pos[1]); i += 1; cur.append(pos)
        elif cmd == "V":
            pos = (pos[0], float(toks[i])); i += 1; cur.append(pos)
        elif cmd == "C":
            p = [pos] + [(float(toks[i + 2 * k]), float(toks[i + 2 * k + 1])) for k in range(3)]
            i += 6
            for k in range(1, n + 1):
                t = k / n; u = 1 - t
                cur.append(tuple(u ** 3 * p[0][j] + 3 * u * u * t * p[1][j] + 3 * u * t * t * p[2][j]
                                 + t ** 3 * p[3][j] for j in range(2)))
            pos = p[3]
        elif cmd == "A":
            rx, ry, rot, la, sw, x, y = (float(toks[i + k]) for k in range(7)); i += 7
            cur += arc_points(pos[0], pos[1], rx, ry, math.radians(rot), int(la), int(sw), x, y, n)
            pos = (x, y)
        elif cmd == "Z":
            pos = start
        else:
            raise ValueError("unsupported path command %s" % cmd)
    if cur:
        subs.append(cur)
    return subs


def ints(polys):
    return [[(int(round(x * SCALE)), int(round(y * SCALE))) for x, y in p] for p in polys]


def left_over(a, b, grow):
    """The area (units^2) of a outside b grown by `grow`."""
    co = pyclipper.PyclipperOffset()
    co.AddPaths(b, pyclipper.JT_ROUND, pyclipper.ET_CLOSEDPOLYGON)
    co.ArcTolerance = max(0.25, grow * SCALE / 64)
    g = co.Execute(grow * SCALE)
    pc = pyclipper.Pyclipper()
    pc.AddPaths(a, pyclipper.PT_SUBJECT, True)
    pc.AddPaths(g, pyclipper.PT_CLIP, True)
    r = pc.Execute(pyclipper.CT_DIFFERENCE, pyclipper.PFT_NONZERO, pyclipper.PFT_NONZERO)
    return sum(abs(pyclipper.Area(p)) for p in r) / SCALE / SCALE


def main(argv):
    args = argv[1:]
    opt = {"--height": "0", "--scale": "1", "--fit": "inside"}
    evenodd = False
    pos = []
    i = 0
    while i < len(args):
        if args[i] == "--evenodd":
            evenodd = True; i += 1
        elif args[i] in ("--d", "--fit", "--tol", "--height", "--scale"):
            opt[args[i]] = args[i + 1]; i += 2
        else:
            pos.append(args[i]); i += 1
    if len(pos) != 1 or "--d" not in opt or "--tol" not in opt:
        print(__doc__, file=sys.stderr)
        return 2
    T, H, K = float(opt["--tol"]), float(opt["--height"]), float(opt["--scale"])
    ref = [[(K * x, K * (H - y)) for x, y in s] for s in dense(opt["--d"])]
    pc = pyclipper.Pyclipper()
    pc.AddPaths(ints(ref), pyclipper.PT_SUBJECT, True)
    rule = pyclipper.PFT_EVENODD if evenodd else pyclipper.PFT_NONZERO
    R = pc.Execute(pyclipper.CT_UNION, rule, rule)
    P = ints(module_polygon(open(pos[0]).read()))
    eps = T / 50
    fit = opt["--fit"]
    gain = left_over(P, R, eps if fit == "inside" else T + eps)
    loss = left_over(R, P, eps if fit == "outside" else T + eps)
    print("%s: area of the module beyond the allowed side %.3g, of the region beyond it %.3g"
          % (fit, gain, loss))
    return 0 if gain == 0 and loss == 0 else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
