#!/usr/bin/env python3
"""Sanity checks for the bundled scenes (standard library only).

Usage:  python3 scenes/tools/check_scenes.py [--preview OUTDIR]

For every scene folder (cornell, door, desk, furnace) it reads the `.toml`, the OBJ and the MTL and
checks:
  * the TOML parses and has the expected tables; the mesh file and its `mtllib` exist (relative);
  * every `usemtl` is defined; Kd + Ks <= 1 per channel; glossy/emissive materials as documented;
  * triangle counts (< 5000 per scene), no degenerate triangles (area < 1e-7 m^2);
  * every object except the listed open surfaces (Cornell walls, area lights) is closed and
    consistently wound: each edge is used by exactly two triangles, once in each direction; its
    signed volume is positive (normals outward), negative for the inward furnace sphere;
  * each area light is one planar quad (2 triangles) facing the expected direction;
  * orientation and leaks by ray casting: from points inside each room (and from the camera and
    light positions) thousands of rays must all hit a front face (n . d < 0) and none may escape
    (the Cornell box may escape only through its open front);
  * camera and lights are not inside any solid;
  * door: the clear gap width, that no straight line from the ceiling light reaches the camera
    room (all light there has been reflected in the light room first), that the camera sees
    neither the light nor is blind to the gap;
  * desk: where the spot light's cone lands (shade inside, desk top), the spot's radius and its
    irradiance.
With --preview it also writes quick direct-lighting PNG previews (not physically based) to OUTDIR.
Exits non-zero on the first failed check.
"""

import math
import os
import struct
import sys
import tomllib
import zlib

SCENES = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FAILURES = []


def check(cond, msg):
    if not cond:
        FAILURES.append(msg)
        print("  FAIL:", msg)
    return cond


# ---- vectors --------------------------------------------------------------------------------

def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def mul(a, s):
    return (a[0] * s, a[1] * s, a[2] * s)


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def norm(a):
    n = math.sqrt(dot(a, a))
    return (a[0] / n, a[1] / n, a[2] / n)


def fibonacci_dirs(n):
    out = []
    ga = math.pi * (3.0 - math.sqrt(5.0))
    for i in range(n):
        y = 1.0 - 2.0 * (i + 0.5) / n
        r = math.sqrt(max(0.0, 1.0 - y * y))
        out.append((r * math.cos(ga * i), y, r * math.sin(ga * i)))
    return out


# ---- parsing --------------------------------------------------------------------------------

def parse_mtl(path):
    mats, cur = {}, None
    with open(path) as f:
        for line in f:
            t = line.split("#")[0].split()
            if not t:
                continue
            if t[0] == "newmtl":
                cur = mats.setdefault(t[1], {})
            else:
                cur[t[0]] = [float(x) for x in t[1:]]
    return mats


def parse_obj(path):
    verts, objects, mtllib = [], [], None
    cur, mat = None, None
    with open(path) as f:
        for line in f:
            t = line.split()
            if not t or t[0].startswith("#"):
                continue
            if t[0] == "mtllib":
                mtllib = t[1]
            elif t[0] == "v":
                verts.append(tuple(float(x) for x in t[1:4]))
            elif t[0] in ("vn", "vt"):
                raise ValueError(f"{path}: unexpected {t[0]}")
            elif t[0] == "o":
                cur = {"name": t[1], "tris": []}
                objects.append(cur)
            elif t[0] == "usemtl":
                mat = t[1]
            elif t[0] == "f":
                idx = [int(x.split("/")[0]) - 1 for x in t[1:]]
                assert len(idx) == 3 and all(i >= 0 for i in idx), line
                cur["tris"].append((idx, mat))
    return verts, objects, mtllib


# ---- BVH ray caster -------------------------------------------------------------------------

