"""MJCF models in MuJoCo Warp (MJWarp), MuJoCo written in NVIDIA Warp: float32, runs batched as worlds.

An MJCF file is read as for MuJoCo (:mod:`pitheorem.engines.fileformats.mjcf`
reads it: the same parameters, scaled copies and saved files), compiled by
MuJoCo's compiler, and put on a Warp device with ``mujoco_warp.put_model``:
a GPU where Warp finds one, else the CPU (``device="cpu"`` asks for it).
MJWarp computes in float32 only.  What it does not support (the PGS
solver, some sensors, flags, plugins, the dense Jacobian beyond 60
degrees of freedom) is refused by name when the file is loaded.

The runs of a verification (the original, its scaled copy, the
yardstick's twins) go to :meth:`WarpRunner.run_many`, which runs them as
the *worlds* of one model: MJWarp reads each of its per-world arrays
(a leading dimension ``"*"`` in ``mujoco_warp.Model``: masses, sizes,
gravity, solver parameters, ...) at ``world % len``, so the models' own
values are stacked there, one row per world.  Models whose other arrays
differ cannot share a call: each group of equal shared arrays is one.
A twin moves every number MJWarp holds by one float32 unit in the last
place.

The first run of a model compiles MJWarp's kernels for its sizes (on the
CPU, minutes for the first model, seconds for the next); Warp keeps them
in its kernel cache (``warp.config.kernel_cache_dir``, set before Warp
initialises), and a later process loads them in seconds.

MJWarp runs open loop only here: a closed-loop controller runs in
``"mujoco"``.  Its own constants are in the catalogue
(``engines.hidden_constants("warp")``), its thresholds are MuJoCo's and
float32's range (``engines.thresholds("warp")``).

Examples
--------
>>> from pitheorem.engines.registry import registered
>>> line = registered("warp")
>>> line.packages, line.extra, line.base, line.precision
(('mujoco', 'warp', 'mujoco_warp'), 'warp', 'mujoco', 'float32')

With MuJoCo Warp installed (``pip install "pitheorem[warp]"``)::

    model = engines.load("pendulum.xml", engine="warp", device="cpu")
    rep = engines.verify(model, scaling, s=4, duration=0.5)  # rep.exact: bit for bit
"""

from __future__ import annotations

import copy
import dataclasses

import numpy as np

from ...errors import EngineModelError, InvalidRequestError
from ..enginemodel import EngineModel
from ..fileformats.mjcf import read_mjcf
from ..packages import engine_module
from .mujoco import MujocoCompiledRunner, MujocoRunner, field_holder, urdf_runner, write_field

__all__ = ["PRECISION", "WarpRunner", "load_urdf", "load_warp"]

#: the one precision MJWarp computes in
PRECISION = "float32"

#: the prefix of MuJoCo's enum names in MJWarp's refusals, and the element each names
_CULPRITS = (
    ("mjSOL_", "option solver"),
    ("mjINT_", "option integrator"),
    ("mjCONE_", "option cone"),
    ("mjDSBL_", "option flag"),
    ("mjENBL_", "option flag"),
    ("mjGEOM_", "geom"),
    ("mjSENS_", "sensor"),
    ("mjTRN_", "actuator"),
    ("mjDYN_", "actuator"),
    ("mjGAIN_", "actuator"),
    ("mjBIAS_", "actuator"),
    ("mjEQ_", "equality"),
    ("mjWRAP_", "tendon"),
    ("plugin", "plugin"),
    ("Flex", "flex"),
    ("flex", "flex"),
    ("noslip", "option noslip_iterations"),
    ("Dense", "option jacobian"),
)


def _warp():
    """Warp and MJWarp, imported (the missing package named, with the extra that installs it)."""
    mjw = engine_module("warp")
    import warp

    return warp, mjw


