"""MuJoCo as a runner: a format's document compiled, stepped in MuJoCo's rollout, copied one ulp off.

:class:`MujocoRunner` runs what a format read (an MJCF file's
:class:`~pitheorem.engines.fileformats.mjcf.MjcfDocument`): open loop in
MuJoCo's own ``rollout`` (the loop in C, spread over the cores), closed
loop step by step, a batch of runs at once; it copies the compiled model
one ulp off for the yardstick's twins and with another solver, tolerance,
contacts or equality constraints for the diagnosis' counter-runs, and
says what MuJoCo stores, which contacts a run makes and which solver it
uses.  :func:`load_mjcf` is the registry's loader of MJCF files for ``"mujoco"``.

A URDF file runs here too (:func:`load_urdf`): MuJoCo's own URDF reader
compiles it (with its ``<mujoco>`` block of compiler, option and size
settings), and :class:`UrdfInMujoco` gives the runner what it needs of a
document.  The table is the URDF's numbers (the URDF format's
:class:`~pitheorem.engines.fileformats.urdf.UrdfDocument`) and the MuJoCo
settings a URDF cannot hold: the options (time step, gravity, wind, ...),
and the contact and limit softness, friction and margins MuJoCo's reader
gives every geom and joint from its default class.  They are written
beside a saved copy (``NAME.urdf.mujoco.json``) and read back by
:func:`load_urdf`.  MuJoCo's URDF reader makes no actuators; the runner
gives every movable joint a motor (:func:`add_joint_motors`), as PyBullet's
runner takes one torque or force per movable joint, so ``run(controls=...)``
sets one torque (revolute) or force (prismatic) per joint.
"""

from __future__ import annotations

import atexit
import functools
import json
import math
import re
from contextlib import contextmanager
from pathlib import Path

import numpy as np

from ...errors import EngineModelError, InvalidRequestError
from ...formatting.pieces import names_text
from ...simulation import nudged
from ..enginemodel import EngineModel
from ..fileformats.mjcf import read_mjcf
from ..fileformats.urdf import UrdfDocument, read_urdf, refuse_units
from ..packages import engine_module
from ..parameters import JointKind, Parameter, dim

__all__ = [
    "MujocoCompiledRunner",
    "MujocoRunner",
    "UrdfInMujoco",
    "add_joint_motors",
    "field_holder",
    "load_mjcf",
    "load_urdf",
    "write_field",
]


@functools.cache  # asked once; a missing MuJoCo raises (named with its extra) and is not cached
def _mujoco():
    return engine_module("mujoco")


@contextmanager
def warnings_collected(heard: list[str]):
    """MuJoCo's warnings appended to `heard` while the block runs, instead of printed and logged.

    MuJoCo prints each warning on the console and appends it to ``MUJOCO_LOG.TXT`` in the working
    folder.  Here its user handler (``mujoco.set_mju_user_warning``) only appends the text, for MuJoCo
    calls it from the threads of a batched rollout too; the caller's handler is back afterwards.  The
    optional hook a runner module gives the command line (:func:`pitheorem.engines.cli.engine_warnings`).
    """
    mj = _mujoco()
    previous = mj.get_mju_user_warning()
    mj.set_mju_user_warning(heard.append)
    try:
        yield
    finally:
        mj.set_mju_user_warning(previous)


#: a parameter's path: its element (``geom 'foot'``, ``geom #3``) and the attribute after it
_ELEMENT_ATTRIBUTE = re.compile(r"^(\w+ (?:'[^']*'|#\d+)) (\S+)")


def _dofs(m, j: int) -> int:
    """The degrees of freedom of joint `j`: 6 free, 3 ball, 1 slide or hinge."""
    return {0: 6, 1: 3}.get(int(m.jnt_type[j]), 1)