class Tracer:
    def __init__(self, tris):
        # tris: list of dict(p=(p0,p1,p2), obj=name, mat=name)
        self.tris = []
        for t in tris:
            p0, p1, p2 = t["p"]
            e1, e2 = sub(p1, p0), sub(p2, p0)
            n = norm(cross(e1, e2))
            self.tris.append((p0, e1, e2, n, t["obj"], t["mat"]))
        self.nodes = []  # (lo, hi, left, right, start, count)
        idx = list(range(len(self.tris)))
        self.order = []
        self._build(idx)

    def _bounds(self, idx):
        lo = [1e30] * 3
        hi = [-1e30] * 3
        for i in idx:
            p0, e1, e2 = self.tris[i][:3]
            for p in (p0, add(p0, e1), add(p0, e2)):
                for k in range(3):
                    lo[k] = min(lo[k], p[k])
                    hi[k] = max(hi[k], p[k])
        return [l - 1e-7 for l in lo], [h + 1e-7 for h in hi]

    def _build(self, idx):
        lo, hi = self._bounds(idx)
        node = len(self.nodes)
        self.nodes.append(None)
        if len(idx) <= 4:
            self.nodes[node] = (lo, hi, -1, -1, len(self.order), len(idx))
            self.order.extend(idx)
            return node
        axis = max(range(3), key=lambda k: hi[k] - lo[k])

        def cen(i):
            p0, e1, e2 = self.tris[i][:3]
            return p0[axis] + (e1[axis] + e2[axis]) / 3.0

        idx.sort(key=cen)
        m = len(idx) // 2
        left = self._build(idx[:m])
        right = self._build(idx[m:])
        self.nodes[node] = (lo, hi, left, right, 0, 0)
        return node

    def _hit_box(self, lo, hi, o, inv, tmax):
        t0, t1 = 0.0, tmax
        for k in range(3):
            a = (lo[k] - o[k]) * inv[k]
            b = (hi[k] - o[k]) * inv[k]
            if a > b:
                a, b = b, a
            if a > t0:
                t0 = a
            if b < t1:
                t1 = b
            if t0 > t1:
                return False
        return True

    def _tri(self, i, o, d, tmin):
        p0, e1, e2 = self.tris[i][:3]
        pv = cross(d, e2)
        det = dot(e1, pv)
        if abs(det) < 1e-14:
            return None
        inv = 1.0 / det
        tv = sub(o, p0)
        u = dot(tv, pv) * inv
        if u < 0.0 or u > 1.0:
            return None
        qv = cross(tv, e1)
        v = dot(d, qv) * inv
        if v < 0.0 or u + v > 1.0:
            return None
        t = dot(e2, qv) * inv
        return t if t > tmin else None

    def hits(self, o, d, tmin=1e-6, tmax=1e30, closest=True):
        """Closest hit (t, tri) or None; or, with closest=False, the list of all hits."""
        inv = tuple(1.0 / c if c != 0.0 else 1e30 for c in d)
        best, best_i, allh = tmax, -1, []
        stack = [0]
        while stack:
            lo, hi, l, r, start, count = self.nodes[stack.pop()]
            if not self._hit_box(lo, hi, o, inv, best if closest else tmax):
                continue
            if l < 0:
                for i in self.order[start:start + count]:
                    t = self._tri(i, o, d, tmin)
                    if t is not None and t < (best if closest else tmax):
                        if closest:
                            best, best_i = t, i
                        else:
                            allh.append((t, i))
            else:
                stack.append(l)
                stack.append(r)
        if not closest:
            return sorted(allh)
        return (best, best_i) if best_i >= 0 else None

    def occluded(self, a, b):
        d = sub(b, a)
        dist = math.sqrt(dot(d, d))
        d = mul(d, 1.0 / dist)
        h = self.hits(a, d, 1e-6, dist * (1 - 1e-6))
        return h is not None

    solids = None  # names of closed objects; set by the caller

    def inside_objects(self, p):
        """Closed objects whose interior contains p (parity along a fixed skew ray)."""
        d = norm((0.3141, 0.8217, 0.4777))
        count = {}
        for t, i in self.hits(p, d, 1e-9, closest=False):
            name = self.tris[i][4]
            if self.solids is None or name in self.solids:
                count[name] = count.get(name, 0) + 1
        return sorted(n for n, c in count.items() if c % 2 == 1)


# ---- generic checks -------------------------------------------------------------------------