class WarpRunner(MujocoCompiledRunner):
    """An MJCF model in MJWarp: MuJoCo's reading of the file, and its ``mujoco_warp.Model`` on a Warp device.

    What MuJoCo's reading gives (the table, copies, files, sizes) is
    :class:`~pitheorem.engines.runners.mujoco.MujocoCompiledRunner`'s.

    Parameters
    ----------
    mjcf : MujocoRunner
        The file as MuJoCo reads and compiles it.
    device : str
        The Warp device (``"cpu"``, ``"cuda:0"``).
    moved : dict, optional
        Arrays that replace the compiled model's (a twin's), by field.

    Examples
    --------
    >>> from pitheorem.engines.protocols import Runner
    >>> from pitheorem.engines.runners.warp import WarpRunner
    >>> all(hasattr(WarpRunner, name) for name in Runner.__dict__ if not name.startswith("_"))
    True
    """

    engine_label = "MuJoCo Warp"
    precision = PRECISION

    def __init__(self, mjcf: MujocoRunner, device: str, moved: dict | None = None):
        self.mjcf = mjcf
        self.device = device
        self._moved = dict(moved or {})
        self._device_model, self._start_mjmodel = _put(mjcf, device, self._moved)

    def _rebuilt(self, mjcf: MujocoRunner, *, same_numbers: bool) -> WarpRunner:
        return WarpRunner(mjcf, self.device, self._moved if same_numbers else None)

    def settings(self) -> dict:
        return {"precision": PRECISION, "device": self.device}

    # -- what MJWarp holds ---------------------------------------------------------------------

    def stored_numbers(self) -> dict[str, np.ndarray]:
        """Every floating-point array MJWarp holds for the model, by field (``opt.x`` for options), in float32.

        A per-world array is given for its one world, laid out as MuJoCo's.
        """
        return {field: _one_world(array, batched) for field, array, batched in _float_arrays(self._device_model)}

    def twin(self, seed: int) -> WarpRunner:
        """A copy whose every number in MJWarp's arrays is one float32 unit in its last place off (signs from `seed`).

        Zeros stay zero and the time step stays.
        """
        rng = np.random.default_rng(seed)
        moved = {}
        for field, array, _batched in _float_arrays(self._device_model):
            if field == "opt.timestep":
                continue
            value = array.numpy()
            toward = np.where(rng.random(value.shape) < 0.5, np.inf, -np.inf).astype(value.dtype)
            moved[field] = np.where(value == 0, value, np.nextafter(value, toward))
        return WarpRunner(self.mjcf, self.device, moved)

    # -- running ------------------------------------------------------------------------------

    def run_many(self, n_steps: int, jobs) -> list[np.ndarray]:
        """The runs of ``(runner, controls, nudge, initial)`` jobs as the worlds of one call per group.

        The models must have the same sizes (a model, its scaled copies and
        its twins do).  Their per-world arrays are stacked, one row per
        world; jobs whose shared arrays differ run in calls of their own.
        Each world starts from its own model's data (:func:`_data`), so that
        it runs bit for bit as it runs alone.
        ``controls`` is None, rows of inputs (one per step) or
        ``t -> inputs``; ``initial`` is None or a first row (qpos, qvel, act).
        """
        wp, mjw = _warp()
        reference = jobs[0][0]
        models = [_aligned(runner, reference) for runner, *_ in jobs]
        groups: dict = {}
        for i, model in enumerate(models):
            groups.setdefault(_shared_key(model), []).append(i)
        out: list = [None] * len(jobs)
        with wp.ScopedDevice(self.device):
            for members in groups.values():
                batch = _worlds([models[i] for i in members], self.device)
                m = jobs[members[0]][0].mjcf.mjmodel  # the sizes, the same for all
                starts = np.stack([_initial(jobs[i][0], jobs[i][2], jobs[i][3]) for i in members])
                rows = np.stack([_control_rows(jobs[i][1], n_steps, m.nu, jobs[i][0].timestep()) for i in members])
                data = _data([jobs[i][0] for i in members])
                data.qpos.assign(starts[:, : m.nq])
                data.qvel.assign(starts[:, m.nq : m.nq + m.nv])
                if m.na:
                    data.act.assign(starts[:, m.nq + m.nv :])
                if m.nmocap:  # each world's mocap bodies where its own model puts them, as mj_resetData does
                    data.mocap_pos.assign(np.stack([_mocap(jobs[i][0]._start_mjmodel, "body_pos") for i in members]))
                    data.mocap_quat.assign(np.stack([_mocap(jobs[i][0]._start_mjmodel, "body_quat") for i in members]))
                runs = np.empty((len(members), n_steps + 1, m.nq + m.nv + m.na), dtype=np.float32)
                runs[:, 0] = starts
                for step in range(n_steps):
                    if m.nu:
                        data.ctrl.assign(rows[:, step])
                    mjw.step(batch, data)
                    runs[:, step + 1, : m.nq] = data.qpos.numpy()
                    runs[:, step + 1, m.nq : m.nq + m.nv] = data.qvel.numpy()
                    if m.na:
                        runs[:, step + 1, m.nq + m.nv :] = data.act.numpy()
                for k, i in enumerate(members):
                    out[i] = runs[k].astype(float)
        return out


