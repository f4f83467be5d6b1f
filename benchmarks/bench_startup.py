"""Time start-up against `import sympy`, in one run, and print ratios.

Each command is a fresh interpreter (subprocess), run interleaved with the
baseline ``python -c "import sympy"`` several times; the medians are compared.
Also checks which heavy modules a command loads.

Targets (issues 13 and 25): ``import pitheorem`` within 1.3 times ``import sympy``;
``pitheorem groups`` within 1.5 times, timed as a newcomer runs it: the
installed ``pitheorem`` console script (when this interpreter has one) on
the shipped ``example:hinged_rod``.  The MJCF example is timed too, for
information: reading MJCF loads MuJoCo itself, which no lazy import avoids.

Run: python benchmarks/bench_startup.py [--quick]
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROD = str(Path(__file__).resolve().parent.parent / "pitheorem" / "examples" / "hinged_rod.toml")
CLI = "import sys; from pitheorem.cli import main; sys.argv = ['pitheorem', *sys.argv[1:]]; sys.exit(main())"
SCRIPT = Path(sys.executable).parent / "pitheorem"  # the console script pip installs beside the interpreter
GROUPS = "pitheorem groups example:hinged_rod"
COMMANDS = {
    "import sympy (baseline)": [sys.executable, "-c", "import sympy"],
    "import pitheorem": [sys.executable, "-c", "import pitheorem"],
    GROUPS: [str(SCRIPT), "groups", "example:hinged_rod"]
    if SCRIPT.exists()
    else [sys.executable, "-c", CLI, "groups", "example:hinged_rod"],
    "pitheorem groups hinged_rod.toml (python -c)": [sys.executable, "-c", CLI, "groups", ROD],
    "pitheorem bases hinged_rod.toml": [sys.executable, "-c", CLI, "bases", ROD],
    "pitheorem search hinged_rod.toml --scale g=1": [sys.executable, "-c", CLI, "search", ROD, "--scale", "g=1"],
    "pitheorem groups example:pendulum.xml": [sys.executable, "-c", CLI, "groups", "example:pendulum.xml"],
}
TARGETS = {"import pitheorem": 1.3, GROUPS: 1.5}
HEAVY = ("sympy", "numpy", "scipy", "matplotlib", "pint")


def loaded_modules(command: list[str]) -> list[str]:
    report = f"import sys as _s; print(','.join(m for m in {HEAVY!r} if m in _s.modules), file=_s.stderr)"
    if command[0] == str(SCRIPT):  # the console script runs main() like CLI does
        command = [sys.executable, "-c", CLI, *command[1:]]
    probe = [command[0], "-c", f"try:\n    exec({command[2]!r})\nexcept SystemExit:\n    pass\n{report}", *command[3:]]
    out = subprocess.run(probe, capture_output=True, text=True, check=False)
    return [m for m in out.stderr.strip().splitlines()[-1].split(",") if m] if out.stderr.strip() else []


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer repetitions")
    args = parser.parse_args(argv)
    repeats = 5 if args.quick else 11
    times: dict[str, list[float]] = {name: [] for name in COMMANDS}
    names = list(COMMANDS)
    for k in range(repeats):
        # interleaved, each round in a rotated order, so load changes hit every command alike
        for name in names[k % len(names) :] + names[: k % len(names)]:
            command = COMMANDS[name]
            start = time.perf_counter()
            subprocess.run(command, capture_output=True, check=True)
            times[name].append(time.perf_counter() - start)
    base = statistics.median(times["import sympy (baseline)"])
    fastest = min(times["import sympy (baseline)"])
    print(
        f"{'command':<46} {'median s':>9} {'vs sympy':>9} {'min s':>7} {'vs sympy':>9} {'target':>7}  "
        "modules loaded (of sympy, numpy, scipy, matplotlib, pint)"
    )
    for name, command in COMMANDS.items():
        t, t_min = statistics.median(times[name]), min(times[name])
        target = f"{TARGETS[name]:.1f}x" if name in TARGETS else ""
        heavy = ", ".join(loaded_modules(command)) or "-"
        print(f"{name:<46} {t:>9.3f} {t / base:>8.2f}x {t_min:>7.3f} {t_min / fastest:>8.2f}x {target:>7}  {heavy}")
    print(
        f"\n{repeats} fresh interpreters per command, interleaved in rotating order; "
        "'vs sympy' = time / the same statistic of import sympy"
    )
    ratio = statistics.median(times[GROUPS]) / base
    print(
        f"start-up ratio: {GROUPS} / import sympy = {ratio:.2f}x (median; target {TARGETS[GROUPS]:.1f}x: "
        f"{'met' if ratio <= TARGETS[GROUPS] else 'NOT met'})"
    )


if __name__ == "__main__":
    main()
