"""The live preview: while a weight slider moves, the reference armature plays the re-styled
result without the UI waiting for it.

Reading the takes out of Blender (every frame played through the depsgraph) happens once per
set of takes, on Blender's thread, as bpy requires. The module's call runs on a worker thread
with those cached Takes; a newer request replaces one not yet started. A timer on Blender's
thread takes up the newest result and writes it into the preview action.

The module's whole calls (mix, transfer) align and decompose the takes on every call. A module
that offers a prepared set of takes, `mostyle.prepare(takes, ...)` with a cheap `.mix(weights,
part_weights)` and `.transfer(strength, ...)`, is used when present, so that a weight change
runs only the mix."""
import threading
import time
import traceback

import bpy

from . import styling, takes as take_io

_POLL_S = 0.02
# How long the weights stay still before the solved result replaces the quick one: a slider being
# dragged moves again sooner, and would otherwise wait for the solve.
_SETTLE_S = 0.15


class Session:
    """One set of takes styled over and over with new weights."""

    def __init__(self, mostyle, ref_obj, ref_action, refs, neutral_ref, mode, fps):
        self.mostyle, self.mode, self.fps = mostyle, mode, fps
        self.obj, self.source = ref_obj, ref_action
        self.key = (tuple((o.name, a.name) for o, a in refs), neutral_ref and (neutral_ref[0].name, neutral_ref[1].name),
                    mode, fps)
        self.takes = [take_io.armature_take(mostyle, o, a) for o, a in refs]
        self.neutral = take_io.armature_take(mostyle, *neutral_ref) if neutral_ref else None
        self.prepared = None
        self.lock = threading.Condition()
        self.pending = None
        self.result = None  # (request id, Take or None, error sentence or None, seconds)
        self.shown = -1
        self.shown_outcome = None
        self.next_id = 0
        self.stopping = False
        self.thread = threading.Thread(target=self._work, name="mostyle preview", daemon=True)
        self.thread.start()
        name = ref_action.name + "_preview"
        self.action = bpy.data.actions.get(name) or bpy.data.actions.new(name)
        self.action.use_fake_user = False
        data = ref_obj.animation_data_create()
        self.restore = data.action
        styling.protect(ref_action)

    def request(self, weights, part_weights, strength):
        with self.lock:
            self.next_id += 1
            self.pending = (self.next_id, weights, part_weights, strength, time.perf_counter())
            self.lock.notify()

    def _work(self):
        while True:
            with self.lock:
                while self.pending is None and not self.stopping:
                    self.lock.wait()
                if self.stopping:
                    return
                request, self.pending = self.pending, None
            rid, weights, parts, strength, asked = request
            # First the result's positions on the reference's own rotations (no solve), shown at
            # once; then, unless the weights moved on meanwhile, the solved result in its place.
            for solve in (False, True):
                if solve:
                    with self.lock:
                        self.lock.wait_for(lambda: self.pending is not None or self.stopping, timeout=_SETTLE_S)
                        if self.pending is not None or self.stopping:
                            break
                try:
                    take = self._style(weights, parts, strength, solve)
                    outcome = (rid, take, None, asked)
                except Exception as e:
                    traceback.print_exc()
                    outcome = (rid, None, str(e).strip().splitlines()[0] if str(e).strip() else type(e).__name__,
                               asked)
                with self.lock:
                    self.result = outcome
                    if outcome[2] is not None or self.pending is not None or self.stopping or take is None:
                        break

    def _style(self, weights, parts, strength, solve):
        prepare = getattr(self.mostyle, "prepare", None)
        if prepare is not None:
            if self.prepared is None:
                self.prepared = prepare(self.takes, neutral=self.neutral, fps=self.fps)
            if self.mode == 'MIX':
                return self.prepared.mix(weights=weights, part_weights=parts, solve=solve)
            part_strength = {p: [strength * w for w in ws[1:]] for p, ws in parts.items()} if parts else None
            return self.prepared.transfer(strength=[strength * w for w in weights[1:]], part_strength=part_strength,
                                          solve=solve)
        if not solve:
            return None
        return styling.style(self.mostyle, self.mode, self.takes, weights, parts, self.neutral, strength, self.fps)

    def take_up(self):
        """Writes the newest result into the preview action; its error sentence, or None."""
        with self.lock:
            outcome = self.result
        if outcome is None or outcome is self.shown_outcome:
            return None
        rid, take, error, asked = outcome
        self.shown, self.shown_outcome = rid, outcome
        if error is not None:
            return error
        take_io.write_take_action(take, self.obj, self.action, self.source.frame_range[0], self.fps)
        if self.obj.animation_data.action is not self.action:
            self.obj.animation_data.action = self.action
        self.action.update_tag()
        self.obj.update_tag(refresh={'TIME'})
        self.last_ms = (time.perf_counter() - asked) * 1000.0
        return None

    def busy(self):
        with self.lock:
            return self.pending is not None or (self.result is None or self.result[0] != self.next_id)

    def stop(self):
        with self.lock:
            self.stopping = True
            self.lock.notify()
        self.thread.join(timeout=5)
        data = self.obj.animation_data
        if data is not None and data.action is self.action:
            data.action = self.restore


_session = None
_status = {"error": None}


def session():
    return _session


def status():
    return _status


def start(settings, obj):
    """A new session for the panel's takes on armature `obj` (replacing any other)."""
    global _session
    stop()
    refs, neutral = settings_refs(settings, obj)
    mostyle = styling.module()
    _session = Session(mostyle, refs[0][0], refs[0][1], refs, neutral, settings.mode,
                       take_io.scene_fps(bpy.context.scene))
    _status["error"] = None
    if not bpy.app.timers.is_registered(_tick):
        bpy.app.timers.register(_tick, first_interval=_POLL_S)
    request(settings)


def request(settings):
    if _session is None:
        return
    weights = [t.weight for t in settings.takes]
    parts = None
    if settings.use_parts:
        parts = {p: [getattr(t, p) for t in settings.takes] for p in styling.PARTS}
    _session.request(weights, parts, settings.strength)


def stop():
    global _session
    if _session is not None:
        _session.stop()
        _session = None
    if bpy.app.timers.is_registered(_tick):
        bpy.app.timers.unregister(_tick)


def _tick():
    if _session is None:
        return None
    try:
        error = _session.take_up()
    except Exception as e:
        traceback.print_exc()
        error = str(e).strip().splitlines()[0] if str(e).strip() else type(e).__name__
    if error is not None or _session.shown >= 0:
        _status["error"] = error
        for window in bpy.context.window_manager.windows:
            for area in window.screen.areas:
                if area.type == 'VIEW_3D':
                    area.tag_redraw()
    return _POLL_S


def settings_refs(settings, obj):
    """The panel's takes as (object, action) pairs, and its neutral (or None)."""
    refs = []
    for t in settings.takes:
        if t.object is None or t.object.type != 'ARMATURE':
            raise ValueError("a take has no armature: pick one or remove the take")
        action = t.action or (t.object.animation_data.action if t.object.animation_data else None)
        if action is None:
            raise ValueError("take '%s' has no action: pick one" % t.object.name)
        refs.append((t.object, action))
    if not refs:
        raise ValueError("no takes: add the armature's action and the takes to mix with it")
    neutral = None
    if settings.mode == 'TRANSFER' and settings.neutral_object is not None:
        action = settings.neutral_action or (settings.neutral_object.animation_data.action
                                             if settings.neutral_object.animation_data else None)
        if action is None:
            raise ValueError("neutral '%s' has no action: pick one" % settings.neutral_object.name)
        neutral = (settings.neutral_object, action)
    return refs, neutral
