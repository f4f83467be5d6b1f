"""MJCF models in MJX, MuJoCo's engine written in JAX: float32 by default, runs batched.

An MJCF file is read as for MuJoCo (:mod:`pitheorem.engines.fileformats.mjcf` reads
it: the same parameters, scaled copies and saved files) and put on JAX's
device with ``mujoco.mjx.put_model``.  MJX computes in float32 unless
asked for float64 (``precision="float64"``, JAX's x64 mode, switched on
only while this runner computes).  What MJX does not support (the PGS
solver, some geom pairs, flex objects, some sensors and actuators) is
refused by name when the file is loaded.  A URDF file goes to MJX as it
goes to MuJoCo (:func:`load_urdf`): compiled by MuJoCo's URDF reader, with
the MuJoCo settings saved beside it.

The runs of a verification (the original, its scaled copy, the
yardstick's twins) go to :meth:`MjxRunner.run_many`, which stacks the
models and runs them as one ``jax.vmap`` of a ``jax.lax.scan`` over the
steps.  Models whose static parts differ (MJX keeps some numbers, such as
mesh vertices and site sizes, outside the arrays it traces) cannot share
a batch: each group of equal static parts is one call.  A twin moves
every number MJX holds in its arrays by one unit in the last place of
*its own* precision (float32 by default).

MJX runs open loop only here: a closed-loop controller runs in
``"mujoco"``.  Its own constants (a ``1e-6`` added to a squared length
when it finds the closest point on a capsule's segment, say) are in the
catalogue (``engines.hidden_constants("mjx")``).

Examples
--------
>>> from pitheorem.engines.runners.mjx import PRECISIONS
>>> from pitheorem.engines.registry import registered
>>> PRECISIONS, registered("mjx").packages
(('float32', 'float64'), ('mujoco', 'jax', 'mujoco.mjx'))

With MJX installed (``pip install "pitheorem[mjx]"``)::

    model = engines.load("pendulum.xml", engine="mjx")      # float32
    rep = engines.verify(model, scaling, s=4, duration=0.5)  # rep.exact: bit for bit
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ...errors import EngineModelError, InvalidRequestError
from ..enginemodel import EngineModel
from ..fileformats.mjcf import read_mjcf
from ..packages import engine_module
from ..parameters import Parameter, dim
from .mujoco import MujocoCompiledRunner, MujocoRunner, urdf_runner

__all__ = ["PRECISIONS", "MjxRunner", "load_mjx", "load_urdf", "mjx_parameters", "threshold_numbers"]

_M, _ML2, _L = dim("M"), dim("M L^2"), dim("L")

#: the precisions MJX computes in: JAX's float32 (its default) or float64 (its x64 mode)
PRECISIONS = ("float32", "float64")

#: the jitted batch runner, one per precision (JAX traces it again for each new shape or static part)
_RUNNERS: dict = {}


def _jax():
    engine_module("mjx")  # names the missing package (jax, mujoco.mjx) before it is imported here
    import jax

    return jax


class MjxRunner(MujocoCompiledRunner):
    """An MJCF model in MJX: MuJoCo's reading of the file, and its ``mjx.Model`` on JAX's device.

    What MuJoCo's reading gives (the table, copies, files, sizes) is
    :class:`~pitheorem.engines.runners.mujoco.MujocoCompiledRunner`'s.

    Parameters
    ----------
    mjcf : MujocoRunner
        The file as MuJoCo reads and compiles it.
    precision : {"float32", "float64"}
    device_model : mjx.Model, optional
        The model on JAX's device (a twin's): by default ``mjcf``'s, put there.

    Examples
    --------
    >>> from pitheorem.engines.protocols import Runner
    >>> from pitheorem.engines.runners.mjx import MjxRunner
    >>> all(hasattr(MjxRunner, name) for name in Runner.__dict__ if not name.startswith("_"))
    True
    """

    engine_label = "MJX"

    def __init__(self, mjcf: MujocoRunner, precision: str = "float32", device_model=None):
        self.mjcf = mjcf
        self.precision = precision
        self._device_model = device_model if device_model is not None else _put(mjcf, precision)

    def _rebuilt(self, mjcf: MujocoRunner, *, same_numbers: bool) -> MjxRunner:
        return MjxRunner(mjcf, self.precision, self._device_model if same_numbers else None)

    def settings(self) -> dict:
        return {"precision": self.precision}

    # -- what MJX holds ------------------------------------------------------------------------

    def stored_numbers(self) -> dict[str, np.ndarray]:
        """Every floating-point array MJX traces for the model, by field, in its own precision."""
        return {field: np.array(value, copy=True, ndmin=1) for field, value in _float_arrays(self._device_model)}

    def twin(self, seed: int) -> MjxRunner:
        """A copy whose every number in MJX's arrays is one unit in its own last place off (signs from `seed`).

        Zeros stay zero and the time step stays; the static parts are the original's.
        """
        jax = _jax()
        rng = np.random.default_rng(seed)
        moved = {}
        for field, value in _float_arrays(self._device_model):
            if field == "opt.timestep":
                continue
            value = np.asarray(value)
            toward = np.where(rng.random(value.shape) < 0.5, np.inf, -np.inf).astype(value.dtype)
            moved[field] = np.where(value == 0, value, np.nextafter(value, toward))
        with jax.enable_x64(self.precision == "float64"):
            device = _replaced(jax, self._device_model, moved)
        return MjxRunner(self.mjcf, self.precision, device)

    # -- running ------------------------------------------------------------------------------

    def run_many(self, n_steps: int, jobs) -> list[np.ndarray]:
        """The runs of ``(runner, controls, nudge, initial)`` jobs, vmapped: one call per static part.

        The models must have the same sizes (a model, its scaled copies and
        its twins do).  ``controls`` is None, rows of inputs (one per step)
        or ``t -> inputs``; ``initial`` is None or a first row (qpos, qvel,
        act; MJX starts every activation at zero).
        """
        jax = _jax()
        import jax.numpy as jnp

        dtype = np.dtype(self.precision)
        nu = self.mjcf.mjmodel.nu
        groups: dict = {}
        devices = [_aligned(runner, jobs[0][0]) for runner, *_ in jobs]
        for i, device in enumerate(devices):
            groups.setdefault(jax.tree_util.tree_structure(device), []).append(i)
        out: list = [None] * len(jobs)
        with jax.enable_x64(self.precision == "float64"):
            step_all = _runner(jax, self.precision)
            for members in groups.values():
                models = [devices[i] for i in members]
                batch = jax.tree_util.tree_map(lambda *xs: jnp.stack(xs), *models)
                starts = [_initial(jobs[i][0], jobs[i][2], jobs[i][3], dtype) for i in members]
                rows = np.stack([_control_rows(jobs[i][1], n_steps, nu, jobs[i][0].timestep(), dtype) for i in members])
                qpos = jnp.asarray(np.stack([q for q, _ in starts]))
                qvel = jnp.asarray(np.stack([v for _, v in starts]))
                runs = np.asarray(step_all(batch, qpos, qvel, jnp.asarray(rows)))
                for k, i in enumerate(members):
                    model = jobs[i][0].mjcf.mjmodel
                    first = np.concatenate([starts[k][0], starts[k][1], np.zeros(model.na, dtype)])
                    out[i] = np.concatenate([first[None, :], runs[k]]).astype(float)
        return out


#: static arrays of an ``mjx.Model`` (NumPy, outside the traced arrays, so part of the compiled program's
#: identity) that MJX's JAX code never reads, or reads only for a kind of geom: (owner, field, geom type or None)
_UNREAD_STATIC = (
    ("", "body_margin", None),  # the compiler's copy of the largest geom margin; MJX reads geom_margin only
    ("_impl", "geom_rbound_hfield", "mjGEOM_HFIELD"),  # sizes a heightfield's collision patch, nothing else
)


def _aligned(runner: MjxRunner, reference: MjxRunner):
    """`runner`'s device model, batchable with `reference`'s where nothing MJX reads tells them apart.

    MJX keeps some arrays static, outside the arrays it traces: two models
    whose static arrays differ are two programs to XLA, compiled apart,
    and two programs may round differently.  A scaled copy changes two
    static arrays MJX's JAX code does not read for its model
    (:data:`_UNREAD_STATIC`: ``body_margin``, and ``geom_rbound_hfield``
    in a model without heightfields).  The copy takes the reference's,
    so that a model and its scaled copy run as one program: with its own
    ``body_margin``, the hopper's copy ran in a call of its own and parted
    from the original after one step, by one float32 ulp.
    """
    device, other = runner._device_model, reference._device_model
    mujoco = engine_module("mujoco")
    for owner, field, geom_type in _UNREAD_STATIC:
        mine, theirs = (getattr(d._impl, field) if owner else getattr(d, field) for d in (device, other))
        if mine.shape != theirs.shape or np.array_equal(mine, theirs):
            continue
        if geom_type is not None and np.any(runner.mjcf.mjmodel.geom_type == int(getattr(mujoco.mjtGeom, geom_type))):
            continue
        device = (
            device.replace(_impl=device._impl.replace(**{field: theirs}))
            if owner
            else device.replace(**{field: theirs})
        )
    return device


def _put(mjcf: MujocoRunner, precision: str):
    """The ``mjx.Model`` of a MuJoCo model, in `precision`; what MJX does not support, refused by name."""
    jax = _jax()
    mjx = engine_module("mjx")
    m = mjcf.mjmodel
    if int(m.opt.solver) == 0:  # MJX has CG and Newton; the file's PGS would be put as nothing it runs
        raise EngineModelError(
            mjcf.path,
            "option solver",
            'MJX does not support the PGS solver; use <option solver="Newton"/> or "CG", or run the file in \'mujoco\'',
        )
    with jax.enable_x64(precision == "float64"):
        try:
            return mjx.put_model(m, impl="jax")
        except NotImplementedError as err:
            reason = str(err).strip() or type(err).__name__
            raise EngineModelError(
                mjcf.path, _unsupported(reason), f"MJX does not support {reason}; run the file in 'mujoco'"
            ) from None


def _unsupported(reason: str) -> str:
    """The element MJX's refusal is about, as a culprit."""
    if "collisions" in reason or "margin" in reason:
        return "geom pair"
    for word in ("Flex", "Contact sensor", "mjtIntegrator", "mjtCone", "mjtJacobian", "mjtEnableBit"):
        if word in reason:
            return {"Flex": "flex", "Contact sensor": "sensor"}.get(word, "option")
    return "model"


