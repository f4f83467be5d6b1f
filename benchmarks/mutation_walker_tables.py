"""Mutants of the MJCF walker's plans and tables, listed by rule and by hand: does the suite notice each?

mutmut (``benchmarks/MUTATION.md``) mutates code inside functions only, and the walker's dimensions of
geoms, sensors and solrefs now live in module-level tables (``_GEOM_PLAN``, ``_SENSOR_READINGS``,
``_OWNED_SENSORS``) and small plan functions.  This script makes each entry of those tables wrong (a
dimension swapped for another, a component range moved, a sensor's reading or rate flipped) and adds the
hand-listed mutants of the plan functions and of the walker lines changed with them (a tendon's joints
from the compiled model, a sensor's lookup, the plan's choice of solref form).  Each mutant rewrites
``mjcf.py``, runs ``tests/test_engines_mjcf.py``, ``tests/test_engines_mjcfunits.py`` and
``tests/test_engines_probes.py`` (stopping at the first failure) and restores the file.

Run from the repository root (not part of ``make test``; about 15 minutes on two cores)::

    python benchmarks/mutation_walker_tables.py            # every mutant
    python benchmarks/mutation_walker_tables.py 6 35       # the mutants numbered 6 and 35
"""

import pathlib
import re
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent
F = ROOT / "pitheorem/engines/fileformats/mjcf.py"
src = F.read_text()
#: a wrong dimension for each right one the tables hold (any other, a dim("..."), becomes a mass)
WRONG = {"_FORCE": "_TORQUE", "_TORQUE": "_FORCE", "_L": "_M", "_ONE": "_L", "_T": "_L", "_M": "_L"}
muts = []  # (label, the line as it is, the line mutated)


def table_lines(name: str) -> list[str]:
    """The lines of the module-level table `name` (a dict closed by "}" or a tuple closed by ")")."""
    start = src.index(f"\n{name} = ")
    closing = "\n)\n" if src[start:].split("\n", 2)[1].rstrip().endswith("(") else "\n}\n"
    return src[start : src.index(closing, start)].splitlines()


for line in table_lines("_SENSOR_READINGS"):
    m = re.match(r'(\s+"mjSENS_\w+": )(.+),$', line)
    if m:
        muts.append(("sensor reading " + line.strip(), line, f"{m.group(1)}{WRONG.get(m.group(2), '_M')},"))
for line in table_lines("_OWNED_SENSORS"):
    for m in re.finditer(r'"(mjSENS_\w+)": \("(q|force)", ([01])\)', line):
        old = m.group(0)
        flip_what = old.replace(f'"{m.group(2)}"', '"force"' if m.group(2) == "q" else '"q"')
        flip_rate = old.replace(f", {m.group(3)})", f", {1 - int(m.group(3))})")
        for new in (flip_what, flip_rate):
            muts.append(("owned sensor " + old, line, line.replace(old, new)))
for line in table_lines("_GEOM_PLAN"):
    m = re.match(r'(\s+\("\w+", )(_\w+|dim\("[^"]+"\))(, .*)$', line)
    if m:
        muts.append(("geom plan " + line.strip(), line, f"{m.group(1)}{WRONG.get(m.group(2), '_M')}{m.group(3)}"))
        if "slice(1, 3)" in line:
            muts.append(("geom plan entries " + line.strip(), line, line.replace("slice(1, 3)", "slice(0, 3)")))
            muts.append(("geom plan entries " + line.strip(), line, line.replace("slice(1, 3)", "slice(1, 2)")))