def _data(runners: list):
    """MJWarp's data for worlds of these runners, each world's first state as its own model's alone.

    ``mujoco_warp.make_data`` fills every world from the one MuJoCo model
    it is given, and some of what it fills the steps never recompute:
    the poses of the geoms fixed to the world (``geom_xpos``,
    ``geom_xmat``, from ``mj_kinematics`` at ``qpos0``; MJWarp's step
    skips them).  A scaled copy moves them, and so does a twin's one
    float32 unit, so each world's rows are taken from the data of its
    own model (a twin's with its moved numbers written in), made for one
    world: what a run of it alone starts from.
    """
    wp, mjw = _warp()
    mjmodels = [runner._start_mjmodel for runner in runners]
    nworld = len(mjmodels)
    data = mjw.make_data(mjmodels[0], nworld=nworld)
    distinct = {id(mjm): mjm for mjm in mjmodels}
    if len(distinct) == 1:
        return data
    alone = {key: mjw.make_data(mjm, nworld=1) for key, mjm in distinct.items()}
    for f in dataclasses.fields(data):
        array = getattr(data, f.name)
        if not isinstance(array, wp.array) or not array.ndim or array.shape[0] != nworld:
            continue
        rows = [getattr(alone[id(mjm)], f.name) for mjm in mjmodels]
        if any(not isinstance(row, wp.array) or row.shape != (1, *array.shape[1:]) for row in rows):
            continue  # not one row per world
        values = [row.numpy() for row in rows]
        if not all(np.array_equal(v, values[0]) for v in values[1:]):
            array.assign(np.concatenate(values))
    return data


def _mocap(mjmodel, field: str) -> np.ndarray:
    """The rows of a body field (``body_pos``, ``body_quat``) of the model's mocap bodies, in mocap order."""
    bodies = np.flatnonzero(np.asarray(mjmodel.body_mocapid) >= 0)
    order = np.asarray(mjmodel.body_mocapid)[bodies]
    return np.asarray(getattr(mjmodel, field))[bodies[np.argsort(order)]].astype(np.float32)


def _put(mjcf: MujocoRunner, device: str, moved: dict):
    """The ``mujoco_warp.Model`` of a MuJoCo model on `device`, `moved` arrays replaced, and the MuJoCo model its
    worlds start from (:func:`_start_mjmodel`); refusals by name."""
    wp, mjw = _warp()
    with wp.ScopedDevice(device):
        try:
            model = mjw.put_model(mjcf.mjmodel)
        except (NotImplementedError, ValueError) as err:
            reason = str(err).strip().rstrip(".") or type(err).__name__
            raise EngineModelError(
                mjcf.path, _unsupported(reason), f"MuJoCo Warp does not support {reason}; run the file in 'mujoco'"
            ) from None
        held = {}
        for field, value in moved.items():
            holder, name = field_holder(model, field)
            old = getattr(holder, name)
            held[field] = old.numpy()
            setattr(holder, name, wp.array(value, dtype=old.dtype, shape=old.shape))
    return model, _start_mjmodel(mjcf.mjmodel, moved, held)


