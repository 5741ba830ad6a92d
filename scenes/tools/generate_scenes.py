#!/usr/bin/env python3
"""Generate the bundled test scenes of footprint (OBJ + MTL).

Usage:  python3 scenes/tools/generate_scenes.py        (from anywhere; standard library only)

Writes, relative to the `scenes/` folder this script lives under:

    cornell/cornell.obj + cornell.mtl   the classic Cornell box (measured data, x 0.01 -> metres)
    door/door.obj       + door.mtl      two rooms, light reaches the camera room through a door ajar
    desk/desk.obj       + desk.mtl      a room lit by a desk lamp (spot light declared in desk.toml)
    furnace/sphere.obj  + sphere.mtl    inward-facing icosphere for the white-furnace test

The `.toml` scene files beside them are hand-written, not generated; where they must agree with the
geometry (door gap, lamp position) the numbers are printed by this script and repeated in the TOML
comments and in `scenes/README.md`.

Conventions (shared by every scene):
  * metres, right-handed, +Y up;
  * triangles only, wound counter-clockwise seen from the side the geometric normal points to,
    i.e. n = (v1 - v0) x (v2 - v0);
  * every solid (wall, slab, block, door leaf, furniture, lamp) is its own closed box (12
    triangles, normals outward) with real thickness; parts that meet overlap a few centimetres
    instead of merely touching, so no ray can slip through a seam.  Because the normals of a wall
    box point out of the box, the face a room sees points into that room;
  * the lampshade is a closed thin shell: an outer and an inner truncated cone 3 mm apart joined
    by a flat ring at each rim; its top and bottom openings are open;
  * area lights are one flat quad (2 triangles) each, 1 mm in front of the surface they hang on,
    emitting on the side their normal points to (into the room);
  * no `vn` / `vt` records (everything is faceted), one `o`/`g` name and `usemtl` per object,
    positive 1-based indices, `mtllib <name>.mtl` relative to the OBJ.

MTL conventions the renderer reads: `Kd` diffuse albedo; `Ks` + `Ns` a Blinn lobe when illum 2 and
Ks > 0 (Kd + Ks <= 1 per channel); `illum 3` with Ks = perfect mirror; `illum 7` = smooth glass
(`Ni`, `Tf`); `Ke` = emitted radiance W/(m^2 sr).  Purely diffuse materials are written with
`Ks 0 0 0` and `illum 1`.

The output is deterministic: no randomness, coordinates printed with 6 decimals, fixed ordering.
Running the script twice gives byte-identical files.
"""

import math
import os

SCENES = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


# --------------------------------------------------------------------------------------------
# small vector helpers
# --------------------------------------------------------------------------------------------

def add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def mul(a, s):
    return (a[0] * s, a[1] * s, a[2] * s)


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def length(a):
    return math.sqrt(dot(a, a))


def normalize(a):
    n = length(a)
    return (a[0] / n, a[1] / n, a[2] / n)


def rot_y(p, deg):
    """Rotate p about the +Y axis by `deg` degrees (right-handed: +X turns toward -Z)."""
    a = math.radians(deg)
    c, s = math.cos(a), math.sin(a)
    return (c * p[0] + s * p[2], p[1], -s * p[0] + c * p[2])


# --------------------------------------------------------------------------------------------
# mesh building
# --------------------------------------------------------------------------------------------

class Obj:
    """One named object: its own vertices and triangles (each triangle carries a material)."""

    def __init__(self, name, material):
        self.name = name
        self.material = material
        self.verts = []
        self.index = {}
        self.tris = []  # (i, j, k, material)

    def vert(self, p):
        key = tuple(round(c, 6) + 0.0 for c in p)  # + 0.0 turns -0.0 into 0.0
        if key not in self.index:
            self.index[key] = len(self.verts)
            self.verts.append(key)
        return self.index[key]

    def tri(self, a, b, c, hint, material=None):
        """Add triangle abc, reordered if needed so that its normal has dot(n, hint) > 0."""
        n = cross(sub(b, a), sub(c, a))
        if length(n) < 1e-12:
            raise ValueError(f"{self.name}: degenerate triangle {a} {b} {c}")
        if dot(n, hint) < 0.0:
            b, c = c, b
        elif dot(n, hint) == 0.0:
            raise ValueError(f"{self.name}: hint perpendicular to triangle normal")
        self.tris.append((self.vert(a), self.vert(b), self.vert(c), material or self.material))

    def quad(self, a, b, c, d, hint, material=None, planar_tol=1e-9):
        """Add quad abcd (given in order around its boundary) as triangles abc, acd."""
        n = cross(sub(c, a), sub(d, b))
        if planar_tol is not None:
            off = abs(dot(normalize(n), sub(d, a))) + abs(dot(normalize(n), sub(b, a)))
            if off > planar_tol:
                raise ValueError(f"{self.name}: non-planar quad ({off:.3g} m)")
        if dot(n, hint) < 0.0:
            a, b, c, d = a, d, c, b
        self.tri(a, b, c, hint, material)
        self.tri(a, c, d, hint, material)


