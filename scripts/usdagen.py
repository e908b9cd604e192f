"""Shared helpers for hdHair's stage generators (standard library only).

Used by examples/generate_examples.py and testenv/stages/generate_stages.py,
which import it as scripts.usdagen (run them from the repository's root
with python3 -m). The C++ reader of the same text is hdHair/usda/.
It does three things:

* builds .usda text in the form usdcat prints it (a small model of layers,
  prims and attributes, rendered with usdcat's layout and compact numbers);
* parses that text back with a small independent parser of the same USD
  subset, and composes it (subLayers, references, payloads, overs);
* checks the composed stage: balanced brackets, valid curve vertex counts for
  each basis and wrap, mesh faces and indices, primvar sizes for each
  interpolation, xformOpOrder entries that exist, and that every curve and
  mesh point is inside the main camera's view and clipping range.

The generators render every file, check it through this round trip, and only
then write it (or, with --check, compare it with the checked-in file).
"""

import decimal
import math
import os
import re
import sys

# ---------------------------------------------------------------------------
# Numbers and values as usdcat prints them
# ---------------------------------------------------------------------------


def fmt(x):
    """A number printed compactly: at most 6 significant digits, no exponent,
    no trailing zeros, integers without a decimal point, no negative zero."""
    if isinstance(x, bool):
        return "true" if x else "false"
    if isinstance(x, int):
        return str(x)
    x = float(x)
    if not math.isfinite(x):
        raise ValueError("non-finite number %r" % x)
    if abs(x) < 1e-6:
        return "0"
    s = "%.6g" % x
    if "e" in s:
        s = format(decimal.Decimal(s), "f")
    if "." in s:
        s = s.rstrip("0").rstrip(".")
    if s in ("-0", ""):
        s = "0"
    return s


def rnd(x):
    """x rounded the way fmt prints it (so models can reason about printed values)."""
    return float(fmt(x))


TUPLE_SIZES = {
    "float": 1, "double": 1, "half": 1, "int": 1, "bool": 1,
    "float2": 2, "double2": 2, "int2": 2,
    "float3": 3, "double3": 3, "point3f": 3, "point3d": 3, "vector3f": 3,
    "normal3f": 3, "color3f": 3, "int3": 3,
    "float4": 4, "double4": 4, "color4f": 4, "quatf": 4, "quatd": 4,
    "matrix4d": 16,
}
STRING_TYPES = ("token", "string", "asset")


def render_scalar(base, v):
    if base in ("token", "string"):
        return '"%s"' % v
    if base == "asset":
        return "@%s@" % v
    n = TUPLE_SIZES[base]
    if base == "matrix4d":
        rows = ["(" + ", ".join(fmt(c) for c in v[r * 4:r * 4 + 4]) + ")" for r in range(4)]
        return "( " + ", ".join(rows) + " )"
    if n == 1:
        return fmt(v)
    assert len(v) == n, (base, v)
    return "(" + ", ".join(fmt(c) for c in v) + ")"


def render_value(type_name, v):
    if type_name.endswith("[]"):
        base = type_name[:-2]
        return "[" + ", ".join(render_scalar(base, e) for e in v) + "]"
    return render_scalar(type_name, v)


# ---------------------------------------------------------------------------
# Layer model and usdcat-style writer
# ---------------------------------------------------------------------------


class Attr:
    """An attribute: a value, time samples, a connection (`connect`, a path), or
    none of them (a declaration, as UsdShade writes outputs)."""

    def __init__(self, type_name, name, value=None, uniform=False, interpolation=None,
                 samples=None, metadata=None, connect=None):
        self.type_name = type_name
        self.name = name
        self.value = value
        self.uniform = uniform
        self.connect = connect
        self.samples = samples  # {time: value}
        self.metadata = list(metadata or [])  # [(key, rendered value)]
        if interpolation is not None:
            self.metadata.insert(0, ("interpolation", '"%s"' % interpolation))

    def lines(self, ind):
        head = ind + ("uniform " if self.uniform else "") + self.type_name + " " + self.name
        out = []
        if self.value is None and self.samples is None and self.connect is None:
            out.append(head)
        if self.value is not None:
            out.append(head + " = " + render_value(self.type_name, self.value))
        if self.connect is not None:
            out.append(head + ".connect = <%s>" % self.connect)
        if self.samples is not None:
            out.append(head + ".timeSamples = {")
            for t in sorted(self.samples):
                out.append(ind + "    %s: %s," % (fmt(t), render_value(self.type_name, self.samples[t])))
            out.append(ind + "}")
        if self.metadata:
            out[-1] += " ("
            for key, val in self.metadata:
                out.append(ind + "    %s = %s" % (key, val))
            out.append(ind + ")")
        return out


class Rel(Attr):
    """A relationship with one target, e.g. material:binding."""

    def __init__(self, name, target):
        super().__init__("rel", name)
        self.target = target

    def lines(self, ind):
        return [ind + "rel %s = <%s>" % (self.name, self.target)]


