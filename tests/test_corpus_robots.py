"""The corpus page's data: docs/howto/corpus_robots.json, written by docs/corpus_verdicts.py.

Not a module of pitheorem: the docs tooling.  The schema is stated here, apart from the
script that writes the file: every row is a robot that ran (its proof at s = 4, its
verdict at s = 10, the wrong copy's verdict) or one that did not, with the reason; every
verdict is one a report can give, every cause has a documented kind and a ``restores``
that is true, false or null (no run tests it), and the numbers agree with one another.
"""

from __future__ import annotations

import importlib.util
import json
import re
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
JSON = ROOT / "docs" / "howto" / "corpus_robots.json"
PAGE = ROOT / "docs" / "howto" / "corpus_robots.md"

#: the verdicts of SimilarityReport.verdict, as the design states them
VERDICTS = {"exact", "similar", "inconclusive", "not similar"}
#: the kinds of Cause, as the design states them (and "dimension", the audit's)
KINDS = {"precision", "solver", "contact", "threshold", "setting", "unscaled", "unknown", "dimension"}
REPORT_KEYS = {
    "s",
    "verdict",
    "exact",
    "excited",
    "max_deviation",
    "yardstick",
    "horizon",
    "detection_limit",
    "inconclusive",
    "controls",
    "first_divergence",
    "causes",
    "scale_free",
    "engine_reset",
    "seconds",
}

_spec = importlib.util.spec_from_file_location("corpus_verdicts", ROOT / "docs" / "corpus_verdicts.py")
corpus_verdicts = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(corpus_verdicts)


def schema_errors(data: dict) -> list[str]:
    """Every way `data` departs from the page's schema, as text (empty when it agrees)."""
    errors = []
    if not re.fullmatch(r"\d{4}-\d{2}-\d{2}", str(data.get("generated"))):
        errors.append(f"generated is no date: {data.get('generated')!r}")
    versions = data.get("versions", {})
    for package in ("pitheorem", "mujoco"):
        if not isinstance(versions.get(package), str) or not versions[package]:
            errors.append(f"no version of {package}")
    settings = data.get("settings", {})
    s_proof, s_verdict = settings.get("s_proof"), settings.get("s_verdict")
    if not (isinstance(s_proof, int) and s_proof > 1 and (s_proof & (s_proof - 1)) == 0 and s_proof.bit_length() % 2):
        errors.append(f"the proof's s is no power of four: {s_proof!r}")
    if not isinstance(data.get("seconds"), (int, float)) or data["seconds"] <= 0:
        errors.append("no total time")
    robots = data.get("robots")
    if not robots:
        return [*errors, "no robots"]
    seen = set()
    for row in robots:
        label = f"{row.get('corpus')}/{row.get('name')}"
        if label in seen:
            errors.append(f"{label}: twice")
        seen.add(label)
        if row.get("engine") not in ("mujoco", "pybullet"):
            errors.append(f"{label}: engine {row.get('engine')!r}")
        if "error" in row:
            if not isinstance(row["error"], str) or not row["error"]:
                errors.append(f"{label}: an empty error")
            continue
        large = row["bodies"] > settings["large_bodies"]
        if row["duration"] != (settings["large_duration"] if large else settings["duration"]):
            errors.append(f"{label}: duration {row['duration']} for {row['bodies']} bodies")
        for key, s in (("proof", s_proof), ("verdict", s_verdict), ("wrong_gravity", s_verdict)):
            if key == "wrong_gravity" and row[key] is None:
                continue  # a robot without gravity: nothing to leave unscaled
            errors += [f"{label}, {key}: {e}" for e in report_errors(row[key], s, row["duration"])]
    return errors