def load_scene(folder, toml_name):
    with open(os.path.join(folder, toml_name), "rb") as f:
        cfg = tomllib.load(f)
    for key in ("camera", "render", "mesh"):
        check(key in cfg, f"{toml_name}: missing [{key}]")
    cam = cfg["camera"]
    for key in ("position", "look_at", "up", "fov_y", "resolution"):
        check(key in cam, f"{toml_name}: camera.{key} missing")
    for key in ("integrator", "spp", "max_depth", "seed"):
        check(key in cfg["render"], f"{toml_name}: render.{key} missing")
    tris, objs, mats = [], [], {}
    for mesh in cfg["mesh"]:
        path = os.path.join(folder, mesh["file"])
        check(os.path.isfile(path), f"{path} missing")
        verts, objects, mtllib = parse_obj(path)
        check(mtllib is not None and not os.path.isabs(mtllib), f"{path}: mtllib must be relative")
        mats.update(parse_mtl(os.path.join(os.path.dirname(path), mtllib)))
        for o in objects:
            o["verts"] = verts
            objs.append(o)
            for idx, m in o["tris"]:
                check(m in mats, f"{o['name']}: material {m} undefined")
                tris.append({"p": tuple(verts[i] for i in idx), "obj": o["name"], "mat": m, "idx": idx})
    return cfg, objs, mats, tris


def check_materials(mats):
    for name, m in mats.items():
        kd = m.get("Kd", [0, 0, 0])
        ks = m.get("Ks", [0, 0, 0])
        check(all(a + b <= 1.0 + 1e-9 for a, b in zip(kd, ks)), f"material {name}: Kd + Ks > 1")
        check(all(0 <= a <= 1 for a in kd + ks), f"material {name}: albedo outside [0, 1]")
        illum = int(m.get("illum", [2])[0])
        if max(ks) > 0:
            check(illum in (2, 3), f"material {name}: Ks > 0 but illum {illum}")


def tri_area(p):
    return 0.5 * math.sqrt(dot(*(cross(sub(p[1], p[0]), sub(p[2], p[0])),) * 2))


def check_geometry(objs, mats, open_objects, inward_objects=()):
    ntris = 0
    for o in objs:
        verts = o["verts"]
        ntris += len(o["tris"])
        min_area = min(tri_area([verts[i] for i in idx]) for idx, _ in o["tris"])
        check(min_area > 1e-7, f"{o['name']}: degenerate triangle (area {min_area:.3g})")
        emissive = any(max(mats[m].get("Ke", [0])) > 0 for _, m in o["tris"])
        if o["name"] in open_objects or (emissive and o["name"] not in inward_objects):
            continue
        # closedness by vertex position (rounded) so that duplicated vertices would not hide holes
        key = lambda i: tuple(round(c, 6) for c in verts[i])
        directed = {}
        for idx, _ in o["tris"]:
            for a, b in ((idx[0], idx[1]), (idx[1], idx[2]), (idx[2], idx[0])):
                e = (key(a), key(b))
                directed[e] = directed.get(e, 0) + 1
        bad = [e for e, c in directed.items() if c != 1 or directed.get((e[1], e[0]), 0) != 1]
        check(not bad, f"{o['name']}: not closed / inconsistent winding ({len(bad)} bad edges)")
        vol = 0.0
        for idx, _ in o["tris"]:
            p0, p1, p2 = (verts[i] for i in idx)
            vol += dot(p0, cross(p1, p2)) / 6.0
        o["closed"] = o["name"] not in inward_objects
        if o["name"] in inward_objects:
            check(vol < 0, f"{o['name']}: signed volume {vol:.4g} should be negative (inward)")
        else:
            check(vol > 0, f"{o['name']}: signed volume {vol:.4g} should be positive (outward)")
        o["volume"] = vol
    return ntris


def check_lights(objs, mats, expect_normal):
    lights = []
    for o in objs:
        emissive = [m for _, m in o["tris"] if max(mats[m].get("Ke", [0])) > 0]
        if not emissive:
            continue
        verts = o["verts"]
        if expect_normal is None:
            lights.append(o)
            continue
        check(len(o["tris"]) == 2, f"light {o['name']}: {len(o['tris'])} triangles, expected 2")
        uniq = {verts[i] for idx, _ in o["tris"] for i in idx}
        check(len(uniq) == 4, f"light {o['name']}: not a quad")
        for idx, _ in o["tris"]:
            p = [verts[i] for i in idx]
            n = norm(cross(sub(p[1], p[0]), sub(p[2], p[0])))
            check(dot(n, expect_normal) > 0.999999, f"light {o['name']}: normal {n}")
        lights.append(o)
    return lights


