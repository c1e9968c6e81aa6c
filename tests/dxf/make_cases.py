# SPDX-License-Identifier: MIT
"""Write the DXF test drawings of tests/cli/scadprofile_dxf.sh with ezdxf
(python3-ezdxf), one file per case, into the directory given:

    python3 tests/dxf/make_cases.py OUTDIR

Every entity type scadprofile reads is here, drawn the way CAD programs
write them (ezdxf is an independent DXF writer): the three reproductions
of issue 35, LINE/ARC outlines in scrambled order and direction, ellipses,
a NURBS with repeated knots and weights, a periodic spline, blocks
inserted rotated, scaled, mirrored, arrayed and nested, 2D POLYLINEs of an
R12 file, an ARC in a mirrored OCS, HATCH boundaries, layers, units."""
import math
import os
import sys

import ezdxf
from ezdxf.math import Vec3

out = sys.argv[1]
os.makedirs(out, exist_ok=True)


def new(units=4, version="R2010"):
    doc = ezdxf.new(version)
    if units is not None:
        doc.header["$INSUNITS"] = units
    return doc, doc.modelspace()


def save(doc, name):
    doc.saveas(os.path.join(out, name))


# --- issue 35's reproductions -------------------------------------------
# a closed LWPOLYLINE 40 x 20 with a bulge (an arc) on its right edge
doc, msp = new()
msp.add_lwpolyline([(0, 0, 0, 0, 0), (40, 0, 0, 0, 0.5), (40, 20, 0, 0, 0), (0, 20, 0, 0, 0)],
                   format="xyseb", close=True)
save(doc, "repro_bulge.dxf")
# a SPLINE of degree 3 with 6 control points (closed by a LINE)
doc, msp = new()
msp.add_open_spline([(0, 0), (8, 12), (20, 4), (30, 16), (42, 6), (50, 0)], degree=3)
msp.add_line((50, 0), (0, 0))
save(doc, "repro_spline.dxf")
# the same spline alone (open: --open closes it)
doc, msp = new()
msp.add_open_spline([(0, 0), (8, 12), (20, 4), (30, 16), (42, 6), (50, 0)], degree=3)
save(doc, "spline_open.dxf")
# two splines (conica plot --entity HANDLE chooses)
doc, msp = new()
msp.add_open_spline([(0, 0), (8, 12), (20, 4), (30, 16), (42, 6), (50, 0)], degree=3)
msp.add_open_spline([(0, 0), (1, 1), (2, 0)], degree=2)
save(doc, "nurbs_two.dxf")
# a CIRCLE r = 3
doc, msp = new()
msp.add_circle((0, 0), 3)
save(doc, "repro_circle.dxf")

# --- separate entities chained ------------------------------------------
# a slot 60 x 20 with round ends, drawn as LINEs and ARCs in scrambled order
# and directions, with a round hole r 4 and a square hole of 4 LINEs
doc, msp = new()
msp.add_arc((50, 10), 10, 270, 90)           # right end, ccw
msp.add_line((10, 20), (50, 20))             # top, drawn left to right
msp.add_line((50, 0), (10, 0))               # bottom, right to left
msp.add_arc((10, 10), 10, 90, 270)           # left end
msp.add_circle((20, 10), 4)
for a, b in [((36, 6), (44, 6)), ((44, 14), (44, 6)), ((36, 14), (44, 14)), ((36, 6), (36, 14))]:
    msp.add_line(a, b)
save(doc, "slot_chain.dxf")

# an outline of an open LWPOLYLINE (with a bulge), a SPLINE and a LINE
doc, msp = new()
msp.add_lwpolyline([(0, 0, 0), (30, 0, -0.4), (30, 20, 0)], format="xyb")
msp.add_open_spline([(30, 20), (20, 30), (10, 10), (0, 20)], degree=3)
msp.add_line((0, 0), (0, 20))
save(doc, "mixed_chain.dxf")

# curves meeting straight edges at corners (issue 35 / 31: the old fit
# moved such a corner off its line): a plate whose convex top ARC meets
# its vertical sides, a concave notch ARC in its bottom edge, and a
# D-shaped hole (an ARC closed by a LINE), all LINE/ARC entities
doc, msp = new()
msp.add_line((0, 0), (15, 0))
msp.add_arc((20, 0), 5, 0, 180)                           # the notch, into the material
msp.add_line((25, 0), (40, 0))
msp.add_line((40, 0), (40, 10))
a = math.degrees(math.atan2(10, 20))
msp.add_arc((20, 0), math.sqrt(500), a, 180 - a)          # the top, (40, 10) to (0, 10)
msp.add_line((0, 10), (0, 0))
msp.add_arc((30, 10), 4, 270, 90)                         # the hole: (30, 6) to (30, 14)
msp.add_line((30, 14), (30, 6))
save(doc, "corner_plate.dxf")

# overlapping contours: two CIRCLEs that cross, filled even-odd as
# OpenSCAD's import() reads them (the lens is not material: two crescents
# that meet where the circles cross)
doc, msp = new()
msp.add_circle((0, 0), 10)
msp.add_circle((12, 0), 10)
save(doc, "overlap.dxf")

# an outline that does not close (a gap of 0.5)
doc, msp = new()
msp.add_line((0, 0), (10, 0))
msp.add_line((10, 0), (10, 10))
msp.add_line((10, 10), (0.5, 0))
save(doc, "open_outline.dxf")

# --- ellipses ------------------------------------------------------------
doc, msp = new()
msp.add_ellipse((0, 0), major_axis=(30 * math.cos(0.5), 30 * math.sin(0.5)), ratio=0.4)
# a partial ellipse from 0.3 to 2.8 rad, closed by its chord
e = msp.add_ellipse((100, 0), major_axis=(0, 25), ratio=0.6, start_param=0.3, end_param=2.8)
t = e.construction_tool()
msp.add_line(t.end_point, t.start_point)
save(doc, "ellipses.dxf")