class MujocoRunner:
    """A model run by MuJoCo: a format's document, compiled, stepped, copied one ulp off, and run again.

    The document (an MJCF file's, :class:`~pitheorem.engines.fileformats.mjcf.MjcfDocument`)
    holds the file's numbers and writes them back; the runner holds the
    compiled ``MjModel`` it steps (its own copy for twins and counter-runs)
    and everything MuJoCo says of a run: the numbers it stores, its
    contacts, its solver.

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.runners.mujoco import MujocoRunner, load_mjcf
    >>> runner = MujocoRunner(load_mjcf(engines.example_path("pendulum.xml")).runner.document)
    >>> runner.mjmodel.nq, runner.run(2).shape
    (1, (3, 2))
    """

    #: MuJoCo computes in double precision
    precision = "float64"

    def __init__(self, document):
        self.document = document
        self.mjmodel = document.mjmodel  # this runner's own copy once a twin or a counter-run changes it
        self.refusal = getattr(document, "refusal", None)
        # each stored field's rows by element, and the elements' names: found once, shared with the copies of
        # this model (twins, counter-runs), which have the same elements
        self._element_row_cache: dict = {}
        self._element_names: dict = {}

    # -- the document's table, copies and files -------------------------------------------------

    @property
    def spec(self):
        """The document's ``MjSpec``."""
        return self.document.spec

    @property
    def path(self) -> str:
        return self.document.path

    def parameters(self):
        return self.document.parameters()

    def settings(self) -> dict:
        return self.document.settings()

    def scaled(self, factors, scaling, s) -> MujocoRunner:
        copy = MujocoRunner(self.document.scaled(factors, scaling, s))
        copy._field_names = self._fields()  # the same elements: the same stored fields
        return copy

    def input_parameters(self) -> list[dict[str, int]]:
        return self.document.input_parameters()

    def coordinate_inputs(self) -> list[int | None]:
        return self.document.coordinate_inputs()

    def scaled_keeping_inputs(self, factors, scaling, s) -> MujocoRunner:
        copy = MujocoRunner(self.document.scaled(factors, scaling, s, keep_inputs=True))
        copy._field_names = self._fields()
        return copy

    def in_units(self, units) -> MujocoRunner:
        """This model, its document recording other units (a saved file then says so); a URDF's stay SI."""
        if isinstance(self.document, UrdfInMujoco):
            self.document.check_units(units)
            return self
        return MujocoRunner(self.document.in_units(units))

    def check_units(self, units) -> None:
        """Nothing to refuse for an MJCF file (in any units, recorded when saved); a URDF's are SI only."""
        if isinstance(self.document, UrdfInMujoco):
            self.document.check_units(units)

    def recorded_units(self) -> dict[str, str] | None:
        return self.document.recorded_units()

    def save(self, path, *, copy_assets: bool = False) -> None:
        self.document.save(path, copy_assets=copy_assets)

    def written_beside(self, path) -> tuple[str, ...]:
        """The files :meth:`save` writes beside `path`: none for MJCF (its file holds every setting), a
        URDF's MuJoCo settings."""
        if isinstance(self.document, UrdfInMujoco):
            return self.document.written_beside(path)
        return ()

    def unread(self) -> frozenset[str]:
        """The parameters MuJoCo holds but never reads in a run.

        A geom's contact numbers (``solref``, ``solimp``, ``margin``, ``gap``,
        ``friction``) when it can never collide (``contype`` and
        ``conaffinity`` both 0, and in no explicit ``<pair>``); a joint's
        limit softness when it has no limit; its friction-loss softness
        when it has no friction loss.
        """
        m = self.mjmodel
        kinds: dict[str, set[str]] = {}  # element path -> attributes never read
        for i in map(int, np.flatnonzero(_never_colliding(m))):
            name = m.geom(i).name
            kinds[f"geom {name!r}" if name else f"geom #{i}"] = {"solref", "solimp", "margin", "gap", "friction"}
        for j in range(m.njnt):
            name = m.joint(j).name
            unread = set() if m.jnt_limited[j] else {"solref_limit", "solimp_limit", "margin"}
            if not np.any(m.dof_frictionloss[m.jnt_dofadr[j] : m.jnt_dofadr[j] + _dofs(m, j)]):
                unread |= {"solref_friction", "solimp_friction"}
            if unread:
                kinds[f"joint {name!r}" if name else f"joint #{j}"] = unread
        out = set()
        for p in self.parameters():
            where = _ELEMENT_ATTRIBUTE.match(p.path)
            if where and where.group(2) in kinds.get(where.group(1), ()):
                out.add(p.name)
        return frozenset(out)

    def unread_stored(self) -> dict[str, np.ndarray]:
        """Per stored field, a mask of the rows no step of a run reads (fields with none are left out).

        The rows of a geom that never collides (``contype`` and
        ``conaffinity`` 0, in no ``<pair>``) and takes no part in the fluid
        model: its pose, size and contact numbers only draw it (MuJoCo used
        its shape for the body's inertia when it compiled, and that shows
        in the body's numbers).  And the rows of a mesh that only such geoms
        use: its vertices, normals and the offset MuJoCo computed for it.
        A visual mesh's centroid, recomputed from vertices four times
        larger, may differ from four times the original's in its last bits;
        that moves nothing in a run.
        """
        m = self.mjmodel
        fluid = np.asarray(m.geom_fluid).reshape(m.ngeom, -1)[:, 0] if m.ngeom else np.zeros(0)
        idle_geom = _never_colliding(m) & (fluid == 0)
        mesh_geoms = (np.asarray(m.geom_type) == int(_mujoco().mjtGeom.mjGEOM_MESH)) & ~idle_geom
        idle_mesh = np.ones(m.nmesh, dtype=bool)
        idle_mesh[np.asarray(m.geom_dataid)[mesh_geoms]] = False
        out = {}
        for field in self._fields():
            kind, ids = self._element_rows(field)
            idle = {"geom": idle_geom, "mesh": idle_mesh}.get(kind)
            if idle is None:
                continue
            mask = idle if ids is None else idle[ids]
            if mask.any():
                out[field] = mask
        return out

    def coordinate_dimensions(self):
        return self.document.coordinate_dimensions()

    def control_dimensions(self):
        return self.document.control_dimensions()

    def activation_dimensions(self):
        return self.document.activation_dimensions()

    def timestep(self) -> float:
        return float(self.mjmodel.opt.timestep)

    def _refuse(self):
        raise EngineModelError(
            self.path,
            self.refusal.element,
            f"{self.refusal.reason}; MuJoCo does not run it. "
            "Convert it to units clear of the threshold (pitheorem.fit_units(model), "
            "model.converted(...), or pitheorem convert FILE --fit mujoco)",
        )

    # -- what the engine holds and how it runs ---------------------------------------------------

    def stored_numbers(self) -> dict[str, np.ndarray]:
        """Every floating-point number the compiled model holds, by field: a copy, in its own precision.

        The arrays of ``MjModel`` (mesh vertices in float32 where MuJoCo keeps them so) and the
        floating-point fields of ``opt`` and ``stat``; colours are left out (they draw, not move), and so
        is a field that only a flag this model leaves off makes MuJoCo read (:data:`_READ_ONLY_WITH`).
        """
        m, out = self.mjmodel, {}
        mj = _mujoco()
        unread = {
            field
            for field, flag in _READ_ONLY_WITH.items()
            if not m.opt.enableflags & int(getattr(mj.mjtEnableBit, flag))
        }
        for field in self._fields():
            if field in unread:
                continue
            holder, attr = field_holder(m, field)
            out[field] = np.array(getattr(holder, attr), copy=True, ndmin=1)
        return out

    def stored_copies(self) -> list:
        """The stored numbers that are the file's numbers, each with its parameter (the document's; none for a
        document that does not list them, a URDF file read through MuJoCo)."""
        listed = getattr(self.document, "stored_copies", None)
        return listed() if listed is not None else []

    def twin(self, seed: int) -> MujocoRunner:
        """A copy whose every stored number is one unit in its own last place off, the signs drawn from `seed`.

        Zeros stay zero (a scaled copy keeps them exactly); the time step stays, for it is the grid
        the runs are compared on.  The model is copied, not compiled again.
        """
        if self.refusal is not None:
            self._refuse()
        fields, up, down = self._neighbours()
        chosen = np.where(np.random.default_rng(seed).random(up.size) < 0.5, up, down)
        twin = self._with_model_copy()
        m = twin.mjmodel
        for field, start, stop, _shape, dtype in fields:  # one draw, then each field written in place
            write_field(m, field, chosen[start:stop].astype(dtype))
        return twin

    def with_stored(self, values) -> MujocoRunner:
        """A copy whose stored numbers (fields of :meth:`stored_numbers`) are `values` (field -> array of its
        shape): the compiled model copied, nothing derived again (a static cause's counter-run: the copy
        repaired)."""
        out = self._with_model_copy()
        for field, array in values.items():
            write_field(out.mjmodel, field, array)
        return out

    def with_gravity_times(self, factor: float) -> MujocoRunner:
        """A copy with gravity times `factor`: the compiled model copied, for MuJoCo derives nothing else from
        gravity when it compiles (a negative control of the verdict)."""
        out = self._with_model_copy()
        out.mjmodel.opt.gravity[:] = np.asarray(out.mjmodel.opt.gravity) * factor
        return out

    def with_masses_times(self, factor: float) -> MujocoRunner:
        """A copy with every body's mass and inertia times `factor` (a negative control of the verdict): the
        compiled model copied, and what MuJoCo derives from masses when it compiles (subtree masses, the
        inverse weights that scale constraint softness, actuators' reference accelerations) computed again."""
        mj = _mujoco()
        out = self._with_model_copy()
        m = out.mjmodel
        m.body_mass[:] = np.asarray(m.body_mass) * factor
        m.body_inertia[:] = np.asarray(m.body_inertia) * factor
        mj.mj_setConst(m, mj.MjData(m))
        return out

    def _neighbours(self):
        """Every stored number's neighbours one ulp up and one down (zeros kept), found once per model.

        Returns the fields as ``(name, start, stop, shape, dtype)`` and the two neighbour arrays, all
        fields end to end, each number stepped in its own precision (float32 where MuJoCo keeps it so)
        and then held as a double, which represents it exactly.
        """
        if getattr(self, "_neighbour_table", None) is None:
            fields, ups, downs, start = [], [], [], 0
            for field in self._fields():
                if field == "opt.timestep":
                    continue
                holder, attr = field_holder(self.mjmodel, field)
                value = np.asarray(getattr(holder, attr))
                flat = value.reshape(-1)
                zero = flat == 0
                ups.append(np.where(zero, flat, np.nextafter(flat, np.array(np.inf, flat.dtype))).astype(float))
                downs.append(np.where(zero, flat, np.nextafter(flat, np.array(-np.inf, flat.dtype))).astype(float))
                fields.append((field, start, start + flat.size, value.shape, value.dtype))
                start += flat.size
            self._neighbour_table = (tuple(fields), np.concatenate(ups), np.concatenate(downs))
        return self._neighbour_table

    def _with_model_copy(self) -> MujocoRunner:
        """This backend over a copy of its compiled model (copied, not compiled again), to change and run."""
        import copy

        out = copy.copy(self)
        out.mjmodel = copy.copy(self.mjmodel)
        return out

    def _fields(self) -> list[str]:
        """The stored floating-point fields of this backend's model, found once (a copy has the same)."""
        if getattr(self, "_field_names", None) is None:
            self._field_names = _stored_fields(self.mjmodel)
        return self._field_names

    def variant(
        self,
        *,
        tolerance: float | None = None,
        contacts: bool = True,
        solver: str | None = None,
        inactive_equalities: tuple[int, ...] = (),
        integrator: str | None = None,
        native_ccd: bool = True,
        contactless_geoms: tuple[int, ...] = (),
        iterations: int | None = None,
        unlimited: tuple[int, ...] = (),
    ) -> MujocoRunner:
        """A copy run with another solver, tolerance, count of iterations or integrator, with contacts switched
        off (all, or some geoms'), with some equality constraints inactive, or with some limits off (indices
        into :meth:`limit_names`): a counter-run's model (or the rod's, in another integrator)."""
        mj = _mujoco()
        out = self._with_model_copy()
        m = out.mjmodel
        if iterations is not None:  # the most the constraint solver takes in a step (opt.iterations)
            m.opt.iterations = iterations
        if integrator is not None:
            m.opt.integrator = int(getattr(mj.mjtIntegrator, f"mjINT_{integrator.upper()}"))
        for i in inactive_equalities:
            m.eq_active0[i] = 0
        if solver is not None:
            m.opt.solver = int(getattr(mj.mjtSolver, f"mjSOL_{solver.upper()}"))
        if tolerance is not None:
            m.opt.tolerance = tolerance
            m.opt.noslip_tolerance = tolerance
        if not contacts:
            m.opt.disableflags |= int(mj.mjtDisableBit.mjDSBL_CONTACT)
        for g in contactless_geoms:  # this geom collides with nothing (its explicit <pair>s stay)
            m.geom_contype[g] = 0
            m.geom_conaffinity[g] = 0
        if not native_ccd:  # convex pairs through MuJoCo's older libccd path instead of its native GJK/EPA
            m.opt.disableflags |= int(mj.mjtDisableBit.mjDSBL_NATIVECCD)
        limited = self._limited() if unlimited else []
        for k in unlimited:  # the joint or tendon moves past its range: no limit constraint is made for it
            field, i = limited[k]
            getattr(m, field)[i] = 0
        return out

    def uses_native_ccd(self) -> bool:
        """Whether some geom pair that can collide (meshes, ellipsoids, cylinders against most, ...) goes
        through MuJoCo's native convex collision, which is on (found once: a copy has the same geoms)."""
        if int(self.mjmodel.opt.disableflags) & int(_mujoco().mjtDisableBit.mjDSBL_NATIVECCD):
            return False
        if getattr(self, "_convex_pairs", None) is None:
            self._convex_pairs = _has_convex_pairs(self.mjmodel)
        return self._convex_pairs

    def control_ranges(self) -> tuple[np.ndarray, np.ndarray]:
        """Each actuator's control range where the file limits it; -inf and inf where it does not."""
        m = self.mjmodel
        limited = np.asarray(m.actuator_ctrllimited, dtype=bool)
        low = np.where(limited, m.actuator_ctrlrange[:, 0], -np.inf)
        high = np.where(limited, m.actuator_ctrlrange[:, 1], np.inf)
        return low, high

    def solver_settings(self) -> dict[str, float]:
        """The solver's stopping rules that have no pure dimension, nonzero ones only."""
        opt = self.mjmodel.opt
        return {
            name: float(getattr(opt, name))
            for name in ("tolerance", "noslip_tolerance")
            if getattr(opt, name) != 0 and (name == "tolerance" or opt.noslip_iterations > 0)
        }

    def solver_iterations(self, n_steps: int, controls=None) -> int:
        """The most iterations the constraint solver takes in a step of an open-loop run from rest, in any island.

        Stepped with ``mj_step`` from the model's reference pose under
        `controls` (as :meth:`run`); MuJoCo counts each island's iterations
        of the last step in ``data.solver_niter`` (the first entry where
        islands are off).  0 where the solver never ran.
        """
        mj, m = _mujoco(), self.mjmodel
        if self.refusal is not None:
            self._refuse()
        data, _first = self._start(False, None)
        rows = self._control_rows(controls, n_steps)
        most = 0
        for i in range(n_steps):
            if rows is not None:
                data.ctrl[:] = rows[i]
            mj.mj_step(m, data)
            most = max(most, int(np.max(data.solver_niter[: max(1, data.nisland)])))
        return most

    def equality_names(self) -> list[str]:
        """Each equality constraint, named as the reports name it."""
        return [self.element_name("eq_data", i) for i in range(self.mjmodel.neq)]

    def limit_names(self) -> list[str]:
        """Each joint and tendon with a limit (its range a constraint), named as the reports name it: the
        joints first, then the tendons."""
        return [self.element_name("jnt_range" if f == "jnt_limited" else "tendon_range", i) for f, i in self._limited()]

    def _limited(self) -> list[tuple[str, int]]:
        """The field that switches each limit (``jnt_limited``, ``tendon_limited``) and the element's index."""
        m = self.mjmodel
        return [(f, int(i)) for f in ("jnt_limited", "tendon_limited") for i in np.flatnonzero(getattr(m, f))]

    def equality_kinds(self) -> list[str]:
        """Each equality constraint's kind: connect, weld, joint, tendon, flex, ... (mjtEq's names, lower case)."""
        mj = _mujoco()
        return [mj.mjtEq(int(k)).name.removeprefix("mjEQ_").lower() for k in self.mjmodel.eq_type]

    def engine_notes(self) -> tuple[str, ...]:
        """Known bugs of the installed MuJoCo that can touch a verdict on this model.

        MuJoCo 4.0.0's Newton solver has a bug in its sparse Cholesky
        factorisation, fixed in 4.0.1 (MuJoCo issue #3767); it touches a
        model that uses the Newton solver with sparse Jacobians (the
        ``jacobian`` option sparse, or auto on a model of 60 or more degrees
        of freedom).  The package index served only 4.0.0 when this was
        written.
        """
        mj, m = _mujoco(), self.mjmodel
        newton = int(m.opt.solver) == int(mj.mjtSolver.mjSOL_NEWTON)
        jacobian = int(m.opt.jacobian)
        sparse = jacobian == int(mj.mjtJacobian.mjJAC_SPARSE) or (
            jacobian == int(mj.mjtJacobian.mjJAC_AUTO) and m.nv >= 60
        )
        if mj.__version__ == "4.0.0" and newton and sparse:
            return (
                "MuJoCo 4.0.0's Newton solver has a sparse Cholesky bug, fixed in 4.0.1 (MuJoCo #3767), "
                "which this model meets (Newton, sparse Jacobians): a verdict may change with 4.0.1",
            )
        return ()

    #: the solver whose iterations are scale-free (its line search is exact in any units)
    scale_free_solver = "Newton"

    def solver_remedy(self, *, tolerance_zero: bool) -> str:
        """How a user runs both models with the scale-free solver (its tolerance at 0 where that is needed)."""
        tolerance = ' tolerance="0"' if tolerance_zero else ""
        return f'load the file with <option solver="Newton"{tolerance}/>'

    def solver_name(self) -> str:
        """The constraint solver: ``"PGS"``, ``"CG"`` or ``"Newton"``."""
        return {0: "PGS", 1: "CG", 2: "Newton"}.get(int(self.mjmodel.opt.solver), str(self.mjmodel.opt.solver))

    def first_contact_difference(self, other: MujocoRunner, n_steps: int, controls=None, other_controls=None):
        """The first step after which other geom pairs touch in `other`'s run than in this one's.

        Both run open loop, step by step side by side, and stop at the first difference: returns
        ``(step, pairs only in other's run, pairs only in this one's, pairs touched so far)``, the
        first two named and sorted, the last as geom ids in the order they first touched; the step is
        None when the same pairs touch after every step.  `other` has the same geoms (a scaled copy).
        """
        mj = _mujoco()
        runs = [
            (self, self._start(False, None)[0], self._control_rows(controls, n_steps)),
            (other, other._start(False, None)[0], other._control_rows(other_controls, n_steps)),
        ]
        touched: dict[tuple[int, int], None] = {}
        for i in range(n_steps):
            touching = []
            for backend, data, rows in runs:
                if rows is not None:
                    data.ctrl[:] = rows[i]
                mj.mj_step(backend.mjmodel, data)
                touching.append(_touching(data))
            mine, theirs = touching
            touched.update(dict.fromkeys(sorted(tuple(sorted(p)) for p in mine)))
            if mine != theirs:

                def named(pairs):
                    return sorted((self._geom_name(a), self._geom_name(b)) for a, b in pairs)

                return i + 1, named(theirs - mine), named(mine - theirs), tuple(touched)
        return None, [], [], tuple(touched)

    def contact_candidates(self, pairs) -> list[tuple[int, str, str, tuple[str, ...]]]:
        """For each pair of geoms that touch, the geom whose contacts a counter-run switches off, named.

        Of a pair, the geom of a moving body (not the world's floor), else the one in fewer of the
        pairs; each geom once.  Returns ``(geom id, the pair, its collision function, the cause
        paths of the catalogue it takes)`` each, in the order of `pairs`.
        """
        m = self.mjmodel
        count: dict[int, int] = {}
        for pair in pairs:
            for g in pair:
                count[g] = count.get(g, 0) + 1
        out, seen = [], set()
        for a, b in pairs:
            g = min((a, b), key=lambda x: (int(m.geom_bodyid[x]) == 0, count[x], x))
            if g in seen:
                continue
            seen.add(g)
            function, paths = _collider(m, a, b)
            out.append((int(g), f"{self._geom_name(a)} / {self._geom_name(b)}", function, paths))
        return out

    def element_name(self, field: str, row: int) -> str:
        """A row of a stored field, named by its element where the field has one row per element."""
        kind, ids = self._element_rows(field)
        if kind is None:
            return f"{field}[{row}]"
        element = int(ids[row]) if ids is not None else int(row)
        names = self._element_names.setdefault(kind, {})
        if element not in names:
            mj = _mujoco()
            name = mj.mj_id2name(self.mjmodel, getattr(mj.mjtObj, f"mjOBJ_{kind.upper()}"), element)
            names[element] = f"{kind} {name!r}" if name else f"{kind} #{element}"
        return names[element]

    def _element_rows(self, field: str):
        """The kind of element a field's rows belong to and each row's element (None: the row is the element),
        found once per field: an audit names thousands of mesh vertices."""
        cache = self._element_row_cache
        if field not in cache:
            m = self.mjmodel
            prefix = field.split("_", 1)[0]
            kind = _FIELD_OBJECTS.get(prefix)
            rows = np.asarray(getattr(m, field)).shape[0] if "." not in field else 0
            if prefix == "dof" and rows == m.nv:
                cache[field] = ("joint", np.asarray(m.dof_jntid))
            elif prefix == "mesh" and field in _MESH_ROWS and rows == np.sum(getattr(m, _MESH_ROWS[field])):
                # the meshes' rows lie end to end in mesh order, each mesh's count of them
                cache[field] = ("mesh", np.repeat(np.arange(m.nmesh), getattr(m, _MESH_ROWS[field])))
            elif kind is None or rows != getattr(m, _COUNTS.get(kind, f"n{kind}"), -1):
                cache[field] = (None, None)
            else:
                cache[field] = (kind, None)
        return cache[field]

    def _geom_name(self, index: int) -> str:
        mj = _mujoco()
        name = mj.mj_id2name(self.mjmodel, mj.mjtObj.mjOBJ_GEOM, int(index))
        return f"geom {name!r}" if name else f"geom #{index}"

    def run(self, n_steps: int, controls=None, nudge: bool = False, policy=None, initial=None):
        """Step the model ``n_steps`` times from its initial state; rows of (qpos, qvel, act).

        ``controls`` is None, an array of ``data.ctrl`` rows (one per step)
        or a callable of the step's start time ``i * dt`` giving one row;
        ``policy`` is None or a closed-loop ``policy(mjmodel, mjdata)``
        giving ``data.ctrl``; ``nudge`` moves every initial coordinate by
        one ulp; ``initial`` is a first row, (qpos, qvel, act) laid out as
        the rows returned.

        Open-loop runs step in MuJoCo's own ``rollout`` (the loop in C,
        bit for bit the same steps as ``mj_step`` in Python); a policy
        needs Python between the steps.
        """
        if self.refusal is not None:
            self._refuse()
        if policy is not None and self.mjmodel.nu:
            data, first = self._start(nudge, initial)
            return self._run_closed_loop(n_steps, data, policy, first)
        return self.run_many(n_steps, [(self, controls, nudge, initial)])[0]

    def run_many(self, n_steps: int, jobs) -> list[np.ndarray]:
        """Several open-loop runs in one call of MuJoCo's rollout, spread over the processor's cores.

        ``jobs`` holds ``(backend, controls, nudge, initial)`` tuples, as the
        arguments of :meth:`run`; the backends' models must have the same
        sizes (a model and its scaled copies do).  Returns the runs' rows.
        """
        import os

        if self.refusal is not None or any(job[0].refusal is not None for job in jobs):
            (self if self.refusal is not None else next(j[0] for j in jobs if j[0].refusal is not None))._refuse()
        mj = _mujoco()  # names a missing MuJoCo before its submodule is imported
        physics = mj.mjtState.mjSTATE_FULLPHYSICS
        spec = _input_spec(mj, jobs[0][0].mjmodel)
        threads = max(1, min(len(jobs), os.cpu_count() or 1))
        # The jobs' models have the same sizes: one data per thread serves them all, and the first also
        # finds each job's initial state.  A thread's data runs several jobs, and rollout sets only the
        # full-physics state between them: each job therefore also gets, at every step, every input that
        # differs between models of these sizes (`_input_spec`), and a zero warm start, so that no run
        # inherits another's.
        datas = [mj.MjData(jobs[0][0].mjmodel) for _ in range(threads)]
        width = mj.mj_stateSize(jobs[0][0].mjmodel, spec)
        initial = np.empty((len(jobs), mj.mj_stateSize(jobs[0][0].mjmodel, physics)))
        inputs = np.empty((len(jobs), n_steps, width))  # filled in place: rollout copies it once more
        models, firsts = [], []
        for k, (backend, controls, nudge, row) in enumerate(jobs):
            m = backend.mjmodel
            data, first = backend._start(nudge, row, datas[0])
            u0 = np.empty(width)
            mj.mj_getState(m, data, initial[k], physics)
            mj.mj_getState(m, data, u0, spec)
            inputs[k] = u0
            ctrl = backend._control_rows(controls, n_steps)
            if ctrl is not None:  # the input state starts with the controls
                inputs[k, :, : m.nu] = ctrl
            models.append(m)
            firsts.append(first)
        if n_steps == 0:
            return [first[None, :] for first in firsts]
        with _thread_pool(threads) as pool:
            states, _ = pool.rollout(
                models,
                datas,
                initial,
                inputs,
                control_spec=spec,
                initial_warmstart=np.zeros((len(jobs), models[0].nv)),
                nstep=n_steps,
            )
        # the full-physics state is laid out by component: time, then qpos, qvel, act
        out = []
        clocks: dict = {}  # each time step's times: MuJoCo adds the step to the time (a copy's step may differ)
        for m, first, rows in zip(models, firsts, states, strict=True):
            start = mj.mj_stateSize(m, mj.mjtState.mjSTATE_TIME)
            run = np.concatenate([first[None, :], rows[:, start : start + m.nq + m.nv + m.na]])
            dt = float(m.opt.timestep)
            if dt not in clocks:
                clocks[dt] = np.add.accumulate(np.full(n_steps, dt))
            _mark_reset(run, rows[:, 0] != clocks[dt])
            out.append(run)
        return out

    def _start(self, nudge: bool, initial, data=None):
        """The initial data (a new one, or `data` reset to this model) and its first row of coordinates.

        `initial` is None (the model's reference pose at rest) or a first row: qpos, qvel, act.
        """
        mj, m = _mujoco(), self.mjmodel
        if data is None:
            data = mj.MjData(m)
        else:
            mj.mj_resetData(m, data)
        if initial is not None:
            data.qpos[:], data.qvel[:] = initial[: m.nq], initial[m.nq : m.nq + m.nv]
            data.act[:] = initial[m.nq + m.nv :]
        if nudge:
            data.qpos[:] = nudged(data.qpos)
            data.qvel[:] = nudged(data.qvel)
        return data, np.concatenate([data.qpos, data.qvel, data.act])

    def _control_rows(self, controls, n_steps: int):
        m = self.mjmodel
        if controls is None or not m.nu or n_steps == 0:
            return None
        if callable(controls):
            dt = float(m.opt.timestep)
            rows = np.array([controls(i * dt) for i in range(n_steps)], dtype=float)
        else:
            rows = np.asarray(controls, dtype=float)
        return rows.reshape(n_steps, m.nu)

    def _run_closed_loop(self, n_steps, data, policy, first):
        mj, m = _mujoco(), self.mjmodel
        nq, nv = m.nq, m.nv
        out = np.empty((n_steps + 1, nq + nv + m.na))
        out[0] = first
        qpos, qvel, act = out[:, :nq], out[:, nq : nq + nv], out[:, nq + nv :]
        # The policy must see the state it acts on: after mj_step, data's positions and velocities are the
        # new ones but everything computed from them (site and body poses, tendon lengths, sensors) is
        # still the last step's.  mj_step1 computes them first, mj_step2 finishes the step: together the
        # same step as mj_step, except for RK4, which mj_step2 does not take (there mj_forward goes first).
        split = int(m.opt.integrator) != int(mj.mjtIntegrator.mjINT_RK4)
        clock = data.time
        for i in range(1, n_steps + 1):
            if split:
                mj.mj_step1(m, data)
                data.ctrl[:] = policy(m, data)
                mj.mj_step2(m, data)
            else:
                mj.mj_forward(m, data)
                data.ctrl[:] = policy(m, data)
                mj.mj_step(m, data)
            clock += m.opt.timestep
            if data.time != clock:  # MuJoCo reset the run: what follows is not this run (`_mark_reset`)
                out[i:] = np.nan
                break
            qpos[i], qvel[i], act[i] = data.qpos, data.qvel, data.act
        return out


