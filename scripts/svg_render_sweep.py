#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Compare the render's flat scene with the document itself, as librsvg paints
them, over directories of SVG files (docs/benchmarks.md, "SVG render").

usage: svg_render_sweep.py SVGSCENE [--every K] [--size PX] [--max-frac F] DIR...

For every K-th file (sorted by name) of each DIR: svgscene writes the scene,
rsvg-convert renders both at PX x PX, tests/support/pixdiff.py's comparison
counts lost and added painted pixels outside a 1-px band. Prints one line per
DIR: files, scene errors, rsvg errors on the original, agreeing files (lost and
added each <= F of the painted pixels, default 0.001), files with warnings;
then the disagreeing files.
"""
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'tests', 'support'))
import pixdiff  # noqa: E402


def compare(a, b, frac):
    wa, ha, ra = pixdiff.alpha_rows(a)
    wb, hb, rb = pixdiff.alpha_rows(b)
    if (wa, ha) != (wb, hb):
        return False, 'size'
    ma, mb = pixdiff.masks(ra, wa, 1), pixdiff.masks(rb, wb, 1)
    da, db = pixdiff.dilate(ma, wa), pixdiff.dilate(mb, wb)
    lost = pixdiff.count([x & ~y for x, y in zip(ma, db)])
    added = pixdiff.count([y & ~x for x, y in zip(da, mb)])
    pa = pixdiff.count(ma)
    lim = frac * max(pa, 1)
    return lost <= lim and added <= lim, 'painted %d lost %d added %d' % (pa, lost, added)


def main(argv):
    scene, every, size, frac, dirs = None, 1, 256, 0.001, []
    i = 1
    while i < len(argv):
        if argv[i] == '--every':
            every = int(argv[i + 1]); i += 2
        elif argv[i] == '--size':
            size = int(argv[i + 1]); i += 2
        elif argv[i] == '--max-frac':
            frac = float(argv[i + 1]); i += 2
        elif scene is None:
            scene = argv[i]; i += 1
        else:
            dirs.append(argv[i]); i += 1
    if not scene or not dirs:
        sys.stderr.write(__doc__)
        return 2
    tmp = tempfile.mkdtemp()
    bad_all = []
    for d in dirs:
        files = sorted(f for f in os.listdir(d) if f.endswith('.svg'))[::every]
        n = err = rerr = ok = warned = 0
        for f in files:
            n += 1
            src = os.path.join(d, f)
            out = os.path.join(tmp, 'scene.svg')
            p = subprocess.run([scene, src, out], capture_output=True, text=True)
            if p.returncode != 0:
                err += 1
                bad_all.append((src, 'scene error: ' + p.stderr.strip()[:200]))
                continue
            if p.stderr.strip():
                warned += 1
            a, b = os.path.join(tmp, 'a.png'), os.path.join(tmp, 'b.png')
            s = ['-w', str(size), '-h', str(size)]
            if subprocess.run(['rsvg-convert'] + s + ['-o', a, src], capture_output=True).returncode:
                rerr += 1
                continue
            subprocess.run(['rsvg-convert'] + s + ['-o', b, out], check=True, capture_output=True)
            good, why = compare(a, b, frac)
            if good:
                ok += 1
            else:
                bad_all.append((src, why + (' (warned: %s)' % p.stderr.strip()[:200] if p.stderr.strip() else '')))
        print('%s: files %d, scene errors %d, rsvg errors %d, agree %d, warned %d'
              % (d, n, err, rerr, ok, warned))
        sys.stdout.flush()
    for src, why in bad_all:
        print('  differs: %s: %s' % (src, why))
    return 0 if not bad_all else 1


if __name__ == '__main__':
    sys.exit(main(sys.argv))