def _float_arrays(device):
    """(field, array) for each floating-point array MJX traces: ``opt.x`` and ``stat.x`` for structs."""
    for name, holder in (("", device), ("opt.", device.opt), ("stat.", device.stat)):
        for f in dataclasses.fields(holder):
            value = getattr(holder, f.name)
            if f.name.startswith("_") or isinstance(value, np.ndarray) or not hasattr(value, "dtype"):
                continue
            if np.dtype(value.dtype).kind == "f" and value.size and not f.name.endswith("rgba"):
                yield name + f.name, value


def _replaced(jax, device, values: dict):
    """`device` with the named arrays replaced (on the device, in their dtype)."""
    import jax.numpy as jnp

    top = {k: jnp.asarray(v) for k, v in values.items() if "." not in k}
    opt = {k.split(".")[1]: jnp.asarray(v) for k, v in values.items() if k.startswith("opt.")}
    stat = {k.split(".")[1]: jnp.asarray(v) for k, v in values.items() if k.startswith("stat.")}
    return device.replace(**top, opt=device.opt.replace(**opt), stat=device.stat.replace(**stat))


def _initial(runner: MjxRunner, nudge: bool, initial, dtype) -> tuple[np.ndarray, np.ndarray]:
    """The initial (qpos, qvel): the model's reference pose at rest, or `initial`'s; nudged by one ulp of `dtype`."""
    m = runner.mjcf.mjmodel
    if initial is None:
        qpos = np.asarray(runner._device_model.qpos0, dtype=dtype)
        qvel = np.zeros(m.nv, dtype)
    else:
        if np.any(initial[m.nq + m.nv :]):
            raise InvalidRequestError(
                "MJX runs start with every activation at zero; run a start with "
                "activations in 'mujoco' (engines.load(path))"
            )
        qpos, qvel = (np.asarray(x, dtype=dtype) for x in (initial[: m.nq], initial[m.nq : m.nq + m.nv]))
    if nudge:
        qpos, qvel = _nudged(qpos, dtype), _nudged(qvel, dtype)
    return qpos, qvel