class MujocoCompiledRunner:
    """What a runner of another engine shares when MuJoCo's compiler builds its model (MJX, MuJoCo Warp).

    The file is read and compiled as for MuJoCo (``mjcf``, a
    :class:`MujocoRunner`), then put on the other engine's device.  The
    table, scaled copies, saved files, units, time step, coordinates,
    controls and solver stopping rule are MuJoCo's reading of the file;
    a subclass holds the device model (``_device_model``) and gives what
    differs: its settings, what its device stores, its twins and its runs
    (``run_many``), and ``_rebuilt``, its copy of another reading.
    Such an engine runs open loop only here: a closed-loop controller runs
    in ``"mujoco"``.

    Examples
    --------
    >>> from pitheorem.engines.runners.mujoco import MujocoCompiledRunner
    >>> from pitheorem.engines.runners.mjx import MjxRunner
    >>> from pitheorem.engines.runners.warp import WarpRunner
    >>> [(c.__name__, c.engine_label) for c in (MjxRunner, WarpRunner) if issubclass(c, MujocoCompiledRunner)]
    [('MjxRunner', 'MJX'), ('WarpRunner', 'MuJoCo Warp')]
    """

    #: the engine's name in messages (``"MJX"``)
    engine_label = "MuJoCo's compilation"

    #: None: such an engine loads only what MuJoCo's compiler accepts (and it supports)
    refusal = None

    mjcf: MujocoRunner
    _device_model: object

    def _rebuilt(self, mjcf: MujocoRunner, *, same_numbers: bool) -> MujocoCompiledRunner:
        """This runner's engine and settings on another reading of the file.

        With `same_numbers` the device model's numbers stay (a twin's moved
        ones): the reading differs only in the units it records.
        """
        raise NotImplementedError

    def device_model(self):
        """The model on the engine's device that this runner runs."""
        return self._device_model

    @property
    def spec(self):
        """MuJoCo's ``MjSpec`` of the file (where a file written by pitheorem records its units)."""
        return self.mjcf.spec

    # -- the table, scaled copies and files: MuJoCo's reading of the file ------------------------

    def parameters(self):
        return self.mjcf.parameters()

    def scaled(self, factors, scaling, s) -> MujocoCompiledRunner:
        return self._rebuilt(self.mjcf.scaled(factors, scaling, s), same_numbers=False)

    def input_parameters(self) -> list[dict[str, int]]:
        return self.mjcf.input_parameters()

    def coordinate_inputs(self) -> list[int | None]:
        return self.mjcf.coordinate_inputs()

    def scaled_keeping_inputs(self, factors, scaling, s) -> MujocoCompiledRunner:
        return self._rebuilt(self.mjcf.scaled_keeping_inputs(factors, scaling, s), same_numbers=False)

    def in_units(self, units) -> MujocoCompiledRunner:
        """This model, MuJoCo's reading recording other units (the device's numbers are the same)."""
        return self._rebuilt(self.mjcf.in_units(units), same_numbers=True)

    def save(self, path: Path, *, copy_assets: bool = False) -> None:
        # an MJCF file (or a URDF and its settings): MuJoCo and this engine load it alike
        self.mjcf.save(path, copy_assets=copy_assets)

    def written_beside(self, path) -> tuple[str, ...]:
        return self.mjcf.written_beside(path)

    def check_units(self, units) -> None:
        self.mjcf.check_units(units)

    def recorded_units(self) -> dict[str, str] | None:
        return self.mjcf.recorded_units()

    def element_name(self, field: str, row: int) -> str:
        """A row of a stored field, named by its element as MuJoCo names it; ``field[row]`` for the engine's own."""
        if "." in field or not hasattr(self.mjcf.mjmodel, field):
            return f"{field}[{row}]"
        return self.mjcf.element_name(field, row)

    # -- counter-runs: another solver tolerance ------------------------------------------------

    def variant(
        self,
        *,
        tolerance: float | None = None,
        contacts: bool = True,
        inactive_equalities: tuple[int, ...] = (),
        unlimited: tuple[int, ...] = (),
    ) -> MujocoCompiledRunner:
        """A copy run with another solver tolerance, contacts off, some equality constraints inactive or some
        limits off (as :meth:`MujocoRunner.variant`): a counter-run's model."""
        changed = self.mjcf.variant(
            tolerance=tolerance, contacts=contacts, inactive_equalities=inactive_equalities, unlimited=unlimited
        )
        return self._rebuilt(changed, same_numbers=False)

    def equality_names(self) -> list[str]:
        return self.mjcf.equality_names()

    def equality_kinds(self) -> list[str]:
        return self.mjcf.equality_kinds()

    def limit_names(self) -> list[str]:
        return self.mjcf.limit_names()

    def solver_settings(self) -> dict[str, float]:
        return {k: v for k, v in self.mjcf.solver_settings().items() if k == "tolerance"}

    # -- running: MuJoCo's sizes and time step, open loop ---------------------------------------

    def timestep(self) -> float:
        return self.mjcf.timestep()

    def coordinate_dimensions(self):
        return self.mjcf.coordinate_dimensions()

    def control_dimensions(self):
        return self.mjcf.control_dimensions()

    def control_ranges(self):
        return self.mjcf.control_ranges()

    def run(self, n_steps: int, controls=None, nudge: bool = False, policy=None, initial=None) -> np.ndarray:
        """Rows of (qpos, qvel, act) after 0..n_steps steps from the initial state, open loop.

        Raises
        ------
        InvalidRequestError
            For a closed-loop `policy` (run it in ``"mujoco"``).
        """
        if policy is not None:
            raise InvalidRequestError(
                f"{self.engine_label} runs open loop here; run a closed-loop controller in 'mujoco' "
                "(engines.load(path))"
            )
        return self.run_many(n_steps, [(self, controls, nudge, initial)])[0]


