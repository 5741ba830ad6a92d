#!/usr/bin/env python3
"""Mitsuba 3 image means of the two tiny scenes of tests/emitters.rs: a box on a floor lit by
a `directional` emitter, and the same lit by an `envmap` (a 64 x 32 sky with a bright sun,
turned by a `to_world` rotation, seen in the background).

Writes the scenes and the map (tests/emitters/directional.xml, envmap.xml, sky.exr, and the map
as sky.hdr too), renders
each with Mitsuba's `path` over independent seeds, and writes the means of the whole image
with their standard errors (the spread of the seeds' means over their square root) to
tests/emitters/mitsuba-means.json, which the test reads: it needs no Python.

    pip install mitsuba numpy      # once
    python3 scripts/emitter_means.py [--seeds 32] [--spp 1024]
"""
import argparse
import json
import math
import os
import time

import mitsuba as mi
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "tests", "emitters")

GEOMETRY = """  <sensor type="perspective"><float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0, 2.2, 6" target="0, 0.4, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="32"/><integer name="height" value="24"/><rfilter type="box"/></film>
  </sensor>
  <shape type="rectangle">
    <transform name="to_world"><scale value="3"/><rotate x="1" angle="-90"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.6, 0.5, 0.4"/></bsdf>
  </shape>
  <shape type="cube">
    <transform name="to_world"><scale value="0.6"/><rotate y="1" angle="30"/><translate x="-0.5" y="0.6" z="0"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.3, 0.6, 0.8"/></bsdf>
  </shape>
  <shape type="cube">
    <transform name="to_world"><scale value="0.4"/><rotate y="1" angle="-20"/><translate x="1" y="0.4" z="0.8"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.8, 0.8, 0.8"/></bsdf>
  </shape>
"""

SCENES = {
    "directional": """<scene version="3.0.0">
  <integrator type="path"><integer name="max_depth" value="4"/></integrator>
%s  <emitter type="directional">
    <vector name="direction" value="-0.4, -1, -0.3"/>
    <rgb name="irradiance" value="3, 2.5, 2"/>
  </emitter>
</scene>
""" % GEOMETRY,
    "envmap": """<scene version="3.0.0">
  <integrator type="path"><integer name="max_depth" value="4"/></integrator>
%s  <emitter type="envmap">
    <string name="filename" value="sky.exr"/>
    <float name="scale" value="1.5"/>
    <transform name="to_world"><rotate y="1" angle="40"/></transform>
  </emitter>
</scene>
""" % GEOMETRY,
}


def sky(width=64, height=32):
    """A sky brighter toward the zenith, a dim ground, and a sun of peak 60 a few texels wide
    at u = 0.3, v = 0.3."""
    v = (np.arange(height) + 0.5)[:, None] / height
    u = (np.arange(width) + 0.5)[None, :] / width
    img = np.zeros((height, width, 3), dtype=np.float32)
    up = np.clip(1.0 - 2.0 * v, 0.0, 1.0)
    img[..., 0] = 0.15 + 0.2 * up + 0 * u
    img[..., 1] = 0.2 + 0.3 * up
    img[..., 2] = 0.3 + 0.6 * up
    img[v[:, 0] > 0.5] *= 0.3
    du = np.minimum(np.abs(u - 0.3), 1.0 - np.abs(u - 0.3)) * width
    dv = (v - 0.3) * height
    sun = 60.0 * np.exp(-(du**2 + dv**2) / (2 * 1.2**2))
    img[..., 0] += sun
    img[..., 1] += 0.9 * sun
    img[..., 2] += 0.7 * sun
    return img


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--seeds", type=int, default=32)
    ap.add_argument("--spp", type=int, default=1024)
    a = ap.parse_args()
    mi.set_variant("scalar_rgb")
    os.makedirs(OUT, exist_ok=True)
    mi.Bitmap(sky()).write(os.path.join(OUT, "sky.exr"))
    # The same map as Radiance RGBE, for the reader of .hdr files.
    mi.Bitmap(sky()).write(os.path.join(OUT, "sky.hdr"))
    result = {"mitsuba": mi.__version__, "variant": "scalar_rgb", "scenes": {}}
    for name, xml in SCENES.items():
        path = os.path.join(OUT, name + ".xml")
        with open(path, "w") as f:
            f.write(xml)
        scene = mi.load_file(path)
        start = time.time()
        means = [np.array(mi.render(scene, seed=s, spp=a.spp)).reshape(-1, 3).mean(0)
                 for s in range(a.seeds)]
        m = np.array(means)
        result["scenes"][name] = {
            "seeds": a.seeds,
            "spp": a.spp,
            "max_depth": 4,
            "seconds": round(time.time() - start, 1),
            "mean": m.mean(0).tolist(),
            "stderr": (m.std(0, ddof=1) / math.sqrt(a.seeds)).tolist(),
        }
        print(name, result["scenes"][name])
    with open(os.path.join(OUT, "mitsuba-means.json"), "w") as f:
        json.dump(result, f, indent=2)
        f.write("\n")


if __name__ == "__main__":
    main()
