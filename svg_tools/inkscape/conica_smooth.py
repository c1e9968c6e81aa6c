#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Conica's Inkscape 1.x extension: Extensions > Modify Path > Conic Smooth...
and Flatten to Tolerance....

Inkscape runs this script with the current document in a file and the
selected objects as --id arguments. The script hands the document, unchanged,
to Conica's `svgsmooth` with `--select` of those ids (no --select when
nothing is selected: the whole document), and gives Inkscape back exactly
what svgsmooth wrote. The geometry is svgsmooth's: conic-preserving
subdivision (Bugel, Romani and Kosinka, "Conic-preserving subdivision") or
the guaranteed adaptive plotter (Dahl, "Adaptive plotting of splines").

svgsmooth is looked for, in this order: the extension's "svgsmooth program"
field, the environment variable CONICA_SVGSMOOTH, the extension's own
directory, the program named in svgsmooth.path beside this script (written
by `make install`: BINDIR/svgsmooth), PREFIX/bin when the extension is
installed under PREFIX/share/inkscape/extensions, then PATH.

When it cannot run, the extension says why in Inkscape's one error dialog.
In a `inkscape --batch-process` run no one would close that dialog and
Inkscape would wait for ever: there the message goes to Inkscape's own
standard error and the document is left unchanged.
"""
import os
import shutil
import subprocess
import sys

import inkex

SCRIPT_DIR = os.path.dirname(os.path.abspath(__file__))


def find_svgsmooth(preference):
    """The svgsmooth program to run, or raise AbortExtension naming where
    it was looked for."""
    tried = []
    candidates = []
    if preference:
        candidates.append(("the svgsmooth program field", os.path.expanduser(preference)))
    if os.environ.get("CONICA_SVGSMOOTH"):
        candidates.append(("CONICA_SVGSMOOTH", os.environ["CONICA_SVGSMOOTH"]))
    candidates.append(("the extension directory", os.path.join(SCRIPT_DIR, "svgsmooth")))
    try:
        with open(os.path.join(SCRIPT_DIR, "svgsmooth.path"), encoding="utf-8") as f:
            candidates.append(("svgsmooth.path", f.read().strip()))
    except OSError:
        pass
    # PREFIX/share/inkscape/extensions/conica -> PREFIX/bin
    for up in (3, 4):
        prefix = os.path.normpath(os.path.join(SCRIPT_DIR, *([os.pardir] * up)))
        candidates.append(("the install prefix", os.path.join(prefix, "bin", "svgsmooth")))
    for where, path in candidates:
        tried.append(f"{path} ({where})")
        if os.path.isfile(path) and os.access(path, os.X_OK):
            return path
        if where not in ("the extension directory", "svgsmooth.path", "the install prefix"):
            # an explicit choice that does not work is an error, not a hint
            raise inkex.AbortExtension(
                f"Conica: svgsmooth not found at {path} ({where}): no executable file there."
            )
    found = shutil.which("svgsmooth")
    if found:
        return found
    raise inkex.AbortExtension(
        "Conica: cannot find the svgsmooth program. Install Conica (make install) so "
        "that svgsmooth is on PATH, or enter its full path in the extension's "
        "'svgsmooth program' field. Looked at: " + "; ".join(tried) + "; PATH"
    )


def batch_stderr():
    """Inkscape's own standard error when it runs with --batch-process (a
    dialog there would wait for a click that never comes), else None.
    Inkscape spawns the script detached (its parent is init), so Inkscape is
    found as the process that holds the other end of our stderr pipe."""
    try:
        mine = os.readlink("/proc/self/fd/2")
    except OSError:
        return None
    if not mine.startswith("pipe:"):
        return None
    me = str(os.getpid())
    for pid in os.listdir("/proc"):
        if not pid.isdigit() or pid == me:
            continue
        try:
            holds = any(os.readlink(f"/proc/{pid}/fd/{fd}") == mine
                        for fd in os.listdir(f"/proc/{pid}/fd"))
            if not holds:
                continue
            with open(f"/proc/{pid}/cmdline", "rb") as f:
                args = f.read().split(b"\0")
        except OSError:
            continue
        if b"--batch-process" in args:
            return f"/proc/{pid}/fd/2"
    return None


def to_batch_log(text):
    """In a --batch-process run, write text to Inkscape's standard error and
    return True; otherwise (a dialog can show it) return False."""
    where = batch_stderr()
    if where is None:
        return False
    try:
        with open(where, "a", encoding="utf-8") as f:
            f.write(text + "\n")
    except OSError:
        pass
    return True


def has_flag(exe, flag):
    """Does `exe --help` list flag (an svgsmooth from before the flag existed
    would refuse it as unknown)."""
    try:
        res = subprocess.run([exe, "--help"], capture_output=True, timeout=30, check=False)
    except OSError as err:
        raise inkex.AbortExtension(f"Conica: cannot run {exe}: {err}") from err
    return any(
        line.lstrip().startswith(flag + " ") or line.lstrip() == flag
        for line in res.stdout.decode("utf-8", "replace").splitlines()
    )


class ConicaSmooth(inkex.EffectExtension):
    """Run svgsmooth on the document with --select of the selected ids."""

    def __init__(self):
        super().__init__()
        self.result = None
        self.input_bytes = None

    def add_arguments(self, pars):
        pars.add_argument("--tab", default="")
        pars.add_argument("--mode", choices=("smooth", "flatten"), default="smooth")
        pars.add_argument("--method", choices=("levels", "tolerance"), default="levels")
        pars.add_argument("--levels", type=int, default=4)  # svgsmooth's default
        pars.add_argument("--tolerance", type=float, default=0.1)
        pars.add_argument("--corner_angle", type=float, default=40.0)
        pars.add_argument("--simplify", type=float, default=0.0)
        pars.add_argument("--lines_as_samples", type=inkex.Boolean, default=False)
        pars.add_argument("--convert_shapes", type=inkex.Boolean, default=False)
        pars.add_argument("--svgsmooth", default="")

    def svgsmooth_args(self, exe):
        """The options for svgsmooth (the program and the input not included)."""
        opt = self.options
        args = []
        if opt.mode == "flatten":
            if not opt.tolerance > 0:
                raise inkex.AbortExtension("Conica: the tolerance must be greater than 0.")
            args += ["--flatten", "--tolerance", repr(opt.tolerance)]
        else:
            if opt.method == "tolerance":
                if not opt.tolerance > 0:
                    raise inkex.AbortExtension("Conica: the tolerance must be greater than 0.")
                args += ["--tolerance", repr(opt.tolerance)]
            else:
                args += ["--levels", str(opt.levels)]
            args += ["--corner-angle", repr(opt.corner_angle)]
            if opt.lines_as_samples:
                args.append("--lines-as-samples")
            if opt.simplify > 0:
                if not has_flag(exe, "--simplify"):
                    raise inkex.AbortExtension(
                        f"Conica: {exe} has no --simplify option (an older Conica); set "
                        "Simplify to 0 or install a Conica whose svgsmooth --help lists "
                        "--simplify."
                    )
                args += ["--simplify", repr(opt.simplify)]
        if opt.convert_shapes:
            args.append("--convert-shapes")
        ids = [i for i in opt.ids if i]
        for i in ids:
            if "," in i:
                raise inkex.AbortExtension(
                    f"Conica: the id '{i}' contains a comma, which svgsmooth --select cannot "
                    "name; rename the object (Object > Object Properties)."
                )
        if ids:
            args += ["--select", ",".join(ids)]
        return args

    def effect(self):
        try:
            self.smooth()
        except inkex.AbortExtension as err:
            if not to_batch_log(str(err)):
                raise  # Inkscape shows it in one dialog
            self.result = None  # the document unchanged, no dialog

    def smooth(self):
        """Run svgsmooth; the result in self.result, or AbortExtension."""
        exe = find_svgsmooth(self.options.svgsmooth)
        args = self.svgsmooth_args(exe)
        # the document exactly as Inkscape wrote it (not re-serialised)
        if isinstance(self.options.input_file, str):
            with open(self.options.input_file, "rb") as f:
                self.input_bytes = f.read()
        else:
            self.input_bytes = self.svg.tostring()
        try:
            res = subprocess.run(
                [exe] + args + ["-"], input=self.input_bytes, capture_output=True, check=False
            )
        except OSError as err:
            raise inkex.AbortExtension(f"Conica: cannot run {exe}: {err}") from err
        messages = res.stderr.decode("utf-8", "replace").strip()
        if res.returncode != 0:
            raise inkex.AbortExtension(
                messages or f"Conica: {exe} failed (exit status {res.returncode})."
            )
        if messages and not to_batch_log(messages):
            self.msg(messages)  # svgsmooth's warnings
        self.result = res.stdout
        self.document = res.stdout

    def has_changed(self, ret):
        return self.result is not None and self.result != self.input_bytes


if __name__ == "__main__":
    ConicaSmooth().run()