class Prim:
    def __init__(self, type_name, name, specifier="def", metadata=None, attrs=None, children=None):
        self.type_name = type_name
        self.name = name
        self.specifier = specifier
        self.metadata = list(metadata or [])  # [(key, rendered value)], key may carry a list op
        self.attrs = list(attrs or [])
        self.children = list(children or [])

    def add(self, *items):
        for item in items:
            (self.attrs if isinstance(item, Attr) else self.children).append(item)
        return self

    def lines(self, ind):
        head = ind + self.specifier + " " + (self.type_name + " " if self.type_name else "") + '"%s"' % self.name
        out = []
        if self.metadata:
            out.append(head + " (")
            for key, val in self.metadata:
                out.append(ind + "    %s = %s" % (key, val))
            out.append(ind + ")")
        else:
            out.append(head)
        out.append(ind + "{")
        for attr in sorted(self.attrs, key=lambda a: a.name):
            out.extend(attr.lines(ind + "    "))
        for i, child in enumerate(self.children):
            if i > 0 or self.attrs:
                out.append("")
            out.extend(child.lines(ind + "    "))
        out.append(ind + "}")
        return out


class Layer:
    def __init__(self, doc=None, default_prim=None, meters_per_unit=0.01, up_axis="Y",
                 start=None, end=None, sublayers=None):
        self.doc = doc
        self.default_prim = default_prim
        self.meters_per_unit = meters_per_unit
        self.up_axis = up_axis
        self.start = start
        self.end = end
        self.sublayers = list(sublayers or [])
        self.prims = []

    def add(self, *prims):
        self.prims.extend(prims)
        return self

    def text(self):
        meta = []
        if self.default_prim:
            meta.append(("defaultPrim", '"%s"' % self.default_prim))
        if self.end is not None:
            meta.append(("endTimeCode", fmt(self.end)))
        if self.meters_per_unit is not None:
            meta.append(("metersPerUnit", fmt(self.meters_per_unit)))
        if self.start is not None:
            meta.append(("startTimeCode", fmt(self.start)))
        if self.up_axis:
            meta.append(("upAxis", '"%s"' % self.up_axis))
        out = ["#usda 1.0", "("]
        if self.doc:
            out.append('    doc = "%s"' % self.doc)
        for key, val in meta:
            out.append("    %s = %s" % (key, val))
        if self.sublayers:
            out.append("    subLayers = [")
            out.extend("        @%s@%s" % (s, "," if i + 1 < len(self.sublayers) else "")
                       for i, s in enumerate(self.sublayers))
            out.append("    ]")
        out.append(")")
        for prim in self.prims:
            out.append("")
            out.extend(prim.lines(""))
        out.append("")
        return "\n".join(out) + "\n"


# ---------------------------------------------------------------------------
# Building blocks
# ---------------------------------------------------------------------------


def xform_attrs(translate=None, rotate=None, scale=None, orient=None, order=None):
    """Xform op attributes; `order` overrides the default translate-rotate-orient-scale order."""
    attrs, names = [], []
    if translate is not None:
        attrs.append(Attr("double3", "xformOp:translate", tuple(translate)))
        names.append("xformOp:translate")
    if rotate is not None:
        attrs.append(Attr("float3", "xformOp:rotateXYZ", tuple(rotate)))
        names.append("xformOp:rotateXYZ")
    if orient is not None:
        attrs.append(Attr("quatf", "xformOp:orient", tuple(orient)))
        names.append("xformOp:orient")
    if scale is not None:
        attrs.append(Attr("float3", "xformOp:scale", tuple(scale)))
        names.append("xformOp:scale")
    attrs.append(Attr("token[]", "xformOpOrder", order if order is not None else names, uniform=True))
    return attrs


def basis_curves(name, counts, points, widths, widths_interp, colors=None, colors_interp=None,
                 basis="catmullRom", curve_type="cubic", wrap="nonperiodic", extra=None):
    attrs = []
    if curve_type == "cubic":
        attrs.append(Attr("token", "basis", basis, uniform=True))
    attrs += [
        Attr("int[]", "curveVertexCounts", list(counts)),
        Attr("float3[]", "extent", extent(points, widths)),
        Attr("point3f[]", "points", list(points)),
        Attr("token", "type", curve_type, uniform=True),
        Attr("float[]", "widths", list(widths), interpolation=widths_interp),
        Attr("token", "wrap", wrap, uniform=True),
    ]
    if colors is not None:
        attrs.append(Attr("color3f[]", "primvars:displayColor", list(colors), interpolation=colors_interp))
    attrs += list(extra or [])
    return Prim("BasisCurves", name, attrs=attrs)


