"""surfcert: certified answers about pairs of surfaces (quadrics, tori, canal, implicit and
parametric surfaces) from Python.

    import surfcert
    r = surfcert.classify("x^2+y^2+z^2=1", {"type": "sphere", "center": [1.5, 0, 0], "radius": 0.5})
    r.status, r.result.morphology          # 'certified', 'point_imaginary_conic_and_lines'
    d = surfcert.distance("x^2+y^2+z^2=1", "(x-3)^2+y^2+z^2=1/4", digits=30)
    d.result.distance.lower                # Fraction: the proven lower bound

Surfaces (each argument a or b): an equation string; a JSON surface as a dict or a string
starting with '{' (docs/input.md: shapes, matrices, tori, canal, parametric surfaces); a 4x4
numpy array or nested list (floats are read as the exact doubles they are; Fraction, int and
strings such as "1/3" or "0.1" are exact). Options are the batch line's fields: mode
("filtered", "exact", "float"), detail, digits, solid, tolerance, budget_ms.

Results mirror the JSON answer of a `surfcert batch` line (docs/json-contract.md): an object
whose attributes are the JSON fields (r.status, r.result.tu_case, ...; r["status"] works too),
with exact rational strings turned into fractions.Fraction (matrices, invariants, roots,
enclosure bounds, exact coordinates), algebraic numbers kept as strings, "approx" fields as
floats, and curves as numpy arrays: branch points (n, 3) float64 exactly as traced, distance
pairs (k, 2, 3). r.json is the answer's JSON as a dict and r.to_json() its text: exactly the
batch line without "id" and "time_ms".

Batch forms (classify_batch, intersect_batch, distance_batch, verify_batch) take sequences of
surfaces, an (N, 4, 4) float64 array of matrices, or an (N, 10) float64 array of shape
parameters (SHAPE_COLUMNS: centre x y z, semi-axes a b c, unit quaternion w x y z; the shape
type is `shape=`, default "ellipsoid"; a sphere reads a only), or one surface used for every
item. They run on `threads` native threads (default: os.cpu_count()) with the interpreter lock
released, and return one result per item; a bad item gives a result with status "error" and
an `error` field (as a batch line does) instead of raising.

generate(case=..., count=..., seed=..., encoding=..., family=..., gaps=[...]) returns the
labelled test cases of `surfcert generate` (docs/cli.md) as dicts, the JSON lines parsed:
{"id", "op", "a", "b", "label"}; c["a"] and c["b"] are JSON surfaces that classify, distance and
the batch forms take as they are, and c["label"] is the certified answer for them.

Errors of a single call raise InputError (bad input: .source, .line, .column, .json_path,
.expected, .found, as the CLI reports them; a surface a is at JSON path "$.a...") or
InternalError.

The compiled half (_surfcert) is built with the project (python/CMakeLists.txt) into
build/python/surfcert/; use PYTHONPATH=build/python with the interpreter it was built for
(Debian's /usr/bin/python3 by default).
"""

import json as _json
import math as _math
import numbers as _numbers
import os as _os
import re as _re
from fractions import Fraction

from . import _surfcert

__version__ = _surfcert.__version__

__all__ = [
    "classify", "intersect", "distance", "verify",
    "classify_batch", "intersect_batch", "distance_batch", "verify_batch", "generate",
    "Result", "Record", "SurfcertError", "InputError", "InternalError", "SHAPE_COLUMNS",
]

#: The 10 columns of a shape-parameter row (batch forms, and a 1-D array of length 10).
SHAPE_COLUMNS = ("cx", "cy", "cz", "a", "b", "c", "qw", "qx", "qy", "qz")


class SurfcertError(Exception):
    """An error answer: .error is the batch line's "error" object as a dict."""

    def __init__(self, error):
        self.error = dict(error)
        self.kind = error.get("kind")
        self.message = error.get("message", "")
        super().__init__(self.message)


