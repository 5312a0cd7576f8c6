#!/usr/bin/env python3
"""The error-message corpus of issue 17: malformed inputs, and what radiant says.

Writes into a scratch folder many malformed inputs derived from the bundled
scenes (JSON scene mutations, OBJ/MTL mutations, broken textures, broken
linear images, truncated and mismatched solution files, bad command-line
values), runs build/radiant on each, and classifies the outcome:

  crash      killed by a signal (or timed out)
  exit 0     accepted (fine for many mutations: a valid scene stays valid)
  clean      a non-zero exit with a message

For a clean error about a file it checks that the message names the file, and,
where the input has positions (JSON text or values, OBJ/MTL lines), that it
carries a line or a JSON path; for a bad flag, that it names the flag. It
prints the counts and lists every failure.

  tools/error_corpus.py [--radiant build/radiant] [--jobs 2] [--keep DIR] [--verbose]

Exit status: 0 when nothing crashed and no message misses its file, position
or flag; 1 otherwise. docs/cli.md (Error messages) has the figures.
"""
import argparse
import concurrent.futures
import copy
import json
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

from error_corpus_readers import reader_cases

SOURCE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TIMEOUT = 60


class Case:
    """One run of radiant. `about`: the file the error must name (None for a
    flag error); `position`: 'line' (OBJ/MTL: file:LINE), 'json' (file:LINE
    or file: at /PATH), or None (binary files, files that cannot be opened);
    `flag`: the flag a command-line error must name."""

    def __init__(self, group, name, args, about=None, position=None, flag=None):
        self.group, self.name, self.args = group, name, args
        self.about, self.position, self.flag = about, position, flag


def run(radiant, case, cwd):
    try:
        p = subprocess.run([radiant] + case.args, cwd=cwd, capture_output=True, text=True, errors="replace",
                           timeout=TIMEOUT)
    except subprocess.TimeoutExpired:
        return "timeout", "", ""
    if p.returncode < 0 or p.returncode >= 128:
        return "crash", p.stderr, "signal %d" % -p.returncode if p.returncode < 0 else "status %d" % p.returncode
    if p.returncode == 0:
        return "exit0", p.stderr, ""
    lines = [l for l in p.stderr.splitlines() if l.startswith("radiant: error:")]
    message = "\n".join(lines) if lines else p.stderr.strip()
    return "clean", message, check(case, message)


def check(case, message):
    """The first thing the message lacks, or ''."""
    if case.flag:
        return "" if case.flag in message else "does not name the flag " + case.flag
    if not case.about:
        return ""
    name = os.path.basename(case.about)
    if name not in message:
        return "does not name the file " + name
    if case.position == "line" and not re.search(re.escape(name) + r":\d+", message):
        return "names " + name + " without a line"
    if case.position == "json" and not re.search(re.escape(name) + r"(:\d+|: at /)", message):
        return "names " + name + " without a line or JSON path"
    return ""


# ---------------------------------------------------------------- fixtures