def report_errors(rep: dict, s, duration: float) -> list[str]:
    """Every way one report's row departs from the schema."""
    if set(rep) != REPORT_KEYS:
        return [f"keys {sorted(set(rep) ^ REPORT_KEYS)} differ"]
    errors = []
    if rep["s"] != s:
        errors.append(f"s = {rep['s']}, expected {s}")
    if rep["verdict"] not in VERDICTS:
        errors.append(f"verdict {rep['verdict']!r} is none of {sorted(VERDICTS)}")
    if (rep["verdict"] == "exact") != (rep["exact"] and rep["verdict"] != "not similar" and not rep["inconclusive"]):
        errors.append(f"verdict {rep['verdict']!r} with exact = {rep['exact']}")
    if rep["exact"] and rep["max_deviation"] != 0:
        errors.append(f"exact with a deviation of {rep['max_deviation']}")
    if rep["inconclusive"] and rep["verdict"] not in ("inconclusive", "not similar"):
        errors.append(f"inconclusive, yet {rep['verdict']!r}")
    caught = [c["error"] for c in rep["controls"] if c["caught"]]
    if rep["detection_limit"] != (min(caught) if caught else None):
        errors.append(f"detection limit {rep['detection_limit']} against the controls caught {caught}")
    groups = {c["group"] for c in rep["controls"]}
    unseen = [g for g in groups if not any(c["caught"] for c in rep["controls"] if c["group"] == g)]
    reset = rep["engine_reset"]  # the time and whose run the engine gave up on (MuJoCo's reset), or None
    if reset is not None and (len(reset) != 2 or reset[1] not in ("original", "copy")):
        errors.append(f"engine reset {reset}")
    original_reset = reset is not None and reset[1] == "original"
    if rep["inconclusive"] != (bool(unseen) or original_reset):
        errors.append(
            f"inconclusive = {rep['inconclusive']}, yet the groups no control caught are {unseen}"
            f" and the engine reset {reset}"
        )
    free = rep["scale_free"]
    if free is not None:
        if rep["exact"] or s & (s - 1):
            errors.append("a scale-free proof where there is none to give (exact, or s no power of two)")
        if not isinstance(free["exact"], bool) or free["exact"] != (free["first_divergence"] is None):
            errors.append(f"scale-free proof: exact {free['exact']} with first divergence {free['first_divergence']}")
        if not free["settings"] or not all(len(pair) == 2 for pair in free["settings"]):
            errors.append(f"scale-free proof without its settings: {free['settings']}")
    for c in rep["controls"]:
        if c["group"] not in ("g", "masses") or not c["error"] > 0 or not isinstance(c["caught"], bool):
            errors.append(f"control {c}")
    if rep["horizon"] is not None and not 0 <= rep["horizon"] <= duration * (1 + 1e-9):
        errors.append(f"horizon {rep['horizon']} outside the run of {duration} s")
    for c in rep["causes"]:
        if c["kind"] not in KINDS:
            errors.append(f"cause kind {c['kind']!r}")
        if c["restores"] not in (True, False, None):
            errors.append(f"cause {c['element']!r}: restores {c['restores']!r}")
        if not c["element"] or not isinstance(c["detail"], str):
            errors.append(f"cause {c}: no element or detail")
    return errors


def test_committed_json_agrees_with_the_schema():
    data = json.loads(JSON.read_text())
    assert schema_errors(data) == []
    assert {r["corpus"] for r in data["robots"]} >= {"dm_control suite", "dm_control locomotion", "gymnasium"}
    assert sum("error" not in r for r in data["robots"]) >= 30


def test_schema_catches_a_broken_row():
    """The check above can fail: each broken copy of the data is refused, by name."""
    data = json.loads(JSON.read_text())
    ran = next(k for k, r in enumerate(data["robots"]) if "error" not in r and r["verdict"]["controls"])
    breaks = {
        "verdict 'fine'": lambda r: r["verdict"].update(verdict="fine"),
        "restores 'yes'": lambda r: r["proof"].update(causes=[{**_cause(), "restores": "yes"}]),
        "cause kind 'luck'": lambda r: r["proof"].update(causes=[{**_cause(), "kind": "luck"}]),
        "detection limit": lambda r: r["verdict"].update(detection_limit=0.5),
        "horizon": lambda r: r["verdict"].update(horizon=r["duration"] * 2),
        "s = 10, expected 4": lambda r: r["proof"].update(s=10),
        "keys": lambda r: r["wrong_gravity" if r["wrong_gravity"] else "proof"].pop("causes"),
    }
    for words, damage in breaks.items():
        broken = json.loads(json.dumps(data))
        damage(broken["robots"][ran])
        assert any(words in e for e in schema_errors(broken)), words


def _cause() -> dict:
    return {"kind": "solver", "element": "option tolerance", "detail": "", "restores": True}


def test_page_renders_the_json_and_is_in_a_toctree():
    text = PAGE.read_text()
    assert 'Path("corpus_robots.json")' in text
    assert "corpus_robots" in (ROOT / "docs" / "howto" / "index.md").read_text()
    assert "{doc}`corpus_robots`" in (ROOT / "docs" / "howto" / "corpus_verdicts.md").read_text()
    assert "docs/corpus_verdicts.py" in text
    assert "--menagerie" in text