def mesh(name, counts, indices, points, scheme="catmullClark", colors=None, colors_interp=None, extra=None):
    """A Mesh prim; `extra` adds attributes (subdivision tags, more primvars)."""
    attrs = [
        Attr("float3[]", "extent", extent(points, [])),
        Attr("int[]", "faceVertexCounts", list(counts)),
        Attr("int[]", "faceVertexIndices", list(indices)),
        Attr("point3f[]", "points", list(points)),
        Attr("token", "subdivisionScheme", scheme, uniform=True),
    ]
    if colors is not None:
        attrs.append(Attr("color3f[]", "primvars:displayColor", list(colors), interpolation=colors_interp))
    attrs += list(extra or [])
    return Prim("Mesh", name, attrs=attrs)


def extent(points, widths):
    half = max(widths) * 0.5 if widths else 0.0
    lo = tuple(min(p[i] for p in points) - half for i in range(3))
    hi = tuple(max(p[i] for p in points) + half for i in range(3))
    return [lo, hi]


def normalize(v):
    n = math.sqrt(sum(c * c for c in v))
    return tuple(c / n for c in v)


def look_rotation(forward):
    """rotateXYZ angles (degrees) that turn -Z into `forward` with no roll (+Y stays up)."""
    f = normalize(forward)
    pitch = math.degrees(math.asin(max(-1.0, min(1.0, f[1]))))
    yaw = math.degrees(math.atan2(-f[0], -f[2]))
    return (rnd(pitch), rnd(yaw), 0.0)


def camera_prim(eye, rotate, focal=50.0, h_ap=20.955, v_ap=15.2908, clip=(1.0, 1000.0), name="main_cam"):
    return Prim("Camera", name, attrs=[
        Attr("float2", "clippingRange", tuple(clip)),
        Attr("float", "focalLength", focal),
        Attr("float", "horizontalAperture", h_ap),
        Attr("token", "projection", "perspective"),
        Attr("float", "verticalAperture", v_ap),
    ] + xform_attrs(translate=eye, rotate=rotate))


def distant_light(name, travel, intensity=2.0, angle=1.0, color=(1, 1, 1), shadow=True):
    """A DistantLight whose light travels along `travel` (it emits along its -Z);
    shadow=False authors inputs:shadow:enable = false (UsdLuxShadowAPI)."""
    return Prim("DistantLight", name, attrs=[
        Attr("float", "inputs:angle", angle),
        Attr("color3f", "inputs:color", tuple(color)),
        Attr("float", "inputs:intensity", intensity),
    ] + ([] if shadow else [Attr("bool", "inputs:shadow:enable", False)])
      + xform_attrs(rotate=look_rotation(travel)))


def sphere_light(name, position, radius, intensity, color=(1, 1, 1)):
    return Prim("SphereLight", name, attrs=[
        Attr("color3f", "inputs:color", tuple(color)),
        Attr("float", "inputs:intensity", intensity),
        Attr("float", "inputs:radius", radius),
    ] + xform_attrs(translate=position))


def sphere_intensity_for_irradiance(irradiance, distance, radius):
    """USD SphereLight intensity (radiance, normalize off) that gives `irradiance`
    at `distance` from its centre: E = L * pi * r^2 / d^2."""
    return irradiance * distance * distance / (math.pi * radius * radius)


def add_phantoms(real):
    """Cubic nonperiodic bspline/catmullRom curves span the 2nd to the 2nd-last
    vertex; extrapolated end points make the curve start and end exactly at the
    first and last real points (for bspline as well as catmullRom)."""
    first = tuple(2 * a - b for a, b in zip(real[0], real[1]))
    last = tuple(2 * a - b for a, b in zip(real[-1], real[-2]))
    return [first] + list(real) + [last]


# ---------------------------------------------------------------------------
# Parser for the emitted USD subset
# ---------------------------------------------------------------------------

TOKEN_RE = re.compile(r"""
    (?P<ws>\s+)
  | (?P<comment>\#[^\n]*)
  | (?P<string>"(?:[^"\\\n]|\\.)*")
  | (?P<asset>@[^@\n]*@)
  | (?P<path><[^<>\s]*>)
  | (?P<number>[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)
  | (?P<ident>[A-Za-z_][\w:.]*)
  | (?P<punct>[()\[\]{}=,:])
""", re.X)


class ParseError(Exception):
    pass


def tokenize(text, name):
    if not text.startswith("#usda 1.0\n"):
        raise ParseError("%s: missing '#usda 1.0' header" % name)
    toks, pos, line = [], 0, 1
    while pos < len(text):
        m = TOKEN_RE.match(text, pos)
        if not m:
            raise ParseError("%s:%d: unexpected character %r" % (name, line, text[pos]))
        kind = m.lastgroup
        if kind not in ("ws", "comment"):
            toks.append((kind, m.group(), line))
        line += m.group().count("\n")
        pos = m.end()
    toks.append(("eof", "", line))
    return toks


def check_brackets(text, name):
    """Balanced (), [], {} outside strings and asset paths."""
    stack, in_str, pairs = [], None, {")": "(", "]": "[", "}": "{"}
    for i, ch in enumerate(text):
        if in_str:
            if ch == in_str:
                in_str = None
            continue
        if ch in "\"@":
            in_str = ch
        elif ch in "([{":
            stack.append(ch)
        elif ch in ")]}":
            if not stack or stack.pop() != pairs[ch]:
                raise ParseError("%s: unbalanced %r at offset %d" % (name, ch, i))
    if stack or in_str:
        raise ParseError("%s: unclosed %r" % (name, (stack or [in_str])[-1]))