# the plan functions and the walker's new lines: by hand
hand = [
    (
        'return ((attr, dim("T^-2"), slice(0, 1), "_stiffness"), (attr, dim("T^-1"), slice(1, 2), "_damping"))',
        'return ((attr, dim("T^-1"), slice(0, 1), "_stiffness"), (attr, dim("T^-1"), slice(1, 2), "_damping"))',
    ),
    (
        'return ((attr, dim("T^-2"), slice(0, 1), "_stiffness"), (attr, dim("T^-1"), slice(1, 2), "_damping"))',
        'return ((attr, dim("T^-2"), slice(0, 1), "_stiffness"), (attr, dim("T^-2"), slice(1, 2), "_damping"))',
    ),
    (
        'return ((attr, dim("T^-2"), slice(0, 1), "_stiffness"), (attr, dim("T^-1"), slice(1, 2), "_damping"))',
        'return ((attr, dim("T^-2"), slice(0, 1), "_stiffness"), (attr, dim("T^-1"), slice(0, 2), "_damping"))',
    ),
    ('return ((attr, _T, slice(0, 1), "_timeconst"),)', 'return ((attr, _T, slice(0, 2), "_timeconst"),)'),
    ('return ((attr, _T, slice(0, 1), "_timeconst"),)', 'return ((attr, _T**-1, slice(0, 1), "_timeconst"),)'),
    ('lambda: ((attr, violation, slice(2, 3), "_width"),)', 'lambda: ((attr, violation, slice(1, 3), "_width"),)'),
    ('lambda: ((attr, violation, slice(2, 3), "_width"),)', 'lambda: ((attr, _L, slice(2, 3), "_width"),)'),
    (
        'terms.append(("stiffness", kind.per(force, i + 1), index, suffix))',
        'terms.append(("stiffness", kind.per(force, i + 1, rate=1), index, suffix))',
    ),
    (
        'terms.append(("damping", kind.per(force, i + 1, rate=1), index, suffix))',
        'terms.append(("damping", kind.per(force, i + 1), index, suffix))',
    ),
    (
        'armature = ("armature", kind.per(force, 1, rate=2), _EVERY, "")',
        'armature = ("armature", kind.per(force, 1, rate=1), _EVERY, "")',
    ),
    (
        'return (*terms, armature, ("frictionloss", force, _EVERY, ""), ("actfrcrange", force, _EVERY, ""))',
        'return (*terms, armature, ("frictionloss", kind.q, _EVERY, ""), ("actfrcrange", force, _EVERY, ""))',
    ),
    (
        'return (*terms, armature, ("frictionloss", force, _EVERY, ""), ("actfrcrange", force, _EVERY, ""))',
        'return (*terms, armature, ("frictionloss", force, _EVERY, ""), ("actfrcrange", kind.q, _EVERY, ""))',
    ),
    (
        'coordinates = tuple((a, kind.q, _EVERY, "") for a in ("range", "ref", "springref", "margin"))',
        'coordinates = tuple((a, kind.q, _EVERY, "") for a in ("range", "ref", "springref"))',
    ),
    (
        'coordinates = tuple((a, kind.q, _EVERY, "") for a in ("range", "ref", "springref", "margin"))',
        'coordinates = tuple((a, _L, _EVERY, "") for a in ("range", "ref", "springref", "margin"))',
    ),
    (
        '*_solref_plan("solref_limit", direct=limit_direct),',
        '*_solref_plan("solref_limit", direct=friction_direct),',
    ),
    ('*_solimp_plan("solimp_limit", q),', '*_solimp_plan("solimp_limit", _L),'),
    ("return (*coordinates, *_spring_plan(kind), *softness)", "return (*coordinates, *softness)"),
    (
        'lambda: (*_GEOM_PLAN, *_solref_plan("solref", direct=direct), *_solimp_plan("solimp", _L)),',
        'lambda: (*_GEOM_PLAN, *_solref_plan("solref", direct=not direct), *_solimp_plan("solimp", _L)),',
    ),
    (
        'lambda: (*_GEOM_PLAN, *_solref_plan("solref", direct=direct), *_solimp_plan("solimp", _L)),',
        'lambda: (*_GEOM_PLAN, *_solref_plan("solref", direct=direct), *_solimp_plan("solimp", _M)),',
    ),
    (
        'lambda: tuple((a, _L, _EVERY, "") for a in attrs if hasattr(element, a))',
        'lambda: tuple((a, _L, _EVERY, "") for a in attrs[:-1] if hasattr(element, a))',
    ),
    ("            if kind == joint:", "            if kind != joint:"),
    (
        "                jk = _joint_kind(self.mj, model.jnt_type[objects[k]])",
        "                jk = _joint_kind(self.mj, model.jnt_type[objects[0]])",
    ),
    ("                joints.append((k, jk))", "                joints.append((0, jk))"),
    (
        "self.fixed_coefficient(float(self.model.wrap_prm[first + k]), ident, path, k, q / jk.q)",
        "self.fixed_coefficient(float(self.model.wrap_prm[first + k]), ident, path, k, jk.q / q)",
    ),
    (
        "        kind = joints[0][1] if joints else JointKind.SLIDE\n        self.tendon_kinds",
        "        kind = joints[-1][1] if joints else JointKind.SLIDE\n        self.tendon_kinds",
    ),
    (
        "        kind = joints[0][1] if joints else JointKind.SLIDE\n        self.tendon_kinds",
        "        kind = joints[0][1] if joints else JointKind.HINGE\n        self.tendon_kinds",
    ),
    ("        if not over_joints:  # a spatial", "        if over_joints:  # a spatial"),
    ("            return what\n", "            return _ONE\n"),
    ('        if what == "force":\n            return force', '        if what != "force":\n            return force'),
    ("        return q / _T if rate else q\n", "        return q / _T if not rate else q\n"),
    ("            elif not entrywise:\n", "            elif entrywise:\n"),
    (
        '            if values == default:\n                source = "default"',
        '            if values != default:\n                source = "default"',
    ),
    (
        '                continue\n            name = f"{ident}_{tail}"',
        '                pass\n            name = f"{ident}_{tail}"',
    ),
    ("solref = _floats(geom.solref)\n", "solref = _floats(geom.solimp)\n"),
    (
        'return _softness_plan(q, read["solref_limit"][0] < 0, read["solref_friction"][0] < 0), read',
        'return _softness_plan(q, read["solref_limit"][0] < 0, read["solref_limit"][0] < 0), read',
    ),
    (
        "self.add_each(kind, elem, ident, path, _solref_plan(attr, direct=ref[0] < 0), read={attr: ref})",
        "self.add_each(kind, elem, ident, path, _solref_plan(attr, direct=ref[0] <= 0), read={attr: ref})",
    ),
    ("entrywise = has_nan and default[0] == default[0]", "entrywise = has_nan"),
]
for old, new in hand:
    muts.append(("hand " + old.strip()[:60], old, new))