def test_script_writes_rows_that_agree_with_the_schema(tmp_path):
    """End to end on one small gymnasium model: the script's own output passes the schema."""
    pytest.importorskip("gymnasium")
    out = tmp_path / "one.json"
    status = corpus_verdicts.main(
        ["--only", "gymnasium/inverted_pendulum", "--gepetto", str(tmp_path / "none"), "--out", str(out)]
    )
    assert status == 0
    data = json.loads(out.read_text())
    assert schema_errors(data) == []
    [row] = data["robots"]
    assert row["proof"]["verdict"] == "exact"  # a pendulum on a cart: bit for bit at s = 4
    assert row["wrong_gravity"]["verdict"] == "not similar"


def test_extract_reads_a_bare_repository_and_counts_absent_files(tmp_path):
    """The robots of a bare git directory are written out; a blob the snapshot lacks is counted."""
    work = tmp_path / "work"
    (work / "robots" / "arm" / "urdf").mkdir(parents=True)
    (work / "robots" / "arm" / "urdf" / "arm.urdf").write_text("<robot name='arm'/>\n")
    (work / "robots" / "arm" / "mesh.stl").write_bytes(b"solid\x00\x01 binary\n")
    git = ["git", "-C", str(work), "-c", "user.name=t", "-c", "user.email=t@t"]
    subprocess.run([*git, "init", "-q"], check=True)
    subprocess.run([*git, "add", "."], check=True)
    subprocess.run([*git, "commit", "-qm", "robots"], check=True)
    bare = work / ".git"
    out = tmp_path / "out"
    assert corpus_verdicts.extract(["git", "--git-dir", str(bare)], ["robots/arm"], out) == set()
    assert (out / "robots" / "arm" / "urdf" / "arm.urdf").read_text() == "<robot name='arm'/>\n"
    assert (out / "robots" / "arm" / "mesh.stl").read_bytes() == b"solid\x00\x01 binary\n"
    # a snapshot without its largest blobs: remove one object, as a partial copy lacks it
    sha = subprocess.run([*git, "rev-parse", "HEAD:robots/arm/mesh.stl"], capture_output=True, text=True).stdout
    (bare / "objects" / sha[:2] / sha.strip()[2:]).unlink()
    again = tmp_path / "again"
    assert corpus_verdicts.extract(["git", "--git-dir", str(bare)], ["robots/arm"], again) == {"robots/arm/mesh.stl"}
    assert (again / "robots" / "arm" / "urdf" / "arm.urdf").is_file()
    assert not (again / "robots" / "arm" / "mesh.stl").exists()


def test_urdf_in_mujoco_fetched_json_names_every_gepetto_robot_once_and_counts_agree():
    """docs/howto/urdf_in_mujoco_fetched.json (benchmarks/urdf_in_mujoco_corpus.py --gepetto), read by its page."""
    data = json.loads((ROOT / "docs" / "howto" / "urdf_in_mujoco_fetched.json").read_text())
    assert re.fullmatch(r"\d{4}-\d{2}-\d{2}", data["generated"])
    assert all(data["versions"][k] for k in ("pitheorem", "mujoco", "example-robot-data", "commit"))
    rows = data["robots"]
    assert [r["name"] for r in rows] == [name.split("/")[-1] for name in corpus_verdicts.GEPETTO_URDFS]
    counts = {}
    for row in rows:
        counts[row["verdict"]] = counts.get(row["verdict"], 0) + 1
        assert row["verdict"] in {"exact", "similar", "inconclusive", "not", "refused", "not run"}
        if row["verdict"] in ("refused", "not run"):
            assert row["reason"]  # the culprit
            assert "/tmp/" not in row["reason"]  # no machine's folder
        elif row["verdict"] != "exact":
            assert row["causes"], row["name"]  # every verdict short of exact names its causes
            assert {c["kind"] for c in row["causes"]} <= KINDS
            assert row["scale_free"]
            assert row["by_hand"].startswith("by hand: ")
        if row["verdict"] != "not run":
            large = row["duration"] == data["settings"]["large_duration"]
            assert large or row["duration"] == data["settings"]["duration"]
    summary = data["summary"]
    assert summary.startswith(f"{len(rows)} files: ")
    for verdict in ("exact", "similar", "refused", "not run"):
        assert f"{counts.get(verdict, 0)} {verdict}" in summary or verdict not in counts
    page = (ROOT / "docs" / "howto" / "urdf_in_mujoco.md").read_text()
    assert 'Path("urdf_in_mujoco_fetched.json")' in page
    assert "--gepetto" in page
