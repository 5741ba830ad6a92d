#!/usr/bin/env python3
"""footprint against LuxCoreRender (pyluxcore, CPU engines): conversion, image check, equal time.

    python3 scripts/vs_luxcore.py convert SCENE -o DIR  # the LuxCore scene (.scn/.cfg + PLY) only
    python3 scripts/vs_luxcore.py check [SCENE ...]     # image means of both renderers on the
                                                        # bundled and the public scenes
    python3 scripts/vs_luxcore.py compare [SCENE]       # equal time: LuxCore PATHCPU, PATHCPU
                                                        # with hybrid back/forward, BIDIRCPU next
                                                        # to `footprint compare`'s methods

SCENE is anything footprint reads (TOML or Mitsuba XML, with -D). The conversion starts from
footprint's own loaded scene: `footprint export` writes it as canonical Mitsuba XML with one
world-space OBJ per material, and this script turns that into LuxCore properties and one PLY
per material, so both renderers see the same triangles, normals and texture coordinates. What
LuxCore has no exact counterpart for is printed as `note:` lines (and listed in docs/luxcore.md).

pyluxcore is installed from PyPI on first use (`pip install pyluxcore`), as Mitsuba is by
scripts/vs_mitsuba.py; image files are read and written with Mitsuba's Bitmap (installed the
same way), and footprint is built with `cargo build --release` first.
"""
import argparse
import contextlib
import csv
import io
import json
import math
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import vs_mitsuba as vm  # noqa: E402  (shared: paths, Mitsuba for image I/O, footprint batches)

ROOT, FOOTPRINT, EXT = vm.ROOT, vm.FOOTPRINT, vm.EXT
REFS = os.path.join(os.path.dirname(ROOT), "shared", "refs")

# check: the bundled scenes' Mitsuba XML (what footprint and Mitsuba agree on exactly) and the
# public scenes, at small sizes.
CHECK_SCENES = {
    "scenes/cornell/mitsuba/scene.xml": dict(defines=dict(resx=48, resy=48), spp=256),
    "scenes/door/mitsuba/scene.xml": dict(defines=dict(resx=48, resy=32), spp=1024),
    "scenes/desk/mitsuba/scene.xml": dict(defines=dict(resx=48, resy=48), spp=512),
    "EXT/cornell-box-bitterli/scene.xml": dict(defines=dict(resx=64, resy=64, max_depth=8), spp=256),
    "EXT/cornell-box-mcguire/mitsuba/scene.xml": dict(defines=dict(res=64), spp=256),
    "EXT/veach-ajar/scene.xml": dict(defines=dict(resx=96, resy=54), spp=512),
}

# compare: scene, -D, footprint's own --resolution, Mitsuba-rendered reference if any.
COMPARE_SCENES = {
    "veach-ajar": dict(scene="EXT/veach-ajar/scene.xml", defines=dict(resx=128, resy=72),
                       reference=os.path.join(REFS, "veach-ajar_128x72.exr")),
    "door": dict(scene="scenes/door/mitsuba/scene.xml", defines=dict(resx=128, resy=128)),
    "desk": dict(scene="scenes/desk/mitsuba/scene.xml", defines=dict(resx=128, resy=128)),
}


LUX_METHODS = ("luxcore-path", "luxcore-hybrid", "luxcore-bidir", "luxcore-bidir-default-rr")


def scene_path(s):
    if s.startswith("EXT/"):
        return os.path.join(EXT, s[4:])
    return s if os.path.isabs(s) else os.path.join(ROOT, s)


# --------------------------------------------------------------------------------------------
# pyluxcore


_LUX = None


def luxcore():
    """pyluxcore, installed on first use. numpy must be imported first, or the process may
    crash on exit (`free(): invalid pointer`), and so must Mitsuba (used here for image files);
    pyluxcore's import banner is swallowed."""
    global _LUX
    if _LUX is not None:
        return _LUX
    import numpy  # noqa: F401  (before pyluxcore)

    vm.mitsuba()  # image I/O; Mitsuba loaded after pyluxcore aborts the process (free())
    try:
        with contextlib.redirect_stdout(io.StringIO()):
            import pyluxcore
    except ImportError:
        print("installing pyluxcore from PyPI ...", flush=True)
        subprocess.check_call([sys.executable, "-m", "pip", "install", "--quiet", "pyluxcore", "numpy"])
        with contextlib.redirect_stdout(io.StringIO()):
            import pyluxcore
    pyluxcore.Init(_lux_log)
    _LUX = pyluxcore
    return pyluxcore


_LOG = []


def _lux_log(msg):
    _LOG.append(msg)
    del _LOG[:-200]


def luxcore_available():
    """Whether pyluxcore (and numpy) can be imported, without importing them: importing
    pyluxcore before Mitsuba aborts the process when Mitsuba loads (see `luxcore`)."""
    import importlib.util

    return all(importlib.util.find_spec(m) is not None for m in ("numpy", "pyluxcore"))


def finish(code):
    """Leaves without running pyluxcore's exit-time destructors (which can abort the process
    after all work is done)."""
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)


# --------------------------------------------------------------------------------------------
# Conversion: footprint export (canonical Mitsuba XML + OBJ per material) -> LuxCore


def export(scene, defines, out, lenient=False):
    """`footprint export`: the scene as footprint loaded it. Returns its notes (stderr)."""
    if not os.path.exists(FOOTPRINT):
        sys.exit(f"{FOOTPRINT} is missing: run `cargo build --release` first")
    cmd = [FOOTPRINT, "export", scene, "-o", out]
    if scene.endswith(".xml"):
        for k, v in defines.items():
            cmd += ["-D", f"{k}={v}"]
        if lenient:
            cmd.append("--lenient")
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"footprint export failed:\n{r.stderr}")
    return [line[len("note: "):] for line in r.stderr.splitlines() if line.startswith("note: ")]


