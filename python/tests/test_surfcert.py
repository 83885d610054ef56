"""Tests of the Python module surfcert (run by CTest "python_module": /usr/bin/python3 -m pytest
python/tests with PYTHONPATH=build/python, SURFCERT_BINARY=build/app/surfcert).

Independent routes: the CLI's `surfcert batch` answers (a separate process reading JSON lines)
for the same questions; one-by-one calls with JSON dicts for the numpy batch forms; exact
Fractions for the round trip; a second Python thread's progress for the released GIL.
"""

import json
import os
import random
import subprocess
import sys
import threading
import time
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest

import surfcert

ROOT = Path(__file__).resolve().parents[2]
BINARY = os.environ.get("SURFCERT_BINARY", str(ROOT / "build" / "app" / "surfcert"))


def fixture_pairs():
    canon = json.loads((ROOT / "data/fixtures/canonical_examples.json").read_text())
    ell = json.loads((ROOT / "data/fixtures/ellipsoid_fixtures.json").read_text())
    pairs = [("canon" + k, v["A"], v["B"]) for k, v in canon.items()]
    pairs += [("ell" + k, v["E1"], v["E2"]) for k, v in ell.items()]
    return pairs


def cli_batch(lines):
    """The CLI's answers to JSON lines, without id and time_ms, keyed by id."""
    text = "".join(json.dumps(l) + "\n" for l in lines)
    p = subprocess.run([BINARY, "batch", "--threads", "2"], input=text, capture_output=True,
                       text=True, check=False)
    assert p.returncode in (0, 2, 3), p.stderr
    out = {}
    for line in p.stdout.splitlines():
        d = json.loads(line)
        key = d.pop("id")
        d.pop("time_ms")
        out[key] = d
    return out


def as_fractions(m):
    return [[Fraction(x) for x in row] for row in m]


def test_fixtures_equal_the_cli():
    pairs = fixture_pairs()
    lines, calls = [], []
    for i, (name, a, b) in enumerate(pairs):
        # Three input forms for the same exact matrices: numpy doubles (integers are exact
        # doubles), nested Fractions, JSON dicts.
        forms = [(np.array(a, dtype=float), as_fractions(b)), ({"matrix": a}, np.array(b, float))]
        fa, fb = forms[i % 2]
        lines.append({"id": f"c{i}", "op": "classify", "a": {"matrix": a}, "b": {"matrix": b}})
        calls.append((f"c{i}", lambda fa=fa, fb=fb: surfcert.classify(fa, fb)))
        lines.append({"id": f"t{i}", "op": "classify", "a": {"matrix": a}, "b": {"matrix": b},
                      "detail": "topology", "mode": "float"})
        calls.append((f"t{i}", lambda fa=fa, fb=fb: surfcert.classify(
            fa, fb, mode="float", detail="topology")))
        if name.startswith("ell") and i % 3 == 0:
            lines.append({"id": f"x{i}", "op": "intersect", "a": {"matrix": a},
                          "b": {"matrix": b}})
            calls.append((f"x{i}", lambda fa=fa, fb=fb: surfcert.intersect(fa, fb)))
            lines.append({"id": f"d{i}", "op": "distance", "a": {"matrix": a},
                          "b": {"matrix": b}, "digits": 20})
            calls.append((f"d{i}", lambda fa=fa, fb=fb: surfcert.distance(fa, fb, digits=20)))
    cli = cli_batch(lines)
    assert len(cli) == len(calls)
    for key, call in calls:
        r = call()
        assert r.json == cli[key], key
        assert json.loads(r.to_json()) == cli[key]
        # The typed fields mirror the JSON.
        assert r.status == cli[key]["status"]
        res = cli[key]["result"]
        if "tu_case" in res:
            assert r.result.tu_case == res["tu_case"]
            assert r.result.morphology == res["morphology"]
        if "matrices" in res:
            assert r.result.matrices.a == [[Fraction(x) for x in row]
                                           for row in res["matrices"]["a"]]
        if "real_roots" in res:
            for got, want in zip(r.result.real_roots, res["real_roots"]):
                assert got.isolating_interval == [Fraction(x)
                                                  for x in want["isolating_interval"]]
                assert got.approx == float(want["approx"])
        if "branches" in res:
            for got, want in zip(r.result.branches, res["branches"]):
                assert isinstance(got.points, np.ndarray) and got.points.shape[1] == 3
                assert np.array_equal(got.points, np.array(want["points"], dtype=float))
        if "distance" in res:
            assert r.result.distance.lower == Fraction(res["distance"]["lower"])
            assert r.result.distance.upper == Fraction(res["distance"]["upper"])
            assert r.result.minimizers == res["minimizers"]