def png_bytes(width, height, depth=8, colour=2, rows=None):
    """A valid PNG (no CRC shortcuts): stb_image checks the CRCs of nothing, but other readers do."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    channels = {0: 1, 2: 3, 6: 4}[colour]
    if rows is None:
        row = b"\x00" + bytes(((x * 37) & 0xFF) for x in range(width * channels * depth // 8))
        rows = row * height
    ihdr = struct.pack(">IIBBBBB", width, height, depth, colour, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b"")


def pfm_bytes(width, height, scale=-1.0, pixels=None):
    header = ("PF\n%d %d\n%g\n" % (width, height, scale)).encode()
    data = pixels if pixels is not None else struct.pack("<%df" % (width * height * 3), *([0.5] * width * height * 3))
    return header + data


def write(path, data):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb" if isinstance(data, bytes) else "w") as f:
        f.write(data)
    return path


def cornell_obj():
    """The Cornell box's quads as an OBJ in metres with an MTL of its materials
    (and a checker texture on the floor): the OBJ/MTL mutations start here."""
    scene = json.load(open(os.path.join(SOURCE, "scenes/cornell-box/scene.json")))
    obj = ["# the Cornell box (scenes/cornell-box), in metres", "mtllib cornell.mtl"]
    vt = ["vt 0 0", "vt 1 0", "vt 1 1", "vt 0 1"]
    obj += vt
    n = 0
    for o in scene["objects"]:
        obj.append("o " + o["name"])
        obj.append("usemtl " + o["material"])
        for v in o["vertices"]:
            obj.append("v %g %g %g" % tuple(c / 1000 for c in v))
        obj.append("f " + " ".join("%d/%d" % (n + k + 1, k + 1) for k in range(len(o["vertices"]))))
        n += len(o["vertices"])
    mtl = ["# the Cornell box's materials"]
    for name, m in scene["materials"].items():
        mtl.append("newmtl " + name)
        mtl.append("Kd %g %g %g" % tuple(m["reflectance"]))
        if "emission" in m:
            mtl.append("Ke %g %g %g" % tuple(m["emission"]))
        mtl.append("illum 1")
    mtl += ["newmtl checker", "Kd 1 1 1", "map_Kd checker.png", "illum 1"]
    return "\n".join(obj) + "\n", "\n".join(mtl) + "\n"


class Fixtures:
    def __init__(self, work, radiant):
        self.work, self.radiant = work, radiant
        self.scenes = {}
        for name in ["cornell-box", "cornell-specular", "cornell-box-spectral", "cornell-textured", "furnace",
                     "two-rooms"]:
            shutil.copytree(os.path.join(SOURCE, "scenes", name), os.path.join(work, "scenes", name))
            self.scenes[name] = os.path.join(work, "scenes", name, "scene.json")
        self.obj_text, self.mtl_text = cornell_obj()
        self.checker = write(os.path.join(work, "obj", "checker.png"), png_bytes(8, 8))
        self.obj = write(os.path.join(work, "obj", "cornell.obj"), self.obj_text)
        self.mtl = write(os.path.join(work, "obj", "cornell.mtl"), self.mtl_text)
        box = json.load(open(self.scenes["cornell-box"]))
        wrapper = {"version": 1, "units": "metres", "camera": {"eye": [0.278, 0.273, -0.8],
                                                               "target": [0.278, 0.273, 0]},
                   "materials": {"white": box["materials"]["white"]},
                   "objects": [{"name": "box", "type": "obj", "file": "cornell.obj"}]}
        self.wrapper = write(os.path.join(work, "obj", "scene.json"), json.dumps(wrapper, indent=2) + "\n")
        # Linear images and a solution, made by radiant itself.
        self.exr = os.path.join(work, "img", "a.exr")
        self.pfm = os.path.join(work, "img", "a.pfm")
        os.makedirs(os.path.dirname(self.exr), exist_ok=True)
        subprocess.run([radiant, "render", self.scenes["cornell-box"], "--spp", "1", "--width", "8", "--height", "8",
                        "-o", self.exr, "-o", self.pfm, "-q"], check=True)
        self.small_exr = os.path.join(work, "img", "small.exr")
        subprocess.run([radiant, "render", self.scenes["cornell-box"], "--spp", "1", "--width", "4", "--height", "4",
                        "-o", self.small_exr, "-q"], check=True)
        self.solution = os.path.join(work, "sol", "furnace.sol")
        os.makedirs(os.path.dirname(self.solution), exist_ok=True)
        subprocess.run([radiant, "solve", self.scenes["furnace"], "--solver", "progressive", "-o", self.solution,
                        "-q"], check=True)
        os.makedirs(os.path.join(work, "out"), exist_ok=True)
        self.counter = 0

    def path(self, folder, name):
        self.counter += 1
        return os.path.join(self.work, "cases", "%04d" % self.counter, folder, name) if folder else \
            os.path.join(self.work, "cases", "%04d" % self.counter, name)


RENDER = ["--spp", "1", "--width", "4", "--height", "4", "-q"]


def render_args(scene, out):
    return ["render", scene, "-m", "path"] + RENDER + ["-o", out]


# ------------------------------------------------------------ JSON scenes


def json_paths(value, path=()):
    """Every (path, value) of a document; of an array of objects, only the first two elements."""
    yield path, value
    if isinstance(value, dict):
        for k, v in value.items():
            if k != "comment":
                yield from json_paths(v, path + (k,))
    elif isinstance(value, list):
        # Objects: the first two, and the first of each other type; long lists (spectra): the first two.
        types = set()
        for i, v in enumerate(value):
            kind = v.get("type") if isinstance(v, dict) else None
            if i < 2 or (isinstance(v, dict) and kind not in types) or (not isinstance(v, dict) and len(value) <= 4):
                yield from json_paths(v, path + (i,))
            types.add(kind)


def set_at(document, path, value, delete=False):
    d = copy.deepcopy(document)
    target = d
    for k in path[:-1]:
        target = target[k]
    if delete:
        del target[path[-1]]
    else:
        target[path[-1]] = value
    return d


def replacements(value):
    """Wrong values for one JSON value."""
    if isinstance(value, bool) or value is None:
        return ["yes", 2]
    if isinstance(value, (int, float)):
        return ["1", None, -1, 0, 1e300, 2.5, [value]]
    if isinstance(value, str):
        return [3, "", value[:-1] or "x", [value]]
    if isinstance(value, list):
        return [[], value[:-1], "x", value + [value[-1]] if value else [1]]
    return [[], "x", 1]


def scene_cases(fx, name, scene_path, limit=None):
    document = json.load(open(scene_path))
    folder = os.path.dirname(scene_path)
    cases = []

    def add(label, doc=None, text=None):
        path = os.path.join(folder, "m%04d.json" % len(cases))
        write(path, text if text is not None else json.dumps(doc, indent=2) + "\n")
        out = os.path.join(fx.work, "out", "%s-%d.exr" % (name, len(cases)))
        cases.append(Case("json " + name, label, render_args(path, out), about=path, position="json"))

    for path, value in json_paths(document):
        if not path:
            continue
        where = "/" + "/".join(str(k) for k in path)
        for r in replacements(value):
            add("%s = %s" % (where, json.dumps(r)[:30]), set_at(document, path, r))
        if isinstance(path[-1], str):
            add("%s deleted" % where, set_at(document, path, None, delete=True))
        if isinstance(value, dict):
            add("%s/colour added" % where, set_at(document, path + ("colour",), 1))
    # Whole-text damage: truncations, empty, garbage, syntax.
    text = json.dumps(document, indent=2) + "\n"
    for fraction in (0.01, 0.1, 0.33, 0.5, 0.77, 0.99):
        add("truncated at %d%%" % (fraction * 100), text=text[:int(len(text) * fraction)])
    add("empty file", text="")
    add("binary garbage", text=bytes(range(256)).decode("latin-1") * 4)
    add("trailing comma", text=text.replace("]\n}", "],\n}", 1))
    add("missing comma", text=text.replace('",\n', '"\n', 1))
    add("single quotes", text=text.replace('"version"', "'version'", 1))
    add("1e999", text=text.replace('"version": 1', '"version": 1e999', 1))
    add("deep nesting", text=text.replace('"version": 1', '"version": ' + "[" * 100 + "]" * 100, 1))
    add("NaN literal", text=text.replace('"version": 1', '"version": NaN', 1))
    return cases[:limit] if limit else cases


# ------------------------------------------------------------ OBJ and MTL


def obj_cases(fx):
    cases = []
    lines = fx.obj_text.splitlines()
    mtl_lines = fx.mtl_text.splitlines()

    def add(label, obj=None, mtl=None, extra=None, about="obj", position="line", bare=True, wrapper=None):
        folder = fx.path("", "")
        objp = write(os.path.join(folder, "cornell.obj"), obj if obj is not None else fx.obj_text)
        mtlp = write(os.path.join(folder, "cornell.mtl"), mtl if mtl is not None else fx.mtl_text)
        shutil.copy(fx.checker, os.path.join(folder, "checker.png"))
        for rel, data in (extra or {}).items():
            write(os.path.join(folder, rel), data)
        shutil.copy(fx.wrapper, os.path.join(folder, "scene.json"))
        target = {"obj": objp, "mtl": mtlp}.get(about, os.path.join(folder, about) if about else None)
        out = os.path.join(folder, "out.exr")
        if bare:
            cases.append(Case("obj bare", label, render_args(objp, out), about=target, position=position))
        cases.append(Case("obj in json", label, render_args(os.path.join(folder, "scene.json"), out), about=target,
                          position=position))
        if wrapper:
            document = json.load(open(fx.wrapper))
            document.update(wrapper)
            path = write(os.path.join(folder, "variant.json"), json.dumps(document, indent=2))
            cases.append(Case("obj in json", label, render_args(path, out), about=target, position=position))

    def replace_line(predicate, new, count=1):
        out, done = [], 0
        for l in lines:
            if done < count and predicate(l):
                out.append(new(l))
                done += 1
            else:
                out.append(l)
        return "\n".join(out) + "\n"

    first_v = lambda l: l.startswith("v ")
    first_f = lambda l: l.startswith("f ")
    for bad in ("x", "nan", "inf", "1e999", "0x10", "1,5", "--1"):
        add("v number " + bad, replace_line(first_v, lambda l: "v %s 0 0" % bad))
    add("v two numbers", replace_line(first_v, lambda l: "v 0 0"))
    add("v no numbers", replace_line(first_v, lambda l: "v"))
    add("vt x", replace_line(lambda l: l.startswith("vt "), lambda l: "vt x 0"))
    add("vn one number", replace_line(first_v, lambda l: l + "\nvn 1"))
    for bad in ("0", "999", "-99", "x", "1/x", "1/2/3/4", "1.5", "99999999999999999999", "1/99", "1//99", "/"):
        add("f index " + bad, replace_line(first_f, lambda l: "f 1 2 " + bad))
    add("f two vertices", replace_line(first_f, lambda l: "f 1 2"))
    add("f empty", replace_line(first_f, lambda l: "f"))
    add("usemtl unknown", replace_line(lambda l: l.startswith("usemtl"), lambda l: "usemtl nosuch"))
    add("mtllib missing", replace_line(lambda l: l.startswith("mtllib"), lambda l: "mtllib missing.mtl"))
    add("mtllib directory", replace_line(lambda l: l.startswith("mtllib"), lambda l: "mtllib ."))
    add("spectral scene, RGB MTL", bare=False, about="mtl",
        wrapper={"spectral": {"range": [400, 700], "samples": 16}, "materials": {}})
    add("transform beyond 1e9 m", bare=False,
        wrapper={"objects": [{"type": "obj", "file": "cornell.obj", "transform": {"scale": 1e10}}]})
    add("v beyond 1e9 m", replace_line(first_v, lambda l: "v 2e9 0 0"))
    add("f line continued", replace_line(first_f, lambda l: l + " \\"))
    add("l element", replace_line(first_f, lambda l: l + "\nl 1 2"))
    add("p element", replace_line(first_f, lambda l: l + "\np 1"))
    add("usemtl without name", replace_line(lambda l: l.startswith("usemtl"), lambda l: "usemtl"))
    add("mtllib without name", replace_line(lambda l: l.startswith("mtllib"), lambda l: "mtllib"))
    add("g without name", replace_line(first_f, lambda l: "g\n" + l))
    text = fx.obj_text
    for fraction in (0.3, 0.5, 0.8, 0.97):
        add("truncated at %d%%" % (fraction * 100), text[:int(len(text) * fraction)])
    add("empty OBJ", "")
    add("binary garbage OBJ", bytes(range(256)) * 4)
    add("NUL in a line", replace_line(first_v, lambda l: "v 0\x00 0 0"))
    # MTL
    def mtl_replace(keyword, new, which=0):
        out, seen = [], 0
        for l in mtl_lines:
            if l.split()[:1] == [keyword]:
                out.append(new if seen == which else l)
                seen += 1
            else:
                out.append(l)
        return "\n".join(out) + "\n"
    for bad in ("x", "nan", "-1", "1.5 1.5 1.5", "1e999", "", "0.5 x 0.5"):
        add("Kd " + (bad or "(none)"), mtl=mtl_replace("Kd", ("Kd " + bad).strip()), about="mtl")
    add("Ke negative", mtl=mtl_replace("Ke", "Ke -1 -1 -1"), about="mtl")
    add("Ke x", mtl=mtl_replace("Ke", "Ke x"), about="mtl")
    add("illum x", mtl=mtl_replace("illum", "illum x"), about="mtl")
    add("glass Ni 0", mtl=mtl_replace("illum", "illum 4\nNi 0"), about="mtl")
    add("glossy Ns -5", mtl=mtl_replace("illum", "illum 2\nKs 0.2 0.2 0.2\nNs -5"), about="mtl")
    add("mirror Ks 2", mtl=mtl_replace("illum", "illum 3\nKs 2 2 2"), about="mtl")
    add("mirror Ks -1", mtl=mtl_replace("illum", "illum 3\nKs -1 -1 -1"), about="mtl")
    floor_checker = replace_line(lambda l: l == "usemtl white", lambda l: "usemtl checker")
    add("map_Kd missing", floor_checker, mtl=fx.mtl_text.replace("map_Kd checker.png", "map_Kd nosuch.png"),
        about="mtl")
    add("map_Kd -s 2 2", floor_checker, mtl=fx.mtl_text.replace("map_Kd checker.png", "map_Kd -s 2 2 checker.png"),
        about="mtl")
    add("map_Kd no file", floor_checker, mtl=fx.mtl_text.replace("map_Kd checker.png", "map_Kd"), about="mtl")
    add("bump missing", floor_checker, mtl=fx.mtl_text.replace("map_Kd checker.png", "map_Kd checker.png\nbump no.png"),
        about="mtl")
    png = png_bytes(8, 8)
    for cut in (10, 40, len(png) - 20):
        add("map_Kd truncated PNG %d bytes" % cut, floor_checker, extra={"bad.png": png[:cut]},
            mtl=fx.mtl_text.replace("map_Kd checker.png", "map_Kd bad.png"), about="bad.png", position=None)
    add("map_Kd text file", floor_checker, extra={"bad.png": "not an image\n"},
        mtl=fx.mtl_text.replace("map_Kd checker.png", "map_Kd bad.png"), about="bad.png", position=None)
    add("newmtl without name", mtl="newmtl\nKd 0.5 0.5 0.5\n" + fx.mtl_text, about="mtl")
    add("Kd before newmtl", mtl="Kd 0.5 0.5 x\n" + fx.mtl_text, about="mtl")
    add("map_Kd a directory", floor_checker, mtl=fx.mtl_text.replace("map_Kd checker.png", "map_Kd ."), about="mtl")
    add("glass Tf 2", mtl=mtl_replace("illum", "illum 4\nNi 1.5\nTf 2 2 2"), about="mtl")
    add("glass Tf -1", mtl=mtl_replace("illum", "illum 4\nNi 1.5\nTf -1 -1 -1"), about="mtl")
    add("d x", mtl=mtl_replace("illum", "illum 1\nd x"), about="mtl")
    add("Ns x", mtl=mtl_replace("illum", "illum 2\nKs 0.1 0.1 0.1\nNs x"), about="mtl")
    add("MTL truncated", mtl=fx.mtl_text[:int(len(fx.mtl_text) * 0.55)], about="mtl")
    add("MTL binary garbage", mtl=bytes(range(256)) * 4, about="mtl")
    add("MTL empty", mtl="", about="mtl")
    return cases


# --------------------------------------------------------------- textures


def texture_cases(fx):
    cases = []
    source = os.path.dirname(fx.scenes["cornell-textured"])
    good = open(os.path.join(source, "textures", "checker.png"), "rb").read()
    bump = open(os.path.join(source, "textures", "egg-crate.png"), "rb").read()
    exr = open(fx.exr, "rb").read()

    def add(label, data, which="checker.png", directory=False):
        folder = fx.path("", "")
        shutil.copytree(source, folder)
        target = os.path.join(folder, "textures", which)
        os.remove(target)
        if directory:
            os.makedirs(target)
        elif data is not None:
            write(target, data)
        cases.append(Case("texture", label, render_args(os.path.join(folder, "scene.json"),
                                                        os.path.join(folder, "o.exr")), about=target))

    for cut in (0, 4, 8, 16, 33, 60, len(good) // 2, len(good) - 12, len(good) - 1):
        add("PNG truncated to %d bytes" % cut, good[:cut])
    for cut in (8, 40, len(bump) // 2):
        add("bump PNG truncated to %d bytes" % cut, bump[:cut], which="egg-crate.png")
    add("PNG missing", None)
    add("PNG is a directory", None, directory=True)
    add("text file named .png", b"hello\n")
    add("PNG with a 5000x5000 header", png_bytes(5000, 5000, rows=b"\x00" * 16)[:200])
    add("PNG 0x0", png_bytes(1, 1).replace(struct.pack(">II", 1, 1), struct.pack(">II", 0, 0), 1))
    bad_idat = bytearray(good)
    at = good.find(b"IDAT")
    bad_idat[at + 8:at + 40] = b"\xff" * 32
    add("PNG corrupt IDAT", bytes(bad_idat))
    add("JPEG truncated", b"\xff\xd8\xff\xe0\x00\x10JFIF\x00\x01\x01\x00\x00\x01\x00\x01\x00\x00")
    for cut in (4, 8, 100, len(exr) // 2, len(exr) - 10):
        add("EXR truncated to %d bytes" % cut, exr[:cut])
    huge = bytearray(exr)
    at = exr.find(b"dataWindow\x00box2i\x00")
    huge[at + 21:at + 37] = struct.pack("<iiii", 0, 0, 99999, 99999)
    add("EXR data window 100000x100000", bytes(huge))
    return cases


# ------------------------------------------------------ images and solutions


def image_cases(fx):
    cases = []
    exr, pfm = open(fx.exr, "rb").read(), open(fx.pfm, "rb").read()

    def add(label, name, data, command="compare", about=True):
        path = write(fx.path("", name), data) if data is not None else fx.path("", name)
        if command == "compare":
            args = ["compare", path, fx.exr]
        elif command == "compare-ref":
            args = ["compare", fx.exr, path]
        else:
            args = ["tonemap", path, "-o", path + ".png"]
        cases.append(Case("image " + command, label, args, about=path if about else None))

    for command in ("compare", "compare-ref", "tonemap"):
        for cut in (0, 4, 8, 60, len(exr) // 2, len(exr) - 8):
            add("EXR truncated to %d bytes" % cut, "t.exr", exr[:cut], command)
        for cut in (0, 2, 8, 20, len(pfm) // 2, len(pfm) - 1):
            add("PFM truncated to %d bytes" % cut, "t.pfm", pfm[:cut], command)
        add("PFM header 512x512, 100 bytes of data", "t.pfm", pfm_bytes(512, 512, pixels=b"\0" * 100), command)
        add("PFM negative size", "t.pfm", b"PF\n-3 4\n-1\n" + b"\0" * 200, command)
        add("PFM huge size", "t.pfm", b"PF\n100000 100000\n-1\n" + b"\0" * 200, command)
        add("PFM bad magic", "t.pfm", b"P6\n2 2\n255\n" + b"\0" * 12, command)
        add("PFM text", "t.pfm", b"hello world\n", command)
        add("missing file", "nosuch.exr", None, command)
        add("PNG given", "t.png", png_bytes(4, 4), command)
        add("EXR that is a PFM", "t.exr", pfm, command)
        add("PFM that is an EXR", "t.pfm", exr, command)
    cases.append(Case("image compare", "size mismatch", ["compare", fx.small_exr, fx.exr], about=fx.small_exr))
    return cases


def solution_cases(fx):
    cases = []
    data = open(fx.solution, "rb").read()
    furnace = fx.scenes["furnace"]

    def add(label, blob, scene=furnace, method="flat"):
        path = write(fx.path("", "s.sol"), blob)
        cases.append(Case("solution", label, ["render", scene, "--solution", path, "-m", method] + RENDER +
                          ["-o", path + ".exr"], about=path))

    for cut in (0, 8, 16, 20, 24, 31, 40, 64, 100, len(data) // 3, len(data) // 2, len(data) - 8, len(data) - 1):
        add("truncated to %d bytes" % cut, data[:cut])
    for offset in (16, 20, 32, 36, 44, 52, 60, 80):
        if offset + 4 <= len(data):
            corrupt = bytearray(data)
            corrupt[offset:offset + 4] = b"\xff\xff\xff\x7f"
            add("bytes %d..%d set to 0x7fffffff" % (offset, offset + 3), bytes(corrupt))
    add("garbage appended", data + b"garbage")
    add("for another scene", data, scene=fx.scenes["cornell-box"])
    add("a scene given as the solution", open(furnace, "rb").read())
    add("with method interpolate", data[:len(data) // 2], method="interpolate")
    # The solution given as the scene.
    cases.append(Case("solution", "solution given as the scene", render_args(fx.solution, fx.solution + ".exr"),
                      about=fx.solution))
    return cases


# ---------------------------------------------------------- command line


def flag_cases(fx):
    cases = []
    scene = fx.scenes["cornell-box"]
    out = os.path.join(fx.work, "out", "flags.exr")
    base = ["render", scene, "-q", "-o", out]
    render_bad = {
        "--spp": ["0", "-1", "x", "1e9", "99999999999"], "--width": ["0", "abc", "99999"], "--height": ["-5"],
        "--time": ["-1", "x"], "--fov": ["0", "200", "nan"], "--eye": ["1,2", "a,b,c", "1e99,0,0"],
        "--target": ["278,273,-800"], "--up": ["0,0,0", "0,0,1x"], "--seed": ["-1", "x"], "--threads": ["-1", "x"],
        "--method": ["nosuch", ""], "--tonemap": ["nosuch"], "--gamma": ["0", "-1"], "--bits": ["12"],
        "--quantity": ["foo"], "--pixel": ["99,99", "x"], "--colour": ["foo"], "--exposure": ["x"],
        "--gamut": ["foo"], "--variance": [out + ".png"],
    }
    for flag, values in render_bad.items():
        for v in values:
            args = base + [flag, v, "--spp", "1", "--width", "4", "--height", "4"] if flag not in (
                "--spp", "--width", "--height") else base + [flag, v]
            if flag in ("--tonemap", "--gamma", "--bits", "--gamut"):
                args = args + ["-o", out + ".png"]
            cases.append(Case("flags render", "%s %s" % (flag, v), args, flag=flag))
    cases.append(Case("flags render", "-o unknown extension", base + ["-o", "x.bmp"], flag="--output"))
    cases.append(Case("flags render", "--solution missing", base + ["-m", "flat", "--solution", "nosuch.sol"],
                      about="nosuch.sol"))
    cases.append(Case("flags render", "--mesh-size with path", base + ["--mesh-size", "0.1"], flag="--mesh-size"))
    cases.append(Case("flags render", "scene missing", ["render", "nosuch.json", "-q"], about="nosuch.json"))
    cases.append(Case("flags render", "scene is a directory", ["render", fx.work, "-q"], about=fx.work))
    solve_bad = {"--solver": ["nosuch"], "--tolerance": ["-1", "x"], "--mesh-size": ["0", "-1", "x"],
                 "--quality": ["foo"], "--threads": ["x"], "--adaptive-rounds": ["99"]}
    for flag, values in solve_bad.items():
        for v in values:
            cases.append(Case("flags solve", "%s %s" % (flag, v), ["solve", fx.scenes["furnace"], "-q", flag, v],
                              flag=flag))
    cases.append(Case("flags solve", "-o into a missing folder",
                      ["solve", fx.scenes["furnace"], "-q", "-o", "/nonexistent/x.sol"], about="/nonexistent/x.sol"))
    tonemap_bad = {"--exposure": ["x"], "--gamma": ["0"], "--bits": ["7"], "--range": ["a,b", "5,1"],
                   "--tonemap": ["foo"], "--quantity": ["foo"], "--output": [out + ".exr"]}
    for flag, values in tonemap_bad.items():
        for v in values:
            extra = ["--falsecolor"] if flag == "--range" else []
            cases.append(Case("flags tonemap", "%s %s" % (flag, v),
                              ["tonemap", fx.exr, "-o", out + ".png", flag, v] + extra, flag=flag))
    cases.append(Case("flags compare", "--diff x.exr", ["compare", fx.exr, fx.exr, "--diff", out], flag="--diff"))
    cases.append(Case("flags compare", "one image", ["compare", fx.exr], flag="reference"))
    return cases


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--radiant", default=os.path.join(SOURCE, "build", "radiant"))
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--keep", help="write the corpus here and keep it")
    parser.add_argument("--verbose", action="store_true", help="print every case's message")
    parser.add_argument("--no-readers", action="store_true",
                        help="leave out the glTF, MGF, IES and EULUMDAT cases (error_corpus_readers.py)")
    parser.add_argument("--only-readers", action="store_true", help="run those cases alone")
    args = parser.parse_args()
    radiant = os.path.abspath(args.radiant)
    work = os.path.abspath(args.keep) if args.keep else tempfile.mkdtemp(prefix="radiant-errors-")
    os.makedirs(work, exist_ok=True)
    try:
        fx = Fixtures(work, radiant)
        cases = []
        for name in () if args.only_readers else ("cornell-box", "cornell-specular", "cornell-textured", "furnace", "two-rooms"):
            cases += scene_cases(fx, name, fx.scenes[name])
        if not args.only_readers:
            cases += scene_cases(fx, "cornell-box-spectral", fx.scenes["cornell-box-spectral"])
            cases += scene_cases(fx, "obj-wrapper", fx.wrapper)
        if not args.only_readers:
            cases += obj_cases(fx) + texture_cases(fx) + image_cases(fx) + solution_cases(fx) + flag_cases(fx)
        if not args.no_readers:
            cases += reader_cases(fx, Case, json_paths, set_at, replacements, write)
        with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
            results = list(pool.map(lambda c: run(radiant, c, work), cases))
    finally:
        if not args.keep:
            shutil.rmtree(work, ignore_errors=True)
    counts = {"crash": 0, "timeout": 0, "exit0": 0, "clean": 0}
    about_file = no_file = positional = no_position = flagged = no_flag = 0
    failures = []
    for case, (kind, message, problem) in zip(cases, results):
        counts[kind] += 1
        if args.verbose:
            print("[%s] %s: %s\n    %s" % (case.group, case.name, kind, message.replace("\n", "\n    ")))
        if kind in ("crash", "timeout"):
            failures.append((case, kind + (" (" + problem + ")" if problem else ""), message))
            continue
        if kind != "clean":
            continue
        if case.flag:
            flagged += 1
            no_flag += bool(problem)
        elif case.about:
            about_file += 1
            no_file += problem.startswith("does not name")
            if case.position:
                positional += 1
                no_position += problem.startswith("names")
        if problem:
            failures.append((case, problem, message))
    print("cases: %d" % len(cases))
    print("crashes: %d, timeouts: %d, exit 0: %d, clean errors: %d" % (counts["crash"], counts["timeout"],
                                                                      counts["exit0"], counts["clean"]))
    print("clean errors about a file: %d, not naming it: %d" % (about_file, no_file))
    print("  of which the input has positions (JSON, OBJ/MTL): %d, without line or JSON path: %d" %
          (positional, no_position))
    print("clean errors about a flag: %d, not naming it: %d" % (flagged, no_flag))
    if failures:
        print("\nfailures:")
        for case, problem, message in failures:
            print("- [%s] %s: %s\n    radiant %s\n    %s" % (case.group, case.name, problem,
                                                              " ".join(case.args)[:200], message[:400].replace(
                                                                  "\n", "\n    ")))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