def _start_mjmodel(mjmodel, moved: dict, held: dict):
    """The MuJoCo model whose data a world starts from: `mjmodel`, or a copy with a twin's `moved` numbers written in.

    ``make_data`` computes with C MuJoCo what MJWarp's steps never
    recompute (the poses of the geoms fixed to the world), so a twin's
    must come from its moved numbers.  A field is written where MJWarp
    holds it as MuJoCo does: its unmoved values (`held`) are MuJoCo's
    rounded to float32, element for element.  The others are MJWarp's
    own (derived, or laid out otherwise), which MuJoCo does not read.
    """
    if not moved:
        return mjmodel
    out = copy.copy(mjmodel)  # MuJoCo's own copy of every array
    for field, value in moved.items():
        holder, name = field_holder(out, field)
        mine = getattr(holder, name, None)
        if not isinstance(mine, float | np.ndarray) or np.size(mine) != value.size:
            continue
        if np.array_equal(np.asarray(mine, dtype=np.float32).ravel(), held[field].ravel()):
            write_field(out, field, value)
    return out


def _unsupported(reason: str) -> str:
    """The element MJWarp's refusal is about, as a culprit."""
    return next((element for word, element in _CULPRITS if word in reason), "model")


def _specs(holder) -> dict:
    """Each array field of an MJWarp dataclass, and whether it is per-world (its spec's leading ``"*"``)."""
    out = {}
    for f in dataclasses.fields(holder):
        shape = getattr(f.type, "shape", None)
        if isinstance(shape, tuple) and shape:
            out[f.name] = shape[0] == "*"
    return out


def _arrays(model):
    """(field, array, per-world) for each Warp array of the model and of its options."""
    wp, _ = _warp()
    for prefix, holder in (("", model), ("opt.", model.opt)):
        specs = _specs(holder)
        for name, batched in specs.items():
            value = getattr(holder, name)
            if isinstance(value, wp.array):
                yield prefix + name, value, batched


def _float_arrays(model):
    """(field, array, per-world) for each floating-point array MJWarp holds, colours left out."""
    for field, array, batched in _arrays(model):
        if array.size and np.dtype(array.numpy().dtype).kind == "f" and not field.endswith("rgba"):
            yield field, array, batched


def _one_world(array, batched: bool) -> np.ndarray:
    value = array.numpy()
    return np.array(value[0] if batched else value, copy=True, ndmin=1)


def _aligned(runner: WarpRunner, reference: WarpRunner):
    """`runner`'s device model, batchable with `reference`'s where nothing MJWarp reads tells them apart.

    ``dof_length`` (a degree of freedom's length scale) is shared by the
    worlds, not per-world, and a scaled copy changes it; MJWarp reads it
    only to put bodies to sleep.  Without sleep the copy takes the
    reference's, so that the original and its copy run as worlds of one
    call.
    """
    model, other = runner._device_model, reference._device_model
    sleep = int(engine_module("mujoco").mjtEnableBit.mjENBL_SLEEP)
    if runner.mjcf.mjmodel.opt.enableflags & sleep or model.dof_length.shape != other.dof_length.shape:
        return model
    if np.array_equal(model.dof_length.numpy(), other.dof_length.numpy()):
        return model
    out = copy.copy(model)
    out.dof_length = other.dof_length
    return out


def _shared_key(model) -> tuple:
    """What the worlds of one call must share: every array that is not per-world, and the plain settings."""
    arrays = tuple((f, a.numpy().tobytes()) for f, a, batched in _arrays(model) if not batched)
    plain = []
    for prefix, holder in (("", model), ("opt.", model.opt)):
        for f in dataclasses.fields(holder):
            value = getattr(holder, f.name)
            if isinstance(value, bool | int | float | str):
                plain.append((prefix + f.name, value))
    return arrays, tuple(plain)


def _worlds(models: list, device: str):
    """One MJWarp model whose worlds are `models`: each per-world array that differs, stacked."""
    wp, _ = _warp()
    first = models[0]
    if len(models) == 1:
        return first
    out = copy.copy(first)
    out.opt = copy.copy(first.opt)
    tables = [{f: a for f, a, _ in _arrays(m)} for m in models]
    for field, array, batched in _arrays(first):
        if not batched:
            continue
        holder, name = field_holder(out, field)
        values = [table[field].numpy() for table in tables]
        if all(np.array_equal(v, values[0]) for v in values[1:]):
            continue
        stacked = np.concatenate(values)  # each has a leading dimension of one world
        setattr(holder, name, wp.array(stacked, dtype=array.dtype, device=device))
    return out


