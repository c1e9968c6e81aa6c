#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Write the small demo curves in examples/ (used by `make demo`).

Run from the repository root: python3 scripts/make-examples.py
The files are committed; this script documents how they were made and
regenerates them bit for bit (Python's repr() of a float round-trips).

- ellipse.txt: x = 3 cos t, y = 2 sin t, 12 points, exact unit normals
  (the ellipse's gradient), counter-clockwise, normals outward. Subdivision
  reproduces it exactly (CONIS: conics are preserved).
- flower.txt: r = 1 + 0.3 cos 5t, 40 points, no normals (conica estimates
  them); non-convex, so inflection points are inserted.
- parabola_open.txt: y = x^2 for x = -1.5 .. 1.5, 7 points, exact unit
  normals on the convex side; an open curve (the `open` in the name makes
  scripts/demo.sh pass --open).
"""
import math
import os


def write(path, comment, pts, normals=None):
    with open(path, "w", encoding="ascii", newline="\n") as f:
        for line in comment:
            f.write("# " + line + "\n")
        for x, y in pts:
            f.write("v %r %r\n" % (x, y))
        if normals:
            for nx, ny in normals:
                f.write("vn %r %r\n" % (nx, ny))


def unit(x, y):
    h = math.hypot(x, y)
    return (x / h, y / h)


def main():
    out = "examples"
    os.makedirs(out, exist_ok=True)

    n = 12
    pts, nrm = [], []
    for i in range(n):
        t = 2 * math.pi * i / n
        x, y = 3 * math.cos(t), 2 * math.sin(t)
        pts.append((x, y))
        nrm.append(unit(x / 9, y / 4))  # gradient of x^2/9 + y^2/4
    write(os.path.join(out, "ellipse.txt"),
          ["ellipse x = 3 cos t, y = 2 sin t, 12 points, exact outward unit normals",
           "made by scripts/make-examples.py"], pts, nrm)

    n = 40
    pts = []
    for i in range(n):
        t = 2 * math.pi * i / n
        r = 1 + 0.3 * math.cos(5 * t)
        pts.append((r * math.cos(t), r * math.sin(t)))
    write(os.path.join(out, "flower.txt"),
          ["flower r = 1 + 0.3 cos 5t, 40 points, no normals (estimated)",
           "made by scripts/make-examples.py"], pts)

    xs = [-1.5 + 0.5 * i for i in range(7)]
    pts = [(x, x * x) for x in xs]
    nrm = [unit(2 * x, -1.0) for x in xs]  # -(gradient of y - x^2): convex side
    write(os.path.join(out, "parabola_open.txt"),
          ["open parabola arc y = x^2, x = -1.5 .. 1.5, exact unit normals",
           "made by scripts/make-examples.py; subdivide with --open"], pts, nrm)


if __name__ == "__main__":
    main()
