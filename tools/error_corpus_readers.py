"""The readers added since issue 17 for tools/error_corpus.py (issue 38):
glTF 2.0 (its JSON mutated value by value: the message must name the file
and a JSON path or line), MGF (line by line: the file and the line), and the
photometric files IES LM-63 and EULUMDAT (line by line, placed by a JSON
scene's luminaire: the photometric file and its line). Loading is what is
tested, so each case runs `radiant info FILE -q`, which loads the scene and
nothing more."""
import copy
import json
import os
import re
import shutil

SOURCE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CORPUS = os.path.join(SOURCE, "fuzz", "corpus")


def info_args(path):
    return ["info", path, "-q"]


def numeric_tokens(line):
    return [m for m in re.finditer(r"(?<![\w.])[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?(?![\w.])", line)]


def line_mutations(line):
    """Wrong versions of one line of a line-based format: a number that is
    not one, a negative or huge count, the line cut short, or extended."""
    out = []
    numbers = numeric_tokens(line)
    for m in numbers[:2]:
        for new in ("x", "-3", "1e300", "nan"):
            out.append(line[:m.start()] + new + line[m.end():])
    tokens = line.split()
    if len(tokens) > 1:
        out.append(" ".join(tokens[:-1]))
        out.append(" ".join(tokens[:1]))
    return out


def gltf_cases(fx, Case, json_paths, set_at, replacements, write):
    cases = []
    for seed in ("textured-triangle.gltf",):
        document = json.load(open(os.path.join(CORPUS, "gltf", seed)))
        for path, value in json_paths(document):
            if not path or (path and path[-1] == "uri" and isinstance(value, str) and value.startswith("data:")):
                variants = [("deleted", None, True)] if path else []
            else:
                variants = [("set to %s" % json.dumps(r)[:40], r, False) for r in replacements(value)]
                variants.append(("deleted", None, True))
            for label, new, delete in variants:
                folder = fx.path("gltf", "")
                mutated = set_at(document, path, new, delete=delete)
                target = write(os.path.join(folder, "model.gltf"), json.dumps(mutated))
                cases.append(Case("gltf", "/%s %s" % ("/".join(map(str, path)), label), info_args(target),
                                  about=target, position="json"))
    return cases


def text_line_cases(fx, Case, write, group, text, file_name, wrap=None, extra=None, limit=None):
    """Every line of `text` mutated in turn (at most `limit` lines with a
    number or a keyword), the file truncated after each of them too.
    `wrap(folder, path)` gives the file that radiant is run on (the file
    itself by default); `extra` are fixture files beside it."""
    cases = []
    lines = text.splitlines()
    mutated_lines = 0
    for i, line in enumerate(lines):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        if limit is not None and mutated_lines >= limit:
            break
        mutated_lines += 1
        variants = [("line %d: %s" % (i + 1, new[:40]), "\n".join(lines[:i] + [new] + lines[i + 1:]) + "\n")
                    for new in line_mutations(line)]
        variants.append(("cut after line %d" % (i + 1), "\n".join(lines[:i + 1]) + "\n"))
        variants.append(("line %d deleted" % (i + 1), "\n".join(lines[:i] + lines[i + 1:]) + "\n"))
        for label, data in variants:
            folder = fx.path(group, "")
            target = write(os.path.join(folder, file_name), data)
            for name, source in (extra or {}).items():
                shutil.copy(source, os.path.join(folder, name))
            run_on = wrap(folder, target) if wrap else target
            cases.append(Case(group, label, info_args(run_on), about=target, position="line"))
    return cases


def mgf_cases(fx, Case, write):
    cases = []
    folder = os.path.join(CORPUS, "mgf")
    for seed, limit in (("examp1.mgf", 60), ("primitives-and-luminaire.mgf", None)):
        text = open(os.path.join(folder, seed)).read()
        extra = {name: os.path.join(folder, name) for name in os.listdir(folder) if name != seed}
        cases += text_line_cases(fx, Case, write, "mgf", text, seed, extra=extra, limit=limit)
    return cases


def photometry_cases(fx, Case, write):
    cases = []
    folder = os.path.join(CORPUS, "photometry")

    def wrap(case_folder, path):
        key = "ldt" if path.endswith(".ldt") else "ies"
        scene = {"version": 1, "materials": {"grey": {"reflectance": 0.5}},
                 "objects": [{"type": "quad", "material": "grey",
                              "vertices": [[-1, 0, -1], [-1, 0, 1], [1, 0, 1], [1, 0, -1]]}],
                 "luminaires": [{key: os.path.basename(path), "position": [0, 1, 0]}]}
        return write(os.path.join(case_folder, "scene.json"), json.dumps(scene))

    for seed, limit in (("lambertian_downlight.ies", None), ("tilt_include.ies", None), ("quadrant.ldt", 40)):
        text = open(os.path.join(folder, seed), errors="replace").read()
        cases += text_line_cases(fx, Case, write, "photometry", text, seed, wrap=wrap, limit=limit)
    return cases


def reader_cases(fx, Case, json_paths, set_at, replacements, write):
    return (gltf_cases(fx, Case, json_paths, set_at, replacements, write) + mgf_cases(fx, Case, write) +
            photometry_cases(fx, Case, write))