#: the element each prefix of a compiled field belongs to, and the count of that element where not n<kind>
_FIELD_OBJECTS = {
    "body": "body",
    "geom": "geom",
    "jnt": "joint",
    "site": "site",
    "cam": "camera",
    "light": "light",
    "mesh": "mesh",
    "tendon": "tendon",
    "actuator": "actuator",
    "sensor": "sensor",
    "eq": "equality",
    "pair": "pair",
    "key": "key",
    "hfield": "hfield",
    "numeric": "numeric",
    "mat": "material",
}


_COUNTS = {"joint": "njnt", "camera": "ncam", "actuator": "nu", "equality": "neq", "material": "nmat"}


_STRUCT_FIELDS = {
    "opt": (
        "timestep",
        "gravity",
        "wind",
        "magnetic",
        "density",
        "viscosity",
        "impratio",
        "tolerance",
        "ls_tolerance",
        "noslip_tolerance",
        "ccd_tolerance",
        "sleep_tolerance",
        "o_margin",
        "o_solref",
        "o_solimp",
        "o_friction",
    ),
    "stat": ("meaninertia", "meanmass", "meansize", "extent", "center"),
}


def _stored_fields(m) -> list[str]:
    """The names of the floating-point fields of a compiled model, in a fixed order (``opt.x`` for structs)."""
    fields = []
    for attr in sorted(dir(m)):
        if attr.startswith("_") or attr.endswith("rgba"):
            continue
        value = getattr(m, attr, None)
        if isinstance(value, np.ndarray) and value.dtype.kind == "f" and value.size:
            fields.append(attr)
    for struct, attrs in _STRUCT_FIELDS.items():
        holder = getattr(m, struct)
        fields.extend(f"{struct}.{a}" for a in attrs if hasattr(holder, a))
    return fields