class Parser:
    LISTOPS = ("prepend", "append", "add", "delete", "reorder")

    def __init__(self, text, name):
        self.name = name
        self.toks = tokenize(text, name)
        self.i = 0

    def peek(self, k=0):
        return self.toks[self.i + k]

    def next(self):
        tok = self.toks[self.i]
        self.i += 1
        return tok

    def expect(self, value):
        tok = self.next()
        if tok[1] != value:
            raise ParseError("%s:%d: expected %r, got %r" % (self.name, tok[2], value, tok[1]))
        return tok

    def fail(self, msg):
        tok = self.peek()
        raise ParseError("%s:%d: %s (at %r)" % (self.name, tok[2], msg, tok[1]))

    def parse_layer(self):
        layer = {"meta": {}, "prims": {}}
        if self.peek()[1] == "(":
            layer["meta"] = self.parse_metadata()
        while self.peek()[0] != "eof":
            prim = self.parse_prim()
            if prim["name"] in layer["prims"]:
                self.fail("duplicate root prim " + prim["name"])
            layer["prims"][prim["name"]] = prim
        return layer

    def parse_metadata(self):
        meta = {}
        self.expect("(")
        while self.peek()[1] != ")":
            listop = None
            if self.peek()[1] in self.LISTOPS:
                listop = self.next()[1]
            key = self.next()
            if key[0] != "ident":
                self.fail("metadata key expected")
            self.expect("=")
            meta[key[1]] = (listop, self.parse_value())
        self.expect(")")
        return meta

    def parse_prim(self):
        spec = self.next()[1]
        if spec not in ("def", "over", "class"):
            self.fail("prim specifier expected")
        type_name = ""
        if self.peek()[0] == "ident":
            type_name = self.next()[1]
        tok = self.next()
        if tok[0] != "string":
            self.fail("prim name expected")
        prim = {"spec": spec, "type": type_name, "name": tok[1][1:-1], "meta": {},
                "attrs": {}, "children": {}}
        if self.peek()[1] == "(":
            prim["meta"] = self.parse_metadata()
        self.expect("{")
        while self.peek()[1] != "}":
            if self.peek()[1] in ("def", "over", "class") and self.peek(1)[0] in ("ident", "string"):
                child = self.parse_prim()
                if child["name"] in prim["children"]:
                    self.fail("duplicate child " + child["name"])
                prim["children"][child["name"]] = child
            else:
                self.parse_property(prim)
        self.expect("}")
        return prim

    def parse_property(self, prim):
        uniform = False
        while self.peek()[1] in ("uniform", "custom"):
            uniform = uniform or self.next()[1] == "uniform"
        type_tok = self.next()
        if type_tok[0] != "ident":
            self.fail("attribute type expected")
        type_name = type_tok[1]
        if type_name == "rel":
            name = self.next()[1]
            self.expect("=")
            target = self.next()
            if target[0] != "path":
                self.fail("relationship target expected")
            prim.setdefault("rels", {})[name] = target[1][1:-1]
            return
        if self.peek()[1] == "[":
            self.expect("[")
            self.expect("]")
            type_name += "[]"
        base = type_name[:-2] if type_name.endswith("[]") else type_name
        if base not in TUPLE_SIZES and base not in STRING_TYPES:
            self.fail("unknown attribute type " + type_name)
        name = self.next()[1]
        if name.endswith(".connect"):
            self.expect("=")
            target = self.next()
            if target[0] != "path":
                self.fail("connection target expected")
            attr = prim["attrs"].setdefault(name[:-len(".connect")], {
                "type": type_name, "uniform": uniform, "value": None, "samples": None, "meta": {}})
            attr["connect"] = target[1][1:-1]
            return
        samples = name.endswith(".timeSamples")
        if samples:
            name = name[:-len(".timeSamples")]
        attr = prim["attrs"].setdefault(name, {"type": type_name, "uniform": uniform, "value": None,
                                               "samples": None, "meta": {}})
        if attr["type"] != type_name:
            self.fail("attribute %s declared with two types" % name)
        if self.peek()[1] != "=":
            return  # declared without a value
        self.expect("=")
        value = self.parse_value()
        if samples:
            if not isinstance(value, dict):
                self.fail("timeSamples need a dictionary")
            attr["samples"] = value
            for v in value.values():
                self.check_type(type_name, v)
        else:
            self.check_type(type_name, value)
            attr["value"] = value
        if self.peek()[1] == "(":
            attr["meta"].update({k: v for k, (_, v) in self.parse_metadata().items()})

    def check_type(self, type_name, value):
        base = type_name[:-2] if type_name.endswith("[]") else type_name
        values = value if type_name.endswith("[]") else [value]
        if type_name.endswith("[]") and not isinstance(value, list):
            self.fail("%s needs an array" % type_name)
        for v in values:
            if base == "asset":
                ok = isinstance(v, tuple) and v[0] == "@"  # parse_value's (@, path, target)
            elif base in STRING_TYPES:
                ok = isinstance(v, str)
            elif base == "matrix4d":
                ok = isinstance(v, tuple) and len(v) == 4 and all(len(r) == 4 for r in v)
            elif base == "bool":
                ok = isinstance(v, bool) or (isinstance(v, float) and v in (0.0, 1.0))
            elif TUPLE_SIZES[base] == 1:
                ok = isinstance(v, float)
            else:
                ok = isinstance(v, tuple) and len(v) == TUPLE_SIZES[base] and all(
                    isinstance(c, float) for c in v)
            if not ok:
                self.fail("value %r does not fit %s" % (v, type_name))

    def parse_value(self):
        kind, text, _ = self.peek()
        if kind == "number":
            self.next()
            if re.search(r"[eE]", text):
                self.fail("number with an exponent")
            return float(text)
        if kind == "string":
            self.next()
            return text[1:-1]
        if kind == "asset":
            self.next()
            target = None
            if self.peek()[0] == "path":
                target = self.next()[1][1:-1]
            return ("@", text[1:-1], target)
        if kind == "ident" and text in ("None", "true", "false"):
            self.next()
            return {"None": None, "true": True, "false": False}[text]
        if text in ("(", "["):
            close = ")" if text == "(" else "]"
            self.next()
            items = []
            while self.peek()[1] != close:
                items.append(self.parse_value())
                if self.peek()[1] == ",":
                    self.next()
                elif self.peek()[1] != close:
                    self.fail("',' or %r expected" % close)
            self.next()
            return tuple(items) if text == "(" else items
        if text == "{":
            self.next()
            out = {}
            while self.peek()[1] != "}":
                key = self.next()
                if key[0] != "number":
                    self.fail("time sample key expected")
                self.expect(":")
                out[float(key[1])] = self.parse_value()
                if self.peek()[1] == ",":
                    self.next()
            self.next()
            return out
        self.fail("value expected")


