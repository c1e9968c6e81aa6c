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

Prints `painted P lost L added A` and exits 1 when lost or added exceeds
--limit of the painted pixels (default 0.1 %), 2 on a usage or tool error.
Reads PNG itself (8-bit RGBA from rsvg-convert), so needs only numpy.
"""
import os
import re
import struct
import subprocess
import sys
import tempfile
import zlib

import numpy as np


def read_png(path):
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG")
    pos, idat, w = 8, [], 0
    h = depth = ctype = 0
    while pos < len(data):
        (n,) = struct.unpack(">I", data[pos:pos + 4])
        kind = data[pos + 4:pos + 8]
        body = data[pos + 8:pos + 8 + n]
        pos += 12 + n
        if kind == b"IHDR":
            w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
        elif kind == b"IDAT":
            idat.append(body)
    if depth != 8 or ctype != 6:
        raise ValueError("expected 8-bit RGBA")
    raw = zlib.decompress(b"".join(idat))
    stride = 4 * w
    img = np.zeros((h, stride), dtype=np.int32)
    prev = np.zeros(stride, dtype=np.int32)
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = np.frombuffer(raw, dtype=np.uint8, count=stride, offset=y * (stride + 1) + 1).astype(np.int32)
        if f == 0:
            cur = line
        elif f == 1:
            cur = line.copy()
            for x in range(4, stride):
                cur[x] = (cur[x] + cur[x - 4]) & 255
        elif f == 2:
            cur = (line + prev) & 255
        elif f == 3:
            cur = line.copy()
            for x in range(stride):
                a = cur[x - 4] if x >= 4 else 0
                cur[x] = (cur[x] + ((a + prev[x]) >> 1)) & 255
        elif f == 4:
            cur = line.copy()
            for x in range(stride):
                a = cur[x - 4] if x >= 4 else 0
                b = prev[x]
                c = prev[x - 4] if x >= 4 else 0
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pr = a if (pa <= pb and pa <= pc) else (b if pb <= pc else c)
                cur[x] = (cur[x] + pr) & 255
        else:
            raise ValueError("bad PNG filter")
        img[y] = cur
        prev = cur
    return img.reshape(h, w, 4)


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
    return read_png(out)[:, :, 3] >= 128


def shift_or(m):
    o = m.copy()
    o[1:, :] |= m[:-1, :]
    o[:-1, :] |= m[1:, :]
    o[:, 1:] |= m[:, :-1]
    o[:, :-1] |= m[:, 1:]
    return o


def main(argv):
    args = [a for a in argv[1:]]
    px, limit, keep = 600, 0.001, None
    pos = []
    i = 0
    while i < len(args):
        if args[i] == "--px":
            px = int(args[i + 1]); i += 2
        elif args[i] == "--limit":
            limit = float(args[i + 1]); i += 2
        elif args[i] == "--keep":
            keep = args[i + 1]; i += 2
        else:
            pos.append(args[i]); i += 1
    if len(pos) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    scad, svg = pos
    contours = module_polygon(open(scad).read())
    w, h = doc_size(svg)
    k = px / max(w, h)
    size = (max(1, round(w * k)), max(1, round(h * k)))
    d = keep or tempfile.mkdtemp()
    os.makedirs(d, exist_ok=True)
    poly_svg = os.path.join(d, "module.svg")
    with open(poly_svg, "w") as f:
        f.write(polygon_svg(contours, w, h))
    ref = render(svg, size, os.path.join(d, "doc.png"))
    got = render(poly_svg, size, os.path.join(d, "module.png"))
    # the 1 px band round the document's edge: pixels whose 4-neighbourhood
    # holds both painted and unpainted pixels, grown by one
    edge = shift_or(ref) & shift_or(~ref)
    band = shift_or(edge)
    painted = int(ref.sum())
    lost = int((ref & ~got & ~band).sum())
    added = int((got & ~ref & ~band).sum())
    print("painted %d lost %d added %d" % (painted, lost, added))
    if painted == 0:
        return 1 if added else 0
    return 1 if (lost > limit * painted or added > limit * painted) else 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv))
    except (ValueError, subprocess.CalledProcessError, OSError) as e:
        print("scad_pixels: error: %s" % e, file=sys.stderr)
        sys.exit(2)