def random_shapes(n, seed):
    rng = random.Random(seed)
    rows = []
    for _ in range(n):
        q = [rng.uniform(-1, 1) for _ in range(4)]
        rows.append([rng.uniform(-0.5, 0.5) for _ in range(3)] +
                    [rng.uniform(0.3, 1.2) for _ in range(3)] + q)
    return np.array(rows, dtype=np.float64)


def shape_dict(row, kind="ellipsoid"):
    row = [float(x) for x in row]
    return {"type": kind, "center": row[0:3], "radii": row[3:6],
            "rotation": {"quaternion": row[6:10]}}


def test_numpy_batches_equal_one_by_one_calls():
    a = random_shapes(24, 1)
    b = random_shapes(24, 2)
    # (N, 10) shape parameters vs dicts in the JSON shape format, one by one.
    batch = surfcert.classify_batch(a, b, detail="topology", threads=2)
    for i, r in enumerate(batch):
        one = surfcert.classify(shape_dict(a[i]), shape_dict(b[i]), detail="topology")
        assert r.json == one.json
    # (N, 4, 4) matrices (a non-symmetric one: a reading) vs one call per 4x4 array.
    rng = np.random.default_rng(3)
    mats = []
    for _ in range(16):
        r = np.linalg.qr(rng.normal(size=(3, 3)))[0]
        m = np.eye(4)
        m[:3, :3] = r @ np.diag(rng.uniform(0.5, 2.0, 3)) @ r.T
        c = rng.uniform(-0.3, 0.3, 3)
        m[:3, 3] = m[3, :3] = -m[:3, :3] @ c
        m[3, 3] = c @ m[:3, :3] @ c - 1
        mats.append(m)
    mats = np.array(mats)
    for op, kw in (("classify", {}), ("distance", {"digits": 12})):
        batch = getattr(surfcert, op + "_batch")(mats, mats[::-1].copy(), threads=2, **kw)
        for i, r in enumerate(batch):
            assert r.json == getattr(surfcert, op)(mats[i], mats[-1 - i], **kw).json
    # One surface for every item, and a sphere from a row (radius = column a).
    spheres = surfcert.distance_batch(a[:4], "x^2+y^2+z^2=9", shape="sphere", threads=2)
    for i, r in enumerate(spheres):
        d = {"type": "sphere", "center": [float(x) for x in a[i, :3]], "radius": float(a[i, 3]),
             "rotation": {"quaternion": [float(x) for x in a[i, 6:]]}}
        assert r.json == surfcert.distance(d, "x^2+y^2+z^2=9").json


def test_batch_releases_the_gil():
    # A batch long enough to see (exact mode, double quaternions: a few hundred microseconds a
    # pair) on one native thread, called from this thread while a second one counts.
    a = random_shapes(400, 4)
    b = random_shapes(400, 5)
    stop = threading.Event()
    stamps = []

    def count():
        while not stop.is_set():
            stamps.append(time.perf_counter())

    counter = threading.Thread(target=count)
    counter.start()
    while not stamps:
        time.sleep(0.001)
    t0 = time.perf_counter()
    out = surfcert.classify_batch(a, b, mode="exact", detail="topology", threads=1)
    t1 = time.perf_counter()
    stop.set()
    counter.join()
    assert all(r.status == "certified" for r in out)
    # Held, the lock would stop the counter for the whole native call (the middle of the
    # span); released, the counter keeps running beside it.
    lo, hi = t0 + 0.2 * (t1 - t0), t1 - 0.2 * (t1 - t0)
    inside = sum(1 for s in stamps if lo <= s <= hi)
    assert inside > 1000, (inside, t1 - t0)