def check_rays(tracer, points, ndirs=3000, allow_escape=None, label=""):
    """From each point, every ray must hit a front face; escapes only where allowed."""
    dirs = fibonacci_dirs(ndirs)
    total = back = esc = 0
    for p in points:
        inside = tracer.inside_objects(p)
        check(not inside, f"{label}: point {p} is inside {inside}")
        for d in dirs:
            total += 1
            h = tracer.hits(p, d)
            if h is None:
                if allow_escape is None or not allow_escape(p, d):
                    esc += 1
                continue
            n = tracer.tris[h[1]][3]
            if dot(n, d) >= 0:
                back += 1
    check(back == 0, f"{label}: {back} rays hit a back face")
    check(esc == 0, f"{label}: {esc} rays escaped the scene")
    print(f"  rays from {len(points)} interior points x {ndirs} directions: {back} back-face hits, {esc} escapes")


# ---- preview --------------------------------------------------------------------------------

def write_png(path, w, h, rgb):
    raw = b"".join(b"\x00" + bytes(rgb[y * w * 3:(y + 1) * w * 3]) for y in range(h))

    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xffffffff)

    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(png)


def camera_rays(cam, w, h):
    pos = tuple(cam["position"])
    fwd = norm(sub(tuple(cam["look_at"]), pos))
    right = norm(cross(fwd, tuple(cam["up"])))
    up = cross(right, fwd)
    th = math.tan(math.radians(cam["fov_y"]) / 2)
    aspect = cam["resolution"][0] / cam["resolution"][1]
    for j in range(h):
        for i in range(w):
            sx = (2 * (i + 0.5) / w - 1) * th * aspect
            sy = (1 - 2 * (j + 0.5) / h) * th
            yield i, j, norm(add(fwd, add(mul(right, sx), mul(up, sy))))


def preview(tracer, cfg, mats, path, light_fn, w=160, on_hit=None, exposure=1.0):
    """Direct light only (+ a small ambient term), one shadow ray per light sample."""
    cam = cfg["camera"]
    h = int(w * cam["resolution"][1] / cam["resolution"][0])
    pos = tuple(cam["position"])
    img = bytearray(w * h * 3)
    for i, j, d in camera_rays(cam, w, h):
        hit = tracer.hits(pos, d)
        col = (0.0, 0.0, 0.0)
        if hit:
            t, k = hit
            p0, e1, e2, n, obj, mat = tracer.tris[k]
            m = mats[mat]
            ke = m.get("Ke", [0, 0, 0])
            x = add(pos, mul(d, t))
            if on_hit:
                on_hit(i, j, x, obj, mat)
            if max(ke) > 0 and dot(n, d) < 0:
                col = tuple(ke)
            else:
                kd = m.get("Kd", [0, 0, 0])
                ks = m.get("Ks", [0, 0, 0])
                nn = n if dot(n, d) < 0 else mul(n, -1)
                e = light_fn(tracer, add(x, mul(nn, 1e-5)), nn)
                amb = 0.02 * abs(dot(n, d))
                col = tuple((kd[c] + ks[c]) * (e[c] / math.pi + amb) for c in range(3))
        for c in range(3):
            v = max(0.0, col[c] * exposure)
            v = v / (1.0 + v)  # Reinhard
            img[(j * w + i) * 3 + c] = int(255 * (v ** (1 / 2.2)) + 0.5)
    write_png(path, w, h, img)


def area_light_fn(quads, ke, n_l, samples=3):
    """Irradiance from area lights (quads as 4 corners), samples x samples grid per light."""
    pts = []
    for q in quads:
        a, b, _, d = q
        area = math.sqrt(dot(*(cross(sub(b, a), sub(d, a)),) * 2))
        for u in range(samples):
            for v in range(samples):
                p = add(a, add(mul(sub(b, a), (u + 0.5) / samples), mul(sub(d, a), (v + 0.5) / samples)))
                pts.append((p, area / samples ** 2))

    def fn(tracer, x, n):
        e = [0.0, 0.0, 0.0]
        for p, dA in pts:
            v = sub(p, x)
            r2 = dot(v, v)
            wv = mul(v, 1 / math.sqrt(r2))
            c1, c2 = dot(n, wv), -dot(n_l, wv)
            if c1 <= 0 or c2 <= 0 or tracer.occluded(x, add(p, mul(n_l, 1e-4))):
                continue
            g = c1 * c2 * dA / r2
            for c in range(3):
                e[c] += ke[c] * g
        return e
    return fn


