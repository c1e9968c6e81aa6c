# SPDX-License-Identifier: GPL-3.0-or-later
# Long runs of the operators in chunks, the way Blender's own long
# operators behave: invoke() (a menu, a shortcut, F3) of a run whose work
# is large starts a modal run that processes chunks (one spline each) for
# SLICE seconds per timer event, shows progress with
# window_manager.progress_*, and stops at Esc. Nothing is written before
# the last chunk, so a cancelled run leaves the scene as it was and, being
# CANCELLED, pushes no undo step. execute() (scripts, the redo panel, F9)
# runs the same chunks to the end in one go. A single chunk (one spline,
# one _conica call) cannot be interrupted: Esc is seen between chunks.
# Called by operators.py only; calls Blender's window manager only.
import time

# Seconds of chunks per timer event: Esc is seen, and the progress shown,
# at least this often between chunks.
SLICE = 0.05

# Estimated output points from which invoke() runs modally (about a
# quarter of a second of work); below it a run is over before Esc matters.
LONG_WORK = 250000

# Test hook (tests/blender: headless Blender has no events to send): an
# int n makes every run stop after n chunks exactly as Esc does. None in
# normal use.
simulated_escape = None


class Job:
    """A run's chunks: an iterator whose every step processes one of
    `total` units of work (progress counts them); nothing of the scene may
    change before the iterator is exhausted."""

    def __init__(self, chunks, total):
        self.chunks = chunks
        self.total = max(1, total)
        self.done = 0

    def step(self, seconds):
        """Process chunks for about `seconds` (at least one): True when all
        are done."""
        t_end = time.perf_counter() + seconds
        for _ in self.chunks:
            self.done += 1
            if self.escaped() or time.perf_counter() >= t_end:
                return False
        return True

    def escaped(self):
        """The test hook's simulated Esc after simulated_escape chunks."""
        return simulated_escape is not None and self.done >= simulated_escape


class ModalRun:
    """invoke/modal/execute of an operator whose class provides
    _start(context) -> (Job, estimated output points), or a result set
    when there is nothing to run, and _finish(context) -> result set (the
    writes and the reports), and _report(level, message)."""

    def execute(self, context):
        started = self._start(context)
        if isinstance(started, set):
            return started
        self._job, work = started
        return self._to_end(context, work >= LONG_WORK)

    def invoke(self, context, event):
        started = self._start(context)
        if isinstance(started, set):
            return started
        self._job, work = started
        if context.window is None or work < LONG_WORK or self._job.total < 2:
            return self._to_end(context, False)
        wm = context.window_manager
        wm.progress_begin(0, self._job.total)
        self._timer = wm.event_timer_add(0.001, window=context.window)
        wm.modal_handler_add(self)
        return {"RUNNING_MODAL"}

    def _to_end(self, context, show):
        """All chunks in one go (progress shown when `show`), then the writes."""
        wm = context.window_manager
        if show:
            wm.progress_begin(0, self._job.total)
        try:
            while True:
                done = self._job.step(SLICE)
                if self._job.escaped():
                    return self._escape(context)
                if done:
                    break
                if show:
                    wm.progress_update(self._job.done)
        finally:
            if show:
                wm.progress_end()
        return self._finish(context)

    def modal(self, context, event):
        if event.type == "ESC":
            return self._escape(context)
        if event.type != "TIMER":
            # the scene must not change under the run: no other input
            return {"RUNNING_MODAL"}
        done = self._job.step(SLICE)
        context.window_manager.progress_update(self._job.done)
        if not done:
            return {"RUNNING_MODAL"}
        self._stop_modal(context)
        return self._finish(context)

    def cancel(self, context):
        """Blender's own cancel (the window closes, a file is loaded)."""
        self._stop_modal(context)
        self._job = None

    def _stop_modal(self, context):
        timer = getattr(self, "_timer", None)
        if timer is not None:
            context.window_manager.event_timer_remove(timer)
            context.window_manager.progress_end()
            self._timer = None

    def _escape(self, context):
        """Esc: drop what was computed; the scene was not touched."""
        done, total = self._job.done, self._job.total
        self._stop_modal(context)
        self._job = None
        self._report("INFO", "%s: cancelled after %d of %d splines; nothing changed"
                     % (self.bl_label, done, total))
        return {"CANCELLED"}