#: the rollout thread pools kept between batches: (process id, thread count) -> (pool, lock)
_POOLS: dict = {}


#: the mesh fields with a row per vertex, normal, texture coordinate or polygon, and each mesh's count of them
_MESH_ROWS = {
    "mesh_vert": "mesh_vertnum",
    "mesh_normal": "mesh_normalnum",
    "mesh_texcoord": "mesh_texcoordnum",
    "mesh_polynormal": "mesh_polynum",
}


def _mark_reset(run: np.ndarray, off_clock: np.ndarray) -> None:
    """Mark the rows of a run after MuJoCo reset it as not a run (NaN), in place.

    When an acceleration or velocity is NaN, infinite or huge (an unstable
    model, or a time step too long for it), MuJoCo warns, resets the data to
    the model's reference pose and time 0 and goes on; rollout stops at any
    warning (a control beyond 1e10 too) and repeats the state it stopped in
    to the end.  Those rows are no simulation of the model, and a copy
    stopped at the same step would match them bit for bit.  It shows in the
    time: no longer the time steps added up.  `off_clock` holds, per step,
    whether that step's time is not (row 0 of `run` is the initial state,
    before any step).
    """
    reset = np.flatnonzero(off_clock)
    if reset.size:
        run[int(reset[0]) + 1 :] = np.nan


def _input_spec(mj, m) -> int:
    """The inputs a run of `m` takes at every step: its controls, and those of the other inputs that a reset
    sets from the model (active equalities, mocap poses, user data), where the model has any.

    A thread's data runs one job after another, and these could otherwise carry the last job's values
    into the next (a scaled copy's mocap poses differ from the original's).  MuJoCo 4's rollout sets
    them from each job's model itself when they are not sent; they are sent for the 3.x versions whose
    rollout may not.  The applied forces are left out: a reset zeroes them and no open-loop step writes
    them, so they are zero in every job, and sending them at every step made the inputs of a robot with
    many bodies several times larger than its states (the fruit fly's: about 500 numbers a step).
    """
    st = mj.mjtState
    spec = st.mjSTATE_CTRL.value
    if m.neq:
        spec |= st.mjSTATE_EQ_ACTIVE.value
    if m.nmocap:
        spec |= st.mjSTATE_MOCAP_POS.value | st.mjSTATE_MOCAP_QUAT.value
    if m.nuserdata:
        spec |= st.mjSTATE_USERDATA.value
    return spec


@contextmanager
def _thread_pool(threads: int):
    """A MuJoCo rollout pool of `threads` threads, kept for the next batch.

    Starting and stopping the threads costs about as much as a small model's whole batch, so the
    pool is kept.  A batch from a second Python thread while the pool is busy gets a pool of its
    own; a process forked after the pool started (whose copy of it has no threads) keeps its own.
    """
    import os
    import threading

    from mujoco import rollout

    key = (os.getpid(), threads)
    if key not in _POOLS:
        _POOLS[key] = rollout.Rollout(nthread=threads), threading.Lock()
    pool, lock = _POOLS[key]
    if not lock.acquire(blocking=False):
        with rollout.Rollout(nthread=threads) as own:
            yield own
        return
    try:
        yield pool
    finally:
        lock.release()


@atexit.register
def _close_pools() -> None:
    """Stop the kept pools' threads before the interpreter stops."""
    import os

    for (pid, _threads), (pool, _lock) in list(_POOLS.items()):
        if pid == os.getpid():
            pool.close()
    _POOLS.clear()


#: MuJoCo's collision function for each pair of geom types that has one of its own (engine_collision_driver.c,
#: mjCOLLISIONFUNC): the primitive colliders; the other convex pairs go to mjc_Convex (GJK/EPA)
_PRIMITIVE_COLLIDERS = {
    ("plane", "sphere"): "mjc_PlaneSphere",
    ("plane", "capsule"): "mjc_PlaneCapsule",
    ("plane", "cylinder"): "mjc_PlaneCylinder",
    ("plane", "box"): "mjc_PlaneBox",
    ("plane", "ellipsoid"): "mjc_PlaneConvex",
    ("plane", "mesh"): "mjc_PlaneConvex",
    ("sphere", "sphere"): "mjc_SphereSphere",
    ("sphere", "capsule"): "mjc_SphereCapsule",
    ("sphere", "cylinder"): "mjc_SphereCylinder",
    ("sphere", "box"): "mjc_SphereBox",
    ("capsule", "capsule"): "mjc_CapsuleCapsule",
    ("capsule", "box"): "mjc_CapsuleBox",
    ("box", "box"): "mjc_BoxBox",
}

#: stored fields that MuJoCo reads in a step only with an enable flag on: ``dof_length`` (each degree of
#: freedom's length scale, from the body sizes mj_setConst finds) only to put bodies to sleep
#: (engine_sleep.c); a copy whose dof_length is not its original's times a power of s runs alike without it
_READ_ONLY_WITH = {"dof_length": "mjENBL_SLEEP"}

#: MuJoCo's geom types in the order of mjtGeom
_GEOM_TYPES = ("plane", "hfield", "sphere", "capsule", "ellipsoid", "cylinder", "box", "mesh", "sdf")


def _collider(m, a: int, b: int) -> tuple[str, tuple[str, ...]]:
    """The collision function MuJoCo calls for two geoms, in words, and the catalogue's cause paths it takes.

    Where neither geom's body can move along a contact at the reference pose (MuJoCo's translational
    ``body_invweight0`` is 0 for both: a body hinged at its own centre of mass, or one welded to the
    world), MuJoCo's approximate inverse weight of their contacts is 0 and the contacts' softness R is
    its floor ``mjMINVAL`` (engine_core_constraint.c, mj_makeImpedance: ``R = mju_max(mjMINVAL,
    (1-imp)*diagApprox/imp)``; the hidden constant ``mujoco_minval_softness``): that, not the collision
    function, is named (the contacts themselves scale bit for bit), in one text for every such pair,
    whatever its geom types.  A contact's R is an inverse mass (its
    rows' J M^-1 J' is an acceleration per force), so the floor is the copy's true R only under a scaling
    that keeps the mass unit: the copy is bit for bit there, and under no scaling that changes it.
    """
    first, second = sorted((int(m.geom_type[a]), int(m.geom_type[b])))
    kinds = (
        _GEOM_TYPES[first] if first < len(_GEOM_TYPES) else str(first),
        _GEOM_TYPES[second] if second < len(_GEOM_TYPES) else str(second),
    )
    body_a, body_b = int(m.geom_bodyid[a]), int(m.geom_bodyid[b])
    weights = m.body_invweight0[body_a, 0] + m.body_invweight0[body_b, 0]
    apart = m.body_weldid[body_a] != m.body_weldid[body_b]  # two geoms of one rigid body never touch
    if apart and weights == 0 and int(m.geom_condim[a]) <= 3 and int(m.geom_condim[b]) <= 3:
        # one text whatever the geom types, so that the diagnosis takes all such pairs out of collision at once
        return (
            "contact softness R at MuJoCo's floor mjMINVAL (neither body "
            "moves along the contact: inverse weight 0; engine_core_constraint.c mj_makeImpedance, "
            "mujoco_minval_softness): R is an inverse mass, so only a scaling that keeps the mass unit "
            "leaves it exact",
            (),
        )
    margin = ("margin",) if m.geom_margin[a] + m.geom_margin[b] > 0 else ()
    mesh = ("mesh",) if "mesh" in kinds else ()
    primitive = _PRIMITIVE_COLLIDERS.get(kinds)
    if primitive is not None:
        return f"{kinds[0]}-{kinds[1]}: {primitive}", ("primitive", *mesh, *margin)
    if "sdf" in kinds:
        return f"{kinds[0]}-{kinds[1]}: MuJoCo's SDF collision", margin
    if "hfield" in kinds:
        return f"{kinds[0]}-{kinds[1]}: mjc_ConvexHField", ("native_ccd", *mesh, *margin)
    return f"{kinds[0]}-{kinds[1]}: mjc_Convex (GJK/EPA)", ("native_ccd", *mesh, *margin)


