"""Shared fixtures: the paper's rail section, a direct RailModel factory, central differences,
and the validation record.

The low-level tests build ``trackwheel._core`` objects directly, so that a rail without supports
(the simply supported beam of docs: Model § Validation), without gravity or with supports at arbitrary
positions can be set up independently of the Scene layer.

``validation`` is how the documentation's Validation page gets its numbers: a test that checks
trackwheel against an independent reference (a closed form, a published number, central
differences, another path of the code) records the error it measured and the tolerance it
asserts. The page is rendered from the committed ``docs/validation.json``; each recording test
compares what it measured with that copy, so the page cannot drift from what the suite measures
(see :class:`Validation`).
"""

from __future__ import annotations

import json
import math
import platform
from pathlib import Path

import numpy as np
import pytest
from trackwheel import Rail, _core

# The paper's rail section (docs: Model § Scene; the preset values themselves are checked in
# test_scene.py): EA [N], EI [N m^2], rho A [kg/m].
EA = Rail().axial_stiffness
EI = Rail().bending_stiffness
RHO_A = Rail().mass_per_length


@pytest.fixture
def section():
    """Factory for one element's CableSection of the paper's rail, length ``l`` [m]."""

    def make(length=0.25, exact=True, n_gauss=5):
        c = _core.testing.CableSection()
        c.length = length
        c.EA = EA
        c.EI = EI
        c.rhoA = RHO_A
        c.exact_curvature = exact
        c.n_gauss = n_gauss
        return c

    return make


@pytest.fixture
def make_rail():
    """Factory for a RailModel of the paper's section with explicit supports.

    ``supports`` [m] may be empty (the bare simply supported beam); ``stiffness`` [N/m] is one
    value for all supports; ``gravity`` [m/s^2] defaults to 0 (rail weight off).
    """

    def make(length=5.0, n_elements=20, supports=(), stiffness=0.0, damping=0.0, gravity=0.0,
             pin_far_end=False, exact=True, n_gauss=5):
        p = _core.RailParams()
        p.length = length
        p.EA = EA
        p.EI = EI
        p.rhoA = RHO_A
        p.n_elements = n_elements
        p.exact_curvature = exact
        p.n_gauss = n_gauss
        p.gravity = gravity
        p.pin_far_end = pin_far_end
        s = _core.SupportParams()
        s.position = [float(x) for x in supports]
        s.stiffness = [float(stiffness)] * len(supports)
        s.damping = [float(damping)] * len(supports)
        return _core.RailModel(p, s)

    return make


def central_jacobian(f, x, h):
    """Central finite-difference Jacobian of f at x: column i = (f(x + h e_i) - f(x - h e_i))/2h.

    ``h`` is a scalar or one step per coordinate. Truncation error O(h^2 f'''), round-off
    O(eps |f| / h).
    """
    x = np.asarray(x, dtype=float)
    h = np.broadcast_to(np.asarray(h, dtype=float), x.shape)
    cols = []
    for i in range(x.size):
        xp = x.copy()
        xm = x.copy()
        xp[i] += h[i]
        xm[i] -= h[i]
        cols.append((np.asarray(f(xp), dtype=float) - np.asarray(f(xm), dtype=float))
                    / (2.0 * h[i]))
    return np.stack(cols, axis=-1)


@pytest.fixture
def fd():
    """The central-difference Jacobian helper (see :func:`central_jacobian`)."""
    return central_jacobian


def rel_err(a, b):
    """||a - b|| / ||b|| (Frobenius)."""
    return float(np.linalg.norm(np.asarray(a) - np.asarray(b)) / np.linalg.norm(b))


@pytest.fixture
def rel():
    return rel_err


# --------------------------------------------------------------------------------------------
# The validation record (docs/validation.md)
# --------------------------------------------------------------------------------------------
ROOT = Path(__file__).resolve().parent.parent
VALIDATION_JSON = ROOT / "docs" / "validation.json"
REFRESH_OPTION = "--refresh-validation"
#: the model levels, in the page's order
LEVELS = ("element", "rail", "statics", "eigen analysis", "contact", "time integration",
          "paths agree", "frequency domain", "periodic level", "excitation", "vehicle",
          "long tracks")
