"""The live preview: while a weight slider moves, the reference armature shows the re-styled
result without the UI waiting for it.

Reading the takes out of Blender happens once per set of takes, on Blender's thread, as bpy
requires; so does the module's preparation of them (`mostyle.prepare`: alignment and
decomposition), on the worker thread. A weight change runs only the prepared mix there; a newer
request replaces one not yet started. A timer on Blender's thread takes up the newest result.

No action is written or changed while previewing. The reference armature's action is taken off
it (and put back when the preview stops), and its bones are posed from the result held in memory
for the frame shown: when a result comes, and on every frame change. That is one frame's work,
where writing an action is every frame's keys. The pose is the one Style Action's action plays
at that frame."""
import collections
import threading
import time
import traceback

import bpy
import numpy as np

from . import styling, takes as take_io

# How often the timer looks for a new result: a result waits for it at most this long.
_POLL_S = 0.005
# How long the weights stay still before the solved result replaces the quick one: a slider being
# dragged moves again sooner, and would otherwise wait for the solve.
_SETTLE_S = 0.15

# A request's result: its id, the result's arrays (take_io.held_take; None: nothing to show) or
# the error sentence, when it was asked for (perf_counter seconds), how long the module's call
# and reading its arrays took, and whether it is solved.
Outcome = collections.namedtuple("Outcome", "request take error asked seconds solved")


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
        self.result = None  # the newest Outcome
        self.shown = None   # the Outcome on the armature
        self.held = None    # its arrays
        self.rig = None     # the armature as take_io.armature_rig reads it, once
        self.error = None
        self.next_id = 0
        self.stopping = False
        self.thread = threading.Thread(target=self._work, name="mostyle preview", daemon=True)
        self.thread.start()
        data = ref_obj.animation_data_create()
        self.restore = data.action
        self.restore_pose = _pose_values(ref_obj)
        styling.protect(ref_action)
        # The action would pose the bones back over the preview's pose at every evaluation.
        data.action = None

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
                called = time.perf_counter()
                try:
                    take, error = self._style(weights, parts, strength, solve), None
                    # Read out here, so that Blender's thread only poses.
                    take = take_io.held_take(take) if take is not None else None
                except Exception as e:
                    traceback.print_exc()
                    take, error = None, styling.one_line(e)
                outcome = Outcome(rid, take, error, asked, time.perf_counter() - called, solve)
                with self.lock:
                    self.result = outcome
                    if error is not None or self.pending is not None or self.stopping or take is None:
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

    def take_up(self, scene):
        """Shows the newest result, if there is one not shown yet, on the armature at `scene`'s
        frame (its error sentence, if it failed, in self.error). Whether there was one."""
        with self.lock:
            outcome = self.result
        if outcome is None or outcome is self.shown:
            return False
        self.shown = outcome
        self.error = outcome.error
        if outcome.take is not None:
            self.held = outcome.take
            self.pose(scene)
            self.last_ms = (time.perf_counter() - outcome.asked) * 1000.0
        return True

    def pose(self, scene):
        """Poses the armature as the result shown at `scene`'s current frame."""
        if self.held is None:
            return
        if self.rig is None:
            self.rig = take_io.armature_rig(self.obj, self.held.joint_names)
        frame = take_io.take_index_at(self.held, scene.frame_current + scene.frame_subframe,
                                      self.source.frame_range[0], self.fps)
        take_io.pose_take_frame(self.held, self.obj, frame, self.rig)

    def busy(self):
        """Whether the newest request's first result is still to come."""
        with self.lock:
            return self.pending is not None or (self.result is None or self.result.request != self.next_id)

    def settled(self):
        """Whether the newest request's last result has come: solved, failed or nothing to show."""
        with self.lock:
            r = self.result
            return self.pending is None and r is not None and r.request == self.next_id and (
                r.solved or r.error is not None or r.take is None)

    def stop(self):
        with self.lock:
            self.stopping = True
            self.lock.notify()
        self.thread.join(timeout=5)
        try:
            data = self.obj.animation_data
        except ReferenceError:  # the armature was deleted, or an undo replaced it
            return
        _set_pose_values(self.obj, self.restore_pose)
        if data is not None and data.action is None:
            data.action = self.restore
            take_io.play_first_slot(data)


# A pose bone's channels the preview sets, with their sizes.
_POSE_CHANNELS = (("location", 3), ("rotation_quaternion", 4), ("rotation_euler", 3), ("rotation_axis_angle", 4))


def _pose_values(obj):
    """The armature's pose bones' own values of _POSE_CHANNELS, as Blender keeps them (float32)."""
    bones = obj.pose.bones
    values = {}
    for prop, size in _POSE_CHANNELS:
        values[prop] = np.empty(len(bones) * size, dtype=np.float32)
        bones.foreach_get(prop, values[prop])
    return values


def _set_pose_values(obj, values):
    for prop, v in values.items():
        obj.pose.bones.foreach_set(prop, v)
    obj.update_tag()


_session = None
_status = {"error": None}


def session():
    return _session


def status():
    return _status


def start(settings, obj):
    """A new session for the panel's takes on armature `obj` (replacing any other)."""
    stop()
    refs, neutral = settings_refs(settings, obj)
    run(Session(styling.module(), refs[0][0], refs[0][1], refs, neutral, settings.mode,
                take_io.scene_fps(bpy.context.scene)))
    request(settings)


def run(session):
    """Makes `session` the preview: the timer takes its results up, frame changes pose its
    armature."""
    global _session
    stop()
    _session = session
    _status["error"] = None
    for handlers, handler in _handlers():
        if handler not in handlers:
            handlers.append(handler)
    if not bpy.app.timers.is_registered(_tick):
        bpy.app.timers.register(_tick, first_interval=_POLL_S)


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
    for handlers, handler in _handlers():
        if handler in handlers:
            handlers.remove(handler)
    if bpy.app.timers.is_registered(_tick):
        bpy.app.timers.unregister(_tick)


def own_action(obj):
    """The action armature `obj` plays, or played before the preview took it off."""
    if _session is not None and _session.obj == obj:
        return _session.restore
    return obj.animation_data.action if obj.animation_data else None


def _handlers():
    """Blender's handler lists the preview is on while it runs, with its function for each: the
    frame shown changes, or another file is opened (the session's armature goes away)."""
    return ((bpy.app.handlers.frame_change_pre, _frame_changed), (bpy.app.handlers.load_pre, _file_closing))


def _frame_changed(scene, *_):
    try:
        if _session is not None and _session.obj.name in scene.objects:
            _session.pose(scene)
    except Exception:
        traceback.print_exc()


def _file_closing(*_):
    stop()


def _tick():
    if _session is None:
        return None
    try:
        shown = _session.take_up(bpy.context.scene)
        error = _session.error
    except Exception as e:
        traceback.print_exc()
        shown, error = True, styling.one_line(e)
    if shown:
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
        action = t.action or own_action(t.object)
        if action is None:
            raise ValueError("take '%s' has no action: pick one" % t.object.name)
        refs.append((t.object, action))
    if not refs:
        raise ValueError("no takes: add the armature's action and the takes to mix with it")
    neutral = None
    if settings.mode == 'TRANSFER' and settings.neutral_object is not None:
        action = settings.neutral_action or own_action(settings.neutral_object)
        if action is None:
            raise ValueError("neutral '%s' has no action: pick one" % settings.neutral_object.name)
        neutral = (settings.neutral_object, action)
    return refs, neutral