def _nudged(values: np.ndarray, dtype) -> np.ndarray:
    """:func:`pitheorem.simulation.nudged` in `dtype`: up one ulp, by the ulp of 1 near 0 (never NaN at 0)."""
    x = np.asarray(values, dtype=dtype)
    one = np.spacing(np.ones((), dtype=dtype))
    return np.where(np.abs(x) >= 1, np.nextafter(x, np.array(np.inf, dtype=dtype)), x + one).astype(dtype)


def _control_rows(controls, n_steps: int, nu: int, dt: float, dtype) -> np.ndarray:
    if controls is None or not nu:
        return np.zeros((n_steps, nu), dtype)
    if callable(controls):
        controls = [controls(i * dt) for i in range(n_steps)]
    return np.asarray(controls, dtype=float).reshape(n_steps, nu).astype(dtype)


def _runner(jax, precision: str):
    """``run(models, qpos, qvel, controls)``: the batch's rows after each step, jitted once per precision."""
    if precision not in _RUNNERS:
        mjx = engine_module("mjx")
        import jax.numpy as jnp

        def one(m, qpos, qvel, rows):
            data = mjx.make_data(m).replace(qpos=qpos, qvel=qvel)

            def step(d, u):
                d = mjx.step(m, d.replace(ctrl=u))
                return d, jnp.concatenate([d.qpos, d.qvel, d.act])

            return jax.lax.scan(step, data, rows)[1]

        _RUNNERS[precision] = jax.jit(jax.vmap(one))
    return _RUNNERS[precision]