#: the kinds of independent reference
KINDS = ("closed form", "published", "finite differences", "path agreement")
#: a committed measured value stays current while the suite measures it within 5 % of itself
#: or 1 % of the test's tolerance, whichever is larger: the page shows two significant digits,
#: and round-off-level errors (1e-13 against a 1e-9 tolerance) may differ between builds. On
#: another processor architecture than the committed copy's (its "machine", e.g. aarch64 in the
#: release wheels' tests) round-off differs more: there only the records themselves are compared.
DRIFT_RELATIVE = 0.05
DRIFT_OF_TOLERANCE = 0.01
#: the fields a record states besides its measured value and tolerance; they must match the
#: committed copy (the tolerance within the drift: some tests estimate theirs from round-off)
FIELDS = ("level", "kind", "quantity", "reference", "metric", "test")


def _refresh_hint(nodeid: str) -> str:
    return (f"refresh the committed copy with `pytest {nodeid.split('::')[0]} "
            f"{REFRESH_OPTION}` (or `pytest tests {REFRESH_OPTION}`), check the diff of "
            "docs/validation.json and commit it")


def pytest_addoption(parser):
    parser.addoption(REFRESH_OPTION, action="store_true", default=False,
                     help="write the validation records measured in this session into "
                          "docs/validation.json instead of comparing them with it")


def pytest_collection_modifyitems(config, items):
    """Tests marked ``slow`` (the long property runs) run only when the marker expression
    names them (``pytest -m slow``); the default suite skips them."""
    if "slow" in (config.getoption("markexpr") or ""):
        return
    skip = pytest.mark.skip(reason="a long run: select it with -m slow")
    for item in items:
        if "slow" in item.keywords:
            item.add_marker(skip)


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    """Keep each phase's report on the item, so that a fixture's teardown knows whether the
    test itself passed."""
    outcome = yield
    report = outcome.get_result()
    setattr(item, f"_report_{report.when}", report)


class Validation:
    """The records one test makes: :meth:`record` after the assertion it documents."""

    def __init__(self, nodeid: str, committed: dict | None, same_machine: bool = True):
        self.nodeid = nodeid
        self.committed = committed  # id -> record, or None without docs/validation.json
        self.same_machine = same_machine  # compare the measured values too
        self.records: list[dict] = []

    def record(self, id: str, *, level: str, kind: str, quantity: str, reference: str,
               measured: float, tolerance: float, metric: str = "relative") -> None:
        """One check against an independent reference.

        ``id`` names it (unique over the suite, stable); ``level`` (one of ``LEVELS``) and
        ``kind`` (one of ``KINDS``) place it in the table; ``quantity`` says what was computed
        and ``reference`` what it was compared with (the formula or source, in plain text);
        ``measured`` is the error the test measured and ``tolerance`` the bound it asserts on
        that error, both in ``metric`` (e.g. "relative", "dB", "of max |y|").
        """
        if level not in LEVELS:
            raise ValueError(f"validation level {level!r}: allowed {LEVELS}")
        if kind not in KINDS:
            raise ValueError(f"validation kind {kind!r}: allowed {KINDS}")
        measured, tolerance = float(measured), float(tolerance)
        if not (math.isfinite(measured) and measured >= 0.0 and measured <= tolerance):
            raise ValueError(f"validation record {id}: measured {measured!r} is not an error "
                             f"within the tolerance {tolerance!r}; record the quantity the "
                             "test asserts on")
        self.records.append(dict(id=id, level=level, kind=kind, quantity=quantity,
                                 reference=reference, metric=metric, measured=measured,
                                 tolerance=tolerance, test=self.nodeid))

    def problems(self) -> list[str]:
        """What differs from the committed copy (empty when it is current)."""
        if self.committed is None:
            return []
        out = []
        mine = {r["id"] for r in self.records}
        for r in self.records:
            old = self.committed.get(r["id"])
            if old is None:
                out.append(f"{r['id']}: not in docs/validation.json")
                continue
            changed = [f for f in FIELDS if old.get(f) != r[f]]
            if abs(r["tolerance"] - old["tolerance"]) > DRIFT_RELATIVE * old["tolerance"]:
                changed.append("tolerance")
            if changed:
                out.append(f"{r['id']}: {', '.join(changed)} changed")
            if not self.same_machine:
                continue
            allowed = max(DRIFT_RELATIVE * abs(old["measured"]),
                          DRIFT_OF_TOLERANCE * r["tolerance"])
            if abs(r["measured"] - old["measured"]) > allowed:
                out.append(f"{r['id']}: measured {r['measured']:.3g}, committed "
                           f"{old['measured']:.3g} (allowed drift {allowed:.2g})")
        for rid, old in self.committed.items():
            if old["test"] == self.nodeid and rid not in mine:
                out.append(f"{rid}: committed for this test, not recorded by it")
        return out


