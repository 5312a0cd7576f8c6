#!/usr/bin/env python3
"""Writes the models of scenes/cornell-knots (Python 3 standard library only):

- knots.obj: three smooth closed models standing on the Cornell box's floor, in the box's
  millimetres (the scene places the OBJ with no transform), 100 000 triangles in all:
    trefoil     a (2,3) torus knot tube, 640 x 25 quads -> 32 000 triangles
    cinquefoil  a (2,5) torus knot tube, 800 x 25 quads -> 40 000 triangles
    blob        a displaced sphere, 140 slices x 100 stacks -> 28 000 triangles
  one `o` group and one `usemtl` per model, every triangle wound counter-clockwise seen
  from outside (the loader's front side, docs/scene-format.md);
- knots.mtl: their diffuse reflectances.

The output is deterministic (the same bytes on every run): fixed tessellations, no randomness,
coordinates printed to 0.001 mm. The script checks what it writes: each model closed (every edge
shared by exactly two triangles, in opposite directions), positive signed volume (outward
winding), no degenerate triangle, the knot tubes clear of themselves, the models' bounding boxes
apart, everything inside the box.

Usage: tools/make_tessellated_room.py [output folder]   (default: scenes/cornell-knots)
"""
import math
import os
import sys

# The Cornell box interior, mm (scenes/cornell-box/scene.json): x 0..556, y 0..548.8, z 0..559.2.
BOX_MIN = (0.0, 0.0, 0.0)
BOX_MAX = (549.6, 548.7, 559.2)  # the walls' innermost extents (the left wall leans to 549.6 at the back)

MATERIALS = [  # name, Kd
    ("knot-blue", (0.25, 0.40, 0.70)),
    ("knot-yellow", (0.75, 0.60, 0.20)),
    ("blob-white", (0.75, 0.75, 0.75)),
]


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def scale(a, s):
    return (a[0] * s, a[1] * s, a[2] * s)


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def normalize(a):
    return scale(a, 1.0 / math.sqrt(dot(a, a)))


def torus_knot(p, q, size, tube, segments, sides):
    """A tube of radius `tube` around the (p,q) torus knot
    c(t) = size (r cos pt, r sin pt, -sin qt), r = 2 + cos qt, in the x-y plane.
    Returns (positions, triangles); the tube's frame is Frenet's (a torus knot's curvature never
    vanishes, and the curve is periodic, so the tube closes on itself without a seam)."""
    def curve(t):
        r, dr, ddr = 2 + math.cos(q * t), -q * math.sin(q * t), -q * q * math.cos(q * t)
        c, s = math.cos(p * t), math.sin(p * t)
        pos = (r * c, r * s, -math.sin(q * t))
        d1 = (dr * c - p * r * s, dr * s + p * r * c, -q * math.cos(q * t))
        d2 = (ddr * c - 2 * p * dr * s - p * p * r * c, ddr * s + 2 * p * dr * c - p * p * r * s,
              q * q * math.sin(q * t))
        return scale(pos, size), scale(d1, size), scale(d2, size)

    centres, positions = [], []
    for i in range(segments):
        centre, d1, d2 = curve(2 * math.pi * i / segments)
        tangent = normalize(d1)
        normal = normalize(sub(d2, scale(tangent, dot(d2, tangent))))
        binormal = cross(tangent, normal)
        # The tube must be thinner than the curve's radius of curvature |c'|^3 / |c' x c''|.
        speed = math.sqrt(dot(d1, d1))
        curvature_radius = speed ** 3 / math.sqrt(dot(cross(d1, d2), cross(d1, d2)))
        assert tube < 0.9 * curvature_radius, "the tube folds over itself where the knot bends"
        centres.append(centre)
        for j in range(sides):
            a = 2 * math.pi * j / sides
            around = add(scale(normal, math.cos(a)), scale(binormal, math.sin(a)))  # the outward normal
            positions.append(add(centre, scale(around, tube)))
    # No two stretches of the tube may meet: centreline points apart along the curve by more
    # than the tube's diameter times pi/2 must be more than a diameter apart in space.
    step = max(1, segments // 400)
    sampled = centres[::step]
    arc = [0.0]
    for k in range(1, len(sampled)):
        arc.append(arc[-1] + math.sqrt(dot(sub(sampled[k], sampled[k - 1]), sub(sampled[k], sampled[k - 1]))))
    length = arc[-1] + math.sqrt(dot(sub(sampled[0], sampled[-1]), sub(sampled[0], sampled[-1])))
    for a in range(len(sampled)):
        for b in range(a + 1, len(sampled)):
            along = min(arc[b] - arc[a], length - (arc[b] - arc[a]))
            if along > math.pi * tube:
                gap = sub(sampled[a], sampled[b])
                assert dot(gap, gap) > (2.2 * tube) ** 2, "two stretches of the knot's tube touch"
    triangles = []
    for i in range(segments):
        i1 = (i + 1) % segments
        for j in range(sides):
            j1 = (j + 1) % sides
            v00, v01, v10, v11 = i * sides + j, i * sides + j1, i1 * sides + j, i1 * sides + j1
            # (around, along) is right-handed about the outward normal: around x tangent = normal.
            triangles.append((v00, v01, v10))
            triangles.append((v10, v01, v11))
    return positions, triangles


def displaced_sphere(radius, amplitude, slices, stacks):
    """A sphere of `radius` pushed in and out by `amplitude` times a smooth function of the
    direction (star-shaped, so it cannot meet itself): a pole at each end, stacks - 1 rings."""
    def point(d):
        x, y, z = d
        bump = 0.5 * math.sin(4 * x + 1.0) * math.cos(3 * y) + 0.35 * math.sin(5 * z + 2 * x) + 0.15 * math.cos(7 * y + 3 * z)
        return scale(d, radius * (1 + amplitude * bump))

    positions = [point((0.0, -1.0, 0.0))]  # south pole
    for k in range(1, stacks):
        polar = math.pi * k / stacks  # from the south pole
        ring_y, ring_r = -math.cos(polar), math.sin(polar)
        for i in range(slices):
            azimuth = 2 * math.pi * i / slices
            positions.append(point((ring_r * math.cos(azimuth), ring_y, ring_r * math.sin(azimuth))))
    positions.append(point((0.0, 1.0, 0.0)))  # north pole
    north = len(positions) - 1

    def ring(k, i):  # k = 1 .. stacks - 1
        return 1 + (k - 1) * slices + i % slices

    # Going up the sphere (+y) and round it from +x towards +z: up x round is the outward normal
    # (+y x +z = +x at the +x side), so each triangle turns from up to round.
    triangles = []
    for i in range(slices):
        triangles.append((0, ring(1, i), ring(1, i + 1)))
    for k in range(1, stacks - 1):
        for i in range(slices):
            a, b, c, d = ring(k, i), ring(k, i + 1), ring(k + 1, i), ring(k + 1, i + 1)
            triangles.append((a, d, b))
            triangles.append((a, c, d))
    for i in range(slices):
        triangles.append((north, ring(stacks - 1, i + 1), ring(stacks - 1, i)))
    return positions, triangles


def place(positions, degrees, x, z):
    """Turns a model about +y by `degrees`, then moves it to stand on the floor (lowest point
    at y = 0) with its bounding box centred on (x, z)."""
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    turned = [(c * p[0] + s * p[2], p[1], -s * p[0] + c * p[2]) for p in positions]
    lo = [min(p[k] for p in turned) for k in range(3)]
    hi = [max(p[k] for p in turned) for k in range(3)]
    shift = (x - 0.5 * (lo[0] + hi[0]), -lo[1], z - 0.5 * (lo[2] + hi[2]))
    return [add(p, shift) for p in turned]


def check(name, positions, triangles):
    edges = {}
    volume = 0.0
    for t in triangles:
        a, b, c = (positions[k] for k in t)
        n = cross(sub(b, a), sub(c, a))
        assert dot(n, n) > 1e-6, f"{name}: a degenerate triangle"
        volume += dot(a, cross(b, c)) / 6
        for u, v in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])):
            assert (u, v) not in edges, f"{name}: an edge used twice in the same direction"
            edges[(u, v)] = True
    assert all((v, u) in edges for (u, v) in edges), f"{name}: not closed"
    assert volume > 0, f"{name}: wound inwards"
    for p in positions:
        assert all(BOX_MIN[k] <= p[k] <= BOX_MAX[k] for k in range(3)), f"{name}: outside the box"
    return volume