#: MuJoCo's geom types (mjtGeom) that mjx_parameters reads
_PLANE, _HFIELD, _SPHERE, _CAPSULE, _CYLINDER, _BOX, _MESH = 0, 1, 2, 3, 5, 6, 7


#: MuJoCo's flag that keeps a body's geoms colliding with its parent's (mjtDisableBit.mjDSBL_FILTERPARENT)
_FILTERPARENT = 1024


#: the geom types a capsule collides with through the closest point on its segment in MJX
#: (collision_primitive sphere_capsule and capsule_capsule, collision_convex capsule_convex and hfield_capsule)
_SEGMENT_PARTNERS = frozenset({_HFIELD, _SPHERE, _CAPSULE, _BOX, _MESH})


def _compiled(model):
    """The model's compiled MjModel (MuJoCo's or MJX's compilation of the file), or None (another engine's)."""
    runner = model.runner
    if isinstance(runner, MjxRunner):
        return runner.mjcf.mjmodel
    return runner.mjmodel if isinstance(runner, MujocoRunner) else None


def _collision_pairs(m) -> list[tuple[int, int]]:
    """The geom pairs a compiled MjModel collides (MuJoCo's filter, MJX's too).

    The explicit ``<pair>`` elements, and every two geoms whose contype
    and conaffinity share a bit, except geoms of bodies welded together,
    of a body and its parent (both other than the world, unless the
    filterparent flag is disabled) and of excluded body pairs.  (Read from
    the model's arrays.)
    """
    out = {(int(min(a, b)), int(max(a, b))) for a, b in zip(m.pair_geom1, m.pair_geom2, strict=True)}
    n = m.ngeom
    if n < 2:
        return sorted(out)
    contype, conaffinity = np.asarray(m.geom_contype), np.asarray(m.geom_conaffinity)
    weld = np.asarray(m.body_weldid)[np.asarray(m.geom_bodyid)]  # each geom's weld body
    parent = np.asarray(m.body_weldid)[np.asarray(m.body_parentid)][weld]  # the weld body of its parent
    body = np.asarray(m.geom_bodyid)
    ok = ((contype[:, None] & conaffinity[None, :]) | (contype[None, :] & conaffinity[:, None])) != 0
    ok &= weld[:, None] != weld[None, :]
    if not m.opt.disableflags & _FILTERPARENT:
        family = (weld[:, None] == parent[None, :]) | (parent[:, None] == weld[None, :])
        ok &= ~(family & (weld[:, None] != 0) & (weld[None, :] != 0))
    lo, hi = np.minimum(body[:, None], body[None, :]), np.maximum(body[:, None], body[None, :])
    ok &= ~np.isin((lo.astype(np.int64) << 16) + hi, np.asarray(m.exclude_signature, dtype=np.int64))
    first, second = np.nonzero(np.triu(ok, 1))
    out.update(zip(first.tolist(), second.tolist(), strict=True))
    return sorted(out)


