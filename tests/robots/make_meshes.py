"""Write the corpus's meshes: small convex polyhedra as binary STL (MuJoCo) and OBJ (PyBullet).

Run ``python tests/robots/make_meshes.py`` from the repository root; it rewrites every mesh file of
``tests/robots`` byte for byte the same (no randomness, no time stamps).  The shapes are convex and
centred on the origin, so every face is turned outward by one test (its normal points away from the
origin); MuJoCo computes a mesh's volume and inertia from the faces and needs them turned outward.

Vertex coordinates are written in the units of the file that uses the mesh (metres), with the shapes
sized in the file by ``scale`` where a size differs from the one written here.
"""

from __future__ import annotations

import math
import struct
from pathlib import Path

HERE = Path(__file__).resolve().parent

Vertex = tuple[float, float, float]
Face = tuple[int, int, int]


def box(hx: float, hy: float, hz: float) -> tuple[list[Vertex], list[Face]]:
    """A box of half sizes hx, hy, hz: 8 vertices, 12 triangles."""
    vertices = [(sx * hx, sy * hy, sz * hz) for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
    quads = ((0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3))
    faces = [t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))]
    return vertices, faces


def prism(radius: float, half_length: float, sides: int) -> tuple[list[Vertex], list[Face]]:
    """A regular prism along z (a low-poly cylinder): 2 * sides vertices."""
    ring = [
        (radius * math.cos(2 * math.pi * k / sides), radius * math.sin(2 * math.pi * k / sides)) for k in range(sides)
    ]
    vertices = [(x, y, -half_length) for x, y in ring] + [(x, y, half_length) for x, y in ring]
    faces = []
    for k in range(sides):
        n = (k + 1) % sides
        faces += [(k, n, sides + n), (k, sides + n, sides + k)]
    for k in range(1, sides - 1):
        faces += [(0, k, k + 1), (sides, sides + k, sides + k + 1)]
    return vertices, faces


def icosphere(radius: float, subdivisions: int) -> tuple[list[Vertex], list[Face]]:
    """An icosahedron, each face split in four `subdivisions` times, pushed onto the sphere."""
    t = (1 + math.sqrt(5)) / 2
    vertices = [
        (-1, t, 0),
        (1, t, 0),
        (-1, -t, 0),
        (1, -t, 0),
        (0, -1, t),
        (0, 1, t),
        (0, -1, -t),
        (0, 1, -t),
        (t, 0, -1),
        (t, 0, 1),
        (-t, 0, -1),
        (-t, 0, 1),
    ]
    faces = [
        (0, 11, 5),
        (0, 5, 1),
        (0, 1, 7),
        (0, 7, 10),
        (0, 10, 11),
        (1, 5, 9),
        (5, 11, 4),
        (11, 10, 2),
        (10, 7, 6),
        (7, 1, 8),
        (3, 9, 4),
        (3, 4, 2),
        (3, 2, 6),
        (3, 6, 8),
        (3, 8, 9),
        (4, 9, 5),
        (2, 4, 11),
        (6, 2, 10),
        (8, 6, 7),
        (9, 8, 1),
    ]
    vertices = [tuple(float(c) for c in v) for v in vertices]
    for _ in range(subdivisions):
        middle: dict[tuple[int, int], int] = {}
        split = []
        for a, b, c in faces:
            ab, bc, ca = (_midpoint(vertices, middle, i, j) for i, j in ((a, b), (b, c), (c, a)))
            split += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = split
    vertices = [tuple(radius * c / math.sqrt(sum(x * x for x in v)) for c in v) for v in vertices]
    return vertices, faces


def _midpoint(vertices: list[Vertex], middle: dict, a: int, b: int) -> int:
    """The index of the midpoint of edge (a, b), appended to `vertices` the first time it is asked for."""
    key = (min(a, b), max(a, b))
    if key not in middle:
        middle[key] = len(vertices)
        vertices.append(tuple((p + q) / 2 for p, q in zip(vertices[a], vertices[b], strict=True)))
    return middle[key]


def capsule(radius: float, half_length: float, sides: int) -> tuple[list[Vertex], list[Face]]:
    """A low-poly capsule along z: a prism closed by two pyramids of height `radius` (convex)."""
    vertices, faces = prism(radius, half_length, sides)
    faces = [f for f in faces if not (all(i < sides for i in f) or all(i >= sides for i in f))]  # open the ends
    bottom, top = len(vertices), len(vertices) + 1
    vertices = [*vertices, (0.0, 0.0, -half_length - radius), (0.0, 0.0, half_length + radius)]
    for k in range(sides):
        n = (k + 1) % sides
        faces += [(bottom, n, k), (top, sides + k, sides + n)]
    return vertices, faces