def _never_colliding(m) -> np.ndarray:
    """Per geom, whether it can never collide: ``contype`` and ``conaffinity`` both 0, and in no ``<pair>``."""
    never = (np.asarray(m.geom_contype) == 0) & (np.asarray(m.geom_conaffinity) == 0)
    never[np.asarray(m.pair_geom1, dtype=int)] = False
    never[np.asarray(m.pair_geom2, dtype=int)] = False
    return never


def _has_convex_pairs(m) -> bool:
    """Whether two geoms of `m` that may collide (their contype and conaffinity match, on two rigid bodies, or
    an explicit ``<pair>``) meet through no primitive collision function of MuJoCo: through its convex one.

    The geoms are grouped by type, contype and conaffinity (a few groups, however many geoms), and each
    rigid body that holds a group's geoms is noted: two groups meet where their bits match and their geoms
    lie on at least two bodies.
    """
    types = np.asarray(m.geom_type)
    weld = np.asarray(m.body_weldid)[np.asarray(m.geom_bodyid)]
    groups: dict[tuple[int, int, int], set[int]] = {}
    for g in range(m.ngeom):
        key = (int(types[g]), int(m.geom_contype[g]), int(m.geom_conaffinity[g]))
        groups.setdefault(key, set()).add(int(weld[g]))
    pairs = {tuple(sorted((int(types[a]), int(types[b])))) for a, b in zip(m.pair_geom1, m.pair_geom2, strict=True)}
    keys = sorted(groups)
    for i, (type_a, contype_a, affinity_a) in enumerate(keys):
        for type_b, contype_b, affinity_b in keys[i:]:
            bodies = groups[(type_a, contype_a, affinity_a)] | groups[(type_b, contype_b, affinity_b)]
            if (contype_a & affinity_b or contype_b & affinity_a) and len(bodies) > 1:
                pairs.add(tuple(sorted((type_a, type_b))))
    for pair in pairs:
        names = tuple(_GEOM_TYPES[k] if k < len(_GEOM_TYPES) else str(k) for k in pair)
        if names not in _PRIMITIVE_COLLIDERS and "sdf" not in names and names != ("plane", "plane"):
            return True
    return False


def _touching(data) -> frozenset:
    """The geom pairs (ids) of a data's contacts."""
    return frozenset(map(tuple, data.contact.geom[: data.ncon].tolist()))


def write_field(m, field: str, values) -> None:
    """Set a stored field (``"geom_pos"``, ``"opt.gravity"``) of a MuJoCo model `m` to `values`, in place.

    The values are shaped as the field (a scalar option as a number), in
    the field's own precision: a twin's moved numbers, a copy's numbers
    set right.

    Examples
    --------
    >>> import mujoco
    >>> from pitheorem.engines.runners.mujoco import write_field
    >>> m = mujoco.MjModel.from_xml_string("<mujoco><worldbody><geom size='1'/></worldbody></mujoco>")
    >>> write_field(m, "opt.gravity", [0, 0, -1]); write_field(m, "opt.timestep", [0.004])
    >>> m.opt.gravity.tolist(), m.opt.timestep
    ([0.0, 0.0, -1.0], 0.004)
    """
    holder, attr = field_holder(m, field)
    if np.ndim(getattr(holder, attr)) == 0:
        setattr(holder, attr, np.asarray(values).item())
    else:
        getattr(holder, attr)[...] = np.asarray(values).reshape(np.shape(getattr(holder, attr)))


def field_holder(m, field: str):
    """The object and attribute name of a stored field: ``m`` and ``"geom_pos"``, or ``m.opt`` and ``"gravity"``.

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> from pitheorem.engines.runners.mujoco import field_holder
    >>> m = SimpleNamespace(opt=SimpleNamespace(gravity=None))
    >>> field_holder(m, "opt.gravity")[1], field_holder(m, "geom_pos")[1]
    ('gravity', 'geom_pos')
    """
    if "." in field:
        struct, attr = field.split(".")
        return getattr(m, struct), attr
    return m, field


def load_mjcf(path) -> EngineModel:
    """Read an MJCF file as a MuJoCo model: its document (the MJCF format), run by MuJoCo.

    Parameters
    ----------
    path : str or Path

    Returns
    -------
    EngineModel
        Of engine ``"mujoco"``.

    Raises
    ------
    EngineModelError
        When MuJoCo rejects the file (the message names its element), or
        an element cannot be scaled.

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.runners.mujoco import load_mjcf
    >>> load_mjcf(engines.example_path("pendulum.xml")).engine
    'mujoco'
    """
    return EngineModel(MujocoRunner(read_mjcf(path)), "mujoco", str(Path(path)))


# -- URDF files, compiled by MuJoCo's own URDF reader ------------------------------------------------

#: the MuJoCo settings a URDF cannot hold, by group: (attribute, entries with a dimension, dimension, suffix).
#: ``option`` is the model's options, ``compiler`` its compiler's mass bounds, ``geom`` what MuJoCo's URDF
#: reader gives every geom from its default class, ``hinge`` and ``slide`` what it gives every joint of that
#: kind (``q`` is the joint's coordinate: 1 for a hinge, a length for a slide); a setting of no dimension
#: (the solver's tolerance) is kept and written, not scaled, and is no parameter
_URDF_SETTINGS = {
    "option": (
        ("timestep", None, "T", ""),
        ("gravity", (0, 3), "L T^-2", ""),
        ("wind", (0, 3), "L T^-1", ""),
        ("density", None, "M L^-3", ""),
        ("viscosity", None, "M L^-1 T^-1", ""),
        ("o_margin", None, "L", ""),
        ("o_solref", (0, 1), "T", "_time"),
        ("o_solimp", (2, 3), "L", "_width"),
        ("o_friction", (2, 5), "L", "_torsional_rolling"),
        ("ccd_tolerance", None, "L", ""),
        ("tolerance", None, None, ""),  # no dimension: copied unchanged (0 runs every iteration: exact)
    ),
    "compiler": (
        ("boundmass", None, "M", ""),
        ("boundinertia", None, "M L^2", ""),
        ("settotalmass", None, "M", ""),
    ),
    "geom": (
        ("friction", (1, 3), "L", "_torsional_rolling"),
        ("solref", (0, 1), "T", "_time"),
        ("solimp", (2, 3), "L", "_width"),
        ("margin", None, "L", ""),
        ("gap", None, "L", ""),
        ("density", None, "M L^-3", ""),
    ),
    "hinge": (
        ("solref_limit", (0, 1), "T", "_time"),
        ("solimp_limit", (2, 3), "q", "_width"),
        ("solref_friction", (0, 1), "T", "_time"),
        ("solimp_friction", (2, 3), "q", "_width"),
        ("margin", None, "q", ""),
        ("eq_solref", (0, 1), "T", "_time"),  # of each <mimic> of a joint of this kind (a joint equality)
        ("eq_solimp", (2, 3), "q", "_width"),
    ),
}
_URDF_SETTINGS["slide"] = _URDF_SETTINGS["hinge"]
_JOINT_Q = {"hinge": "1", "slide": "L"}
#: the suffix of the settings file a saved URDF's MuJoCo settings are written to
SETTINGS_SUFFIX = ".mujoco.json"
#: where a URDF names the folder MuJoCo looks for its meshes in: its extension ``<mujoco><compiler meshdir>``
MESH_FOLDER = ("mujoco/compiler", "meshdir")


def _setting_name(group: str, attr: str, suffix: str) -> str:
    return "g" if attr == "gravity" else "timestep" if attr == "timestep" else f"{group}_{attr}{suffix}"


def _setting_dimension(group: str, text: str):
    return dim(text.replace("q", _JOINT_Q.get(group, "1")))


def _joint_groups(mj, spec) -> list[str]:
    """The joint kinds of a URDF's spec (MuJoCo makes hinges and slides of it), in a fixed order."""
    types = {int(j.type) for j in spec.joints}
    return [g for g, t in (("hinge", mj.mjtJoint.mjJNT_HINGE), ("slide", mj.mjtJoint.mjJNT_SLIDE)) if int(t) in types]


def _holders(mj, spec, group: str) -> list:
    """The spec's objects a group of settings is written on."""
    if group == "option":
        return [spec.option]
    if group == "compiler":
        return [spec.compiler]
    if group == "geom":
        return list(spec.geoms)
    kind = int(getattr(mj.mjtJoint, f"mjJNT_{group.upper()}"))
    return [j for j in spec.joints if int(j.type) == kind] + _mimics(mj, spec, kind)


def _mimics(mj, spec, kind: int) -> list:
    """The joint equalities (a URDF's ``<mimic>``) whose first joint is of `kind`."""
    types = {j.name: int(j.type) for j in spec.joints}
    return [e for e in spec.equalities if e.type == mj.mjtEq.mjEQ_JOINT and types.get(e.name1) == kind]


def _refuse_mixed_mimics(mj, spec, path: str) -> None:
    """Refuse a ``<mimic>`` whose offset or multiplier has a dimension (the URDF format does not list them)."""
    types = {j.name: int(j.type) for j in spec.joints}
    slide = int(mj.mjtJoint.mjJNT_SLIDE)
    for e in spec.equalities:
        if e.type != mj.mjtEq.mjEQ_JOINT:
            continue
        offset, multiplier = float(e.data[0]), float(e.data[1])
        mixed = types.get(e.name1) != types.get(e.name2) and multiplier != 0
        if (offset != 0 and types.get(e.name1) == slide) or mixed:
            raise EngineModelError(
                path,
                f"joint {e.name1!r} mimic",
                "its offset (a length) or its multiplier between a prismatic and a revolute joint has a "
                "dimension, and the URDF format does not list it, so a scaled copy would keep it; "
                "use offset 0 and joints of one kind",
            )