def _label(mjmodel, kind: str, index: int, names: set[str], suffix: str) -> tuple[str, str]:
    """A derived parameter's name and the start of its path, for a geom or a body."""
    label = getattr(mjmodel, kind)(index).name
    ident = f"{kind}_{label}_{suffix}" if label else f"{kind}{index}_{suffix}"
    if ident in names or not ident.isidentifier():
        ident = f"{kind}{index}_{suffix}"
    names.add(ident)
    return ident, f"{kind} {label!r}" if label else f"{kind} #{index}"


def mjx_parameters(model) -> tuple[Parameter, ...]:
    """The numbers MJX's own constants are held against, from the compiled model.

    MJX finds the closest point on a capsule's segment with a constant
    of its own added to the segment's squared length (the threshold
    ``mjx_segment_regularizer_float32``), and takes a cylinder whose
    axis, times its half-length, leans less than 1 mm from a plane as
    lying on it (``mjx_cylinder_plane_parallel``): the half-lengths of
    the geoms in a pair MJX collides through such a function (kinds
    ``capsule_segment`` and ``cylinder_on_plane``).  With the fluid
    model on (the option's density, viscosity or wind), MJX floors each
    body's mass and the sums of its principal moments that give the
    body's equivalent box (``I1 + I2 - I0`` and its turns) at 1e-12
    (``mjx_fluid_*``): those masses and sums (kinds ``fluid_mass`` and
    ``fluid_box_moments``).  None of these numbers is in the file's table
    as such (a capsule's ``fromto`` holds its ends).

    Parameters
    ----------
    model : EngineModel
        An MJCF model (in MuJoCo or MJX).

    Returns
    -------
    tuple of Parameter
        Source ``"derived"``, geoms then bodies; ``()`` for a model with no
        such number or no compiled model (a URDF).  A file MuJoCo refuses
        (read from a probe in another mass unit) has its half-lengths only.

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.runners.mjx import mjx_parameters
    >>> mjx_parameters(engines.load(engines.example_path("pendulum.xml")))  # its rod touches nothing
    ()
    """
    mjmodel = _compiled(model)
    if mjmodel is None:
        return ()
    partners: dict[int, set[int]] = {}
    for a, b in _collision_pairs(mjmodel):
        partners.setdefault(a, set()).add(int(mjmodel.geom_type[b]))
        partners.setdefault(b, set()).add(int(mjmodel.geom_type[a]))
    out, names = [], set()
    for g in sorted(partners):
        kind = int(mjmodel.geom_type[g])
        if kind == _CAPSULE and partners[g] & _SEGMENT_PARTNERS:
            shape = "capsule"
        elif kind == _CYLINDER and _PLANE in partners[g]:
            shape = "cylinder"
        else:
            continue
        ident, path = _label(mjmodel, "geom", g, names, "half_length")
        out.append(
            Parameter(
                ident,
                f"{path} {shape} half-length",
                (float(mjmodel.geom_size[g][1]),),
                _L,
                "derived",
                "file",
                note="read from the compiled model",
            )
        )
    opt = mjmodel.opt
    # MJX's inertia-box fluid model, on every body; a refused file's compiled masses are a probe's: left out
    fluid = opt.density > 0 or opt.viscosity > 0 or any(opt.wind)
    if fluid and model.runner.refusal is None:
        for b in range(1, mjmodel.nbody):
            mass, moments = float(mjmodel.body_mass[b]), [float(i) for i in mjmodel.body_inertia[b]]
            if mass <= 0:
                continue
            ident, path = _label(mjmodel, "body", b, names, "mass_in_fluid")
            out.append(
                Parameter(
                    ident,
                    f"{path} mass in the fluid model",
                    (mass,),
                    _M,
                    "derived",
                    "file",
                    note="read from the compiled model",
                )
            )
            sums = tuple(sum(moments) - 2 * moments[i] for i in range(3))  # I1 + I2 - I0, I0 + I2 - I1, ...
            ident, path = _label(mjmodel, "body", b, names, "fluid_box_moments")
            out.append(
                Parameter(
                    ident,
                    f"{path} fluid box moments",
                    sums,
                    _ML2,
                    "derived",
                    "file",
                    note="sums of the body's principal moments, read from the compiled model",
                )
            )
    return tuple(out)