def _initial(runner: WarpRunner, nudge: bool, initial) -> np.ndarray:
    """The first row (qpos, qvel, act) in float32: the model's reference pose at rest, or `initial`'s; nudged."""
    m = runner.mjcf.mjmodel
    if initial is None:
        first = np.concatenate(
            [_one_world(runner._device_model.qpos0, True), np.zeros(m.nv + m.na, np.float32)]
        ).astype(np.float32)
    else:
        first = np.asarray(initial, dtype=np.float32).copy()
    if nudge:  # pitheorem.simulation.nudged in float32: up one ulp, by the ulp of 1 near 0
        x = first[: m.nq + m.nv]
        up = np.nextafter(x, np.float32(np.inf))
        first[: m.nq + m.nv] = np.where(np.abs(x) >= 1, up, x + np.spacing(np.float32(1)))
    return first


def _control_rows(controls, n_steps: int, nu: int, dt: float) -> np.ndarray:
    """One row of inputs per step, in float32 (zeros for none)."""
    if controls is None or not nu:
        return np.zeros((n_steps, nu), np.float32)
    if callable(controls):
        controls = [controls(i * dt) for i in range(n_steps)]
    return np.asarray(controls, dtype=float).reshape(n_steps, nu).astype(np.float32)


def load_warp(path, *, device: str | None = None) -> EngineModel:
    """Read an MJCF file through MuJoCo's parser and put it in MuJoCo Warp.

    Parameters
    ----------
    path : str or Path
    device : str, optional
        The Warp device: ``"cpu"``, ``"cuda"`` or ``"cuda:N"``.  Default:
        Warp's preferred device (its first GPU, else the CPU).

    Returns
    -------
    EngineModel
        Of engine ``"warp"``, in float32.

    Raises
    ------
    EngineModelError
        When MuJoCo rejects the file, or MJWarp does not support a part of
        it (the message names it: the PGS solver, a sensor, a flag, ...).
    InvalidRequestError
        For a device Warp does not have.

    Examples
    --------
    >>> from pitheorem.engines.runners.warp import load_warp
    >>> load_warp.__name__
    'load_warp'
    """
    name = _device(device)
    reading = MujocoRunner(read_mjcf(path))
    if reading.refusal is not None:  # MuJoCo's compiler refused it: there is no model to put in MJWarp
        raise reading.refusal
    return EngineModel(WarpRunner(reading, name), "warp", str(path))


def load_urdf(path, *, settings=None, device: str | None = None) -> EngineModel:
    """Read a URDF file as an MJWarp model: compiled by MuJoCo's URDF reader, put on a Warp device.

    The same model as :func:`pitheorem.engines.runners.mujoco.load_urdf`'s (its
    parameters, settings file and scaled copies), run by MJWarp.

    Parameters
    ----------
    path : str or Path
    settings : str, Path or bool, optional
        The MuJoCo settings file: by default ``<path>.mujoco.json`` if it
        exists; ``False`` ignores it.
    device : str, optional
        As for :func:`load_warp`.

    Returns
    -------
    EngineModel
        Of engine ``"warp"``, in float32.

    Raises
    ------
    EngineModelError
        For a file the URDF format, MuJoCo or MJWarp rejects (named).
    InvalidRequestError
        For a device Warp does not have.

    Examples
    --------
    >>> from pitheorem.engines.runners.warp import load_urdf
    >>> load_urdf.__name__
    'load_urdf'
    """
    name = _device(device)
    return EngineModel(WarpRunner(urdf_runner(path, settings=settings), name), "warp", str(path))


def _device(device) -> str:
    """The name of a Warp device (Warp's preferred one for None); one Warp does not have, refused by name."""
    wp, _ = _warp()
    try:
        return str(wp.get_device(device))
    except (RuntimeError, ValueError) as err:
        devices = ", ".join(repr(str(d)) for d in wp.get_devices())
        raise InvalidRequestError(
            f"Warp has no device {device!r} ({err}); its devices: {devices}", culprit=device
        ) from None
