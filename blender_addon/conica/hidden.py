# SPDX-License-Identifier: GPL-3.0-or-later
# Hidden points of a POLY spline under Conic Subdivide, as Blender's own
# Subdivide treats them: a hidden point stays where it is and stays hidden,
# and no point is inserted on a segment that has a hidden end. The whole
# spline is still subdivided as one curve (the shown parts keep the shape
# they would have had), then the points inserted next to hidden points are
# dropped again. Which output point is which input point comes back through
# two extra attribute columns (the curve front end carries attributes
# linearly along each segment): the point's index, and 1 at point 0 / 0
# elsewhere, which tells the closing segment (n-1 -> 0) from the others.
# Called by operators.py only; calls nothing of Blender's.
import array

# Extra attribute columns appended after radius and tilt.
NCOLS = 2


def index_columns(n):
    """The two marker columns for n points, as a flat list of pairs."""
    out = [0.0] * (2 * n)
    out[0::2] = [float(i) for i in range(n)]
    out[1] = 1.0
    return out


def vertices(marks, n):
    """[(output position, input index)] of the output points that are input
    points, from the marker columns (flat pairs) of the output."""
    found = []
    for k in range(len(marks) // 2):
        a, b = marks[2 * k], marks[2 * k + 1]
        if a != int(a):
            continue
        if (a == 0.0 and b == 1.0) or (a > 0.0 and b == 0.0):
            found.append((k, int(a)))
    return found


def keep_mask(verts, hide, m, closed):
    """Which of the m output points to keep: all but the inner points of
    segments with a hidden end (input indices of consecutive vertices)."""
    keep = [True] * m
    pairs = list(zip(verts, verts[1:]))
    if closed and verts:
        pairs.append((verts[-1], (verts[0][0] + m, verts[0][1])))
    for (p0, i0), (p1, i1) in pairs:
        if hide[i0] or hide[i1]:
            for k in range(p0 + 1, p1):
                keep[k % m] = False
    return keep


def drop_hidden_segments(co, attrs, hide, closed, stride):
    """(co, attrs, hide) of the output with the segments next to hidden
    points left as they were; attrs holds radius, tilt and the two marker
    columns per point (4 values), the result radius and tilt (2 values).
    None when the markers do not find every input point once, in order
    (the caller then leaves the spline unchanged)."""
    n = len(hide)
    m = len(co) // stride
    verts = vertices([v for k in range(m) for v in attrs[4 * k + 2:4 * k + 4]], n)
    if [i for _, i in verts] != list(range(n)):
        return None
    keep = keep_mask(verts, hide, m, closed)
    out_co = array.array(co.typecode)
    out_at = array.array(attrs.typecode)
    out_hide = array.array("b")
    is_vertex = dict(verts)
    for k in range(m):
        if not keep[k]:
            continue
        out_co.extend(co[stride * k:stride * k + stride])
        out_at.extend(attrs[4 * k:4 * k + 2])
        i = is_vertex.get(k)
        out_hide.append(1 if i is not None and hide[i] else 0)
    return out_co, out_at, out_hide
