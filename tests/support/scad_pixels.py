#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Pixels of a scadprofile module beside librsvg's pixels of its SVG.

    scad_pixels.py MODULE.scad DOC.svg [--px 600] [--limit 0.001] [--keep DIR]

MODULE.scad must have been written with `--units px` from DOC.svg (so its
numbers are the document's root frame in CSS px, y up from the bottom).
Its polygon (NAME_points / NAME_paths) becomes an SVG of the same width and
height, filled nonzero (outlines counter-clockwise, holes clockwise, as the
writer orders them), and both documents are rendered by rsvg-convert at
--px pixels on their longer side. A pixel is painted when its alpha is at
least half. Painted pixels of the document that the module does not paint
are lost, the other way added; pixels within 1 px of the document's edge
(the band where antialiasing decides) are not counted.

The comparison is tests/support/pixdiff.py's (alpha >= 128 is painted; a
pixel counts as lost or added only outside the 1 px band round the other
image's painted pixels): its line `painted A B lost L added D` is printed,
exit 1 when lost or added exceeds --limit of the painted pixels (default
0.1 %), 2 on a usage or tool error.

    scad_pixels.py --batch LIST [--px 600] [--limit 0.001]

compares many pairs in one process (the CLI suites: one python start, not
one per icon): each line of LIST is `LABEL MODULE.scad DOC.svg`; prints
`ok LABEL: LINE` or `FAIL LABEL: LINE` (or the error) per line, exit 1 when
any failed, 2 on a usage error.
"""
import os
import re
import struct
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.dont_write_bytecode = True  # nothing written into the source tree
import pixdiff  # noqa: E402  (tests/support/pixdiff.py)


def module_polygon(text):
    pts = re.search(r"function (\w+)_points\(\) = \[(.*?)\];", text, re.S)
    paths = re.search(r"function \w+_paths\(\) = \[(.*?)\];", text, re.S)
    if not pts or not paths:
        raise ValueError("no NAME_points() / NAME_paths() in the module")
    xy = [tuple(map(float, p)) for p in re.findall(r"\[([-0-9.e+]+),([-0-9.e+]+)\]", pts.group(2))]
    idx = [list(map(int, re.findall(r"\d+", p))) for p in re.findall(r"\[([0-9,\s]*)\]", paths.group(1))]
    return [[xy[i] for i in q] for q in idx]


def doc_size(svg_path):
    """The document's size in px as librsvg sees it (its PNG at 96 dpi)."""
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "s.png")
        subprocess.run(["rsvg-convert", "-o", out, svg_path], check=True)
        data = open(out, "rb").read()
        return struct.unpack(">II", data[16:24])


def polygon_svg(contours, w, h):
    d = []
    for c in contours:
        d.append("M" + " L".join("%.17g %.17g" % (x, h - y) for x, y in c) + "Z")
    return ('<svg xmlns="http://www.w3.org/2000/svg" width="%.17g" height="%.17g" '
            'viewBox="0 0 %.17g %.17g"><path fill="#000" fill-rule="nonzero" d="%s"/></svg>\n'
            % (w, h, w, h, " ".join(d)))


def render(svg_path, px, out):
    subprocess.run(["rsvg-convert", "-w", str(px[0]), "-h", str(px[1]), "-o", out, svg_path],
                   check=True)


def compare(scad, svg, px, limit, d):
    """Render both into directory d; pixdiff's (line, ok)."""
    contours = module_polygon(open(scad).read())
    w, h = doc_size(svg)
    k = px / max(w, h)
    size = (max(1, round(w * k)), max(1, round(h * k)))
    os.makedirs(d, exist_ok=True)
    poly_svg = os.path.join(d, "module.svg")
    with open(poly_svg, "w") as f:
        f.write(polygon_svg(contours, w, h))
    render(svg, size, os.path.join(d, "doc.png"))
    render(poly_svg, size, os.path.join(d, "module.png"))
    return pixdiff.compare(os.path.join(d, "doc.png"), os.path.join(d, "module.png"), limit, 128)


def batch(listfile, px, limit):
    bad = 0
    with tempfile.TemporaryDirectory() as d:
        for row in open(listfile):
            f = row.split()
            if not f:
                continue
            if len(f) != 3:
                print("FAIL %s: not LABEL MODULE DOC" % row.strip())
                bad += 1
                continue
            try:
                line, ok = compare(f[1], f[2], px, limit, d)
            except (ValueError, subprocess.CalledProcessError, OSError) as e:
                line, ok = "error: %s" % e, False
            print("%s %s: %s" % ("ok" if ok else "FAIL", f[0], line))
            bad += not ok
    return 1 if bad else 0


def main(argv):
    args = [a for a in argv[1:]]
    px, limit, keep, lst = 600, 0.001, None, None
    pos = []
    i = 0
    while i < len(args):
        if args[i] == "--px":
            px = int(args[i + 1]); i += 2
        elif args[i] == "--limit":
            limit = float(args[i + 1]); i += 2
        elif args[i] == "--keep":
            keep = args[i + 1]; i += 2
        elif args[i] == "--batch":
            lst = args[i + 1]; i += 2
        else:
            pos.append(args[i]); i += 1
    if lst is not None and not pos:
        return batch(lst, px, limit)
    if len(pos) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    line, ok = compare(pos[0], pos[1], px, limit, keep or tempfile.mkdtemp())
    print(line)
    return 0 if ok else 1


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv))
    except (ValueError, subprocess.CalledProcessError, OSError) as e:
        print("scad_pixels: error: %s" % e, file=sys.stderr)
        sys.exit(2)