def _read_urdf_settings(mj, spec) -> dict:
    """The settings MuJoCo's URDF reader left in `spec`: its options, and its default class's geom and joint."""
    sources = {"option": spec.option, "compiler": spec.compiler, "geom": spec.default.geom}
    out = {}
    for group in ("option", "compiler", "geom", *_joint_groups(mj, spec)):
        holder = sources.get(group, spec.default.joint)
        out[group] = {}
        for attr, entries, _dimension, _suffix in _URDF_SETTINGS[group]:
            source = spec.default.equality if attr.startswith("eq_") else holder
            value = np.asarray(getattr(source, attr.removeprefix("eq_")), dtype=float)
            out[group][attr] = value.tolist() if entries is not None else float(value)
    return out


def _apply_urdf_settings(mj, spec, settings: dict) -> None:
    """Write `settings` on `spec`: the options, and every geom and joint MuJoCo's URDF reader made.

    A geom the reader made massless (a visual one, of density 0) stays massless.
    """
    for group, values in settings.items():
        for holder in _holders(mj, spec, group):
            equality = isinstance(holder, mj.MjsEquality)
            for attr, value in values.items():
                if group == "geom" and attr == "density" and holder.density == 0:
                    continue
                if attr.startswith("eq_") != equality:  # a joint's settings, or a mimic's
                    continue
                value = np.asarray(value, dtype=float) if isinstance(value, list) else value
                setattr(holder, attr.removeprefix("eq_"), value)


def add_joint_motors(mj, spec) -> list[str]:
    """Give every hinge and slide joint of `spec` a motor: its input is the joint's torque or force.

    One ``<motor>`` per joint, in the spec's joint order (the order of
    ``qpos``), named after its joint, with gear 1 and no control range: the
    input ``ctrl`` is the torque (a hinge, M L^2 T^-2) or force (a slide,
    M L T^-2) itself, as PyBullet's ``TORQUE_CONTROL`` takes it.  The
    joint's ``actuatorfrcrange`` (MuJoCo's URDF reader writes a joint's
    ``effort`` limit there) still caps the force the motor applies.

    Returns the names of the joints given a motor.

    Examples
    --------
    >>> import mujoco
    >>> from pitheorem.engines.runners.mujoco import add_joint_motors
    >>> spec = mujoco.MjSpec.from_string(
    ...     '<mujoco><worldbody><body><joint name="j" type="slide"/><geom size="0.1"/></body></worldbody></mujoco>'
    ... )
    >>> add_joint_motors(mujoco, spec), spec.compile().actuator_gear[0, 0]
    (['j'], np.float64(1.0))
    """
    kinds = (int(mj.mjtJoint.mjJNT_HINGE), int(mj.mjtJoint.mjJNT_SLIDE))
    names = []
    for joint in spec.joints:
        if int(joint.type) not in kinds:
            continue
        motor = spec.add_actuator(name=joint.name, target=joint.name, trntype=mj.mjtTrn.mjTRN_JOINT)
        motor.set_to_motor()
        motor.ctrllimited = mj.mjtLimited.mjLIMITED_FALSE
        motor.forcelimited = mj.mjtLimited.mjLIMITED_FALSE
        names.append(joint.name)
    return names


class UrdfInMujoco:
    """A URDF document as MuJoCo's runner holds a model: compiled by MuJoCo's URDF reader, with its settings.

    Parameters
    ----------
    urdf : UrdfDocument
        The URDF file's numbers, each with its address (the URDF format).
    settings : dict, optional
        The MuJoCo settings a URDF cannot hold, by group (``option``,
        ``compiler``, ``geom``, ``hinge``, ``slide``), as :meth:`settings`
        returns them; by default those MuJoCo's reader leaves (its
        defaults, and the ``<mujoco>`` block's options).

    Raises
    ------
    EngineModelError
        When MuJoCo's URDF reader or compiler rejects the file (the
        message is MuJoCo's), or `settings` is not a table of this file's
        settings (the message names the group or the setting).

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.fileformats.urdf import read_urdf
    >>> from pitheorem.engines.runners.mujoco import UrdfInMujoco
    >>> document = UrdfInMujoco(read_urdf(engines.example_path("hinged_rod.urdf")))
    >>> document.mjmodel.nq, document.settings()["option"]["timestep"]
    (1, 0.002)
    """

    def __init__(self, urdf: UrdfDocument, settings: dict | None = None):
        import warnings

        mj = _mujoco()
        self.urdf, self.path, self.refusal = urdf, urdf.path, None
        text = urdf.portable_text()  # meshes by absolute path; package:// found as the URDF format finds it
        try:
            spec = mj.MjSpec.from_string(text if text is not None else urdf.text())
        except ValueError as err:
            raise EngineModelError(self.path, "MuJoCo's URDF reader", _first_line(str(err))) from None
        if text is None:
            spec.modelfiledir = str(urdf.source_dir)
        _refuse_mixed_mimics(mj, spec, self.path)
        add_joint_motors(mj, spec)  # a URDF states no actuators: a torque or force per movable joint
        found = _read_urdf_settings(mj, spec)
        if settings is not None:
            _check_urdf_settings(self.path, settings, found)
            _apply_urdf_settings(mj, spec, settings)
        self._settings = found if settings is None else json.loads(json.dumps(settings))
        self.spec = spec
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                self.mjmodel = spec.compile()
        except ValueError as err:
            raise _compile_refusal(self.path, err, spec) from None
        self._coordinates = None

    @property
    def fixed_units(self) -> dict[str, str]:
        """The units a URDF file is in (SI, by its specification)."""
        return dict(self.urdf.fixed_units)

    def settings(self) -> dict:
        """The MuJoCo settings a URDF cannot hold, by group: a copy, as the settings file holds them."""
        return json.loads(json.dumps(self._settings))

    def parameters(self) -> list[Parameter]:
        """The URDF's numbers, then each MuJoCo setting with a dimension (the gravity as its magnitude ``g``)."""
        out = self.urdf.parameters()
        for group, values in self._settings.items():
            for attr, entries, dimension, suffix in _URDF_SETTINGS[group]:
                value = values[attr]
                if dimension is None:
                    continue
                if attr == "gravity":
                    value = (math.hypot(*value),)
                elif entries is not None:
                    value = tuple(value[entries[0] : entries[1]])
                else:
                    value = (value,)
                where = "option" if group in ("option", "compiler") else f"every {group}"
                out.append(
                    Parameter(
                        _setting_name(group, attr, suffix),
                        f"{group} {attr}" + (f" of {where}" if group not in ("option", "compiler") else ""),
                        value,
                        _setting_dimension(group, dimension),
                        "engine",
                        f"settings file ({SETTINGS_SUFFIX})",
                        note="a MuJoCo setting a URDF cannot hold",
                    )
                )
        return out

    def input_parameters(self) -> list[dict[str, int]]:
        """None: the joints' motors take the joint forces themselves, with no gain in the file to carry a factor."""
        return []

    def coordinate_inputs(self) -> list[int | None]:
        return [None] * len(self.coordinate_dimensions()[0])

    def scaled(self, factors, scaling=None, s=None, *, keep_inputs: bool = False) -> UrdfInMujoco:
        """A copy: the URDF scaled by address, each setting multiplied by its factor, compiled again.

        `keep_inputs` changes nothing: the model has no actuators.
        """
        settings = self.settings()
        for group, values in settings.items():
            for attr, entries, dimension, suffix in _URDF_SETTINGS[group]:
                factor = factors.get(_setting_name(group, attr, suffix), 1.0)
                if factor == 1.0 or dimension is None:
                    continue
                if attr == "gravity":
                    values[attr] = [v * factor for v in values[attr]]
                elif entries is not None:
                    start, stop = entries
                    values[attr][start:stop] = [v * factor for v in values[attr][start:stop]]
                else:
                    values[attr] *= factor
        copy = UrdfInMujoco(self.urdf.scaled(factors), settings)
        copy._coordinates = self.coordinate_dimensions()
        return copy

    def check_units(self, units) -> None:
        """Refuse units other than SI: a URDF file is in SI units by its specification."""
        if dict(units) != self.fixed_units:
            refuse_units(self.path, units)

    def recorded_units(self) -> dict[str, str] | None:
        """None: a URDF file records no units (it is in SI)."""
        return None

    def written_beside(self, path) -> tuple[str, ...]:
        """The settings file :meth:`save` writes beside `path`."""
        return (f"{path}{SETTINGS_SUFFIX}",)

    def save(self, path, *, copy_assets: bool = False) -> None:
        """Write the URDF (meshes relative to it, or copied beside it) and its MuJoCo settings beside it."""
        self.urdf.save(path, copy_assets=copy_assets)
        Path(f"{path}{SETTINGS_SUFFIX}").write_text(json.dumps(self._settings, indent=2))

    def coordinate_dimensions(self):
        """Names and dimensions of qpos and qvel entries: a hinge's angle is 1, a slide's position a length.

        A URDF's spherical joint is MuJoCo's ball (a quaternion, then an angular velocity of three) and
        its floating joint a free joint (a position and a quaternion), named ``qpos[NAME][k]`` as in MJCF.
        """
        if self._coordinates is None:
            mj, m = _mujoco(), self.mjmodel
            names, dims = [], []
            for label, rate in (("qpos", 0), ("qvel", 1)):
                turn = [dim("1")] * (4 if rate == 0 else 3)  # a quaternion, or an angular velocity
                for j in range(m.njnt):
                    jtype = int(m.jnt_type[j])
                    if jtype == int(mj.mjtJoint.mjJNT_FREE):
                        per = [dim("L")] * 3 + turn
                    elif jtype == int(mj.mjtJoint.mjJNT_BALL):
                        per = turn
                    else:
                        per = [dim(_JOINT_Q["hinge" if jtype == int(mj.mjtJoint.mjJNT_HINGE) else "slide"])]
                    jname = mj.mj_id2name(m, mj.mjtObj.mjOBJ_JOINT, j) or f"joint{j}"
                    for k, d in enumerate(per):
                        names.append(f"{label}[{jname}]" + (f"[{k}]" if len(per) > 1 else ""))
                        dims.append(d * dim("T") ** (-rate))
            self._coordinates = (names, dims)
        return self._coordinates

    def control_dimensions(self) -> list:
        """One per movable joint (its motor, :func:`add_joint_motors`): a torque (hinge) or a force (slide)."""
        mj, m = _mujoco(), self.mjmodel
        slide = int(mj.mjtJoint.mjJNT_SLIDE)
        return [
            (JointKind.SLIDE if int(m.jnt_type[int(m.actuator_trnid[i, 0])]) == slide else JointKind.HINGE).force
            for i in range(m.nu)
        ]

    def activation_dimensions(self) -> list:
        return []