TESTS = ("tests/test_engines_mjcf.py", "tests/test_engines_mjcfunits.py", "tests/test_engines_probes.py")


def tests_status() -> subprocess.CompletedProcess:
    """The tests run on the file as it is now (pytest's status: 0 when they pass)."""
    return subprocess.run(
        [sys.executable, "-m", "pytest", "-q", "-x", "-p", "no:cacheprovider", "-n", "2", *TESTS],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )


if __name__ == "__main__":
    clean = tests_status()  # they must pass unmutated (and pytest must run), or no mutant can be judged
    if clean.returncode != 0:
        sys.exit(f"the tests do not pass on the walker as it is:\n{clean.stdout[-2000:]}{clean.stderr[-2000:]}")
    only = sys.argv[1:]
    killed = survived = 0
    for i, (label, old, new) in enumerate(muts):
        if only and str(i) not in only:
            continue
        assert src.count(old) == 1, (label, old, src.count(old))
        F.write_text(src.replace(old, new))
        try:
            start = time.time()
            caught = tests_status().returncode != 0  # a failure, or an error on import: noticed either way
        finally:
            F.write_text(src)
        killed += caught
        survived += not caught
        print(f"{i:3d} {'KILLED  ' if caught else 'SURVIVED'} {time.time() - start:5.1f}s {label[:110]}", flush=True)
    print("killed", killed, "survived", survived, "of", killed + survived)