def floats(s):
    return [float(x) for x in s.replace(",", " ").split()]


def read_obj(path):
    """The exported OBJ: `v`, optional `vn`/`vt` with one index per corner (f a/a/a)."""
    import numpy as np

    v, vn, vt, f = [], [], [], []
    with open(path) as fh:
        for line in fh:
            t = line.split()
            if not t:
                continue
            if t[0] == "v":
                v.append([float(x) for x in t[1:4]])
            elif t[0] == "vn":
                vn.append([float(x) for x in t[1:4]])
            elif t[0] == "vt":
                vt.append([float(x) for x in t[1:3]])
            elif t[0] == "f":
                idx = [int(c.split("/")[0]) - 1 for c in t[1:4]]
                f.append(idx)
    v = np.array(v, dtype=np.float32)
    vn = np.array(vn, dtype=np.float32) if vn else None
    vt = np.array(vt, dtype=np.float32) if vt else None
    return v, vn, vt, np.array(f, dtype=np.int32)


def write_ply(path, v, vn, vt, f):
    """Binary PLY. Texture coordinates as `s`, `t` with t = 1 - v (Mitsuba's uv: the OBJ's v
    flipped), so every texture lookup below happens in Mitsuba's (u, v)."""
    import numpy as np

    cols = [v]
    props = ["x", "y", "z"]
    if vn is not None:
        cols.append(vn)
        props += ["nx", "ny", "nz"]
    if vt is not None:
        cols.append(np.stack([vt[:, 0], 1.0 - vt[:, 1]], axis=1))
        props += ["s", "t"]
    verts = np.ascontiguousarray(np.concatenate(cols, axis=1).astype("<f4"))
    head = ["ply", "format binary_little_endian 1.0", f"element vertex {len(v)}"]
    head += [f"property float {p}" for p in props]
    head += [f"element face {len(f)}", "property list uchar int vertex_indices", "end_header"]
    faces = np.zeros(len(f), dtype=[("n", "u1"), ("i", "<i4", (3,))])
    faces["n"] = 3
    faces["i"] = f
    with open(path, "wb") as fh:
        fh.write(("\n".join(head) + "\n").encode())
        fh.write(verts.tobytes())
        fh.write(faces.tobytes())


def fmt(xs):
    return " ".join(repr(float(x)) for x in xs)