def _first_line(text: str) -> str:
    return text.strip().splitlines()[0] if text.strip() else "rejected"


def _check_urdf_settings(path: str, settings, found: dict) -> None:
    """Refuse a settings table that is not one of this file's, naming the group or setting at fault."""
    if not isinstance(settings, dict) or sorted(settings) != sorted(found):
        got = sorted(settings) if isinstance(settings, dict) else type(settings).__name__
        raise EngineModelError(
            path, "MuJoCo settings", f"groups {got}; this file's are {sorted(found)} (as settings() returns them)"
        )
    for group, values in found.items():
        given = settings[group]
        if not isinstance(given, dict) or sorted(given) != sorted(values):
            raise EngineModelError(path, f"MuJoCo settings {group!r}", f"must set exactly {sorted(values)}")
        for attr, value in values.items():
            shape = len(value) if isinstance(value, list) else None
            v = given[attr]
            ok = (
                isinstance(v, list) and len(v) == shape and all(_finite(x) for x in v)
                if shape is not None
                else _finite(v)
            )
            if not ok:
                size = f"a list of {shape} finite numbers" if shape is not None else "a finite number"
                raise EngineModelError(path, f"MuJoCo setting {group}.{attr}", f"got {v!r}; use {size}")
            if attr.startswith(("solref", "o_solref")) and v[0] <= 0:
                raise EngineModelError(
                    path,
                    f"MuJoCo setting {group}.{attr}",
                    f"got {v!r}; a time constant and a damping ratio (both > 0) scale, a stiffness and a "
                    "damping (negative) mix dimensions",
                )


def _finite(x) -> bool:
    return isinstance(x, int | float) and not isinstance(x, bool) and math.isfinite(x)


def urdf_runner(path, *, settings=None) -> MujocoRunner:
    """A URDF file compiled by MuJoCo's URDF reader, with the settings saved beside it: the runner of
    :func:`load_urdf` (MJX puts the same model on its device).

    Parameters
    ----------
    path : str or Path
    settings : str, Path or bool, optional
        The settings file: by default ``<path>.mujoco.json`` if it exists
        (one :meth:`UrdfInMujoco.save` wrote); ``False`` ignores it.

    Returns
    -------
    MujocoRunner

    Examples
    --------
    >>> from pitheorem import engines
    >>> from pitheorem.engines.runners.mujoco import urdf_runner
    >>> urdf_runner(engines.example_path("hinged_rod.urdf")).mjmodel.njnt
    1
    """
    path = Path(path)
    document = read_urdf(path, mesh_folder=MESH_FOLDER)
    saved = Path(f"{path}{SETTINGS_SUFFIX}") if settings is None or settings is True else settings
    table = None
    if saved is not False:
        saved = Path(saved)
        if saved.is_file():
            try:
                table = json.loads(saved.read_text())
            except (ValueError, UnicodeDecodeError) as err:
                raise EngineModelError(str(saved), "settings", f"not a MuJoCo settings file ({err})") from None
        elif settings not in (None, True):
            raise EngineModelError(str(saved), "", "no such settings file")
    return MujocoRunner(UrdfInMujoco(document, table))


#: what a URDF's author can do about MuJoCo's refusals that PyBullet does not share: a fragment of MuJoCo's
#: message, and the remedy appended to it (MuJoCo 4.0's XML reference: compiler balanceinertia, mesh file)
_URDF_REMEDIES = (
    (
        "mass and inertia of moving bodies",
        "give the link an <inertial> with a mass and moments of inertia above 1e-15 (mjMINVAL), as every "
        "moving link needs in MuJoCo",
    ),
    (
        "inertia must satisfy A + B >= C",
        "the link's principal moments of inertia break the triangle inequality; correct its <inertia>, or put "
        '<mujoco><compiler balanceinertia="true"/></mujoco> inside <robot>, and MuJoCo sets the three moments '
        "of such a link to their mean (which changes its dynamics)",
    ),
    (
        "inertia must have positive eigenvalues",
        "the link's <inertia> (ixx to izz) is no positive definite matrix, as MuJoCo needs: a moment of 0 "
        "or products of inertia too large for the moments",
    ),
    (
        "no decoder found for mesh file",
        "MuJoCo reads mesh files in STL, OBJ and MSH only; convert the mesh to one of them (a Collada .dae "
        "file, say, to .obj), or load the file with engine='pybullet'",
    ),
)


def _compile_refusal(path: str, err: ValueError, spec) -> EngineModelError:
    """MuJoCo's compiler's refusal of a URDF: the element it names (its ``Element name '...'`` line: a link, or
    a mesh and the links that use it), and a remedy where one is known (a refusal that PyBullet does not
    share: a point-mass link, unbalanced or singular moments of inertia, a mesh format MuJoCo cannot read, an
    ASCII STL file)."""
    text = str(err)
    named = re.search(r"Element name '([^']*)'", text)
    reason = _first_line(text)
    remedies = [remedy for fragment, remedy in _URDF_REMEDIES if fragment in text]
    stl = re.search(r"stl_decoder: .* in STL file '([^']*)'", text)
    if stl and _ascii_stl(Path(spec.modelfiledir or Path(path).parent, spec.meshdir or "", stl.group(1))):
        remedies.append(
            "it is (it begins with 'solid' and a facet), and MuJoCo reads binary STL only: save it as binary STL or OBJ"
        )
    if remedies:
        reason += "; " + "; ".join(remedies) + " (PyBullet runs the file as it is)"
    culprit = _refused_element(spec, named.group(1), text) if named and named.group(1) else "MuJoCo's compiler"
    return EngineModelError(path, culprit, reason)


def _refused_element(spec, name: str, text: str) -> str:
    """The element MuJoCo's refusal names, which its message gives by name only: a mesh (named after its file, as
    MuJoCo's URDF reader names it) where the refusal is about a mesh, with the links that use it; else a link."""
    about_mesh = re.search(r"mesh|STL|OBJ|decoder", text, flags=re.IGNORECASE) is not None
    if about_mesh and spec.mesh(name) is not None:
        users = sorted({geom.parent.name for geom in spec.geoms if geom.meshname == name})
        shown = names_text(users, code=repr, shown=3, in_all=False)
        return f"mesh {name!r}" + (f" (of link{'s' if len(users) > 1 else ''} {shown})" if users else "")
    return f"link {name!r}"


def _ascii_stl(path) -> bool:
    """Whether an STL file is ASCII: it begins with ``solid`` and a line of text (a binary one has 80 bytes of any
    header, which may begin with ``solid`` too, then a count of triangles)."""
    try:
        with open(path, "rb") as f:
            head = f.read(512)
    except OSError:
        return False
    return head.lstrip().startswith(b"solid") and b"facet" in head


def load_urdf(path, *, settings=None) -> EngineModel:
    """Read a URDF file as a MuJoCo model: compiled by MuJoCo's own URDF reader, with its MuJoCo settings.

    MuJoCo reads the file's ``<mujoco>`` block (compiler, option and size),
    merges links joined by fixed joints, drops the visual geoms unless the
    block keeps them, and welds the root link to the world.  Mesh files are
    found in the block's ``<compiler meshdir>`` first, where it has one (as
    MuJoCo finds them), then as the URDF format finds them: beside the
    file, or a ``package://NAME/...`` path in the folders above it.  Every
    movable joint gets a motor (:func:`add_joint_motors`).

    Parameters
    ----------
    path : str or Path
    settings : str, Path or bool, optional
        The settings file to read: by default ``<path>.mujoco.json`` if it
        exists (a saved copy's); ``False`` ignores it.

    Returns
    -------
    EngineModel
        Of engine ``"mujoco"``; its parameters are the URDF's numbers and
        the MuJoCo settings a URDF cannot hold.

    Raises
    ------
    EngineModelError
        For a file the URDF format or MuJoCo rejects, and a settings file
        that is missing or not one of this file's (the message names it).

    Examples
    --------
    >>> from pitheorem import engines
    >>> model = engines.load(engines.example_path("hinged_rod.urdf"), engine="mujoco")
    >>> model.engine, [p.name for p in model.parameters if p.source == "engine"][:2]
    ('mujoco', ['timestep', 'g'])
    """
    return EngineModel(urdf_runner(path, settings=settings), "mujoco", str(Path(path)))
