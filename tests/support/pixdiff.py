#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""pixdiff: compare the painted pixels of two PNG renderings (python3 stdlib only).

usage: pixdiff.py A.png B.png [--max-frac F] [--alpha T]

A pixel is painted when its alpha is >= T (default 1; 8-bit RGBA or grey+alpha
PNG, as rsvg-convert writes; RGB/grey without alpha: any non-white pixel).
A pixel painted in A but not in B is *lost* unless some pixel of its 3x3
neighbourhood is painted in B (it then lies in the 1-px band around B's painted
boundary); *added* is the same with A and B swapped. Prints one line

    painted A B lost L added D

and exits 0 when L and D are each at most F (default 0.001) times the painted
pixels of A (at least 1), 1 when not, 2 on bad input or different sizes.
"""
import struct
import sys
import zlib


def alpha_rows(fname):
    """The image's size and its 'painted' source: rows of alpha (or darkness) bytes."""
    data = open(fname, 'rb').read()
    if data[:8] != b'\x89PNG\r\n\x1a\n':
        raise ValueError('%s: not a PNG' % fname)
    pos, idat, hdr = 8, [], None
    while pos + 8 <= len(data):
        n, kind = struct.unpack('>I4s', data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b'IHDR':
            hdr = struct.unpack('>IIBBBBB', body)
        elif kind == b'IDAT':
            idat.append(body)
        elif kind == b'IEND':
            break
        pos += 12 + n
    if hdr is None:
        raise ValueError('%s: no IHDR' % fname)
    w, h, depth, ctype, _, _, inter = hdr
    chans = {0: 1, 2: 3, 4: 2, 6: 4}.get(ctype)
    if depth != 8 or chans is None or inter != 0:
        raise ValueError('%s: only 8-bit non-interlaced grey/RGB(A) PNGs are read' % fname)
    raw = zlib.decompress(b''.join(idat))
    stride = w * chans
    # the channel that decides: alpha, else the first colour channel (inverted
    # below); PNG filters work per byte against the same channel, so one
    # channel can be unfiltered alone
    ch = chans - 1 if ctype in (4, 6) else 0
    rows, prev, i = [], bytearray(w), 0
    for _ in range(h):
        f = raw[i]
        line = bytearray(raw[i + 1 + ch:i + 1 + stride:chans])
        i += 1 + stride
        if f == 1:
            for x in range(1, w):
                line[x] = (line[x] + line[x - 1]) & 255
        elif f == 2:
            for x in range(w):
                line[x] = (line[x] + prev[x]) & 255
        elif f == 3:
            for x in range(w):
                a = line[x - 1] if x else 0
                line[x] = (line[x] + ((a + prev[x]) >> 1)) & 255
        elif f == 4:
            for x in range(w):
                a = line[x - 1] if x else 0
                b = prev[x]
                c = prev[x - 1] if x else 0
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        elif f != 0:
            raise ValueError('%s: bad PNG filter %d' % (fname, f))
        rows.append(line)
        prev = line
    if ctype in (0, 2):
        rows = [bytearray(255 - v for v in r) for r in rows]
    return w, h, rows


def masks(rows, w, t):
    """Each row as an int whose bit x is set where the pixel is painted."""
    table = bytes(ord('1') if v >= t else ord('0') for v in range(256))
    return [int(bytes(r.translate(table))[::-1] or b'0', 2) for r in rows]


def dilate(m, w):
    full = (1 << w) - 1
    horiz = [(r | (r << 1) | (r >> 1)) & full for r in m]
    out = []
    for y in range(len(m)):
        v = horiz[y]
        if y:
            v |= horiz[y - 1]
        if y + 1 < len(m):
            v |= horiz[y + 1]
        out.append(v)
    return out


def count(m):
    return sum(bin(r).count('1') for r in m)


def main(argv):
    args, frac, t = [], 0.001, 1
    i = 1
    while i < len(argv):
        if argv[i] == '--max-frac' and i + 1 < len(argv):
            frac = float(argv[i + 1])
            i += 2
        elif argv[i] == '--alpha' and i + 1 < len(argv):
            t = int(argv[i + 1])
            i += 2
        else:
            args.append(argv[i])
            i += 1
    if len(args) != 2:
        sys.stderr.write(__doc__)
        return 2
    try:
        line, ok = compare(args[0], args[1], frac, t)
    except (OSError, ValueError, zlib.error, struct.error) as e:
        sys.stderr.write('pixdiff: error: %s\n' % e)
        return 2
    print(line)
    return 0 if ok else 1


def compare(png_a, png_b, frac=0.001, t=1):
    """The comparison of main(): (its line, whether it holds); ValueError
    (and the PNG reader's errors) on bad input or different sizes. For
    callers that compare many pairs in one process."""
    wa, ha, ra = alpha_rows(png_a)
    wb, hb, rb = alpha_rows(png_b)
    if (wa, ha) != (wb, hb):
        raise ValueError('sizes differ: %dx%d and %dx%d' % (wa, ha, wb, hb))
    ma, mb = masks(ra, wa, t), masks(rb, wb, t)
    da, db = dilate(ma, wa), dilate(mb, wb)
    lost = count([a & ~b for a, b in zip(ma, db)])
    added = count([b & ~a for a, b in zip(da, mb)])
    pa, pb = count(ma), count(mb)
    lim = frac * max(pa, 1)
    return ('painted %d %d lost %d added %d' % (pa, pb, lost, added),
            lost <= lim and added <= lim)


if __name__ == '__main__':
    sys.exit(main(sys.argv))