def _load_committed() -> tuple[dict | None, bool]:
    """The committed records by id (None without docs/validation.json: an sdist or a tree
    without docs/, where nothing is compared), and whether they were measured on this
    processor architecture."""
    if not VALIDATION_JSON.exists():
        return None, True
    data = json.loads(VALIDATION_JSON.read_text(encoding="utf-8"))
    return ({r["id"]: r for r in data["records"]},
            data.get("machine", platform.machine()) == platform.machine())


@pytest.fixture(scope="session")
def _validation_session(request):
    """Every record of the session, and with --refresh-validation the rewrite of the copy."""
    committed, same_machine = _load_committed()
    session = {"committed": committed, "same_machine": same_machine, "records": {},
               "passed": set()}
    yield session
    if request.config.getoption(REFRESH_OPTION):
        _write_refreshed(session)


def _write_refreshed(session: dict) -> None:
    """Replace the records of every test that passed in this session by what it recorded;
    keep those of tests that did not run."""
    kept = {rid: r for rid, r in (session["committed"] or {}).items()
            if r["test"] not in session["passed"]}
    kept.update(session["records"])
    records = sorted(kept.values(), key=lambda r: (LEVELS.index(r["level"]), r["id"]))
    VALIDATION_JSON.write_text(json.dumps(
        {"about": "Checks of trackwheel against independent references, as measured by the "
                  "test suite (tests/conftest.py, fixture `validation`); rendered by "
                  "docs/validation.md. Refresh: pytest tests " + REFRESH_OPTION + ".",
         "machine": platform.machine(), "records": records}, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")


@pytest.fixture
def validation(request, _validation_session):
    """Record checks against independent references for the Validation page (see
    :class:`Validation`). After a passing test, its records must match docs/validation.json;
    with ``--refresh-validation`` they replace those in it instead."""
    # the test's id relative to the repository, whatever pytest's rootdir
    name = request.node.nodeid.split("::", 1)[1]
    test = f"{Path(request.node.path).resolve().relative_to(ROOT).as_posix()}::{name}"
    v = Validation(test, _validation_session["committed"], _validation_session["same_machine"])
    yield v
    report = getattr(request.node, "_report_call", None)
    if report is None or not report.passed:
        return  # the test's own failure is the message
    for r in v.records:
        if r["id"] in _validation_session["records"]:
            pytest.fail(f"validation record {r['id']} recorded twice (also by "
                        f"{_validation_session['records'][r['id']]['test']})")
        _validation_session["records"][r["id"]] = r
    _validation_session["passed"].add(v.nodeid)
    if request.config.getoption(REFRESH_OPTION):
        return
    problems = v.problems()
    if problems:
        pytest.fail("docs/validation.json is not what this test measures:\n  "
                    + "\n  ".join(problems) + "\n" + _refresh_hint(v.nodeid), pytrace=False)