class InputError(SurfcertError, ValueError):
    """Bad input, with where it is: .source, .line, .column (0 when unknown), .json_path
    ("$.a.radius"), .expected, .found (the fields of the CLI's error object)."""

    def __init__(self, error):
        super().__init__(error)
        self.source = error.get("source", "")
        self.line = error.get("line", 0)
        self.column = error.get("column", 0)
        self.json_path = error.get("json_path", "")
        self.expected = error.get("expected", "")
        self.found = error.get("found", "")


class InternalError(SurfcertError, RuntimeError):
    """The engine failed inside (a bug, or FLINT/Arb aborting): not the input's fault."""


# --- results -------------------------------------------------------------------------------

# "p/q", integers and decimals with an optional exponent ("7.4505805969238281e-09"): exact.
_RATIONAL = _re.compile(r"-?[0-9]+(/[0-9]+|(\.[0-9]+)?([eE][-+]?[0-9]+)?)")
# Fields whose strings are labels or counts, never numbers to convert.
_TEXT_FIELDS = {"minimizers", "note", "message", "expected", "found", "source", "json_path",
                "segre", "root_pattern", "signature_sequence", "characteristic_polynomial"}


class Record:
    """A JSON object of an answer: attribute access to its fields (r.tu_case), r["tu_case"],
    `in`, keys(); repr lists the fields. Fields are converted when first read (a batch of many
    answers pays only for what is looked at)."""

    __slots__ = ("_raw", "_done")

    def __init__(self, raw, done=None):
        object.__setattr__(self, "_raw", raw)
        object.__setattr__(self, "_done", {} if done is None else done)

    def _get(self, key):
        done = self._done
        if key in done:
            return done[key]
        v = _convert(self._raw[key], key)
        done[key] = v
        return v

    @property
    def _fields(self):
        return {k: self._get(k) for k in self._raw}

    def __getattr__(self, name):
        if name.startswith("__"):
            raise AttributeError(name)
        try:
            return self._get(name)
        except KeyError:
            raise AttributeError(name) from None

    def __setattr__(self, name, value):
        raise AttributeError("answers are read-only")

    def __getitem__(self, key):
        return self._get(key)

    def __contains__(self, key):
        return key in self._raw

    def __iter__(self):
        return iter(self._raw)

    def keys(self):
        return self._raw.keys()

    def get(self, key, default=None):
        return self._get(key) if key in self._raw else default

    def __eq__(self, other):
        return isinstance(other, Record) and _plain(self) == _plain(other)

    __hash__ = None

    def __dir__(self):
        return list(self._raw)

    def __repr__(self):
        inner = ", ".join(f"{k}={_short(self._get(k))}" for k in self._raw)
        return f"{type(self).__name__}({inner})"


class Result(Record):
    """One answer: the fields of the batch line's JSON (status, mode, result, note, reason,
    readings, error, ...) plus .op, .json (the JSON as a dict) and .to_json() (its text)."""

    __slots__ = ("op", "json", "_text")

    def __init__(self, op, text, curves=None):
        object.__setattr__(self, "_done", {})
        object.__setattr__(self, "op", op)
        object.__setattr__(self, "_text", text)
        # The JSON is parsed when first read (_raw and json are unset slots until then, see
        # __getattr__): the parse is serial Python under the interpreter lock, as costly per
        # item as a cheap query, and a batch's caller often reads only a few answers.
        if curves is not None:
            raw = self._parse()
            if "result" in raw:
                _attach_curves(self._get("result"), curves)

    def _parse(self):
        raw = _json.loads(self._text)
        object.__setattr__(self, "_raw", raw)
        object.__setattr__(self, "json", raw)
        return raw

    def __getattr__(self, name):
        if name in ("_raw", "json"):
            return self._parse()
        return Record.__getattr__(self, name)

    def to_json(self):
        return self._text

    @property
    def ok(self):
        return self._raw.get("status") != "error"


class Classification(Result):
    __slots__ = ()