def test_errors_carry_locations():
    bad = {"type": "sphere", "center": [0, 0, 0], "radius": 0}
    with pytest.raises(surfcert.InputError) as e:
        surfcert.classify(bad, "x^2+y^2=1")
    cli = cli_batch([{"id": 1, "op": "classify", "a": bad, "b": "x^2+y^2=1"}])[1]
    assert cli["status"] == "error"
    assert e.value.json_path == cli["error"]["json_path"] == "$.a.radius"
    assert e.value.expected == cli["error"]["expected"]
    assert e.value.found == cli["error"]["found"]
    assert e.value.line == 1 and e.value.column > 1 and e.value.source == "<a>"
    # An equation: line and column of the bad character.
    with pytest.raises(surfcert.InputError) as e:
        surfcert.distance("x^2+y^2+z^2=1", "x^2 + * y = 1")
    assert e.value.source == "<b>" and e.value.line == 1 and e.value.column > 1
    # A torus where classify needs a quadric; an option out of range.
    torus = {"type": "torus", "center": [0, 0, 0], "axis": [0, 0, 1], "major_radius": 3,
             "minor_radius": 1}
    with pytest.raises(surfcert.InputError) as e:
        surfcert.classify("x^2+y^2+z^2=1", torus)
    assert e.value.json_path == "$.b"
    with pytest.raises(surfcert.InputError) as e:
        surfcert.distance("x^2+y^2+z^2=1", torus, digits=0)
    assert e.value.json_path == "$.digits"
    with pytest.raises(surfcert.InputError) as e:
        surfcert.classify("x^2+y^2+z^2=1", "x^2+y^2=1", detail="value")
    assert e.value.json_path == "$.detail"
    # In a batch a bad item is an error answer, and the others are answered.
    out = surfcert.classify_batch([bad, "x^2+y^2+z^2=4"], "x^2+y^2=1")
    assert out[0].status == "error" and out[0].error.json_path == "$.a.radius"
    assert out[0].error.source == "<a[0]>"
    assert out[1].status == "certified"


def test_fractions_round_trip():
    a = [[Fraction(1, 3), 0, 0, Fraction(-1, 7)], [0, Fraction(2, 5), 0, 0],
         [0, 0, 1, 0], [Fraction(-1, 7), 0, 0, Fraction(-10, 3)]]
    b = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, "-9/4"]]
    r = surfcert.classify(a, b, detail="certificate")
    assert r.result.matrices.a == a
    assert all(isinstance(x, Fraction) for row in r.result.matrices.a for x in row)
    assert r.result.matrices.b[3][3] == Fraction(-9, 4)
    # Exact in, exact out: spheres touching at (1/3, 0, 0): the contact point comes back as
    # Fractions; two spheres 1/3 apart: the proven enclosure (outward decimals, as Fractions)
    # holds 1/3 exactly.
    s1 = "x^2 + y^2 + z^2 = 1/9"
    s2 = [[1, 0, 0, Fraction(-1)], [0, 1, 0, 0], [0, 0, 1, 0], [Fraction(-1), 0, 0,
                                                                  Fraction(5, 9)]]
    c = surfcert.classify(s1, s2)
    pts = [p for p in c.result.special_points if not p.at_infinity]
    assert pts and pts[0].exact == [Fraction(1, 3), 0, 0]
    d = surfcert.distance(s1, "(x - 1)^2 + y^2 + z^2 = 1/9")
    assert d.result.distance.lower <= Fraction(1, 3) <= d.result.distance.upper
    assert d.result.distance.upper - d.result.distance.lower <= Fraction(1, 10**15)


def test_intersect_curves_and_verify():
    x = surfcert.intersect("x^2+y^2+z^2=1", {"type": "cylinder", "center": [0.3, 0.1, 0],
                                             "radius": 0.45})
    assert x.status == "certified"
    assert all(b.points.dtype == np.float64 and b.points.ndim == 2 for b in x.result.branches)
    assert len(x.result.branches) == len(x.json["result"]["branches"])
    v = surfcert.verify("x^2+y^2+z^2=1", "(x-3)^2+y^2+z^2=1/4",
                        [{"kind": "distance", "value": 1.5, "abs_tol": 1e-9},
                         {"kind": "solids_collide", "value": True}])
    assert [c.verdict for c in v.result.verdicts] == ["confirmed", "refuted"]
    assert "Classification(" in repr(surfcert.classify("x^2+y^2+z^2=1", "x^2+y^2=1"))


def test_readme_python_example_runs(capsys):
    text = (ROOT / "README.md").read_text()
    block = text.split("<!-- python-example -->\n```python\n", 1)[1].split("```", 1)[0]
    exec(compile(block, "README.md", "exec"), {})
    out = capsys.readouterr().out.split("\n")
    assert out[0] == "certified point_imaginary_conic_and_lines"
    assert out[1] == "Fraction(3, 2)"


