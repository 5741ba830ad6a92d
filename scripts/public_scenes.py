#!/usr/bin/env python3
"""The public scenes too large (or of a licence too unclear) to keep in the repository,
fetched into scenes/public/fetched/<name>/ from the public Git repositories that hold them,
each at a pinned commit.

    python3 scripts/public_scenes.py list                  # the scenes, their sources and licences
    python3 scripts/public_scenes.py fetch [NAME ...]      # download (all by default)
    python3 scripts/public_scenes.py fetch --git OWNER/REPO=PATH ...
                                                           # read from a local clone instead

Each file is downloaded from GitHub at the pinned commit (the same bytes every time); the
scene's XML is read first and every file it names is fetched beside it, so a scene that loads
is complete. Where a copy differs from its authors' original in a way that matters to a
renderer (a default integrator of the copy's own), the change is made here and said in the
SOURCE.md written beside it. A scene is written to a temporary folder and moved into place
only when every file arrived, so an interrupted fetch leaves no half scene.

Render one with `footprint render scenes/public/fetched/NAME/scene.xml`; `tests/mitsuba.rs`
checks each one present against its Mitsuba 3 reference and says that it skipped the others.
Python 3 standard library only.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import urllib.request

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEST = os.path.join(ROOT, "scenes", "public", "fetched")

def bitterli_0_5_edits(integrator=None):
    """The edits that make a scene of Bitterli's Mitsuba 0.5 exports in
    jgarciapueyo/mitsuba2-transient-scenes his original again, with its resolution (and, given
    `integrator`, the tail of the reason why, its integrator) made a parameter."""
    defaults = '\t<default name="resx" value="1280" />\n\t<default name="resy" value="720" />\n'
    made = "the resolution made parameters (`-D resx=... -D resy=...`; defaults the original's 1280x720)"
    edits = []
    if integrator:
        defaults += '\t<default name="integrator" value="path" />\n'
        made = ("the resolution and the integrator made parameters (`-D resx=... -D resy=... "
                "-D integrator=volpath`; defaults the original's 1280x720 and " + integrator)
        edits.append(('<integrator type="path" >', '<integrator type="$integrator" >',
                      "the integrator reads `$integrator`"))
    return [
        ('\t\t\t<boolean name="high_quality_edges" value="true" />\n', "",
         "the copy's film property `high_quality_edges` (not in Bitterli's original, and "
         "rejected by Mitsuba 3) removed"),
        ('<scene version="0.5.0" >\n', '<scene version="0.5.0" >\n' + defaults, made),
        *edits,
        ('<integer name="width" value="1280" />', '<integer name="width" value="$resx" />',
         "the film's width reads `$resx`"),
        ('<integer name="height" value="720" />', '<integer name="height" value="$resy" />',
         "the film's height reads `$resy`"),
    ]


# name -> where it lives, what it is, and the edits that make the copy the original again.
SCENES = {
    "torus": dict(
        repo="takkasila/practical_path_guiding_lab",
        commit="c4b6605b3c78dccaa5721275d96ef6cd30c0630c",
        path="scenes/torus",
        what="The torus of Practical Path Guiding (Müller et al. 2017) and of Cline et al. 2005's "
        "energy redistribution: a glass torus lit by a directional light, seen mostly through "
        "caustics. By Olesya Jakob, from the Mitsuba renderer's example scenes.",
        licence="none stated with this copy (Mitsuba's example scenes)",
        extra=[],
        edits=[
            (
                '<default name="integrator" value="path_guiding_integrator" />',
                '<default name="integrator" value="path" />',
                "the copy's default integrator is a plugin of its own; Mitsuba's `path` restored",
            )
        ],
    ),
    "staircase": dict(
        repo="SojeongKim-42/denoising-nerf",
        commit="8d2557c28b1096e9f13a7e7b609d591aebe8cb24",
        path="scenes/staircase",
        what="Bitterli's 'The Wooden Staircase' (by Wig42): a staircase lit by one area light "
        "through a doorway, 774 OBJ meshes, 10 bitmap textures (39 MB).",
        licence="CC-BY 3.0 (LICENSE.txt)",
        extra=["LICENSE.txt"],
        edits=[],
    ),
    "modern-hall": dict(
        repo="jgarciapueyo/mitsuba2-transient-scenes",
        commit="ab67c4caa9228aa9d4115aeb90c3d3bab0aaf7b5",
        path="staircase2",
        what="Bitterli's 'Modern Hall' (staircase2, by NewSee2l035): a hall with a glass "
        "balustrade, lit by thirteen disk and rectangle lamps, in Bitterli's Mitsuba 0.5 form "
        "(which footprint and Mitsuba 3 both upgrade as they load it); 19 OBJ meshes, three "
        "bitmap textures (7.8 MB).",
        licence="CC-BY (LICENSE.txt)",
        extra=["LICENSE.txt"],
        edits=bitterli_0_5_edits(),
    ),
    "matpreview": dict(
        repo="zhiwei-c/Monte-Carlo-Path-Tracing",
        commit="7482bda9b6be617e8bc5cef06a274ba1e1a7e914",
        path="resources/scene/matpreview",
        xml="rough_dielectric.xml",
        what="Mitsuba's material preview scene (the test ball on a checkerboard plane, in "
        "Mitsuba 3 form), the ball a rough dielectric (water, Beckmann alpha 0.1) lit by an "
        "HDR environment map; three meshes of one .serialized file.",
        licence="none stated with this copy (Mitsuba's example scenes)",
        extra=[],
        edits=[],
    ),
    "dining-room": dict(
        repo="woAIxuexiSR/dynamic-neural-radiosity",
        commit="bb01b6da5cfe84bb572c37bdc0ab059afe43ad9a",
        path="scenes/dining-room",
        what="Bitterli's 'The Breakfast Room' (dining-room, by Wig42) in Mitsuba 3 form: a room "
        "lit by the sky through its windows, 52 OBJ meshes, three bitmap textures (25 MB). The "
        "copy replaced Bitterli's `sunsky` by an HDR environment map whose file its snapshot "
        "lacks; footprint's own test sky (`tests/emitters/sky.exr`, a sky with a sun, made by "
        "`scripts/emitter_means.py`) stands in for it.",
        licence="CC-BY 3.0 (Bitterli's resources page; the copy's repository is MIT)",
        extra=[],
        local=[("tests/emitters/sky.exr", "textures/sky.exr")],
        edits=[
            (
                '<string name="filename" value="textures/spaichingen_hill_2k.exr" />',
                '<string name="filename" value="textures/sky.exr" />',
                "the environment map `textures/spaichingen_hill_2k.exr` (absent from the copy's "
                "snapshot) replaced by footprint's `tests/emitters/sky.exr`",
            )
        ],
    ),
    "living-room": dict(
        repo="jgarciapueyo/mitsuba2-transient-scenes",
        commit="ab67c4caa9228aa9d4115aeb90c3d3bab0aaf7b5",
        path="living-room",
        what="Bitterli's 'The Grey & White Room' (living-room, by Wig42) in Bitterli's Mitsuba 0.5 "
        "form (which footprint and Mitsuba 3 both upgrade as they load it): a room lit by an HDR "
        "sky through its windows, with a plant whose leaves are cut-outs (`mask` with a bitmap "
        "opacity); 50 OBJ meshes, eleven textures (19 MB).",
        licence="CC-BY 3.0 (LICENSE.txt)",
        extra=["LICENSE.txt"],
        edits=bitterli_0_5_edits(
            integrator=(
                "`path`): Mitsuba's `path` loses light seen through cut-outs, so its references "
                "are rendered with `volpath` (docs/mitsuba.md, \"Cut-outs\")"
            )
        ),
    ),
}


def named_files(xml_text):
    """The files a Mitsuba XML names (`<string name="filename" value="..."/>`)."""
    return sorted(set(re.findall(r'<string\s+name="filename"\s+value="([^"]+)"', xml_text)))


def reader(scene, clones):
    """A function that returns a file of `scene` (a path inside its folder) as bytes."""
    clone = clones.get(scene["repo"])
    if clone:
        def read(rel):
            obj = f"{scene['commit']}:{scene['path']}/{rel}"
            out = subprocess.run(["git", "-C", clone, "show", obj], capture_output=True)
            if out.returncode != 0:
                raise OSError(f"{clone}: git show {obj}: {out.stderr.decode().strip()}")
            return out.stdout
        return read

    def download(rel):
        url = (f"https://raw.githubusercontent.com/{scene['repo']}/{scene['commit']}/"
               f"{scene['path']}/{urllib.request.quote(rel)}")
        with urllib.request.urlopen(url, timeout=60) as r:
            return r.read()
    return download


def fetch(name, clones):
    scene = SCENES[name]
    read = reader(scene, clones)
    # The scene's XML (`xml`, where the folder holds several), written as scene.xml.
    xml = read(scene.get("xml", "scene.xml")).decode("utf-8")
    notes = []
    for old, new, why in scene["edits"]:
        if old not in xml:
            raise RuntimeError(f"{name}: the expected text to change is not in scene.xml: {old}")
        xml = xml.replace(old, new)
        notes.append(why)
    # Files this repository supplies (`local`: its path, the path in the scene's folder).
    local = dict((dst, src) for src, dst in scene.get("local", []))
    files = [f for f in named_files(xml) if f not in local] + scene["extra"]
    os.makedirs(DEST, exist_ok=True)
    tmp = tempfile.mkdtemp(prefix=f".{name}-", dir=DEST)
    try:
        with open(os.path.join(tmp, "scene.xml"), "w", encoding="utf-8") as f:
            f.write(xml)
        for i, rel in enumerate(files):
            data = read(rel)
            out = os.path.join(tmp, rel)
            os.makedirs(os.path.dirname(out), exist_ok=True)
            with open(out, "wb") as f:
                f.write(data)
            if sys.stdout.isatty():
                print(f"\r{name}: {i + 1}/{len(files)} files", end="", flush=True)
        if sys.stdout.isatty():
            print()
        for dst, src in local.items():
            out = os.path.join(tmp, dst)
            os.makedirs(os.path.dirname(out), exist_ok=True)
            shutil.copyfile(os.path.join(ROOT, src), out)
        with open(os.path.join(tmp, "SOURCE.md"), "w", encoding="utf-8") as f:
            f.write(f"# {name}: source\n\n{scene['what']}\n\nLicence: {scene['licence']}.\n\n")
            f.write(f"GitHub `{scene['repo']}` at `{scene['commit']}`, `{scene['path']}/`, "
                    f"fetched by `scripts/public_scenes.py`.\n")
            if "xml" in scene:
                f.write(f"\n`scene.xml` is the folder's `{scene['xml']}`.\n")
            for n in notes:
                f.write(f"\nChanged: {n}.\n")
        final = os.path.join(DEST, name)
        if os.path.exists(final):
            shutil.rmtree(final)
        os.replace(tmp, final)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    print(f"{name}: {len(files) + len(local) + 1} files in {os.path.relpath(final, ROOT)}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    sub.add_parser("list", help="the scenes, their sources and licences")
    f = sub.add_parser("fetch", help="download scenes into scenes/public/fetched/")
    f.add_argument("names", nargs="*", help=f"scenes [default: all of {', '.join(SCENES)}]")
    f.add_argument("--git", action="append", default=[], metavar="OWNER/REPO=PATH",
                   help="read OWNER/REPO from this local clone rather than download it")
    args = ap.parse_args()
    if args.cmd == "list":
        for name, s in SCENES.items():
            print(f"{name}: {s['what']}\n    {s['repo']} @ {s['commit'][:12]}, {s['path']}/; licence: {s['licence']}")
        return 0
    clones = {}
    for g in args.git:
        repo, _, path = g.partition("=")
        if not path or not os.path.isdir(path):
            ap.error(f"--git {g}: expected OWNER/REPO=PATH to a local clone")
        clones[repo] = path
    unknown = [n for n in args.names if n not in SCENES]
    if unknown:
        ap.error(f"unknown scene(s) {', '.join(unknown)} (known: {', '.join(SCENES)})")
    failed = 0
    for name in args.names or SCENES:
        try:
            fetch(name, clones)
        except Exception as e:  # noqa: BLE001 - report every scene, then fail
            print(f"\n{name}: failed: {e}", file=sys.stderr)
            failed += 1
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