def wedge(length: float, width: float, height: float) -> tuple[list[Vertex], list[Face]]:
    """A foot-like wedge: a box whose top is narrower at the front (a convex hull of 8 points)."""
    hl, hw, hh = length / 2, width / 2, height / 2
    vertices = [
        (-hl, -hw, -hh),
        (-hl, hw, -hh),
        (hl, -hw, -hh),
        (hl, hw, -hh),
        (-hl, -hw, hh),
        (-hl, hw, hh),
        (hl / 3, -hw * 0.75, hh),
        (hl / 3, hw * 0.75, hh),
    ]
    faces = [
        (0, 2, 3),
        (0, 3, 1),
        (4, 5, 7),
        (4, 7, 6),
        (0, 1, 5),
        (0, 5, 4),
        (2, 6, 7),
        (2, 7, 3),
        (0, 4, 6),
        (0, 6, 2),
        (1, 3, 7),
        (1, 7, 5),
    ]
    return vertices, faces


def outward(vertices: list[Vertex], faces: list[Face]) -> list[Face]:
    """Each face ordered so that its normal points away from the origin (the shapes are convex, centred)."""
    out = []
    for a, b, c in faces:
        n = _normal(vertices[a], vertices[b], vertices[c])
        centre = [sum(vertices[i][k] for i in (a, b, c)) / 3 for k in range(3)]
        out.append((a, b, c) if sum(x * y for x, y in zip(n, centre, strict=True)) > 0 else (a, c, b))
    return out


def _normal(p: Vertex, q: Vertex, r: Vertex) -> Vertex:
    u = [q[k] - p[k] for k in range(3)]
    v = [r[k] - p[k] for k in range(3)]
    n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    length = math.sqrt(sum(x * x for x in n)) or 1.0
    return tuple(x / length for x in n)


def write_stl(path: Path, vertices: list[Vertex], faces: list[Face]) -> None:
    """Binary STL: an 80-byte header, the triangle count, then normal and three vertices per triangle."""
    header = f"pitheorem test corpus: {path.stem}".encode().ljust(80, b" ")
    chunks = [header, struct.pack("<I", len(faces))]
    for a, b, c in faces:
        chunks.append(
            struct.pack(
                "<12fH", *_normal(vertices[a], vertices[b], vertices[c]), *vertices[a], *vertices[b], *vertices[c], 0
            )
        )
    path.write_bytes(b"".join(chunks))


def write_obj(path: Path, vertices: list[Vertex], faces: list[Face]) -> None:
    """Wavefront OBJ of one object (PyBullet loads a single object as one convex hull)."""
    lines = [f"# pitheorem test corpus: {path.stem}", f"o {path.stem}"]
    lines += [f"v {x:.9g} {y:.9g} {z:.9g}" for x, y, z in vertices]
    lines += [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in faces]
    path.write_text("\n".join(lines) + "\n")


#: folder (relative to tests/robots) -> file name -> shape; STL for MuJoCo's folders, OBJ for PyBullet's
MESHES = {
    "mjcf/meshes": {
        "torso.stl": box(0.2, 0.08, 0.05),
        "foot.stl": icosphere(0.025, 1),
        "thigh.stl": capsule(0.02, 0.07, 8),
        "shin.stl": prism(0.015, 0.075, 6),
        "head.stl": icosphere(0.09, 1),
        "sole.stl": wedge(0.2, 0.08, 0.04),
        "link.stl": capsule(0.04, 0.1, 8),
        "palm.stl": box(0.04, 0.05, 0.015),
        "phalanx.stl": capsule(0.01, 0.02, 6),
        "rotor.stl": prism(0.05, 0.005, 10),
        "crate.stl": box(0.05, 0.05, 0.05),
        "top.stl": icosphere(0.05, 2),
    },
    "mjcf/attach/arm_parts": {
        "base.stl": prism(0.08, 0.04, 12),
        "upper.stl": capsule(0.035, 0.15, 10),
        "fore.stl": capsule(0.03, 0.125, 10),
    },
    "mjcf/attach/gripper/gripper_parts": {
        "palm.stl": box(0.03, 0.06, 0.02),
        "finger.stl": wedge(0.06, 0.015, 0.02),
    },
    "urdf/meshes": {
        "body.obj": box(0.2, 0.1, 0.05),
        "leg.obj": capsule(0.02, 0.08, 8),
        "foot.obj": icosphere(0.025, 1),
        "link.obj": capsule(0.035, 0.15, 10),
        "base.obj": prism(0.08, 0.04, 12),
        "palm.obj": box(0.03, 0.06, 0.02),
        "finger.obj": wedge(0.06, 0.015, 0.02),
        "chassis.obj": wedge(0.4, 0.25, 0.1),
        "wheel.obj": prism(0.08, 0.02, 16),
    },
}


def main() -> None:
    for folder, files in MESHES.items():
        target = HERE / folder
        target.mkdir(parents=True, exist_ok=True)
        for name, (vertices, faces) in files.items():
            faces = outward(vertices, faces)
            (write_stl if name.endswith(".stl") else write_obj)(target / name, vertices, faces)


if __name__ == "__main__":
    main()