class Scene:
    def __init__(self, name):
        self.name = name
        self.materials = {}  # name -> list of (key, value string), in insertion order
        self.objects = []

    def material(self, name, comment, **fields):
        lines = []
        for key in ("Kd", "Ks", "Ns", "Ke", "Ni", "Tf", "illum"):
            if key in fields:
                v = fields[key]
                if isinstance(v, (tuple, list)):
                    v = " ".join(f"{x:g}" for x in v)
                lines.append((key, str(v)))
        if "Kd" in fields and "Ks" in fields:
            for kd, ks in zip(fields["Kd"], fields["Ks"]):
                assert kd + ks <= 1.0 + 1e-12, f"{name}: Kd + Ks > 1"
        self.materials[name] = (comment, lines)

    def obj(self, name, material):
        o = Obj(name, material)
        assert all(p.name != name for p in self.objects), name
        self.objects.append(o)
        return o

    # ---- primitives ----------------------------------------------------------------------

    def box(self, name, material, lo, hi, rotate_y=0.0, pivot=(0.0, 0.0, 0.0), offset=(0.0, 0.0, 0.0)):
        """Closed box [lo, hi] (12 triangles, normals outward); optionally rotated about the
        vertical axis through `pivot` by `rotate_y` degrees, then translated by `offset`."""
        o = self.obj(name, material)

        def place(p):
            return add(add(rot_y(sub(p, pivot), rotate_y), pivot), offset)

        x0, y0, z0 = lo
        x1, y1, z1 = hi
        assert x1 > x0 and y1 > y0 and z1 > z0, name
        c = [place(((x0, x1)[i & 1], (y0, y1)[(i >> 1) & 1], (z0, z1)[(i >> 2) & 1])) for i in range(8)]
        centre = place(((x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2))
        faces = [(0, 2, 6, 4), (1, 3, 7, 5), (0, 1, 5, 4), (2, 3, 7, 6), (0, 1, 3, 2), (4, 5, 7, 6)]
        for f in faces:
            a, b, cc, d = (c[i] for i in f)
            fc = mul(add(add(a, b), add(cc, d)), 0.25)
            o.quad(a, b, cc, d, sub(fc, centre), planar_tol=1e-6)
        return o

    def prism(self, name, material, footprint, y0, y1):
        """Closed vertical prism over a convex quadrilateral footprint [(x, z), ...]."""
        o = self.obj(name, material)
        bot = [(x, y0, z) for x, z in footprint]
        top = [(x, y1, z) for x, z in footprint]
        centre = (sum(p[0] for p in bot) / 4, (y0 + y1) / 2, sum(p[2] for p in bot) / 4)
        o.quad(*top, hint=(0.0, 1.0, 0.0))
        o.quad(*bot, hint=(0.0, -1.0, 0.0))
        for i in range(4):
            j = (i + 1) % 4
            a, b, c, d = bot[i], bot[j], top[j], top[i]
            fc = mul(add(add(a, b), add(c, d)), 0.25)
            o.quad(a, b, c, d, hint=sub(fc, centre))
        return o

    def light_quad(self, name, material, corners, normal):
        """Area light: one planar quad (2 triangles) emitting toward `normal`."""
        o = self.obj(name, material)
        o.quad(*corners, hint=normal)
        return o

    # ---- output --------------------------------------------------------------------------

    def write(self, folder, basename, header):
        os.makedirs(folder, exist_ok=True)
        used = []
        for o in self.objects:
            for t in o.tris:
                if t[3] not in used:
                    used.append(t[3])
        missing = [m for m in used if m not in self.materials]
        assert not missing, missing

        with open(os.path.join(folder, basename + ".mtl"), "w", newline="\n") as f:
            f.write(f"# {basename}.mtl - generated by scenes/tools/generate_scenes.py, do not edit\n")
            for name in used:
                comment, lines = self.materials[name]
                f.write(f"\n# {comment}\nnewmtl {name}\n")
                for k, v in lines:
                    f.write(f"{k} {v}\n")

        ntris = sum(len(o.tris) for o in self.objects)
        nverts = sum(len(o.verts) for o in self.objects)
        with open(os.path.join(folder, basename + ".obj"), "w", newline="\n") as f:
            f.write(f"# {basename}.obj - generated by scenes/tools/generate_scenes.py, do not edit\n")
            for line in header.strip("\n").split("\n"):
                f.write(f"# {line}\n".replace("# \n", "#\n"))
            f.write(f"# {nverts} vertices, {ntris} triangles, {len(self.objects)} objects\n")
            f.write(f"mtllib {basename}.mtl\n")
            base = 1
            for o in self.objects:
                f.write(f"\no {o.name}\ng {o.name}\n")
                for v in o.verts:
                    f.write("v {:.6f} {:.6f} {:.6f}\n".format(*v))
                current = None
                for i, j, k, m in o.tris:
                    if m != current:
                        f.write(f"usemtl {m}\n")
                        current = m
                    f.write(f"f {i + base} {j + base} {k + base}\n")
                base += len(o.verts)
        return nverts, ntris


# --------------------------------------------------------------------------------------------
# 1. Cornell box
# --------------------------------------------------------------------------------------------

def cornell():
    """The measured Cornell box (www.graphics.cornell.edu/online/box/data.html), x 0.01.

    The real box is slightly out of square; its data is used as published (the red wall quad is
    a little twisted, so it is written as two triangles without the planarity check).  The front
    (z = 0) is open; the camera sits at z = -8 looking toward +Z, so +X is on the image's LEFT
    (red wall at x ~ 5.56 left, green wall at x = 0 right)."""
    s = Scene("cornell")
    s.material("white", "white walls, floor, ceiling, blocks", Kd=(0.73, 0.73, 0.73), Ks=(0, 0, 0), illum=1)
    s.material("red", "left wall (x ~ 5.56)", Kd=(0.63, 0.065, 0.05), Ks=(0, 0, 0), illum=1)
    s.material("green", "right wall (x = 0)", Kd=(0.14, 0.45, 0.091), Ks=(0, 0, 0), illum=1)
    s.material("light", "ceiling area light, radiance 17 12 4", Kd=(0.78, 0.78, 0.78), Ks=(0, 0, 0),
               Ke=(17, 12, 4), illum=1)

    def P(x, y, z):
        return (x * 0.01, y * 0.01, z * 0.01)

    inside = P(278, 274.4, 279.6)

    def wall(name, mat, pts, check_planar=True):
        o = s.obj(name, mat)
        fc = mul(add(add(pts[0], pts[1]), add(pts[2], pts[3])), 0.25)
        o.quad(*pts, hint=sub(inside, fc), planar_tol=1e-9 if check_planar else None)

    wall("floor", "white", [P(552.8, 0, 0), P(0, 0, 0), P(0, 0, 559.2), P(549.6, 0, 559.2)])
    wall("ceiling", "white", [P(556, 548.8, 0), P(556, 548.8, 559.2), P(0, 548.8, 559.2), P(0, 548.8, 0)])
    wall("back_wall", "white", [P(549.6, 0, 559.2), P(0, 0, 559.2), P(0, 548.8, 559.2), P(556, 548.8, 559.2)],
         check_planar=False)
    wall("right_wall_green", "green", [P(0, 0, 559.2), P(0, 0, 0), P(0, 548.8, 0), P(0, 548.8, 559.2)])
    wall("left_wall_red", "red", [P(552.8, 0, 0), P(549.6, 0, 559.2), P(556, 548.8, 559.2), P(556, 548.8, 0)],
         check_planar=False)

    # blocks: closed prisms over the published (rotated) footprints
    s.prism("short_block", "white", [(x * 0.01, z * 0.01) for x, z in
                                    [(130, 65), (82, 225), (240, 272), (290, 114)]], 0.0, 1.65)
    s.prism("tall_block", "white", [(x * 0.01, z * 0.01) for x, z in
                                   [(423, 247), (265, 296), (314, 456), (472, 406)]], 0.0, 3.30)

    y = 5.488 - 0.001
    s.light_quad("light", "light", [(3.43, y, 2.27), (3.43, y, 3.32), (2.13, y, 3.32), (2.13, y, 2.27)],
                 normal=(0.0, -1.0, 0.0))
    return s.write(os.path.join(SCENES, "cornell"), "cornell", """
Cornell box, measured data (www.graphics.cornell.edu/online/box/data.html) scaled by 0.01 -> metres.
Box spans x 0..5.56, y 0..5.488, z 0..5.592; the front (z = 0) is open.
Walls are single quads facing the inside; blocks are closed prisms; light 1.30 x 1.05 m, 1 mm below the ceiling.
Camera (cornell.toml): (2.78, 2.73, -8.0) looking at +Z, fov_y 39.3; red wall (x ~ 5.56) appears on the left.""")


# --------------------------------------------------------------------------------------------
# 2. door scene
# --------------------------------------------------------------------------------------------

# layout (metres): camera room x 0..4, light room x 4.1..8.1, both z 0..4, y 0..2.6
DOOR = dict(
    room_h=2.6,
    wall_x0=4.0, wall_x1=4.1,          # separating wall
    door_z0=0.4, door_w=0.9, door_h=2.05,
    leaf_t=0.04, hinge_overlap=0.005,  # leaf thickness; the hinge end sinks 5 mm into the jamb
    gap=0.040,                         # target clear gap between leaf and latch-side jamb
    light=(6.3, 6.9, 2.2, 2.8),        # x0, x1, z0, z1 of the ceiling light in the light room
    light_ke=(40, 40, 36),
)


def door_leaf_angle(d):
    """Angle (degrees) the leaf is swung into the camera room so that the clear gap between the
    leaf's light-room face/edge and the latch-side jamb corner J = (wall_x0, door_z0 + door_w)
    is `gap`.  The leaf rotates about the vertical axis through its camera-side hinge corner
    H = (wall_x0, door_z0 - hinge_overlap).  Returns (angle, gap) with the gap measured."""
    W, t, e = d["door_w"], d["leaf_t"], d["hinge_overlap"]

    def gap(theta):
        c, s = math.cos(theta), math.sin(theta)
        # J in leaf coordinates: u along the thickness (toward the light room), w along the width
        jx, jz = 0.0, W + e               # J - H
        u = jx * c + jz * s
        w = -jx * s + jz * c
        du = max(0.0, u - t) if u > 0 else -u
        dw = max(0.0, w - W, -w)
        if 0 <= u <= t and 0 <= w <= W:
            return -1.0
        return math.hypot(du, dw)

    lo, hi = math.radians(0.5), math.radians(30.0)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if gap(mid) < d["gap"]:
            lo = mid
        else:
            hi = mid
    theta = 0.5 * (lo + hi)
    return math.degrees(theta), gap(theta)


def door():
    d = DOOR
    s = Scene("door")
    s.material("wall", "walls", Kd=(0.72, 0.72, 0.70), Ks=(0, 0, 0), illum=1)
    s.material("ceiling", "ceilings", Kd=(0.78, 0.78, 0.78), Ks=(0, 0, 0), illum=1)
    s.material("floor", "floor of both rooms, warm grey", Kd=(0.62, 0.54, 0.44), Ks=(0, 0, 0), illum=1)
    s.material("door", "door leaf", Kd=(0.60, 0.46, 0.32), Ks=(0, 0, 0), illum=1)
    s.material("table", "table in the camera room", Kd=(0.55, 0.40, 0.28), Ks=(0, 0, 0), illum=1)
    s.material("cabinet", "cabinet in the camera room", Kd=(0.35, 0.48, 0.62), Ks=(0, 0, 0), illum=1)
    s.material("sofa", "block in the light room", Kd=(0.65, 0.30, 0.25), Ks=(0, 0, 0), illum=1)
    s.material("light", "ceiling area light in the light room", Kd=(0.8, 0.8, 0.8), Ks=(0, 0, 0),
               Ke=d["light_ke"], illum=1)

    H = d["room_h"]
    X0, X1 = 0.0, 8.1            # inner extent of the building
    Z0, Z1 = 0.0, 4.0
    T = 0.1                      # outer wall thickness
    wx0, wx1 = d["wall_x0"], d["wall_x1"]
    dz0, dz1, dh = d["door_z0"], d["door_z0"] + d["door_w"], d["door_h"]

    # slabs and outer walls: every wall box reaches 5 cm into the slabs and into its neighbours
    s.box("floor_slab", "floor", (X0 - 0.15, -0.15, Z0 - 0.15), (X1 + 0.15, 0.0, Z1 + 0.15))
    s.box("ceiling_slab", "ceiling", (X0 - 0.15, H, Z0 - 0.15), (X1 + 0.15, H + 0.15, Z1 + 0.15))
    s.box("wall_west", "wall", (X0 - T, -0.05, Z0 - T), (X0, H + 0.05, Z1 + T))
    s.box("wall_east", "wall", (X1, -0.05, Z0 - T), (X1 + T, H + 0.05, Z1 + T))
    s.box("wall_south", "wall", (X0 - T, -0.05, Z0 - T), (X1 + T, H + 0.05, Z0))
    s.box("wall_north", "wall", (X0 - T, -0.05, Z1), (X1 + T, H + 0.05, Z1 + T))
    # separating wall with the door opening z dz0..dz1, y 0..dh
    s.box("partition_south", "wall", (wx0, -0.05, Z0 - 0.05), (wx1, H + 0.05, dz0))
    s.box("partition_north", "wall", (wx0, -0.05, dz1), (wx1, H + 0.05, Z1 + 0.05))
    s.box("partition_lintel", "wall", (wx0, dh, dz0 - 0.05), (wx1, H + 0.05, dz1 + 0.05))

    # door leaf: local box x 0..t (toward the light room), z 0..W, hinge corner at the origin;
    # swung into the camera room (free edge toward -X) about H = (wx0, ., dz0 - overlap)
    angle, gap = door_leaf_angle(d)
    hinge = (wx0, 0.0, dz0 - d["hinge_overlap"])
    s.box("door_leaf", "door", (0.0, 0.0, 0.0), (d["leaf_t"], dh, d["door_w"]),
          rotate_y=-angle, pivot=(0.0, 0.0, 0.0), offset=hinge)

    # camera room furniture: a table near the south wall, a cabinet against the door wall (it
    # catches the light coming through the gap), a crate near the north wall
    ty, tt = 0.75, 0.04
    tx0, tx1, tz0, tz1 = 1.5, 2.7, 0.35, 1.15
    s.box("table_top", "table", (tx0, ty - tt, tz0), (tx1, ty, tz1))
    leg = 0.05
    for i, (lx, lz) in enumerate([(tx0 + 0.04, tz0 + 0.04), (tx1 - 0.04 - leg, tz0 + 0.04),
                                  (tx0 + 0.04, tz1 - 0.04 - leg), (tx1 - 0.04 - leg, tz1 - 0.04 - leg)]):
        s.box(f"table_leg_{i}", "table", (lx, 0.0, lz), (lx + leg, ty - tt + 0.01, lz + leg))
    s.box("cabinet", "cabinet", (3.5, 0.0, 2.3), (wx0 + 0.02, 1.2, 3.3))
    s.box("crate", "cabinet", (2.5, 0.0, 3.3), (3.1, 0.5, 3.8), rotate_y=20.0, pivot=(2.8, 0.0, 3.55))

    # light room: a block so it is not empty, and the ceiling light
    s.box("sofa", "sofa", (7.3, 0.0, 0.6), (8.1 + 0.02, 0.45, 2.2))
    lx0, lx1, lz0, lz1 = d["light"]
    y = H - 0.001
    s.light_quad("light", "light", [(lx0, y, lz0), (lx1, y, lz0), (lx1, y, lz1), (lx0, y, lz1)],
                 normal=(0.0, -1.0, 0.0))

    c, sn = math.cos(math.radians(angle)), math.sin(math.radians(angle))
    free_front = (wx0 - d["door_w"] * sn, dz0 - d["hinge_overlap"] + d["door_w"] * c)
    info = dict(angle=angle, gap=gap, free_front=free_front)
    header = f"""
Door scene (Hey & Purgathofer 2001, sec. 3): camera room x 0..4, light room x 4.1..8.1, z 0..4, y 0..2.6.
Separating wall x 4.0..4.1, door opening z {dz0:.2f}..{dz1:.2f}, y 0..{dh:.2f}.
Door leaf 0.04 m thick, hinge at (4.0, z {dz0 - d['hinge_overlap']:.3f}), swung {angle:.3f} deg into the camera room;
clear gap at the latch jamb (x 4.0, z {dz1:.2f}): {gap * 100:.2f} cm, 2.05 m tall.
Ceiling light x {lx0}..{lx1}, z {lz0}..{lz1}, y {y:.3f}, Ke {d['light_ke']}.
Every wall, slab and piece of furniture is a closed box; the building is watertight."""
    return s.write(os.path.join(SCENES, "door"), "door", header), info


# --------------------------------------------------------------------------------------------
# 3. desk scene
# --------------------------------------------------------------------------------------------

DESK = dict(
    room=(4.0, 2.7, 4.0),
    desk_centre=(2.0, 3.6),            # x, z of the desk top centre
    desk_size=(1.4, 0.05, 0.7),
    desk_h=0.75,                       # height of the desk top surface
    shade_r_bottom=0.11, shade_r_top=0.05, shade_h=0.16, shade_t=0.003,
    shade_rim=0.30,                    # bottom rim above the desk top
    shade_axis=(2.0, 3.6),             # x, z of the lampshade axis
    light_below_top=0.012,             # spot light position below the shade's top rim
    segments=48,
)


def lampshade(s, name, cx, cz, y0, y1, r0, r1, thick, n, mat_in, mat_out):
    """Closed thin shell: outer cone (normals away from the axis), inner cone 'thick' inside it
    (normals toward the axis), flat rings at both rims.  Open at top and bottom."""
    o = s.obj(name, mat_out)
    slope = (r0 - r1) / (y1 - y0)
    dr = thick * math.sqrt(1.0 + slope * slope)   # horizontal offset for a normal offset `thick`
    q0, q1 = r0 - dr, r1 - dr
    ring = []
    for i in range(n):
        a = 2.0 * math.pi * i / n
        ring.append((math.cos(a), math.sin(a)))

    def pt(r, y, k):
        return (cx + r * ring[k][0], y, cz + r * ring[k][1])

    for i in range(n):
        j = (i + 1) % n
        mid = 2.0 * math.pi * (i + 0.5) / n
        radial = (math.cos(mid), 0.0, math.sin(mid))
        # outer cone
        o.quad(pt(r0, y0, i), pt(r0, y0, j), pt(r1, y1, j), pt(r1, y1, i), hint=radial, material=mat_out)
        # inner cone
        o.quad(pt(q0, y0, i), pt(q0, y0, j), pt(q1, y1, j), pt(q1, y1, i), hint=mul(radial, -1.0),
               material=mat_in)
        # bottom rim ring (faces down) and top rim ring (faces up)
        o.quad(pt(q0, y0, i), pt(q0, y0, j), pt(r0, y0, j), pt(r0, y0, i), hint=(0, -1, 0), material=mat_out)
        o.quad(pt(q1, y1, i), pt(q1, y1, j), pt(r1, y1, j), pt(r1, y1, i), hint=(0, 1, 0), material=mat_out)
    return o, q0, q1


def desk():
    d = DESK
    s = Scene("desk")
    s.material("wall", "walls", Kd=(0.7, 0.7, 0.68), Ks=(0, 0, 0), illum=1)
    s.material("ceiling", "ceiling", Kd=(0.75, 0.75, 0.75), Ks=(0, 0, 0), illum=1)
    s.material("floor", "floor", Kd=(0.45, 0.40, 0.35), Ks=(0, 0, 0), illum=1)
    s.material("desk_top", "desk top: soft glossy (Blinn), Kd + Ks <= 1",
               Kd=(0.25, 0.18, 0.12), Ks=(0.4, 0.4, 0.4), Ns=30, illum=2)
    s.material("desk_leg", "desk legs", Kd=(0.3, 0.3, 0.3), Ks=(0, 0, 0), illum=1)
    s.material("shade_inside", "lampshade inside (bright)", Kd=(0.9, 0.85, 0.7), Ks=(0, 0, 0), illum=1)
    s.material("shade_outside", "lampshade outside and rims (dark)", Kd=(0.12, 0.2, 0.15), Ks=(0, 0, 0),
               illum=1)
    s.material("lamp_metal", "lamp base, pole and arm", Kd=(0.2, 0.2, 0.2), Ks=(0, 0, 0), illum=1)
    s.material("book", "book on the desk", Kd=(0.6, 0.12, 0.1), Ks=(0, 0, 0), illum=1)
    s.material("chair", "chair", Kd=(0.3, 0.35, 0.5), Ks=(0, 0, 0), illum=1)

    RX, RH, RZ = d["room"]
    T = 0.1
    s.box("floor_slab", "floor", (-0.15, -0.15, -0.15), (RX + 0.15, 0.0, RZ + 0.15))
    s.box("ceiling_slab", "ceiling", (-0.15, RH, -0.15), (RX + 0.15, RH + 0.15, RZ + 0.15))
    s.box("wall_west", "wall", (-T, -0.05, -T), (0.0, RH + 0.05, RZ + T))
    s.box("wall_east", "wall", (RX, -0.05, -T), (RX + T, RH + 0.05, RZ + T))
    s.box("wall_south", "wall", (-T, -0.05, -T), (RX + T, RH + 0.05, 0.0))
    s.box("wall_north", "wall", (-T, -0.05, RZ), (RX + T, RH + 0.05, RZ + T))

    # desk
    cx, cz = d["desk_centre"]
    w, th, dp = d["desk_size"]
    top = d["desk_h"]
    x0, x1, z0, z1 = cx - w / 2, cx + w / 2, cz - dp / 2, cz + dp / 2
    s.box("desk_top", "desk_top", (x0, top - th, z0), (x1, top, z1))
    leg = 0.05
    for i, (lx, lz) in enumerate([(x0 + 0.03, z0 + 0.03), (x1 - 0.03 - leg, z0 + 0.03),
                                  (x0 + 0.03, z1 - 0.03 - leg), (x1 - 0.03 - leg, z1 - 0.03 - leg)]):
        s.box(f"desk_leg_{i}", "desk_leg", (lx, 0.0, lz), (lx + leg, top - th + 0.01, lz + leg))

    # lamp: base and pole to the side (outside the spot), horizontal arm to the shade's top rim
    ax, az = d["shade_axis"]
    yb = top + d["shade_rim"]
    yt = yb + d["shade_h"]
    px = ax + 0.43
    s.box("lamp_base", "lamp_metal", (px - 0.07, top - 0.005, az - 0.07), (px + 0.07, top + 0.02, az + 0.07))
    s.box("lamp_pole", "lamp_metal", (px - 0.01, top + 0.01, az - 0.01), (px + 0.01, yt + 0.014, az + 0.01))
    s.box("lamp_arm", "lamp_metal", (ax, yt - 0.004, az - 0.008), (px + 0.005, yt + 0.012, az + 0.008))
    _, q0, q1 = lampshade(s, "lampshade", ax, az, yb, yt, d["shade_r_bottom"], d["shade_r_top"], d["shade_t"],
                          d["segments"], "shade_inside", "shade_outside")

    # book (rotated, partly inside the spot) and a chair in front of the desk
    s.box("book", "book", (-0.085, top - 0.002, -0.12), (0.085, top + 0.035, 0.12),
          rotate_y=18.0, pivot=(0.0, 0.0, 0.0), offset=(1.62, 0.0, 3.52))
    chx, chz = 2.65, 2.9           # chair seat centre
    sw = 0.44
    s.box("chair_seat", "chair", (chx - sw / 2, 0.43, chz - sw / 2), (chx + sw / 2, 0.47, chz + sw / 2))
    s.box("chair_back", "chair", (chx - sw / 2, 0.46, chz - sw / 2 - 0.01), (chx + sw / 2, 0.92, chz - sw / 2 + 0.025))
    cl = 0.035
    for i, (lx, lz) in enumerate([(chx - sw / 2 + 0.01, chz - sw / 2 + 0.005), (chx + sw / 2 - 0.01 - cl, chz - sw / 2 + 0.005),
                                  (chx - sw / 2 + 0.01, chz + sw / 2 - 0.01 - cl), (chx + sw / 2 - 0.01 - cl, chz + sw / 2 - 0.01 - cl)]):
        s.box(f"chair_leg_{i}", "chair", (lx, 0.0, lz), (lx + cl, 0.44, lz + cl))

    ly = yt - d["light_below_top"]
    tan_open = q0 / (ly - yb)                       # opening half-angle seen from the light
    spot_r = (ly - top) * tan_open
    info = dict(light=(ax, ly, az), shade=(yb, yt), inner_r=(q0, q1),
                open_half_angle=math.degrees(math.atan(tan_open)), spot_radius=spot_r,
                light_to_desk=ly - top, desk_z=(z0, z1))
    header = f"""
Desk scene (Hey & Purgathofer 2001, sec. 3): room x 0..{RX}, y 0..{RH}, z 0..{RZ}; no emitting faces.
Light: SPOT declared in desk.toml at ({ax}, {ly:.3f}, {az}) pointing -Y, inside the shade near its top.
Desk top {w} x {th} x {dp} m, surface y {top}, x {x0:.2f}..{x1:.2f}, z {z0:.2f}..{z1:.2f} (Blinn glossy).
Lampshade axis ({ax}, {az}), open truncated cone y {yb:.3f}..{yt:.3f}, outer radius {d['shade_r_bottom']}..{d['shade_r_top']},
double-walled ({d['shade_t'] * 1000:.0f} mm) and closed by rim rings; opening half-angle seen from the light {math.degrees(math.atan(tan_open)):.1f} deg,
hard-edged spot of radius {spot_r:.3f} m on the desk, centred under the axis."""
    return s.write(os.path.join(SCENES, "desk"), "desk", header), info


# --------------------------------------------------------------------------------------------
# 4. white furnace
# --------------------------------------------------------------------------------------------

def icosphere(level):
    t = (1.0 + math.sqrt(5.0)) / 2.0
    verts = [normalize(v) for v in [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0),
                                    (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
                                    (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11),
             (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6), (7, 1, 8),
             (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9),
             (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(level):
        cache = {}

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in cache:
                cache[key] = len(verts)
                verts.append(normalize(mul(add(verts[a], verts[b]), 0.5)))
            return cache[key]

        new = []
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            new += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = new
    return verts, faces


def furnace():
    s = Scene("sphere")
    s.material("furnace", "albedo 0.5 and emission 0.5: radiance is exactly 1 everywhere inside",
               Kd=(0.5, 0.5, 0.5), Ks=(0, 0, 0), Ke=(0.5, 0.5, 0.5), illum=1)
    verts, faces = icosphere(3)
    o = s.obj("sphere", "furnace")
    for a, b, c in faces:
        pa, pb, pc = verts[a], verts[b], verts[c]
        centroid = mul(add(add(pa, pb), pc), 1.0 / 3.0)
        o.tri(pa, pb, pc, hint=mul(centroid, -1.0))   # inward
    return s.write(os.path.join(SCENES, "furnace"), "sphere", """
White furnace: closed icosphere (level 3, 1280 triangles), radius 1, centre at the origin, faces INWARD.
Material Kd 0.5, Ke 0.5 on every face: L = Le + rho * L gives L = 1 exactly at every point and direction inside.
Every triangle is emissive (this is the one scene whose emitter is not a single quad).""")


def main():
    v, t = cornell()
    print(f"cornell/cornell.obj   {v:5d} vertices {t:5d} triangles")
    (v, t), info = door()
    print(f"door/door.obj         {v:5d} vertices {t:5d} triangles")
    print(f"    door leaf swung {info['angle']:.3f} deg into the camera room, clear gap {info['gap'] * 100:.2f} cm, "
          f"free edge (camera side) at x {info['free_front'][0]:.4f}, z {info['free_front'][1]:.4f}")
    (v, t), info = desk()
    print(f"desk/desk.obj         {v:5d} vertices {t:5d} triangles")
    print("    spot light at ({:.3f}, {:.3f}, {:.3f}); shade y {:.3f}..{:.3f}; inner radii {:.4f}..{:.4f}".format(
        *info["light"], *info["shade"], *info["inner_r"]))
    print(f"    opening half-angle {info['open_half_angle']:.2f} deg, spot radius on desk {info['spot_radius']:.3f} m, "
          f"light {info['light_to_desk']:.3f} m above the desk (desk z {info['desk_z'][0]:.2f}..{info['desk_z'][1]:.2f})")
    v, t = furnace()
    print(f"furnace/sphere.obj    {v:5d} vertices {t:5d} triangles")


if __name__ == "__main__":
    main()
