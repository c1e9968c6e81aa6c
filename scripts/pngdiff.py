#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Print how many pixels of two PNGs of one size differ by more than 1/8 of
full scale in any channel (alpha included). Standard library only: reads
8-bit RGBA/RGB non-interlaced PNGs, as rsvg-convert writes them."""
import struct
import sys
import zlib


def pixels(path):
    with open(path, 'rb') as f:
        data = f.read()
    pos, idat, w = 8, b'', 0
    while pos < len(data):
        n, kind = struct.unpack('>I4s', data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b'IHDR':
            w, h, depth, ctype = struct.unpack('>IIBB', body[:10])
            if depth != 8 or ctype not in (2, 6):
                raise SystemExit(f'{path}: unsupported PNG')
            bpp = 4 if ctype == 6 else 3
        elif kind == b'IDAT':
            idat += body
        pos += 12 + n
    raw, stride, out, prev = zlib.decompress(idat), w * bpp, [], bytearray(w * bpp)
    for y in range(h):
        ft, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if ft == 1:
                line[i] = (line[i] + a) & 255
            elif ft == 2:
                line[i] = (line[i] + b) & 255
            elif ft == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif ft == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        out.append(bytes(line))
        prev = line
    return w, h, bpp, out


def main():
    wa, ha, ba, pa = pixels(sys.argv[1])
    wb, hb, bb, pb = pixels(sys.argv[2])
    if (wa, ha, ba) != (wb, hb, bb):
        print(wa * ha)
        return
    n = 0
    for ra, rb in zip(pa, pb):
        for x in range(wa):
            if any(abs(ra[x * ba + k] - rb[x * ba + k]) > 32 for k in range(ba)):
                n += 1
    print(n)


main()