def spot_light_fn(light):
    pos = tuple(light["position"])
    axis = norm(tuple(light["direction"]))
    inten = light["intensity"]
    ci, co = math.cos(math.radians(light["inner_angle"])), math.cos(math.radians(light["outer_angle"]))

    def fn(tracer, x, n):
        v = sub(pos, x)
        r2 = dot(v, v)
        wv = mul(v, 1 / math.sqrt(r2))
        c = dot(n, wv)
        ca = -dot(wv, axis)
        if c <= 0 or ca <= co or tracer.occluded(x, pos):
            return [0.0, 0.0, 0.0]
        f = 1.0 if ca >= ci else (ca - co) / (ci - co)
        return [inten[k] * f * c / r2 for k in range(3)]
    return fn


# ---- scenes ---------------------------------------------------------------------------------

def light_quads(lights):
    quads = []
    for o in lights:
        verts = o["verts"]
        (a, b, c), _ = o["tris"][0]
        (a2, b2, c2), _ = o["tris"][1]
        quads.append((verts[a], verts[b], verts[c], verts[c2]))
    return quads


def scene_cornell(prev):
    print("cornell")
    folder = os.path.join(SCENES, "cornell")
    cfg, objs, mats, tris = load_scene(folder, "cornell.toml")
    check_materials(mats)
    walls = {"floor", "ceiling", "back_wall", "left_wall_red", "right_wall_green"}
    n = check_geometry(objs, mats, open_objects=walls)
    lights = check_lights(objs, mats, (0.0, -1.0, 0.0))
    print(f"  {n} triangles, {len(objs)} objects, {len(lights)} area light(s)")
    tr = Tracer(tris)
    tr.solids = {o["name"] for o in objs if o.get("closed")}
    centre = (2.78, 2.744, 2.796)
    for o in objs:
        if o["name"] in walls:
            verts = o["verts"]
            for idx, _ in o["tris"]:
                p = [verts[i] for i in idx]
                nrm = norm(cross(sub(p[1], p[0]), sub(p[2], p[0])))
                c = mul(add(add(p[0], p[1]), p[2]), 1 / 3)
                check(dot(nrm, sub(centre, c)) > 0, f"{o['name']}: normal does not face the box centre")

    def front(p, d):  # escaping through the open front z = 0
        if d[2] >= 0:
            return False
        t = -p[2] / d[2]
        x, y = p[0] + t * d[0], p[1] + t * d[1]
        return -0.01 <= x <= 5.57 and -0.01 <= y <= 5.50

    check_rays(tr, [centre, (1.0, 1.0, 1.0), (4.5, 4.5, 4.5), (2.0, 0.3, 5.0)], allow_escape=front,
               label="cornell interior")
    cam = tuple(cfg["camera"]["position"])
    occ = sum(tr.occluded(cam, c) for q in light_quads(lights) for c in q)
    print(f"  camera {cam}: light corners occluded {occ}/4 (seen from below, expected visible)")
    if prev:
        ke = mats["light"]["Ke"]
        preview(tr, cfg, mats, os.path.join(prev, "cornell.png"),
                area_light_fn(light_quads(lights), ke, (0, -1, 0)), exposure=1.0)