def parse(text, name):
    check_brackets(text, name)
    if re.search(r"\b(nan|inf)\b", text):
        raise ParseError("%s: non-finite number" % name)
    return Parser(text, name).parse_layer()


# ---------------------------------------------------------------------------
# Composition (the subset hdHair's reader supports)
# ---------------------------------------------------------------------------


def _merge(strong, weak):
    """Merges a weaker prim opinion into a stronger one (new dict)."""
    out = {"spec": "def" if "def" in (strong["spec"], weak["spec"]) else strong["spec"],
           "type": strong["type"] or weak["type"], "name": strong["name"],
           "meta": dict(weak["meta"]), "attrs": {}, "children": {}}
    out["meta"].update(strong["meta"])
    for name in list(weak["attrs"]) + [n for n in strong["attrs"] if n not in weak["attrs"]]:
        s, w = strong["attrs"].get(name), weak["attrs"].get(name)
        if s and w:
            a = dict(w)
            a["meta"] = dict(w["meta"])
            a["meta"].update(s["meta"])
            for key in ("value", "samples"):
                if s[key] is not None:
                    a[key] = s[key]
            out["attrs"][name] = a
        else:
            out["attrs"][name] = s or w
    for name in list(strong["children"]) + [n for n in weak["children"] if n not in strong["children"]]:
        s, w = strong["children"].get(name), weak["children"].get(name)
        out["children"][name] = _merge(s, w) if s and w else (s or w)
    return out


def compose(path, texts, _seen=None):
    """Composes the layer at `path` (a key of `texts`, the generated files).
    Returns (layer metadata, {root prim name: composed prim})."""
    layer = parse(texts[path], path)
    base = os.path.dirname(path)
    prims = dict(layer["prims"])
    sub = layer["meta"].get("subLayers")
    for asset in (sub[1] if sub else []):
        _, sub_prims = compose(os.path.normpath(os.path.join(base, asset[1])), texts)
        for name, prim in sub_prims.items():
            prims[name] = _merge(prims[name], prim) if name in prims else prim

    def arcs(prim):
        for key in ("references", "payload"):
            if key not in prim["meta"]:
                continue
            value = prim["meta"][key][1]
            for ref in (value if isinstance(value, list) else [value]):
                target = os.path.normpath(os.path.join(base, ref[1]))
                if target not in texts:
                    raise ParseError("%s: %s names a missing file %s" % (path, key, ref[1]))
                meta, ref_prims = compose(target, texts)
                prim_name = (ref[2] or "/" + meta["defaultPrim"][1]).lstrip("/")
                if prim_name not in ref_prims:
                    raise ParseError("%s: %s names a missing prim %s" % (path, key, prim_name))
                prim = _merge(prim, ref_prims[prim_name])
        prim = dict(prim)
        prim["meta"] = {k: v for k, v in prim["meta"].items() if k not in ("references", "payload")}
        prim["children"] = {n: arcs(c) for n, c in prim["children"].items()}
        return prim

    return layer["meta"], {n: arcs(p) for n, p in prims.items()}