class Converter:
    """Reads `footprint export`'s XML (a fixed, known subset of Mitsuba 3) and writes LuxCore
    scene properties. `self.notes` lists every approximation."""

    def __init__(self, export_dir, work_dir):
        self.src = export_dir
        self.dir = work_dir
        self.notes = []
        self.scene = []  # "key = value" lines of the .scn
        self.tex_count = 0
        root = ET.parse(os.path.join(export_dir, "scene.xml")).getroot()
        self.defaults = {d.get("name"): d.get("value") for d in root.findall("default")}
        self.root = root
        self.width = int(self.defaults["resx"])
        self.height = int(self.defaults["resy"])
        self.max_depth = int(self.defaults["max_depth"])
        self.rfilter = self.defaults["rfilter"]
        self.filter_param = None
        self.bsdfs = {b.get("id"): b for b in root.findall("bsdf")}
        self._camera(root.find("sensor"))
        for i, shape in enumerate(root.findall("shape")):
            self._shape(i, shape)
        for i, em in enumerate(root.findall("emitter")):
            self._emitter(i, em)

    def note(self, s):
        if s not in self.notes:
            self.notes.append(s)

    def add(self, key, value):
        self.scene.append(f"{key} = {value}")

    # camera ---------------------------------------------------------------------------------
    def _camera(self, sensor):
        fov_y = float(sensor.find("float[@name='fov']").get("value"))
        la = sensor.find("transform/lookat")
        film = sensor.find("film")
        rf = film.find("rfilter")
        for p in rf:
            self.filter_param = (p.get("name"), float(p.get("value")))
        w, h = self.width, self.height
        # LuxCore's fieldofview spans [-1, 1] of its screen window, whose default is
        # [-a, a] x [-1, 1] (a = w/h >= 1) or [-1, 1] x [-1/a, 1/a]. An explicit window
        # [-a, a] x [-1, 1] makes fieldofview the vertical one whatever the aspect. LuxCore's
        # image then lies one pixel row low against Mitsuba's and footprint's (its raster y is
        # off by one row after the flip): the window moves down by one row, 2/h.
        self.add("scene.camera.type", '"perspective"')
        self.add("scene.camera.lookat.orig", fmt(floats(la.get("origin"))))
        self.add("scene.camera.lookat.target", fmt(floats(la.get("target"))))
        self.add("scene.camera.up", fmt(floats(la.get("up"))))
        self.fov_y = fov_y
        self.add("scene.camera.fieldofview", repr(fov_y))
        a, dy = w / h, 2.0 / h
        self.add("scene.camera.screenwindow", fmt([-a, a, -1.0 - dy, 1.0 - dy]))

    # textures -------------------------------------------------------------------------------
    def _to_uv(self, tex):
        """Mitsuba's to_uv as LuxCore's uvmapping2d (scale, delta); only axis-aligned ones."""
        m = tex.find("transform[@name='to_uv']/matrix")
        if m is None:
            return (1.0, 1.0), (0.0, 0.0)
        a = floats(m.get("value"))
        if abs(a[1]) > 0 or abs(a[4]) > 0:
            self.note("a texture's to_uv rotates or shears: LuxCore's uvmapping2d takes its axis-aligned part only")
        return (a[0], a[5]), (a[3], a[7])

    def _mapping(self, name, scale, delta):
        self.add(f"scene.textures.{name}.mapping.type", '"uvmapping2d"')
        self.add(f"scene.textures.{name}.mapping.uvscale", fmt(scale))
        self.add(f"scene.textures.{name}.mapping.uvdelta", fmt(delta))

    def texture(self, el, transform=None):
        """A colour property (rgb or texture element) -> LuxCore texture name or constant.
        `transform(c)` maps colours (used to build float amounts)."""
        tf = transform or (lambda c: c)
        if el.tag == "rgb":
            return fmt(tf(floats(el.get("value"))))
        if el.tag == "float":
            return fmt(tf([float(el.get("value"))] * 3))
        kind = el.get("type")
        self.tex_count += 1
        name = f"tex{self.tex_count}"
        scale, delta = self._to_uv(el)
        if kind == "checkerboard":
            c0 = tf(floats(el.find("rgb[@name='color0']").get("value")))
            c1 = tf(floats(el.find("rgb[@name='color1']").get("value")))
            # Mitsuba: colour0 where frac(u) > .5 == frac(v) > .5, i.e. where
            # floor(2u) + floor(2v) is even: LuxCore's checkerboard2d at twice the scale.
            self.add(f"scene.textures.{name}.type", '"checkerboard2d"')
            self.add(f"scene.textures.{name}.texture1", fmt(c0))
            self.add(f"scene.textures.{name}.texture2", fmt(c1))
            self._mapping(name, [2 * s for s in scale], [2 * d for d in delta])
            return name
        if kind == "bitmap":
            if transform is not None:
                self.note("a bitmap used as a scale of a LuxCore mix amount is approximated by its luminance")
            fn = el.find("string[@name='filename']").get("value")
            src = os.path.join(self.src, fn)
            dst = os.path.join(self.dir, f"{name}.exr")
            linearise(src, dst)
            self.add(f"scene.textures.{name}.type", '"imagemap"')
            self.add(f"scene.textures.{name}.file", f'"{dst}"')
            self.add(f"scene.textures.{name}.gamma", "1.0")
            self.add(f"scene.textures.{name}.gain", "1.0")
            self._mapping(name, scale, delta)
            return name
        raise SystemExit(f"vs_luxcore: texture type {kind} is not converted")

    # materials ------------------------------------------------------------------------------
    def material(self, name, bsdf, emission=None):
        two_sided = bsdf.get("type") == "twosided"
        inner = bsdf.find("bsdf") if two_sided else bsdf
        kind = inner.get("type")
        base = f"{name}_front" if (not two_sided and kind not in ("dielectric", "thindielectric")) else name
        self._inner(base, inner)
        if base != name:
            # Mitsuba's one-sided BSDFs are black from behind: LuxCore's twosided material
            # with a black matte back.
            self.add(f"scene.materials.{name}_back.type", '"matte"')
            self.add(f"scene.materials.{name}_back.kd", "0 0 0")
            self.add(f"scene.materials.{name}.type", '"twosided"')
            self.add(f"scene.materials.{name}.frontmaterial", f'"{base}"')
            self.add(f"scene.materials.{name}.backmaterial", f'"{name}_back"')
        if emission is not None:
            self.add(f"scene.materials.{name}.emission", fmt(emission))
            self.add(f"scene.materials.{name}.emission.gain", "1 1 1")
            self.add(f"scene.materials.{name}.emission.power", "0")
            self.add(f"scene.materials.{name}.emission.efficency", "0")

    def _prop(self, inner, name):
        for el in inner:
            if el.get("name") == name:
                return el
        return None

    def _inner(self, name, b):
        kind = b.get("type")
        P = f"scene.materials.{name}"
        if kind == "diffuse":
            self.add(f"{P}.type", '"matte"')
            self.add(f"{P}.kd", self.texture(self._prop(b, "reflectance")))
        elif kind in ("conductor", "roughconductor"):
            none = (b.find("string[@name='material']") is not None)
            spec = self._prop(b, "specular_reflectance")
            if kind == "conductor" and none:
                self.add(f"{P}.type", '"mirror"')
                self.add(f"{P}.kr", self.texture(spec) if spec is not None else "1 1 1")
                return
            eta = [0.0] * 3 if none else floats(self._prop(b, "eta").get("value"))
            k = [1.0] * 3 if none else floats(self._prop(b, "k").get("value"))
            if kind == "conductor":
                alpha = 1e-3
                self.note("smooth conductor with a complex IOR: LuxCore's metal2 at alpha 0.001 (its mirror has no Fresnel term)")
            else:
                alpha = float(self._prop(b, "alpha").get("value"))
                dist = self._prop(b, "distribution")
                dist = dist.get("value") if dist is not None else "beckmann"
                self.note("rough conductor: LuxCore's metal2 with u = v = alpha has GGX's D but Schlick's approximation of Smith's G")
                if dist == "beckmann":
                    self.note("Beckmann rough conductor: written as GGX (metal2) of the same alpha")
            metal = f"{name}_metal" if not self._is_white(spec) else name
            M = f"scene.materials.{metal}"
            self.add(f"{M}.type", '"metal2"')
            self.add(f"{M}.n", fmt(eta))
            self.add(f"{M}.k", fmt(k))
            self.add(f"{M}.uroughness", repr(alpha))
            self.add(f"{M}.vroughness", repr(alpha))
            if metal != name:
                # Mitsuba's specular_reflectance scales the conductor. LuxCore's metal2 has no
                # scale: mix(metal, black, amount = 1 - s) is metal * s, exact for grey s.
                if not self._is_grey(spec):
                    self.note("a coloured specular_reflectance on a conductor: LuxCore's mix amount takes its luminance")
                lum = lambda c: [1.0 - (0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2])] * 3  # noqa: E731
                amount = self.texture(spec, lum)
                self.add(f"scene.materials.{name}_black.type", '"matte"')
                self.add(f"scene.materials.{name}_black.kd", "0 0 0")
                self.add(f"{P}.type", '"mix"')
                self.add(f"{P}.material1", f'"{metal}"')
                self.add(f"{P}.material2", f'"{name}_black"')
                self.add(f"{P}.amount", amount)
        elif kind in ("plastic", "roughplastic"):
            ior = float(self._prop(b, "int_ior").get("value")) / float(self._prop(b, "ext_ior").get("value"))
            alpha = float(self._prop(b, "alpha").get("value")) if kind == "roughplastic" else 1e-3
            self.note(f"{kind}: LuxCore's glossy2 (Schlick-Fresnel coating of index {ior:g} over the diffuse base, GGX of the same alpha, Schlick's G); Mitsuba's internal scattering and Fresnel-weighted diffuse term differ")
            spec = self._prop(b, "specular_reflectance")
            if spec is not None and not self._is_white(spec):
                self.note(f"{kind}: specular_reflectance other than 1 is dropped (glossy2's coating strength comes from the index)")
            self.add(f"{P}.type", '"glossy2"')
            self.add(f"{P}.kd", self.texture(self._prop(b, "diffuse_reflectance")))
            self.add(f"{P}.ks", "1 1 1")
            self.add(f"{P}.index", fmt([ior] * 3))
            self.add(f"{P}.uroughness", repr(alpha))
            self.add(f"{P}.vroughness", repr(alpha))
            self.add(f"{P}.multibounce", "0")
        elif kind == "dielectric":
            self.add(f"{P}.type", '"glass"')
            self.add(f"{P}.kr", "1 1 1")
            self.add(f"{P}.kt", self.texture(self._prop(b, "specular_transmittance")))
            self.add(f"{P}.interiorior", self._prop(b, "int_ior").get("value"))
            self.add(f"{P}.exteriorior", self._prop(b, "ext_ior").get("value"))
        elif kind == "thindielectric":
            self.note("thindielectric: LuxCore's archglass (a thin sheet without Mitsuba's sum over internal reflections)")
            self.add(f"{P}.type", '"archglass"')
            self.add(f"{P}.kr", "1 1 1")
            self.add(f"{P}.kt", self.texture(self._prop(b, "specular_transmittance")))
            self.add(f"{P}.interiorior", self._prop(b, "int_ior").get("value"))
            self.add(f"{P}.exteriorior", self._prop(b, "ext_ior").get("value"))
        else:
            raise SystemExit(f"vs_luxcore: BSDF type {kind} is not converted")

    def _is_white(self, el):
        return el is None or (el.tag == "rgb" and floats(el.get("value")) == [1.0, 1.0, 1.0])

    def _is_grey(self, el):
        if el.tag == "rgb":
            c = floats(el.get("value"))
            return max(c) - min(c) < 1e-6
        if el.get("type") == "checkerboard":
            return all(self._is_grey(c) for c in el.findall("rgb"))
        return False

    # shapes ---------------------------------------------------------------------------------
    def _shape(self, i, shape):
        fn = shape.find("string[@name='filename']").get("value")
        ref = shape.find("ref").get("id")
        em = shape.find("emitter")
        emission = floats(em.find("rgb").get("value")) if em is not None else None
        mat = f"mat{i}"
        self.material(mat, self.bsdfs[ref], emission)
        v, vn, vt, f = read_obj(os.path.join(self.src, fn))
        ply = os.path.join(self.dir, f"mesh{i}.ply")
        write_ply(ply, v, vn, vt, f)
        self.add(f"scene.shapes.mesh{i}.type", '"mesh"')
        self.add(f"scene.shapes.mesh{i}.ply", f'"{ply}"')
        self.add(f"scene.objects.obj{i}.shape", f'"mesh{i}"')
        self.add(f"scene.objects.obj{i}.material", f'"{mat}"')

    # lights ---------------------------------------------------------------------------------
    def _emitter(self, i, em):
        kind = em.get("type")
        L = f"scene.lights.light{i}"
        if kind == "point":
            self.add(f"{L}.type", '"point"')
            self.add(f"{L}.position", fmt(floats(em.find("point[@name='position']").get("value"))))
            # LuxCore's point light (power 0) has intensity color / (4 pi).
            self.add(f"{L}.color", fmt([4 * math.pi * c for c in floats(em.find("rgb").get("value"))]))
        elif kind == "constant":
            self.add(f"{L}.type", '"constantinfinite"')
            self.add(f"{L}.color", fmt(floats(em.find("rgb").get("value"))))
        elif kind == "spot":
            self._spot(L, i, em)
            return
        else:
            raise SystemExit(f"vs_luxcore: emitter type {kind} is not converted")
        self.add(f"{L}.gain", "1 1 1")
        self.add(f"{L}.power", "0")
        self.add(f"{L}.efficency", "0")

    def _spot(self, L, i, em):
        """Mitsuba's spot as LuxCore's `mappoint`: a point light whose intensity follows an
        image over the sphere of directions, here the exact profile (1 inside beam_width,
        linear in angle to 0 at cutoff_angle) in a latitude-longitude map around the spot's
        axis. LuxCore's own `spot` has a different falloff and a 1/cos factor."""
        import numpy as np

        la = em.find("transform/lookat")
        pos, target = np.array(floats(la.get("origin"))), np.array(floats(la.get("target")))
        cutoff = math.radians(float(em.find("float[@name='cutoff_angle']").get("value")))
        beam = math.radians(float(em.find("float[@name='beam_width']").get("value")))
        intensity = floats(em.find("rgb").get("value"))
        z = target - pos
        z /= np.linalg.norm(z)
        a = np.array([1.0, 0.0, 0.0]) if abs(z[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
        x = np.cross(a, z)
        x /= np.linalg.norm(x)
        y = np.cross(z, x)
        H = SPOT_ROWS
        theta = math.pi * (np.arange(H) + 0.5) / H

        def profile(t):
            if beam >= cutoff:
                return np.where(t <= cutoff, 1.0, 0.0)
            return np.clip((cutoff - t) / (cutoff - beam), 0.0, 1.0)

        img = np.repeat(profile(theta)[:, None], 4, axis=1)
        # LuxCore normalises the map by its average over the sphere, 4 pi times the
        # sin-weighted mean over a 512 x 256 grid of directions (bilinear look-ups of the map),
        # and divides a point light by 4 pi: the colour carries both back.
        mean = spot_map_mean(img)
        path = os.path.join(self.dir, f"spot{i}.exr")
        write_exr(np.repeat(img[:, :, None], 3, axis=2), path)
        self.add(f"{L}.type", '"mappoint"')
        self.add(f"{L}.mapfile", f'"{path}"')
        self.add(f"{L}.gamma", "1.0")
        m = [x[0], y[0], z[0], pos[0], x[1], y[1], z[1], pos[1], x[2], y[2], z[2], pos[2], 0, 0, 0, 1]
        # LuxCore reads transformation matrices column by column.
        mt = [m[c + 4 * r] for c in range(4) for r in range(4)]
        self.add(f"{L}.transformation", fmt(mt))
        self.add(f"{L}.position", "0 0 0")
        self.add(f"{L}.color", fmt([c * 16 * math.pi**2 * mean for c in intensity]))
        self.add(f"{L}.gain", "1 1 1")
        self.add(f"{L}.power", "0")
        self.add(f"{L}.efficency", "0")

    # render configuration -------------------------------------------------------------------
    def filter_props(self):
        if self.rfilter == "box":
            return {"film.filter.type": "BOX", "film.filter.width": 0.5}
        if self.rfilter == "gaussian":
            sd = self.filter_param[1] if self.filter_param else 0.5
            return {"film.filter.type": "GAUSSIAN", "film.filter.width": 4 * sd,
                    "film.filter.gaussian.alpha": 1 / (2 * sd * sd)}
        if self.rfilter == "tent":
            r = self.filter_param[1] if self.filter_param else 1.0
            sd = r / math.sqrt(6)
            self.note(f"tent filter (radius {r:g}): LuxCore has none; a Gaussian of equal variance (stddev {sd:.3f}, cut at {2 * sd * 2:.2f})")
            return {"film.filter.type": "GAUSSIAN", "film.filter.width": 4 * sd,
                    "film.filter.gaussian.alpha": 1 / (2 * sd * sd)}
        raise SystemExit(f"vs_luxcore: filter {self.rfilter} is not converted")


SPOT_ROWS = 1024


def spot_map_mean(img):
    """The sin-weighted mean LuxCore's SampleableSphericalFunction takes of a map constant
    along phi: 256 rows of directions at (y + .5) / 256 * pi, bilinear look-ups with texel
    centres at (i + .5) / H (clamped at the poles)."""
    import numpy as np

    col = img[:, 0]
    H = len(col)
    ys = (np.arange(256) + 0.5) / 256
    t = ys * H - 0.5
    i0 = np.clip(np.floor(t).astype(int), 0, H - 1)
    i1 = np.clip(i0 + 1, 0, H - 1)
    f = t - np.floor(t)
    v = col[i0] * (1 - f) + col[i1] * f
    w = np.sin(np.pi * ys)
    return float((v * w).sum() / w.sum())


def linearise(src, dst):
    """The exported sRGB PNG as a linear float EXR (LuxCore's own gamma is a pure power)."""
    mi = vm.mitsuba()
    bmp = mi.Bitmap(src).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32, srgb_gamma=False)
    bmp.write(dst)


def engine_props(conv, method, threads, seed, rr_depth=None):
    """Render configuration of one LuxCore method. Depths: PATHCPU's path.pathdepth.total is
    Mitsuba's max_depth (segments, camera ray = 1): checked on Bitterli's Cornell box at depth
    3, where depth - 1 is 12-19% dark."""
    d = max(1, conv.max_depth)
    p = {
        "film.width": conv.width, "film.height": conv.height,
        "native.threads.count": threads, "renderengine.seed": seed,
        "sampler.type": "SOBOL", "sampler.sobol.adaptive.strength": 0.0,
        "lightstrategy.type": "POWER",
    }
    p.update(conv.filter_props())
    if method in ("luxcore-path", "luxcore-hybrid"):
        p.update({"renderengine.type": "PATHCPU", "path.pathdepth.total": d, "path.pathdepth.diffuse": d,
                  "path.pathdepth.glossy": d, "path.pathdepth.specular": d})
        if method == "luxcore-hybrid":
            p["path.hybridbackforward.enable"] = 1
    elif method.startswith("luxcore-bidir"):
        # BIDIRCPU caps each subpath, not the whole path: eye and light subpaths of max_depth - 1
        # vertices make every path of up to max_depth segments by every strategy but the last
        # emitter hit, and add longer ones (up to 2 max_depth - 1) by some strategies (measured
        # on Bitterli's Cornell box at depth 3: 3.5% brighter than the depth-3 image).
        p.update({"renderengine.type": "BIDIRCPU", "path.maxdepth": max(1, d - 1), "light.maxdepth": max(1, d - 1),
                  "sampler.type": "SOBOL"})
        if method == "luxcore-bidir":
            # LuxCore's BIDIRCPU is biased by its Russian roulette (measured on Veach Ajar:
            # 34% too bright at the defaults): start it past the longest path.
            p["path.russianroulette.depth"] = 2 * (d + 2)
    else:
        raise SystemExit(f"unknown LuxCore method {method}")
    if rr_depth is not None:
        p["path.russianroulette.depth"] = rr_depth
    return p


def props_text(d):
    out = []
    for k, v in d.items():
        if isinstance(v, str) and not v.replace(".", "").replace("-", "").isdigit():
            v = f'"{v}"'
        out.append(f"{k} = {v}")
    return "\n".join(out)


class LuxScene:
    """A converted scene, ready to render with any engine."""

    def __init__(self, scene, defines=None, keep=None, lenient=False, quiet=False):
        self.tmp = tempfile.mkdtemp(prefix="vs_luxcore-")
        self.dir = keep or self.tmp
        os.makedirs(self.dir, exist_ok=True)
        exp = os.path.join(self.tmp, "export")
        self.export_notes = export(scene, defines or {}, exp, lenient)
        self.conv = Converter(exp, self.dir)
        self.conv.filter_props()  # collects the filter note
        self.notes = [f"footprint export: {n}" for n in self.export_notes] + self.conv.notes
        with open(os.path.join(self.dir, "scene.scn"), "w") as f:
            f.write("\n".join(self.conv.scene) + "\n")
        if not quiet:
            for n in self.notes:
                print(f"note: {n}")

    def render(self, method, threads=2, seed=1, spp=None, seconds=None, rr_depth=None):
        """Renders; returns (image HxWx3 float64, stats dict)."""
        import numpy as np

        lux = luxcore()
        cfg = engine_props(self.conv, method, threads, seed, rr_depth)
        if spp is not None:
            cfg["batch.haltspp"] = spp
        if seconds is not None:
            cfg["batch.halttime"] = seconds
        scene_props = lux.Properties()
        scene_props.SetFromString("\n".join(self.conv.scene))
        scene = lux.Scene()
        scene.Parse(scene_props)
        cprops = lux.Properties()
        cprops.SetFromString(props_text(cfg))
        config = lux.RenderConfig(cprops, scene)
        lux_render = lux.RenderSession(config)
        t0 = time.time()
        lux_render.Start()
        t_started = time.time()
        while not lux_render.HasDone():
            time.sleep(0.05)
            lux_render.UpdateStats()
        t_done = time.time()
        lux_render.UpdateStats()
        stats = lux_render.GetStats()
        passes = stats.Get("stats.renderengine.pass").GetInt()
        film = lux_render.GetFilm()
        w, h = self.conv.width, self.conv.height
        buf = np.zeros(w * h * 3, dtype=np.float32)
        film.GetOutputFloat(lux.FilmOutputType.RGB, buf)
        lux_render.Stop()
        img = buf.reshape(h, w, 3)[::-1].astype(np.float64)  # LuxCore's row 0 is the bottom
        return img, dict(spp=passes, seconds=t_done - t0, start_seconds=t_started - t0, config=cfg)

    def cleanup(self):
        shutil.rmtree(self.tmp, ignore_errors=True)


def write_exr(img, path):
    import numpy as np

    mi = vm.mitsuba()
    mi.Bitmap(np.ascontiguousarray(img.astype(np.float32))).write(path)


def read_exr(path):
    import numpy as np

    mi = vm.mitsuba()
    layers = mi.Bitmap(path).split()
    return np.array(layers[0][1], dtype=np.float64)[..., :3]


# --------------------------------------------------------------------------------------------
# Commands


def lux_batches(ls, method, batches, spp, rr_depth=None):
    import numpy as np

    out, t0 = [], time.time()
    for k in range(batches):
        img, _ = ls.render(method, seed=1 + k, spp=spp, rr_depth=rr_depth)
        out.append(img)
    return np.stack(out), time.time() - t0


def mean_ratio(a, b):
    """Ratio of image means per channel and its standard error (from the batch means)."""
    import numpy as np

    ma, mb = a.mean(axis=(1, 2)), b.mean(axis=(1, 2))  # batches x 3
    ra, rb = ma.mean(axis=0), mb.mean(axis=0)
    sa = ma.std(axis=0, ddof=1) / math.sqrt(len(ma))
    sb = mb.std(axis=0, ddof=1) / math.sqrt(len(mb))
    ratio = ra / np.maximum(rb, 1e-30)
    va, vb = (sa / np.maximum(ra, 1e-30)) ** 2, (sb / np.maximum(rb, 1e-30)) ** 2
    se = ratio * np.sqrt(va + vb)
    # Welch-Satterthwaite degrees of freedom of that standard error (it is estimated from a
    # few batch means: Student's t, not the normal, says how far the ratio may stray).
    dof = (va + vb) ** 2 / np.maximum(va ** 2 / (len(ma) - 1) + vb ** 2 / (len(mb) - 1), 1e-300)
    return ra, rb, ratio, se, dof


def cmd_convert(args):
    defines = dict(d.split("=", 1) for d in args.define)
    os.makedirs(args.out, exist_ok=True)
    ls = LuxScene(os.path.abspath(args.scene), defines, keep=os.path.abspath(args.out), lenient=args.lenient)
    cfg = engine_props(ls.conv, args.method, 2, 1)
    with open(os.path.join(args.out, "render.cfg"), "w") as f:
        f.write(props_text(cfg) + f'\nscene.file = "{os.path.join(os.path.abspath(args.out), "scene.scn")}"\n')
    with open(os.path.join(args.out, "notes.txt"), "w") as f:
        f.write("\n".join(ls.notes) + "\n")
    print(f"{args.scene} -> {args.out}/scene.scn, render.cfg ({args.method}), {len(ls.notes)} notes")
    ls.cleanup()
    return 0


def cmd_check(args):
    """Both renderers on each scene: K independent batches each; the image means must agree
    within --tolerance (2%) per channel, or within Student's t (Welch, 0.001 per scene) times
    the ratio's standard error when the batches are noisier, or the conversion's notes must
    say why not."""
    import numpy as np

    if args.no_install and not luxcore_available():
        print("SKIPPED: pyluxcore is not installed (run without --no-install to install it)")
        return 0
    luxcore()
    scenes = args.scenes or list(CHECK_SCENES)
    failed = 0
    rows = []
    for s in scenes:
        path = scene_path(s)
        if not os.path.exists(path):
            print(f"SKIPPED {s}: {path} is absent (the public scenes live beside the repository, not in it)")
            continue
        p = CHECK_SCENES.get(s, dict(defines={}, spp=256))
        defines = dict(p["defines"])
        for d in args.define:
            k, v = d.split("=", 1)
            defines[k] = v
        spp = args.spp or p["spp"]
        ls = LuxScene(path, defines, quiet=True)
        a, ta = vm.footprint_batches(path, defines, args.batches, spp, ["--integrator", args.integrator])
        b, tb = lux_batches(ls, args.method, args.batches, spp, args.rr_depth)
        ra, rb, ratio, se, dof = mean_ratio(a, b)
        t = vm.compare(a, b, args.block)
        # Within --tolerance, or within Student's t critical value (Welch degrees of freedom;
        # a false alarm once in 1000 checks of a scene, Šidák over its 3 channels) times the
        # standard error of the ratio where the batches are noisier than that (door at
        # 8 x 128 spp: about 1% per channel). A fixed "4 standard errors" with a standard error
        # from 4 batches failed a correct render about once in 30 channels.
        alpha = 1 - (1 - 0.001) ** (1 / 3)
        crit = np.array([vm.t_quantile(1 - alpha / 2, max(float(d), 1.0)) for d in dof])
        bound = np.maximum(args.tolerance, crit * se)
        ok = bool(np.all(np.abs(ratio - 1) <= bound))
        failed += not ok
        print(f"{'PASS' if ok else 'FAIL'} {s}: {args.batches} x {spp} spp, -D {defines}, LuxCore {args.method}")
        print(f"     means footprint {['%.5f' % x for x in ra]} luxcore {['%.5f' % x for x in rb]}")
        print(f"     ratio footprint/luxcore {['%.4f' % x for x in ratio]} (+- {['%.4f' % x for x in se]} standard error; bound {['%.4f' % x for x in bound]})")
        print(f"     per {args.block}x{args.block} block: max |t| {t['max_t']:.2f} (limit {t['crit']:.2f}), "
              f"{t['failing']} of {t['blocks']} block-channels beyond it (informative: converted approximations show here)")
        print(f"     time footprint {ta:.1f} s, luxcore {tb:.1f} s")
        for n in ls.notes:
            print(f"     note: {n}")
        rows.append(dict(scene=s, defines=defines, spp=spp, batches=args.batches, method=args.method,
                         mean_footprint=ra.tolist(), mean_luxcore=rb.tolist(), ratio=ratio.tolist(),
                         ratio_se=se.tolist(), max_t=t["max_t"], t_limit=t["crit"], failing_blocks=t["failing"],
                         blocks=t["blocks"], ok=ok, notes=ls.notes))
        ls.cleanup()
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=2)
    return 1 if failed else 0


