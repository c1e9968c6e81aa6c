# SPDX-License-Identifier: GPL-3.0-or-later
# Esc in a real Blender window (tests/cli/blender.sh runs it under Xvfb):
#   CONICA_ZIP=build/conica-blender.zip BLENDER_USER_SCRIPTS=$tmp xvfb-run -a \
#   blender --factory-startup --enable-event-simulate --python tests/blender/test_escape_window.py
# Conic Subdivide is invoked as a menu would (INVOKE_DEFAULT in the 3D
# Viewport) on three big splines, so it runs modally (job.py); an Esc
# press is sent through Blender's own event queue (Window.event_simulate),
# and the run must stop CANCELLED with the curve as it was; a second run
# without Esc must finish through its timer events. Prints `PASS name` or
# `FAIL name: why` per check and `SUMMARY`, then quits Blender.
import math
import os
import sys

import addon_utils
import bpy

RESULTS = []


def report(name, ok, why=""):
    RESULTS.append(ok)
    print("%s %s%s" % ("PASS" if ok else "FAIL", name, ": " + why if why else ""), flush=True)


def finish():
    print("SUMMARY %d passed, %d failed" % (sum(RESULTS), len(RESULTS) - sum(RESULTS)),
          flush=True)
    os._exit(0 if all(RESULTS) else 1)


def setup():
    bpy.ops.preferences.addon_install(filepath=os.path.abspath(os.environ["CONICA_ZIP"]),
                                      overwrite=True)
    if addon_utils.enable("conica", default_set=True) is None:
        report("escape_window_addon_loads", False)
        finish()
    for ob in list(bpy.data.objects):
        bpy.data.objects.remove(ob, do_unlink=True)
    cu = bpy.data.curves.new("big", "CURVE")
    cu.dimensions = "3D"
    n = N
    for k in range(3):
        sp = cu.splines.new("POLY")
        sp.points.add(n - 1)
        co = []
        for i in range(n):
            t = 2 * math.pi * i / n
            co += [3 * k + math.cos(t), math.sin(t), 0.0, 1.0]
        sp.points.foreach_set("co", co)
        sp.use_cyclic_u = True
    ob = bpy.data.objects.new("big", cu)
    bpy.context.scene.collection.objects.link(ob)
    ob.select_set(True)
    bpy.context.view_layer.objects.active = ob
    return ob


def counts(ob):
    return [len(sp.points) for sp in ob.data.splines]


def viewport():
    win = bpy.context.window_manager.windows[0]
    area = next(a for a in win.screen.areas if a.type == "VIEW_3D")
    region = next(r for r in area.regions if r.type == "WINDOW")
    return win, area, region


# Points per spline: 3 x 8000 at level 5 is about 770 000 output points,
# above job.LONG_WORK, so invoke() runs modally, one spline per chunk.
N = 8000
STATE = {"step": "start", "waits": 0}


def tick():
    """One step of the test per timer call; returns the delay to the next."""
    win, area, region = viewport()
    st = STATE
    if st["step"] == "start":
        st["ob"] = setup()
        st["before"] = counts(st["ob"])
        with bpy.context.temp_override(window=win, area=area, region=region):
            bpy.ops.ed.undo_push(message="three splines")
            r = bpy.ops.curve.conic_subdivide("INVOKE_DEFAULT", levels=5)
        report("escape_window_goes_modal", r == {"RUNNING_MODAL"}, repr(r))
        if r != {"RUNNING_MODAL"}:
            finish()
        st["step"] = "escape"
        return 0.05
    ops = sys.modules["conica"].operators
    if st["step"] == "escape":
        win.event_simulate(type="ESC", value="PRESS")
        win.event_simulate(type="ESC", value="RELEASE")
        st["step"] = "check"
        return 1.0
    if st["step"] == "check":
        msg = [m for _, m in ops.last_reports]
        report("escape_window_cancels_unchanged",
               counts(st["ob"]) == st["before"] and len(msg) == 1 and
               "cancelled after" in msg[0] and msg[0].endswith("nothing changed"),
               "%r -> %r %r" % (st["before"], counts(st["ob"]), msg))
        ops.last_reports.clear()
        with bpy.context.temp_override(window=win, area=area, region=region):
            r = bpy.ops.curve.conic_subdivide("INVOKE_DEFAULT", levels=5)
        report("escape_window_second_run_modal", r == {"RUNNING_MODAL"}, repr(r))
        st["step"] = "wait"
        return 0.25
    done = counts(st["ob"]) == [N << 5] * 3
    st["waits"] += 1
    if not done and st["waits"] < 240:
        return 0.25
    report("escape_window_finishes_without_escape", done,
           "%r after %d waits, reports %r" % (counts(st["ob"]), st["waits"], ops.last_reports))
    # undo: the finished run's step goes back to the three splines; the
    # cancelled run pushed none, so the next undo goes past their creation
    # (the step "three splines" is the one before both runs)
    with bpy.context.temp_override(window=win, area=area, region=region):
        r1 = bpy.ops.ed.undo()
        ob = bpy.data.objects.get("big")
        after1 = counts(ob) if ob is not None else None
        r2 = bpy.ops.ed.undo()
    report("escape_window_undo_restores_and_no_step_for_escape",
           after1 == st["before"] and bpy.data.objects.get("big") is None,
           "undo %r: %r; undo %r: object %s" % (r1, after1, r2,
                                                "still there" if bpy.data.objects.get("big")
                                                else "gone"))
    finish()
    return None


def tick_wrapper():
    try:
        return tick()
    except Exception as exc:  # noqa: BLE001 - report and quit
        report("escape_window_runs", False, "%s: %s" % (type(exc).__name__, exc))
        finish()


bpy.app.timers.register(tick_wrapper, first_interval=0.5)
