# SPDX-License-Identifier: MIT
"""scadprofile beside OpenSCAD's import() on the same DXF drawings.

    python3 bench/bench_dxf_import.py BUILD_DIR FILE.dxf...

For each drawing: OpenSCAD's `import("FILE.dxf")` at its defaults,
exported as DXF (`openscad -o x.dxf`) and read back with ezdxf; and
`scadprofile --tolerance 0.01`. Both measured against the exact geometry
of the drawing by tests/dxf/check.py's independent evaluation (two-sided
deviation: the larger of polygon -> drawing and drawing -> polygon).
Where import() reads the file, the scadprofile tolerance whose measured
deviation matches import()'s (bisection) and the points it needs there.
Prints a markdown table, asserts nothing."""
import os
import re
import subprocess
import sys
import tempfile

import ezdxf
import numpy as np

sys.argv, _argv = sys.argv[:1] + ["x", "x", "m", "1"], sys.argv
exec(open(os.path.join(os.path.dirname(__file__), "..", "tests", "dxf", "check.py")).read().split("def main")[0])
sys.argv = _argv
build = sys.argv[1]
files = sys.argv[2:]
tmp = tempfile.mkdtemp()


def exact_of(path, tol):
    """check.py's exact geometry (samples within 1e-3 tol of the curves)."""
    pieces, _size = exact_geometry(path, tol, 1.0, None, False)
    return (np.concatenate([p[:-1] for p in pieces]), np.concatenate([p[1:] for p in pieces]),
            np.concatenate(pieces), len(list(ezdxf.readfile(path).modelspace())))


def deviation(polys, ex):
    A0, A1, samples, _ = ex
    if not polys:
        return float("inf")
    E0 = np.concatenate(polys)
    E1 = np.concatenate([np.roll(q, -1, 0) for q in polys])
    f = np.linspace(0, 1, 9)[:-1]
    dense = np.concatenate([E0 + t * (E1 - E0) for t in f])
    w = 5.0
    return max(seg_dist(dense, A0, A1, w).max(), seg_dist(samples, E0, E1, w).max())


def scad_polys(path):
    text = open(path).read()
    pts = re.search(r"function m_points\(\) = \[(.*?)\];", text, re.S).group(1)
    P = np.array([[float(a), float(b)] for a, b in re.findall(r"\[([-0-9.e+]+),([-0-9.e+]+)\]", pts)])
    paths = re.search(r"function m_paths\(\) = \[(.*?)\];\s*\n", text, re.S).group(1)
    return [P[[int(i) for i in re.findall(r"\d+", p)]] for p in re.findall(r"\[([0-9, \n]+)\]", paths)]


def scadprofile(path, tol):
    out = os.path.join(tmp, "s.scad")
    r = subprocess.run([os.path.join(build, "bin", "scadprofile"), "--module", "m", "--tolerance",
                        repr(tol), "-o", out, path], capture_output=True, text=True)
    if r.returncode != 0:
        return None, r.stderr.strip().splitlines()[-1] if r.stderr else "error"
    return scad_polys(out), open(out).read()


def openscad_import(path):
    scad = os.path.join(tmp, "i.scad")
    out = os.path.join(tmp, "i.dxf")
    if os.path.exists(out):
        os.remove(out)
    open(scad, "w").write('import("%s");\n' % os.path.abspath(path))
    r = subprocess.run(["openscad", "-o", out, scad], capture_output=True, text=True)
    warn = sorted(set(re.findall(r"WARNING: ([^\n]*?)(?: in \"|,|\n|$)", r.stderr)))
    if r.returncode != 0 or not os.path.exists(out):
        return None, warn
    doc = ezdxf.readfile(out)
    polys = []
    for e in doc.modelspace():
        if e.dxftype() == "LWPOLYLINE":
            polys.append(np.array([(x, y) for x, y, *_ in e.get_points()], float))
        elif e.dxftype() == "POLYLINE":
            polys.append(np.array([(v.dxf.location.x, v.dxf.location.y) for v in e.vertices], float))
    if not polys:  # LINE entities: chain them back into loops
        segs = [(tuple(e.dxf.start)[:2], tuple(e.dxf.end)[:2]) for e in doc.modelspace() if e.dxftype() == "LINE"]
        nxt = {a: b for a, b in segs}
        seen = set()
        for a, _ in segs:
            if a in seen:
                continue
            loop = [a]
            seen.add(a)
            b = nxt.get(a)
            while b is not None and b not in seen:
                loop.append(b)
                seen.add(b)
                b = nxt.get(b)
            polys.append(np.array(loop, float))
    return polys, warn


print("| drawing | entities | import(): contours, points, deviation | scadprofile T=0.01: contours, points, deviation | scadprofile at import()'s deviation: points |")
print("|---|---|---|---|---|")
for f in files:
    name = os.path.basename(f)
    ex = exact_of(f, 0.01)
    sp, text = scadprofile(f, 0.01)
    if sp is None:
        spcol = "error: " + text[:80]
        entities = "%d" % ex[3]
    else:
        m = re.search(r"^// DXF: (\d+) entities read, (\d+) skipped", text, re.M)
        entities = "%d (%s read)" % (ex[3], m.group(1) if m else "?")
        spcol = "%d, %d, %.3g mm" % (len(sp), sum(len(q) for q in sp), deviation(sp, ex))
    ip, warn = openscad_import(f)
    if ip is None or not ip:
        icol = "nothing imported" + ("; " + "; ".join(warn) if warn else "")
        eq = "-"
    else:
        di = deviation(ip, ex)
        icol = "%d, %d, %.3g mm%s" % (len(ip), sum(len(q) for q in ip), di,
                                      ("; " + "; ".join(warn)) if warn else "")
        eq = "-"
        if sp is not None and di < 1e3 and di > 1e-9:
            lo, hi = di / 64, di * 4
            best = None
            for _ in range(14):
                mid = (lo * hi) ** 0.5
                q, _t = scadprofile(f, mid)
                if q is None:
                    break
                if deviation(q, ex) <= di:
                    best, lo = q, mid
                else:
                    hi = mid
            if best is not None:
                eq = "%d (vs %d)" % (sum(len(q) for q in best), sum(len(q) for q in ip))
    print("| %s | %s | %s | %s | %s |" % (name, entities, icol, spcol, eq))