def cli_generate(*args):
    p = subprocess.run([BINARY, "generate", *args], capture_output=True, text=True, check=False)
    assert p.returncode in (0, 3), p.stderr
    return [json.loads(line) for line in p.stdout.splitlines()]


GENERATE_OPTIONS = [
    (dict(case=5, count=3, seed=2), ["--case", "5", "--count", "3", "--seed", "2"]),
    (dict(case="all", encoding="double"), ["--case", "all", "--encoding", "double"]),
    (dict(case="ellipsoid", encoding="shape", seed=7),
     ["--case", "ellipsoid", "--encoding", "shape", "--seed", "7"]),
    (dict(case="distance", count=2), ["--case", "distance", "--count", "2"]),
    (dict(family="all", gaps=[3, 30], encoding="double"),
     ["--family", "all", "--gaps", "3,30", "--encoding", "double"]),
]


@pytest.mark.parametrize("kwargs,args", GENERATE_OPTIONS)
def test_generate_equals_the_cli(kwargs, args):
    py = surfcert.generate(**kwargs, threads=2)
    assert py == cli_generate(*args)
    assert len(py) > 0


def test_generated_cases_feed_back_into_the_batch_forms():
    cases = surfcert.generate(case="all", count=2, seed=5, encoding="double")
    cases += surfcert.generate(family="all", gaps=[4, 25], encoding="exact")
    cls = [c for c in cases if c["op"] == "classify" and c["label"]["status"] == "certified"]
    dis = [c for c in cases if c["op"] == "distance" and c["label"]["status"] == "certified"]
    assert len(cls) > 60 and len(dis) > 3
    rs = surfcert.classify_batch([c["a"] for c in cls], [c["b"] for c in cls], threads=2)
    for c, r in zip(cls, rs):
        assert r.status == "certified", c["id"]
        assert r.json["result"]["morphology"] == c["label"]["morphology"], c["id"]
        assert r.json["result"].get("tu_case") == c["label"].get("tu_case"), c["id"]
    ds = surfcert.distance_batch([c["a"] for c in dis], [c["b"] for c in dis], threads=2)
    for c, r in zip(dis, ds):
        assert r.json["result"]["distance"] == c["label"]["distance"], c["id"]
    # one by one too (the single-call forms take the same dicts)
    c = cls[0]
    assert surfcert.classify(c["a"], c["b"]).json["result"]["morphology"] == \
        c["label"]["morphology"]


def test_generate_errors_are_input_errors():
    with pytest.raises(surfcert.InputError):
        surfcert.generate(case="36")
    with pytest.raises(surfcert.InputError):
        surfcert.generate(encoding="float")
    with pytest.raises(surfcert.InputError):
        surfcert.generate(family="tangency", gaps=[0])


@pytest.mark.parametrize("kwargs,path", [
    (dict(case="bogus"), "$.case"),
    (dict(case="36"), "$.case"),
    (dict(family="bogus"), "$.family"),
    (dict(encoding="float"), "$.encoding"),
    (dict(count=0), "$.count"),
    (dict(family="tangency", gaps=[10, 0]), "$.gaps[1]"),
    (dict(family="tangency", gaps=[]), "$.gaps"),
    # 3/2 + 2^-53, the touching family's centre, is no binary64
    (dict(family="touching", gaps=[53], encoding="double"), "$.encoding"),
])
def test_generate_errors_name_the_option(kwargs, path):
    with pytest.raises(surfcert.InputError) as e:
        surfcert.generate(**kwargs, threads=1)
    assert e.value.json_path == path
    assert e.value.source == "<options>"


def test_degenerate_sweep_example_runs(tmp_path):
    """examples/degenerate_sweep.py (docs/api.md) runs to its picture: undecided answers (float
    mode's, without a relation) are shown as undecided, not a crash."""
    pytest.importorskip("matplotlib")
    out = tmp_path / "sweep.png"
    p = subprocess.run([sys.executable, str(ROOT / "examples" / "degenerate_sweep.py"), str(out)],
                       capture_output=True, text=True, check=False, timeout=600)
    assert p.returncode == 0, p.stderr[-3000:]
    assert out.stat().st_size > 0
