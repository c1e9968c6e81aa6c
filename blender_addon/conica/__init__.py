# SPDX-License-Identifier: GPL-3.0-or-later
# Conica for Blender: conic-preserving curve subdivision and adaptive
# curve-to-polyline conversion, backed by libconica through the _conica
# C extension that ships inside this package.
bl_info = {
    "name": "Conica",
    "author": "Conica project",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Edit Mode: Curve > Segments / context menu; "
                "Object Mode: Object > Convert / context menu; F3 search",
    "description": "Conic Subdivide (circles stay circles) and "
                   "Curve to Polyline (Adaptive)",
    "category": "Add Curve",
    "support": "COMMUNITY",
}

import importlib
import os
import platform
import sys
import sysconfig

# The add-on works only with the binary built for the running Python. Check
# before importing it, so a mismatch gives a sentence, not a traceback.
_EXPECTED_SUFFIX = sysconfig.get_config_var("EXT_SUFFIX") or ""
IMPORT_ERROR = None


def _binary_problem():
    here = os.path.dirname(os.path.abspath(__file__))
    found = sorted(f for f in os.listdir(here) if f.startswith("_conica") and
                   (f.endswith(".so") or f.endswith(".pyd")))
    running = "Python %d.%d on %s-%s" % (sys.version_info[0], sys.version_info[1],
                                         sys.platform, platform.machine())
    if not found:
        return ("Conica: the compiled module _conica is missing from %s; "
                "install the zip built by `make blender-addon`." % here)
    if "_conica" + _EXPECTED_SUFFIX not in found:
        return ("Conica: this add-on was built for %s, but Blender runs %s "
                "(it needs _conica%s). Rebuild it with that Python's "
                "python3-config (`make blender-addon`)."
                % (", ".join(f[len("_conica"):] for f in found), running,
                   _EXPECTED_SUFFIX))
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
        if tuple(_conica.PY_VERSION) != tuple(sys.version_info[:2]):
            IMPORT_ERROR = ("Conica: the compiled module was built for Python %d.%d, "
                            "Blender runs %d.%d." % (tuple(_conica.PY_VERSION) +
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