# ---------------------------------------------------------------------------
# Transforms (column vectors: world = parent @ local, local = op0 @ op1 @ ...)
# ---------------------------------------------------------------------------


def mat_mul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def identity():
    return [[1.0 if i == j else 0.0 for j in range(4)] for i in range(4)]


def mat_inverse(m):
    a = [list(row) + [1.0 if i == j else 0.0 for j in range(4)] for i, row in enumerate(m)]
    for c in range(4):
        p = max(range(c, 4), key=lambda r: abs(a[r][c]))
        if abs(a[p][c]) < 1e-12:
            raise ValueError("singular matrix")
        a[c], a[p] = a[p], a[c]
        pivot = a[c][c]
        a[c] = [v / pivot for v in a[c]]
        for r in range(4):
            if r != c:
                f = a[r][c]
                a[r] = [v - f * w for v, w in zip(a[r], a[c])]
    return [row[4:] for row in a]


def _rot(axis, deg):
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    m = identity()
    i, j = {"X": (1, 2), "Y": (2, 0), "Z": (0, 1)}[axis]
    m[i][i], m[i][j], m[j][i], m[j][j] = c, -s, s, c
    return m


def op_matrix(op_type, value):
    m = identity()
    if op_type == "translate":
        for i in range(3):
            m[i][3] = value[i]
    elif op_type == "scale":
        for i in range(3):
            m[i][i] = value[i]
    elif op_type in ("rotateX", "rotateY", "rotateZ"):
        m = _rot(op_type[-1], value)
    elif op_type.startswith("rotate") and len(op_type) == 9:
        for axis, angle in zip(op_type[6:], value):  # first axis applied first
            m = mat_mul(_rot(axis, angle), m)
    elif op_type == "orient":
        w, x, y, z = normalize(value)
        m = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w), 0],
             [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w), 0],
             [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y), 0],
             [0, 0, 0, 1]]
    elif op_type == "transform":
        m = [[value[j][i] for j in range(4)] for i in range(4)]  # usda is row-vector
    else:
        raise ValueError("unknown xform op " + op_type)
    return m


def value_at(attr, time):
    samples = attr.get("samples")
    if not samples:
        return attr["value"]
    times = sorted(samples)
    if time <= times[0]:
        return samples[times[0]]
    if time >= times[-1]:
        return samples[times[-1]]
    for t0, t1 in zip(times, times[1:]):
        if t0 <= time <= t1:
            u = (time - t0) / (t1 - t0)
            a, b = samples[t0], samples[t1]
            if isinstance(a, tuple):
                return tuple(x + u * (y - x) for x, y in zip(a, b))
            return a + u * (b - a)


def local_matrix(prim, time, where):
    order = prim["attrs"].get("xformOpOrder")
    if not order:
        return identity(), False
    m, reset = identity(), False
    for k, entry in enumerate(order["value"]):
        if entry == "!resetXformStack!":
            if k != 0:
                raise ParseError("%s: !resetXformStack! must come first" % where)
            reset = True
            continue
        invert = entry.startswith("!invert!")
        name = entry[len("!invert!"):] if invert else entry
        if not name.startswith("xformOp:") or name not in prim["attrs"]:
            raise ParseError("%s: xformOpOrder names %s, which is not authored" % (where, name))
        op = op_matrix(name.split(":")[1], value_at(prim["attrs"][name], time))
        m = mat_mul(m, mat_inverse(op) if invert else op)
    return m, reset


def transform_point(m, p):
    return tuple(m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2] + m[i][3] for i in range(3))


def walk(prims, time, parent=None, prefix=""):
    """Yields (path, composed prim, world matrix) depth first, skipping class prims."""
    for name, prim in prims.items():
        if prim["spec"] == "class":
            continue
        path = prefix + "/" + name
        local, reset = local_matrix(prim, time, path)
        world = local if (reset or parent is None) else mat_mul(parent, local)
        yield path, prim, world
        yield from walk(prim["children"], time, world, path)


# ---------------------------------------------------------------------------
# Checks
# ---------------------------------------------------------------------------


def segments(curve_type, basis, wrap, n):
    """Number of segments of one curve, or None when n is not valid."""
    if curve_type == "linear":
        if wrap == "periodic":
            return n if n >= 3 else None
        return n - 1 if n >= 2 else None
    if basis == "bezier":
        if wrap == "periodic":
            return n // 3 if n >= 3 and n % 3 == 0 else None
        return (n - 1) // 3 if n >= 4 and (n - 1) % 3 == 0 else None
    if wrap == "periodic":
        return n if n >= 3 else None
    if wrap == "pinned":
        return n - 1 if n >= 2 else None
    return n - 3 if n >= 4 else None