def number(value):
    text = f"{value:.3f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    folder = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "scenes", "cornell-knots")
    os.makedirs(folder, exist_ok=True)

    models = []
    positions, triangles = torus_knot(2, 3, size=32.0, tube=22.0, segments=640, sides=25)
    models.append(("trefoil", "knot-blue", place(positions, -20, 410, 390), triangles))
    positions, triangles = torus_knot(2, 5, size=30.0, tube=13.0, segments=800, sides=25)
    models.append(("cinquefoil", "knot-yellow", place(positions, 30, 150, 330), triangles))
    positions, triangles = displaced_sphere(radius=80.0, amplitude=0.12, slices=140, stacks=101)
    models.append(("blob", "blob-white", place(positions, 0, 290, 130), triangles))

    lines = ["# Written by tools/make_tessellated_room.py: do not edit, run it again.",
             "# Millimetres, in the Cornell box's coordinates; counter-clockwise = outside.",
             "mtllib knots.mtl"]
    boxes = [[[min(p[k] for p in m[2]) for k in range(3)], [max(p[k] for p in m[2]) for k in range(3)]] for m in models]
    for a in range(len(models)):
        for b in range(a + 1, len(models)):
            (lo_a, hi_a), (lo_b, hi_b) = boxes[a], boxes[b]
            assert any(hi_a[k] < lo_b[k] or hi_b[k] < lo_a[k] for k in range(3)), \
                f"{models[a][0]} and {models[b][0]} may overlap"
    base, total = 1, 0
    for name, material, positions, triangles in models:
        check(name, positions, triangles)
        lines.append(f"o {name}")
        lines.append(f"usemtl {material}")
        lines.extend(f"v {number(p[0])} {number(p[1])} {number(p[2])}" for p in positions)
        lines.extend(f"f {t[0] + base} {t[1] + base} {t[2] + base}" for t in triangles)
        base += len(positions)
        total += len(triangles)
        lo, hi = boxes[[m[0] for m in models].index(name)]
        print(f"{name}: {len(positions)} vertices, {len(triangles)} triangles, x {lo[0]:.0f}..{hi[0]:.0f} "
              f"y {lo[1]:.0f}..{hi[1]:.0f} z {lo[2]:.0f}..{hi[2]:.0f} mm", file=sys.stderr)
    with open(os.path.join(folder, "knots.obj"), "w", newline="\n") as f:
        f.write("\n".join(lines) + "\n")
    with open(os.path.join(folder, "knots.mtl"), "w", newline="\n") as f:
        f.write("# Written by tools/make_tessellated_room.py.\n")
        for name, kd in MATERIALS:
            f.write(f"newmtl {name}\nKd {kd[0]} {kd[1]} {kd[2]}\nillum 1\n")
    print(f"wrote {folder}/knots.obj ({total} triangles) and knots.mtl", file=sys.stderr)


if __name__ == "__main__":
    main()