#: the numbers MJX's own thresholds are held against, beside a model's table (``thresholds.held_against``)
threshold_numbers = mjx_parameters


def load_mjx(path, *, precision: str = "float32") -> EngineModel:
    """Read an MJCF file through MuJoCo's parser and put it in MJX.

    Parameters
    ----------
    path : str or Path
    precision : {"float32", "float64"}
        MJX's own float32 (the default) or float64 (JAX's x64 mode, on
        only while this model computes).

    Returns
    -------
    EngineModel
        Of engine ``"mjx"``.

    Raises
    ------
    EngineModelError
        When MuJoCo rejects the file, or MJX does not support a part of
        it (the message names it: the PGS solver, a geom pair, ...).
    InvalidRequestError
        For another precision.

    Examples
    --------
    >>> import pitheorem as pt
    >>> from pitheorem import engines
    >>> from pitheorem.engines.runners.mjx import load_mjx
    >>> try:
    ...     load_mjx(engines.example_path("pendulum.xml"), precision="float16")
    ... except pt.InvalidRequestError as err:
    ...     print(err)
    precision must be 'float32' or 'float64', got 'float16'
    """
    _check_precision(precision)
    reading = MujocoRunner(read_mjcf(path))
    if reading.refusal is not None:  # MuJoCo's compiler refused it: there is no model to put in MJX
        raise reading.refusal
    return EngineModel(MjxRunner(reading, precision), "mjx", str(path))


def _check_precision(precision) -> None:
    if precision not in PRECISIONS:
        raise InvalidRequestError(f"precision must be 'float32' or 'float64', got {precision!r}", culprit=precision)


def load_urdf(path, *, settings=None, precision: str = "float32") -> EngineModel:
    """Read a URDF file as an MJX model: compiled by MuJoCo's URDF reader, put on JAX's device.

    The same model as :func:`pitheorem.engines.runners.mujoco.load_urdf`'s (its
    parameters, settings file and scaled copies), run by MJX.

    Parameters
    ----------
    path : str or Path
    settings : str, Path or bool, optional
        The MuJoCo settings file: by default ``<path>.mujoco.json`` if it
        exists; ``False`` ignores it.
    precision : {"float32", "float64"}

    Returns
    -------
    EngineModel
        Of engine ``"mjx"``.

    Raises
    ------
    EngineModelError
        For a file the URDF format, MuJoCo or MJX rejects (named).
    InvalidRequestError
        For another precision.

    Examples
    --------
    >>> from pitheorem import engines
    >>> engines.load(engines.example_path("hinged_rod.urdf"), engine="mjx").engine
    'mjx'
    """
    _check_precision(precision)
    return EngineModel(MjxRunner(urdf_runner(path, settings=settings), precision), "mjx", str(path))