class Intersection(Result):
    __slots__ = ()


class Distance(Result):
    __slots__ = ()


class Verification(Result):
    __slots__ = ()


_CLASSES = {"classify": Classification, "intersect": Intersection, "distance": Distance,
            "verify": Verification}


def _plain(v):
    if isinstance(v, Record):
        return {k: _plain(v._get(k)) for k in v._raw}
    if isinstance(v, dict):
        return {k: _plain(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_plain(x) for x in v]
    if hasattr(v, "tolist"):
        return v.tolist()
    return v


def _short(v):
    if hasattr(v, "shape"):
        return f"array(shape={tuple(v.shape)})"
    if isinstance(v, list) and len(v) > 4:
        return "[" + ", ".join(_short(x) for x in v[:3]) + f", ... ({len(v)} items)]"
    if isinstance(v, list):
        return "[" + ", ".join(_short(x) for x in v) + "]"
    if isinstance(v, Fraction):
        return f"Fraction('{v}')"
    return repr(v)


def _number(key, s):
    if key == "approx" or (key or "").endswith("_approx"):
        try:
            return float(s)
        except ValueError:
            return s
    if key in ("lower", "upper") and s == "inf":
        return _math.inf
    if key not in _TEXT_FIELDS and _RATIONAL.fullmatch(s):
        return Fraction(s)
    return s


def _convert(v, key):
    if isinstance(v, dict):
        if key == "readings" or key == "error":
            return Record(v, dict(v))
        if key == "estimate":  # a float answer (mode float): a double, never exact
            return Record(v, {k: (float(x) if k == "value" else x) for k, x in v.items()})
        return Record(v)
    if isinstance(v, list):
        if key == "readings":
            return [Record(r, {k: (Record(x, dict(x)) if isinstance(x, dict) else x)
                               for k, x in r.items()}) for r in v]
        if key == "pairs" and v and all(isinstance(p, list) and len(p) == 2 for p in v):
            import numpy as np
            return np.array(v, dtype=float).reshape(len(v), 2, 3)
        return [_convert(x, key) for x in v]
    if isinstance(v, str):
        return _number(key, v)
    return v


def _attach_curves(result, curves):
    branches, isolated = curves
    if "branches" in result:
        result._done["branches"] = [
            Record({"kind": kind, "closed": closed, "points": None},
                   {"kind": kind, "closed": closed, "points": pts})
            for kind, closed, pts in branches]
    if "isolated_points" in result:
        result._done["isolated_points"] = isolated


# --- inputs --------------------------------------------------------------------------------

def _exact_text(x):
    """A number of a matrix or shape: exact JSON (ints as ints, floats as their shortest
    round-trip repr, i.e. the same double; Fraction as "p/q"; strings as given)."""
    if isinstance(x, bool):
        raise TypeError("a number, not a bool")
    if isinstance(x, Fraction):
        return str(x) if x.denominator != 1 else x.numerator
    if isinstance(x, _numbers.Integral):
        return int(x)
    if isinstance(x, _numbers.Real):
        return float(x)
    if isinstance(x, str):
        return x
    raise TypeError(f"a number (int, float, Fraction or string), not {type(x).__name__}")


def _jsonable(v):
    if isinstance(v, dict):
        return {k: _jsonable(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_jsonable(x) for x in v]
    if hasattr(v, "tolist") and not isinstance(v, (str, bytes)):
        return _jsonable(v.tolist())
    if isinstance(v, (Fraction,)) or (isinstance(v, _numbers.Number) and not isinstance(v, bool)):
        return _exact_text(v)
    return v


def _dumps(obj):
    # allow_nan=False: NaN and infinity are not numbers the reader takes (an InputError).
    try:
        return _json.dumps(obj, allow_nan=False)
    except ValueError:
        raise InputError({"kind": "input", "message": "NaN or infinity in a surface",
                          "expected": "finite numbers", "found": "NaN or infinity"}) from None


def _side(s):
    """One surface -> the extension's single side."""
    if isinstance(s, str):
        return ("text", s)
    if isinstance(s, dict):
        return ("text", _dumps(_jsonable(s)))
    if hasattr(s, "shape") and hasattr(s, "dtype"):
        import numpy as np
        a = np.asarray(s)
        if a.shape == (4, 4) and a.dtype.kind == "f":
            return ("matrix", np.ascontiguousarray(a, dtype=np.float64))
        if a.shape == (10,) and a.dtype.kind == "f":
            return ("shape", "ellipsoid", np.ascontiguousarray(a, dtype=np.float64))
        s = a.tolist() if a.dtype.kind != "O" else [list(r) for r in a]
    if isinstance(s, (list, tuple)) and len(s) == 4 and all(
            isinstance(r, (list, tuple)) and len(r) == 4 for r in s):
        return ("text", _dumps({"matrix": _jsonable([list(r) for r in s])}))
    raise TypeError("a surface: an equation string, a JSON dict, a 4x4 matrix (numpy array "
                    f"or nested lists), or 10 shape parameters; got {type(s).__name__}")


def _batch_side(items, shape):
    import numpy as np
    if hasattr(items, "shape") and hasattr(items, "dtype") and items.dtype.kind in "fiu":
        a = np.ascontiguousarray(items, dtype=np.float64)
        if a.ndim == 3 and a.shape[1:] == (4, 4):
            return ("matrices", a)
        if a.ndim == 2 and a.shape[1] == 10:
            return ("shapes", shape, a)
        if a.shape == (4, 4):
            return ("matrix", a)
        if a.shape == (10,):
            return ("shape", shape, a)
        raise ValueError("an array of surfaces must have shape (N, 4, 4) or (N, 10)")
    if isinstance(items, (str, dict)):
        return _side(items)
    texts = []
    for s in items:
        side = _side(s)
        if side[0] == "text":
            texts.append(side[1])
        elif side[0] == "matrix":
            texts.append(_dumps({"matrix": side[1].tolist()}))
        else:
            raise ValueError("a list of surfaces: give shape parameters as an (N, 10) array")
    return ("texts", texts)


def _answer(op, triple):
    ok, text, curves = triple
    if not ok:
        err = _json.loads(text)
        if err.get("kind") == "input":
            raise InputError(err)
        raise InternalError(err)
    return _CLASSES[op](op, text, curves)


def _batch_answer(op, triple, index):
    ok, text, curves = triple
    if ok:
        return _CLASSES[op](op, text, curves)
    return _CLASSES[op](op, _json.dumps({"status": "error", "error": _json.loads(text)}))


def _claims_text(claims):
    if isinstance(claims, str):
        return claims
    return _dumps(_jsonable(list(claims)))


_DEFAULTS = dict(mode="filtered", detail="full", digits=15, solid=False, tolerance=2e-4,
                 budget_ms=0.0)


def _opts(mode, detail, digits, solid, tolerance, budget_ms):
    if isinstance(digits, bool) or not isinstance(digits, _numbers.Integral):
        raise InputError({"kind": "input", "message": "digits: an integer from 1 to 1000",
                          "json_path": "$.digits", "expected": "an integer from 1 to 1000",
                          "found": repr(digits)})
    return (str(mode), str(detail), int(digits), bool(solid), float(tolerance),
            float(budget_ms))


# --- the operations ------------------------------------------------------------------------

def classify(a, b, mode="filtered", detail="full", budget_ms=0):
    """The certified topology of the intersection curve of two quadrics (JSON op classify)."""
    o = _opts(mode, detail, 15, False, 2e-4, budget_ms)
    return _answer("classify", _surfcert.run("classify", _side(a), _side(b), *o, ""))


def intersect(a, b, mode="filtered", detail="full", tolerance=2e-4, budget_ms=0):
    """The topology plus every branch of the curve (result.branches[i].points: (n, 3) arrays)."""
    o = _opts(mode, detail, 15, False, tolerance, budget_ms)
    return _answer("intersect", _surfcert.run("intersect", _side(a), _side(b), *o, ""))


def distance(a, b, digits=15, solid=False, mode="filtered", detail="full", budget_ms=0):
    """The minimum distance: result.distance.lower / .upper (Fraction, proven), minimizers."""
    o = _opts(mode, detail, digits, solid, 2e-4, budget_ms)
    return _answer("distance", _surfcert.run("distance", _side(a), _side(b), *o, ""))


def verify(a, b, claims, mode="filtered", budget_ms=0):
    """Verdicts on claims (a list of claim dicts, docs/json-contract.md op verify)."""
    o = _opts(mode, "full", 15, False, 2e-4, budget_ms)
    return _answer("verify",
                   _surfcert.run("verify", _side(a), _side(b), *o, _claims_text(claims)))


def _batch(op, a, b, shape, threads, o, claims=""):
    threads = threads or _os.cpu_count() or 1
    out = _surfcert.run_batch(op, _batch_side(a, shape), _batch_side(b, shape), *o, claims,
                              int(threads))
    return [_batch_answer(op, t, i) for i, t in enumerate(out)]


def classify_batch(a, b, mode="filtered", detail="full", budget_ms=0, shape="ellipsoid",
                   threads=None):
    """classify for every item (see the module doc for the forms of a and b)."""
    return _batch("classify", a, b, shape, threads,
                  _opts(mode, detail, 15, False, 2e-4, budget_ms))


def intersect_batch(a, b, mode="filtered", detail="full", tolerance=2e-4, budget_ms=0,
                    shape="ellipsoid", threads=None):
    return _batch("intersect", a, b, shape, threads,
                  _opts(mode, detail, 15, False, tolerance, budget_ms))


def distance_batch(a, b, digits=15, solid=False, mode="filtered", detail="full", budget_ms=0,
                   shape="ellipsoid", threads=None):
    return _batch("distance", a, b, shape, threads,
                  _opts(mode, detail, digits, solid, 2e-4, budget_ms))


def verify_batch(a, b, claims, mode="filtered", budget_ms=0, shape="ellipsoid", threads=None):
    """The same claims checked on every pair."""
    return _batch("verify", a, b, shape, threads, _opts(mode, "full", 15, False, 2e-4, budget_ms),
                  _claims_text(claims))


def generate(case="all", count=1, seed=1, encoding="exact", family=None, gaps=(10, 20, 40),
             threads=None):
    """The labelled test cases of `surfcert generate` for the same options (the same lines,
    parsed): a list of dicts {"id", "op", "a", "b", "label"}. case is "1".."35" (or an int),
    "all", "degenerate_pencil", "coincident", "ellipsoid" or "distance"; family (instead of
    case) a path through a degeneracy sampled at g = +-2^-k, 0 for k in gaps; encoding
    "exact", "double" or "shape". The label is what the certified classifier (op classify:
    status, tu_case, morphology, segre, pencil) or distance engine (op distance: distance,
    minimizers, method) answers on exactly c["a"], c["b"]; label["construction"] says how
    the case was built. Labelling runs on `threads` native threads (default os.cpu_count())
    with the interpreter lock released; the lines do not depend on it."""
    if isinstance(count, bool) or not isinstance(count, _numbers.Integral):
        raise TypeError("count: an integer")
    if isinstance(seed, bool) or not isinstance(seed, _numbers.Integral) or seed < 0:
        raise TypeError("seed: a non-negative integer")
    threads = threads or _os.cpu_count() or 1
    ok, out = _surfcert.generate(str(case), family or "", [int(k) for k in gaps], int(count),
                                 int(seed), str(encoding), int(threads))
    if not ok:
        err = _json.loads(out)
        if err.get("kind") == "input":
            raise InputError(err)
        raise InternalError(err)
    return [_json.loads(line) for line in out]