def check_curves(path, prim):
    a = prim["attrs"]

    def token(name, fallback):
        return a[name]["value"] if name in a else fallback

    curve_type, basis, wrap = token("type", "cubic"), token("basis", "bezier"), token("wrap", "nonperiodic")
    assert curve_type in ("linear", "cubic"), (path, curve_type)
    assert basis in ("bezier", "bspline", "catmullRom"), (path, basis)
    assert wrap in ("nonperiodic", "periodic", "pinned"), (path, wrap)
    for name in ("type", "basis", "wrap"):
        assert name not in a or a[name]["uniform"], "%s.%s must be uniform" % (path, name)
    counts = [int(c) for c in a["curveVertexCounts"]["value"]]
    points = a["points"]["value"]
    assert sum(counts) == len(points), "%s: sum(curveVertexCounts) %d != %d points" % (
        path, sum(counts), len(points))
    segs = [segments(curve_type, basis, wrap, n) for n in counts]
    assert None not in segs, "%s: invalid vertex count for %s %s %s: %s" % (
        path, curve_type, basis, wrap, counts)
    if curve_type == "linear":
        varying = len(points)
    else:
        varying = sum(s if wrap == "periodic" else s + 1 for s in segs)
    sizes = {"constant": 1, "uniform": len(counts), "varying": varying, "vertex": len(points)}
    for name, attr in a.items():
        if name == "widths" or (name.startswith("primvars:") and not name.endswith(":indices")):
            default = "vertex" if name == "widths" else "constant"
            interp = attr["meta"].get("interpolation", default)
            assert interp in sizes, (path, name, interp)
            if not isinstance(attr["value"], list):
                assert interp == "constant", (path, name, "a scalar primvar is constant")
                continue
            assert len(attr["value"]) == sizes[interp], "%s.%s: %d values for %s (expected %d)" % (
                path, name, len(attr["value"]), interp, sizes[interp])
    if "extent" in a:
        lo, hi = a["extent"]["value"]
        for p in points:
            assert all(lo[i] - 1e-3 <= p[i] <= hi[i] + 1e-3 for i in range(3)), (path, "extent")
    return len(counts), len(points)


def check_mesh(path, prim):
    """Face counts that use every index, indices inside the points, primvar
    sizes for each interpolation, a known scheme. Returns (faces, points)."""
    a = prim["attrs"]
    counts = [int(c) for c in a["faceVertexCounts"]["value"]]
    indices = [int(i) for i in a["faceVertexIndices"]["value"]]
    points = a["points"]["value"]
    assert all(c >= 3 for c in counts), "%s: a face with fewer than 3 vertices" % path
    assert sum(counts) == len(indices), "%s: sum(faceVertexCounts) %d != %d indices" % (path, sum(counts), len(indices))
    assert all(0 <= i < len(points) for i in indices), "%s: an index outside the points" % path
    scheme = a["subdivisionScheme"]["value"] if "subdivisionScheme" in a else "catmullClark"
    assert scheme in ("catmullClark", "loop", "bilinear", "none"), (path, scheme)
    sizes = {"constant": 1, "uniform": len(counts), "varying": len(points), "vertex": len(points),
             "faceVarying": len(indices)}
    for name, attr in a.items():
        if name.startswith("primvars:") and not name.endswith(":indices"):
            interp = attr["meta"].get("interpolation", "constant")
            indexed = name + ":indices" in a
            size = len(a[name + ":indices"]["value"]) if indexed else len(attr["value"])
            assert size == sizes[interp], "%s.%s: %d values for %s (expected %d)" % (path, name, size, interp,
                                                                                    sizes[interp])
    return len(counts), len(points)