# --- splines ---------------------------------------------------------------
# a rational NURBS of degree 3 with a repeated interior knot (multiplicity 2)
# and weights, closed by two lines
doc, msp = new()
cps = [(0, 0), (10, 25), (25, 30), (40, 5), (55, 25), (70, 10), (80, 0)]
w = [1, 2.5, 0.6, 1.7, 0.8, 3, 1]
knots = [0, 0, 0, 0, 1, 2, 2, 3, 3, 3, 3]
sp = msp.add_spline(dxfattribs={"degree": 3})
sp.control_points = [Vec3(x, y, 0) for x, y in cps]
sp.knots = knots
sp.weights = w
msp.add_line((80, 0), (80, -10))
msp.add_line((80, -10), (0, -10))
msp.add_line((0, -10), (0, 0))
save(doc, "nurbs_knots.dxf")

# a closed periodic cubic spline (flags closed + periodic, unclamped knots)
doc, msp = new()
sp = msp.add_spline()
sp.set_closed([Vec3(x, y, 0) for x, y in [(0, 0), (30, -10), (50, 10), (40, 40), (10, 35), (-10, 15)]])
save(doc, "periodic.dxf")

# --- blocks ----------------------------------------------------------------
# a block (a 10 x 6 plate with a bulged end and a hole) inserted plain,
# rotated, scaled non-uniformly, mirrored (negative x scale), as a 2 x 3
# array, and inside another block (nesting)
doc, msp = new()
blk = doc.blocks.new(name="TAB", base_point=(1, 1))
blk.add_lwpolyline([(0, 0, 0), (10, 0, 0.6), (10, 6, 0), (0, 6, 0)], format="xyb", close=True)
blk.add_circle((3, 3), 1.2)
outer = doc.blocks.new(name="PAIR")
outer.add_blockref("TAB", (0, 0))
outer.add_blockref("TAB", (0, 20), dxfattribs={"rotation": 15})
msp.add_blockref("TAB", (0, 0))
msp.add_blockref("TAB", (40, 0), dxfattribs={"rotation": 30})
msp.add_blockref("TAB", (80, 0), dxfattribs={"xscale": 1.5, "yscale": 0.75})
msp.add_blockref("TAB", (130, 0), dxfattribs={"xscale": -1})
msp.add_blockref("TAB", (150, 0), dxfattribs={"xscale": -1, "yscale": -1, "rotation": 10})
ref = msp.add_blockref("TAB", (0, 40))
ref.grid(size=(2, 3), spacing=(12, 16))
msp.add_blockref("PAIR", (100, 60), dxfattribs={"rotation": -20, "xscale": 0.8, "yscale": 0.8})
save(doc, "blocks.dxf")

# --- R12: 2D POLYLINE with VERTEX bulges -------------------------------------
doc, msp = new(units=None, version="R12")
pl = msp.add_polyline2d([(0, 0), (20, 0), (20, 10), (0, 10)], close=True)
pl.vertices[1].dxf.bulge = 0.3
pl.vertices[3].dxf.bulge = -0.25
msp.add_circle((6, 5), 2)
save(doc, "r12_polyline.dxf")

# --- an ARC in a mirrored OCS (extrusion 0, 0, -1), closed by its chord ------
doc, msp = new()
arc = msp.add_arc((10, 0), 8, 20, 160, dxfattribs={"extrusion": (0, 0, -1)})
sp0, sp1 = arc.start_point, arc.end_point
msp.add_line(sp1, sp0)
save(doc, "mirrored_ocs.dxf")

# --- HATCH only: an edge path (lines, a clockwise arc, an ellipse arc) and a
#     polyline path with a bulge --------------------------------------------
doc, msp = new()
h = msp.add_hatch()
ep = h.paths.add_edge_path()
ep.add_line((0, 0), (30, 0))
ep.add_arc((30, 10), 10, 270, 90, ccw=True)
ep.add_line((30, 20), (0, 20))
ep.add_ellipse((0, 10), major_axis=(0, 10), ratio=0.5, start_angle=0, end_angle=180, ccw=True)
h.paths.add_polyline_path([(8, 6, 0), (16, 6, 0.5), (16, 14, 0), (8, 14, 0)], is_closed=True)
save(doc, "hatch_only.dxf")

# --- layers: A and B visible, C frozen, D off --------------------------------
doc, msp = new()
doc.layers.add("A")
doc.layers.add("B")
doc.layers.add("C").freeze()
doc.layers.add("D").off()
msp.add_circle((0, 0), 10, dxfattribs={"layer": "A"})
msp.add_circle((30, 0), 5, dxfattribs={"layer": "B"})
msp.add_circle((60, 0), 5, dxfattribs={"layer": "C"})
msp.add_circle((90, 0), 5, dxfattribs={"layer": "D"})
msp.add_text("not geometry", dxfattribs={"layer": "A"})
msp.add_text("neither", dxfattribs={"layer": "B"})
msp.add_mtext("nor this", dxfattribs={"layer": "A"})
msp.add_point((5, 5))
save(doc, "layers.dxf")

# --- units: inches, and the same drawing in metres -----------------------------
for name, units in (("inch.dxf", 1), ("metre.dxf", 6)):
    doc, msp = new(units=units)
    msp.add_lwpolyline([(0, 0), (2, 0), (2, 1), (0, 1)], close=True)
    msp.add_circle((0.5, 0.5), 0.25)
    save(doc, name)