def scene_door(prev):
    print("door")
    folder = os.path.join(SCENES, "door")
    cfg, objs, mats, tris = load_scene(folder, "door.toml")
    check_materials(mats)
    n = check_geometry(objs, mats, open_objects=set())
    lights = check_lights(objs, mats, (0.0, -1.0, 0.0))
    check(len(lights) == 1, "door: expected one area light")
    check(n < 5000, "door: too many triangles")
    print(f"  {n} triangles, {len(objs)} objects, {len(lights)} area light(s)")
    tr = Tracer(tris)
    tr.solids = {o["name"] for o in objs if o.get("closed")}
    cam = tuple(cfg["camera"]["position"])

    # every wall box: the face toward its room points into the room (checked by rays below too)
    for room, centre in (("camera room", (2.0, 1.3, 2.0)), ("light room", (6.1, 1.3, 2.0))):
        check_rays(tr, [centre], ndirs=4000, label=room + " centre")
    check_rays(tr, [cam, (0.5, 0.2, 0.2), (3.8, 2.5, 3.8), (3.98, 1.0, 1.2985), (3.999, 2.3, 1.0), (4.05, 1.0, 1.0),
                    (4.3, 0.1, 0.2), (7.9, 2.5, 3.9), (6.6, 2.4, 2.5)], ndirs=2000, label="door interior")

    # gap width: the latch jamb corner J = (4.0, z 1.3) to the leaf (its vertices, projected to xz)
    leaf = next(o for o in objs if o["name"] == "door_leaf")
    lv = sorted({o_v for idx, _ in leaf["tris"] for o_v in (leaf["verts"][i] for i in idx)})
    foot = sorted({(round(v[0], 6), round(v[2], 6)) for v in lv})
    J = (4.0, 1.3)

    def seg_dist(p, a, b):
        ab = (b[0] - a[0], b[1] - a[1])
        t = max(0.0, min(1.0, ((p[0] - a[0]) * ab[0] + (p[1] - a[1]) * ab[1]) / (ab[0] ** 2 + ab[1] ** 2)))
        q = (a[0] + t * ab[0], a[1] + t * ab[1])
        return math.hypot(p[0] - q[0], p[1] - q[1])

    # footprint is a rectangle: order it around its centre
    cx = sum(p[0] for p in foot) / 4
    cz = sum(p[1] for p in foot) / 4
    foot.sort(key=lambda p: math.atan2(p[1] - cz, p[0] - cx))
    gap = min(seg_dist(J, foot[i], foot[(i + 1) % 4]) for i in range(4))
    check(0.03 <= gap <= 0.05, f"door gap {gap:.4f} m outside 3..5 cm")
    inside_jamb = [p for p in foot if 4.0 < p[0] < 4.1 and p[1] > 1.3]
    check(not inside_jamb, f"door leaf intersects the latch jamb: {inside_jamb}")
    print(f"  clear gap between leaf and latch jamb: {gap * 100:.2f} cm; leaf footprint {foot}")

    # Which side of the door an air point is on. Camera side: x < 4.0, except the wedge between
    # the wall plane x = 4.0 and the leaf's light-room face (that air belongs to the light room's
    # side: it is before the gap). Above the opening (y > 2.05) the lintel face x = 4.0 separates.
    hinge = sorted(foot, key=lambda p: p[1])[:2]
    fh, bh = sorted(hinge)                      # front (camera side) and back hinge corners
    u = ((bh[0] - fh[0]) / 0.04, (bh[1] - fh[1]) / 0.04)

    def camera_side(p):
        x, y, z = p
        if x >= 4.0:
            return False
        if y > 2.05 or z > 1.3 or z < fh[1]:
            return True
        return (x - bh[0]) * u[0] + (z - bh[1]) * u[1] < 0

    # direct light must not reach the camera room: rays from the light toward the whole opening
    q = light_quads(lights)[0]
    lpts = []
    for iu in range(5):
        for iv in range(5):
            a, b, _, d = q
            lpts.append(add(a, add(mul(sub(b, a), (iu + 0.5) / 5), mul(sub(d, a), (iv + 0.5) / 5))))
    lpts += [q[0], q[1], q[2], q[3]]
    lpts = [add(lp, (0, -1e-4, 0)) for lp in lpts]
    targets = []
    for x in (3.92, 3.96, 3.99, 4.0, 4.05, 4.1):
        for yi in range(24):
            for zi in range(20):
                targets.append((x, 0.01 + 2.1 * yi / 23, 0.38 + 0.95 * zi / 19))
    for xi in range(11):                         # the gap window itself, densely
        for yi in range(24):
            targets.append((3.9603 + 0.0397 * xi / 10, 0.01 + 2.04 * yi / 23, 1.2975))
    leaks = through = 0
    for lp in lpts:
        for tg in targets:
            dvec = norm(sub(tg, lp))
            h = tr.hits(lp, dvec)
            if not h:
                leaks += 1
                continue
            x = add(lp, mul(dvec, h[0] - 1e-4))
            if camera_side(x):
                leaks += 1
            elif x[0] < 4.0:
                through += 1
    check(leaks == 0, f"door: {leaks} direct rays from the light reach the camera room")
    print(f"  {len(lpts) * len(targets)} rays from the light aimed at the door opening and the gap: {leaks} reach "
          f"the camera room ({through} end in the wedge behind the leaf)")
    # and the other way round: points on camera-room surfaces never see the light
    pts = [(0.02 + 3.96 * i / 39, 0.0005, 0.02 + 3.96 * k / 39) for i in range(40) for k in range(40)]
    pts += [(3.9995, 0.02 + 2.56 * i / 24, 0.02 + 3.96 * k / 39) for i in range(25) for k in range(40)]
    pts += [(0.02 + 3.96 * i / 39, 2.5995, 0.02 + 3.96 * k / 39) for i in range(40) for k in range(40)]
    pts += [(0.0005, 0.02 + 2.56 * i / 24, 0.02 + 3.96 * k / 39) for i in range(25) for k in range(40)]
    # the leaf's camera-side face
    ffree = min((p for p in foot if p not in hinge), key=lambda p: p[0])
    for i in range(40):
        for k in range(20):
            t = (k + 0.5) / 20
            pts.append((fh[0] + t * (ffree[0] - fh[0]) - 0.0005 * u[0], 0.02 + 2.0 * i / 39,
                        fh[1] + t * (ffree[1] - fh[1]) - 0.0005 * u[1]))
    pts = [p for p in pts if camera_side(p) and not tr.inside_objects(p)]
    seen = 0
    for p in pts:
        for lp in lpts[:25:3]:
            if not tr.occluded(p, lp):
                seen += 1
    check(seen == 0, f"door: {seen} camera-room points see the light")
    print(f"  {len(pts)} camera-room surface points (floor, ceiling, walls, leaf) x 9 light points: {seen} unoccluded")
    occ = sum(tr.occluded(cam, lp) for lp in lpts)
    check(occ == len(lpts), "door: the camera sees the light")
    print(f"  camera {cam}: light occluded from {occ}/{len(lpts)} light points")

    stats = {"light": 0, "light_room": 0, "total": 0}

    def on_hit(i, j, x, obj, mat):
        stats["total"] += 1
        if obj == "light":
            stats["light"] += 1
        if x[0] > 4.1:
            stats["light_room"] += 1

    ke = mats["light"]["Ke"]
    if prev:
        preview(tr, cfg, mats, os.path.join(prev, "door.png"),
                area_light_fn([q], ke, (0, -1, 0), samples=2), w=256, on_hit=on_hit, exposure=4.0)
        # the light room seen from its own corner, for the layout
        c2 = dict(cfg)
        c2["camera"] = dict(cfg["camera"], position=[7.9, 2.3, 3.9], look_at=[4.1, 0.8, 0.8], fov_y=70)
        preview(tr, c2, mats, os.path.join(prev, "door_lightroom.png"),
                area_light_fn([q], ke, (0, -1, 0), samples=2), w=128)
    else:
        for i, j, d in camera_rays(cfg["camera"], 256, 256):
            h = tr.hits(cam, d)
            if h:
                on_hit(i, j, add(cam, mul(d, h[0])), tr.tris[h[1]][4], tr.tris[h[1]][5])
    check(stats["light"] == 0, "door: light visible from the camera")
    check(stats["light_room"] > 0, "door: camera does not see through the gap")
    print(f"  256x256 primary rays: {stats['light']} see the light, {stats['light_room']} see into the light room "
          f"through the gap")