def check_stage(path, texts, camera_path="/World/main_cam", need_lights=True, margin=0.97):
    """Composes and checks a stage; returns a summary dictionary."""
    meta, prims = compose(path, texts)
    assert "defaultPrim" in meta and meta["defaultPrim"][1] in prims, path + ": bad defaultPrim"
    assert meta["upAxis"][1] == "Y" and meta["metersPerUnit"][1] == 0.01, path
    start = meta.get("startTimeCode", (None, 1.0))[1]
    end = meta.get("endTimeCode", (None, start))[1]
    summary = {"curves": {}, "meshes": {}, "lights": [], "camera": None, "bounds": {}}
    world_points = {}
    for time in sorted({start, end}):
        for prim_path, prim, world in walk(prims, time):
            for attr in prim["attrs"].values():
                for t in (attr["samples"] or {}):
                    assert start <= t <= end, "%s: time sample %g outside the stage's range" % (prim_path, t)
            if prim["type"] == "BasisCurves":
                summary["curves"][prim_path] = check_curves(prim_path, prim)
                a = prim["attrs"]
                pts = [transform_point(world, p) for p in a["points"]["value"]]
                world_points.setdefault(prim_path, []).extend(pts)
            elif prim["type"] == "Mesh":
                summary["meshes"][prim_path] = check_mesh(prim_path, prim)
                pts = [transform_point(world, p) for p in prim["attrs"]["points"]["value"]]
                world_points.setdefault(prim_path, []).extend(pts)
            elif prim["type"] == "Camera" and prim_path == camera_path:
                summary["camera"] = (prim, world)
            elif prim["type"].endswith("Light"):
                if prim_path not in summary["lights"]:
                    summary["lights"].append(prim_path)
    assert summary["camera"], path + ": no camera at " + camera_path
    if need_lights:
        assert summary["lights"], path + ": no lights"
    cam, cam_world = summary["camera"]
    ca = cam["attrs"]
    to_cam = mat_inverse(cam_world)
    kx = ca["focalLength"]["value"] / (ca["horizontalAperture"]["value"] / 2)
    ky = ca["focalLength"]["value"] / (ca["verticalAperture"]["value"] / 2)
    near, far = ca["clippingRange"]["value"]
    for prim_path, pts in world_points.items():
        lo = [min(p[i] for p in pts) for i in range(3)]
        hi = [max(p[i] for p in pts) for i in range(3)]
        summary["bounds"][prim_path] = (lo, hi)
        for p in pts:
            x, y, z = transform_point(to_cam, p)
            depth = -z
            assert near < depth < far, "%s: %s has a point at depth %g outside clipping" % (path, prim_path, depth)
            ndc = (x * kx / depth, y * ky / depth)
            assert abs(ndc[0]) <= margin and abs(ndc[1]) <= margin, \
                "%s: %s has a point outside the view (ndc %s)" % (path, prim_path, ndc)
    return summary


# ---------------------------------------------------------------------------
# Camera framing
# ---------------------------------------------------------------------------


def frame_camera(points, forward, focal=50.0, h_ap=20.955, v_ap=15.2908, fill=0.85, target=None,
                 round_to=None):
    """Places a camera looking along `forward` so every point is inside `fill`
    of the view (NDC), centred on the points' bounding box (or `target`), at a
    distance rounded up to a multiple of `round_to` when given.
    Returns the camera prim, the eye and the distance."""
    rotate = look_rotation(forward)
    rot = op_matrix("rotateXYZ", rotate)
    right = (rot[0][0], rot[1][0], rot[2][0])
    up = (rot[0][1], rot[1][1], rot[2][1])
    fwd = (-rot[0][2], -rot[1][2], -rot[2][2])
    if target is None:
        lo = [min(p[i] for p in points) for i in range(3)]
        hi = [max(p[i] for p in points) for i in range(3)]
        target = [(a + b) / 2 for a, b in zip(lo, hi)]
    kx, ky = focal / (h_ap / 2), focal / (v_ap / 2)
    dist = 0.0
    depths = []
    for p in points:
        rel = [p[i] - target[i] for i in range(3)]
        a = sum(r * c for r, c in zip(rel, right))
        b = sum(r * c for r, c in zip(rel, up))
        e = sum(r * c for r, c in zip(rel, fwd))
        dist = max(dist, abs(a) * kx / fill - e, abs(b) * ky / fill - e)
        depths.append(e)
    if round_to:
        dist = math.ceil(dist / round_to) * round_to
    eye = tuple(rnd(target[i] - fwd[i] * dist) for i in range(3))
    near = max(0.1, rnd(0.5 * (dist + min(depths))))
    far = max(1000.0, 2 * (dist + max(depths)))
    far = float(10 ** math.ceil(math.log10(far)))
    cam = camera_prim(eye, rotate, focal=focal, h_ap=h_ap, v_ap=v_ap, clip=(min(near, 1.0), far))
    return cam, eye, dist


# ---------------------------------------------------------------------------
# Driver
# ---------------------------------------------------------------------------


def write_or_check(outdir, texts, argv=None, max_bytes=None):
    """Writes {relative path: text} under outdir, or with --check compares them
    with the files there and exits 1 on any difference."""
    argv = sys.argv[1:] if argv is None else argv
    for rel, text in texts.items():
        if max_bytes is not None:
            limit = max_bytes(rel) if callable(max_bytes) else max_bytes
            assert len(text.encode()) <= limit, "%s is %d bytes (limit %d)" % (rel, len(text.encode()), limit)
    if "--check" in argv:
        stale = []
        for rel, text in sorted(texts.items()):
            full = os.path.join(outdir, rel)
            try:
                with open(full, encoding="utf-8", newline="") as f:
                    same = f.read() == text
            except OSError:
                same = False
            if not same:
                stale.append(rel)
        if stale:
            print("out of date (re-run the generator): " + ", ".join(stale), file=sys.stderr)
            sys.exit(1)
        print("%d files up to date" % len(texts))
        return
    for rel, text in sorted(texts.items()):
        full = os.path.join(outdir, rel)
        os.makedirs(os.path.dirname(full), exist_ok=True)
        with open(full, "w", encoding="utf-8", newline="\n") as f:
            f.write(text)
        print("wrote %s (%d bytes)" % (os.path.relpath(full), len(text.encode())))
