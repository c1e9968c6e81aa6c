# SPDX-License-Identifier: GPL-3.0-or-later
# Conica for Blender: conic-preserving curve subdivision and adaptive
# curve-to-polyline conversion, backed by libconica through the _conica
# C extension that ships inside this package.
bl_info = {
    "name": "Conica",
    "author": "Conica project",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Edit Mode: Segments menu / context menu; "
                "Object Mode: Object > Convert / context menu; F3 search",
    "description": "Conic Subdivide (circles stay circles), "
                   "Curve to Polyline (Adaptive) and Surface to Mesh (Adaptive)",
    "category": "Add Curve",
    "support": "COMMUNITY",
}

import importlib
import importlib.machinery
import os
import platform
import re
import sys

# The compiled module is built against CPython's stable ABI (abi3) at
# Python 3.11, so one binary serves every CPython from 3.11 on of the
# platform it was built for. Check what matters before importing it (the
# ABI tag, the Python version, the platform), so a mismatch gives one
# sentence, not a traceback.
MIN_PYTHON = (3, 11)
IMPORT_ERROR = None


def running_platform():
    """The running system in the words of blender_manifest.toml's
    `platforms` (linux-x64, windows-x64, macos-arm64, ...)."""
    system = {"linux": "linux", "darwin": "macos", "win32": "windows"}.get(
        sys.platform, sys.platform)
    machine = platform.machine().lower()
    machine = {"x86_64": "x64", "amd64": "x64", "aarch64": "arm64"}.get(machine, machine)
    return "%s-%s" % (system, machine)


def built_platforms(here):
    """The platforms the package's binary was built for, as its manifest
    lists them (a regular expression: tomllib is not in Python 3.10)."""
    try:
        with open(os.path.join(here, "blender_manifest.toml"), encoding="utf-8") as f:
            text = f.read()
    except OSError:
        return []
    m = re.search(r"^platforms\s*=\s*\[([^\]]*)\]", text, re.M)
    return re.findall(r'"([^"]+)"', m.group(1)) if m else []


def _binary_problem():
    here = os.path.dirname(os.path.abspath(__file__))
    found = sorted(f for f in os.listdir(here) if f.startswith("_conica.") and
                   (f.endswith(".so") or f.endswith(".pyd")))
    want = "_conica.pyd" if sys.platform == "win32" else "_conica.abi3.so"
    pyver = "%d.%d" % sys.version_info[:2]
    rebuild = "rebuild the zip there with `make blender-addon` (docs/blender.md)"
    if not found:
        return ("Conica: the compiled module %s is missing from %s; install the zip "
                "built by `make blender-addon`." % (want, here))
    if sys.implementation.name != "cpython" or sys.version_info[:2] < MIN_PYTHON:
        return ("Conica needs a Blender whose Python is CPython %d.%d or later "
                "(Blender 4.1 and newer, or Debian's 3.4), but this one runs %s %s."
                % (MIN_PYTHON + (sys.implementation.name, pyver)))
    plats = built_platforms(here)
    if plats and running_platform() not in plats:
        return ("Conica: this zip was built for %s but Blender runs on %s: %s."
                % (", ".join(plats), running_platform(), rebuild))
    if want not in found:
        return ("Conica: this zip holds %s, not the stable-ABI module %s that Python %s "
                "on %s loads: %s." % (", ".join(found), want, pyver, running_platform(),
                                      rebuild))
    abi3 = ".pyd" if sys.platform == "win32" else ".abi3.so"
    if abi3 not in importlib.machinery.EXTENSION_SUFFIXES:
        return ("Conica: this Python %s does not load stable-ABI (%s) modules: %s."
                % (pyver, abi3, rebuild))
    return None


IMPORT_ERROR = _binary_problem()
_conica = None
if IMPORT_ERROR is None:
    try:
        # not `from . import _conica`: the name already exists (None) here,
        # and from-import would then skip loading the submodule
        _conica = importlib.import_module("._conica", __package__)
    except ImportError as exc:  # wrong libc, missing LAPACK, ...
        IMPORT_ERROR = "Conica: the compiled module could not be loaded: %s" % exc
        _conica = None
    else:
        if getattr(_conica, "ABI", None) != "abi3" or \
                tuple(_conica.PY_MIN_VERSION) > tuple(sys.version_info[:2]):
            IMPORT_ERROR = ("Conica: the compiled module needs Python %d.%d or later "
                            "(stable ABI), Blender runs %d.%d." %
                            (tuple(getattr(_conica, "PY_MIN_VERSION", MIN_PYTHON)) +
                             tuple(sys.version_info[:2])))
            _conica = None

if IMPORT_ERROR is None:
    from . import operators
else:
    operators = None


_error_prefs = None


def _make_error_prefs():
    import bpy

    class ConicaBrokenPreferences(bpy.types.AddonPreferences):
        bl_idname = __package__

        def draw(self, context):
            col = self.layout.column()
            col.alert = True
            for line in IMPORT_ERROR.split(". "):
                col.label(text=line.strip(), icon="ERROR")

    return ConicaBrokenPreferences


def register():
    global _error_prefs
    if IMPORT_ERROR is not None:
        # Say it where the user looks (the console and the add-on's
        # preferences panel) instead of a traceback from inside the import;
        # no operator is registered.
        import bpy
        print(IMPORT_ERROR, file=sys.stderr)
        _error_prefs = _make_error_prefs()
        bpy.utils.register_class(_error_prefs)
        return
    operators.register()


def unregister():
    global _error_prefs
    if _error_prefs is not None:
        import bpy
        bpy.utils.unregister_class(_error_prefs)
        _error_prefs = None
    if operators is not None:
        operators.unregister()