def cached_luxcore_reference(ls, out, seconds, method="luxcore-path"):
    """LuxCore's own high-sample reference of the converted scene, cached in `out` with a key
    of the converted scene and the settings."""
    import hashlib

    key = hashlib.sha256(("\n".join(ls.conv.scene) + f"|{method}|{seconds}|{ls.conv.max_depth}|"
                          + json.dumps(ls.conv.filter_props(), sort_keys=True)).encode()).hexdigest()[:16]
    path = os.path.join(out, f".luxcore-reference-{ls.conv.width}x{ls.conv.height}-{key}.exr")
    if os.path.exists(path):
        return path, json.load(open(path + ".json"))
    print(f"rendering LuxCore's reference: {method}, {seconds:g} s ...", flush=True)
    img, st = ls.render(method, seed=12345, seconds=seconds)
    write_exr(img, path)
    meta = dict(method=method, seconds=round(st["seconds"], 1), spp=st["spp"])
    json.dump(meta, open(path + ".json", "w"))
    return path, meta


def cmd_compare(args):
    """Equal time: `footprint compare` for footprint's methods; LuxCore's engines given the same
    wall-clock budget (scene preprocessing included, as footprint's budget includes its map
    passes). Each method is measured against its own renderer's reference (the converted
    images differ where the conversion approximates) and, for reference, against footprint's."""
    if args.no_install and not luxcore_available():
        print("SKIPPED: pyluxcore is not installed (run without --no-install to install it)")
        return 0
    luxcore()
    names = args.scenes or list(COMPARE_SCENES)
    out_root = args.out or "compare-luxcore"
    table = []
    for name in names:
        c = COMPARE_SCENES.get(name, dict(scene=name, defines={}))
        xml = scene_path(c["scene"])
        if not os.path.exists(xml):
            print(f"SKIPPED {name}: {xml} is absent")
            continue
        defines = dict(c["defines"])
        if args.resolution:
            w, h = args.resolution.split("x")
            if "res" in defines:
                defines["res"] = w
            else:
                defines.update(resx=w, resy=h)
        out = os.path.abspath(os.path.join(out_root, os.path.basename(name).replace(".xml", "")))
        os.makedirs(out, exist_ok=True)
        ls = LuxScene(xml, defines)
        w, h = ls.conv.width, ls.conv.height
        dflags = [x for k, v in defines.items() for x in ("-D", f"{k}={v}")]
        ref = c.get("reference")
        if ref and not (os.path.exists(ref) and f"{w}x{h}" in os.path.basename(ref)):
            ref = None
        cmd = [FOOTPRINT, "compare", xml, *dflags, "--time", str(args.time), "--ladder", str(args.time),
               "--methods", args.methods, "--threads", str(args.threads), "-o", out]
        cmd += ["--reference", ref] if ref else ["--reference-spp", str(args.reference_spp), "--reference-cache", out]
        print(" ".join(cmd), flush=True)
        subprocess.run(cmd, check=True)
        if not ref:
            ref = next(os.path.join(out, f) for f in sorted(os.listdir(out))
                       if f.startswith(".") and "reference" in f and f.endswith(".exr") and "luxcore" not in f)
        ours = [{k.strip(): v.strip().strip('"') for k, v in r.items()}
                for r in csv.DictReader(open(os.path.join(out, "metrics.csv")))]
        for r in ours:
            table.append(dict(scene=name, method=r["method"], seconds=float(r["seconds"]), spp=r["spp"],
                              rel_mse_own=float(r["rel_mse"]), rel_mse_fp_ref=float(r["rel_mse"]),
                              mean_ratio=None))
        lref, lmeta = cached_luxcore_reference(ls, out, args.luxcore_reference_time)
        import numpy as np

        lref_img = read_exr(lref)
        for m in args.luxcore_methods.split(","):
            img, st = ls.render(m, threads=args.threads, seed=7, seconds=args.time)
            path = os.path.join(out, f"{m}.exr")
            write_exr(img, path)
            own = vm.metrics(path, lref)
            fp = vm.metrics(path, ref)
            table.append(dict(scene=name, method=m, seconds=st["seconds"], spp=st["spp"], rel_mse_own=own["rel_mse"],
                              rel_mse_fp_ref=fp["rel_mse"],
                              mean_ratio=float(img.mean() / max(lref_img.mean(), 1e-30))))
            print(f"  {m}: {st['spp']} spp in {st['seconds']:.1f} s, rel. MSE {own['rel_mse']:.4g} "
                  f"(against footprint's reference {fp['rel_mse']:.4g})", flush=True)
        print(f"  footprint's reference: {ref}; LuxCore's: {lref} ({lmeta['method']}, {lmeta['spp']} spp, "
              f"{lmeta['seconds']} s)")
        ls.cleanup()
    lines = [f"| scene | method | spp in {args.time:g} s | rel. MSE (own reference) | rel. MSE (footprint's reference) | mean / own reference |",
             "|---|---|---|---|---|---|"]
    for r in table:
        mr = f"{r['mean_ratio']:.3f}" if r["mean_ratio"] is not None else ""
        lines.append(f"| {r['scene']} | {r['method']} | {r['spp']} | {r['rel_mse_own']:.4g} | {r['rel_mse_fp_ref']:.4g} | {mr} |")
    text = "\n".join(lines)
    print("\n" + text)
    os.makedirs(out_root, exist_ok=True)
    with open(os.path.join(out_root, "table.md"), "w") as f:
        f.write(text + "\n")
    with open(os.path.join(out_root, "table.json"), "w") as f:
        json.dump(table, f, indent=2)
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    v = sub.add_parser("convert", help="write the LuxCore scene (scene.scn, render.cfg, PLY) of SCENE")
    v.add_argument("scene")
    v.add_argument("-o", "--out", required=True)
    v.add_argument("-D", dest="define", action="append", default=[])
    v.add_argument("--method", default="luxcore-path", choices=LUX_METHODS)
    v.add_argument("--lenient", action="store_true")
    c = sub.add_parser("check", help="image means of footprint and LuxCore on the bundled and public scenes")
    c.add_argument("scenes", nargs="*", help=f"scenes [default: {', '.join(CHECK_SCENES)}; EXT/ = ../shared/scenes-ext/]")
    c.add_argument("-D", dest="define", action="append", default=[])
    c.add_argument("--batches", type=int, default=8)
    c.add_argument("--spp", type=int, help="samples per pixel per batch")
    c.add_argument("--block", type=int, default=4)
    c.add_argument("--tolerance", type=float, default=0.02)
    c.add_argument("--integrator", default="pt", help="footprint's integrator")
    c.add_argument("--method", default="luxcore-path", choices=LUX_METHODS, help="LuxCore's engine")
    c.add_argument("--rr-depth", type=int, help="LuxCore's path.russianroulette.depth")
    c.add_argument("--no-install", action="store_true", help="say SKIPPED instead of installing pyluxcore (for tests)")
    c.add_argument("--json", help="write the results here")
    q = sub.add_parser("compare", help="equal time: LuxCore's engines next to footprint's methods")
    q.add_argument("scenes", nargs="*", help=f"[default: {', '.join(COMPARE_SCENES)}]")
    q.add_argument("--time", type=float, default=30.0)
    q.add_argument("--threads", type=int, default=2)
    q.add_argument("--resolution", help="WxH instead of the defaults (128x72 Veach Ajar, 128x128 door, desk)")
    q.add_argument("--methods", default="pt-bsdf,lt-bsdf,combined-footprint", help="footprint's methods")
    q.add_argument("--luxcore-methods", default=",".join(LUX_METHODS))
    q.add_argument("--reference-spp", type=int, default=4096, help="footprint's reference where none is given")
    q.add_argument("--luxcore-reference-time", type=float, default=600.0, help="seconds of PATHCPU for LuxCore's reference")
    q.add_argument("--no-install", action="store_true")
    q.add_argument("-o", "--out")
    args = ap.parse_args()
    if args.cmd == "convert":
        luxcore()
    finish({"convert": cmd_convert, "check": cmd_check, "compare": cmd_compare}[args.cmd](args) or 0)


if __name__ == "__main__":
    main()