def scene_desk(prev):
    print("desk")
    folder = os.path.join(SCENES, "desk")
    cfg, objs, mats, tris = load_scene(folder, "desk.toml")
    check_materials(mats)
    n = check_geometry(objs, mats, open_objects=set())
    lights = check_lights(objs, mats, (0.0, -1.0, 0.0))
    check(not lights, "desk: no emissive faces expected")
    check(n < 5000, "desk: too many triangles")
    print(f"  {n} triangles, {len(objs)} objects")
    tr = Tracer(tris)
    tr.solids = {o["name"] for o in objs if o.get("closed")}
    spot = cfg["light"][0]
    lp = tuple(spot["position"])
    cam = tuple(cfg["camera"]["position"])
    check_rays(tr, [(2.0, 1.3, 2.0), cam, (3.8, 2.5, 0.2), (2.0, 0.3, 3.6), (1.0, 0.72, 3.8), lp],
               ndirs=3000, label="desk interior")

    # where does the spot's cone land?
    axis = norm(tuple(spot["direction"]))
    co = math.cos(math.radians(spot["outer_angle"]))
    counts = {}
    open_max = 0.0
    shade_min = 90.0
    for d in fibonacci_dirs(40000):
        ca = dot(d, axis)
        if ca <= co:
            continue
        h = tr.hits(lp, d)
        key = tr.tris[h[1]][5] if h else "escaped"
        counts[key] = counts.get(key, 0) + 1
        ang = math.degrees(math.acos(min(1.0, ca)))
        if key == "shade_inside":
            shade_min = min(shade_min, ang)
        else:
            open_max = max(open_max, ang)
    tot = sum(counts.values())
    print("  spot cone (outer {:.0f} deg) lands on: {}".format(
        spot["outer_angle"], ", ".join(f"{k} {100 * v / tot:.1f}%" for k, v in sorted(counts.items()))))
    print(f"  directions leaving through the opening: up to {open_max:.1f} deg; shade inside hit from {shade_min:.1f} deg")
    allowed = {"shade_inside", "desk_top", "book"}
    check(set(counts) <= allowed, f"desk: spot cone reaches {set(counts) - allowed}")
    check(counts.get("shade_inside", 0) > 0, "desk: spot does not hit the inside of the shade")
    # spot on the desk
    top_y = max(p[1] for t in tris if t["mat"] == "desk_top" for p in t["p"])
    dist = lp[1] - top_y
    r = dist * math.tan(math.radians(open_max))
    inten = spot["intensity"]
    e0 = [i / dist ** 2 for i in inten]
    ce = math.cos(math.radians(open_max))
    e1 = [i * ce ** 3 / dist ** 2 for i in inten]
    print(f"  spot on the desk: radius ~{r:.3f} m around ({lp[0]}, {lp[2]}); irradiance centre "
          f"{e0[0]:.1f}/{e0[1]:.1f}/{e0[2]:.1f}, edge {e1[0]:.1f}/{e1[1]:.1f}/{e1[2]:.1f} W/m^2")
    check(5 <= max(e0) <= 20, "desk: spot irradiance outside 5..20 W/m^2")
    occ = tr.occluded(cam, (lp[0], top_y + 0.001, lp[2]))
    check(not occ, "desk: camera does not see the spot centre")
    if prev:
        preview(tr, cfg, mats, os.path.join(prev, "desk.png"), spot_light_fn(spot), w=256, exposure=1.0)


def scene_furnace(prev):
    print("furnace")
    folder = os.path.join(SCENES, "furnace")
    cfg, objs, mats, tris = load_scene(folder, "furnace.toml")
    check_materials(mats)
    n = check_geometry(objs, mats, open_objects=set(), inward_objects={"sphere"})
    check(n == 1280, f"furnace: {n} triangles, expected 1280")
    m = mats["furnace"]
    check(m["Kd"] == [0.5] * 3 and m["Ke"] == [0.5] * 3, "furnace: material")
    verts = objs[0]["verts"]
    rmin = min(math.sqrt(dot(v, v)) for v in verts)
    rmax = max(math.sqrt(dot(v, v)) for v in verts)
    check(abs(rmin - 1) < 1e-5 and abs(rmax - 1) < 1e-5, "furnace: vertices not on the unit sphere")
    print(f"  {n} triangles, vertex radius {rmin:.6f}..{rmax:.6f}, signed volume {objs[0]['volume']:.4f} "
          f"(sphere -4.18879)")
    tr = Tracer(tris)
    tr.solids = {o["name"] for o in objs if o.get("closed")}
    check_rays(tr, [(0, 0, 0), (0.3, 0.2, -0.5), (0.0, 0.0, 0.93)], ndirs=3000, label="furnace interior")


def main():
    prev = None
    if "--preview" in sys.argv:
        prev = sys.argv[sys.argv.index("--preview") + 1]
        os.makedirs(prev, exist_ok=True)
    scene_cornell(prev)
    scene_door(prev)
    scene_desk(prev)
    scene_furnace(prev)
    if FAILURES:
        print(f"\n{len(FAILURES)} check(s) failed")
        sys.exit(1)
    print("\nall checks passed")


if __name__ == "__main__":
    main()
