#!/usr/bin/env python3
"""Mutation check: does the fast test suite notice plausible physics bugs? (issue 17)

Each mutant in ``MUTANTS`` is one exact source replacement (the old text must occur exactly once
in its file). The driver copies the repository's working tree (tracked and untracked,
non-ignored files) into a scratch directory, configures and builds the C++ module there once
with CMake + Ninja, checks that the unmutated suite passes, and then for each mutant: applies
it, rebuilds incrementally before every run, whatever the mutated file (Ninja recompiles only
what changed: the mutated C++ file, or the one the previous mutant touched and that has been
restored, so a Python mutant never runs against a C++ mutant's module), runs the fast suite

    pytest -x -q -o addopts="-ra --strict-markers --strict-config" -m "not slow" tests
    (without the timing-dependent tests listed in TIMING_DEPENDENT)

with a per-mutant timeout, records whether it was caught and by which test, and reverts it.
The suite runs in a bare virtual environment that sees the running environment's packages
but imports trackwheel from the scratch copy (see make_venv), so the developer's build is never
touched or used.

Statuses: ``caught`` (a test failed; the first failing test's node id is reported),
``survived`` (the suite passed: a missing test, or an equivalent mutant, see ``equivalent``),
``timeout``, ``build error`` (the mutant does not compile: fix its text), ``pattern not found`` /
``ambiguous`` (the source changed: update the mutant's ``old`` text; after a restructure of the
kernel this list is the only thing to edit).

Usage (from anywhere in the repository; needs cmake, ninja, pybind11 and cmeel-eigen in the
running Python environment, as for an editable install):

    python scripts/mutants.py                 # all mutants, table to stdout and benchmarks/
    python scripts/mutants.py --only slip-threshold linear-support-damping
    python scripts/mutants.py --list          # the mutants without running anything
    python scripts/mutants.py --only linear-support-damping --deselect tests/test_golden.py \
        --out /tmp/m.md                       # which physics test catches it after the golden

It takes 5-50 s per mutant on two cores (the incremental rebuild and the suite up to its first
failure) after a first build and unmutated suite run of about two minutes: 23 minutes for the
46 mutants of an earlier list on an idle machine; run it on demand, not in CI.
"""

from __future__ import annotations

import argparse
import csv
import dataclasses
import datetime as _dt
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
#: Tests whose outcome depends on the machine's load, not on the physics: a failure there says
#: nothing about a mutant. The automatic fidelity choice picks the adequate level with the least
#: measured wall time (linear/sprung and linear/hertz are within a few per cent of each other).
#: The Ctrl-C test asks for an interruption latency below 2 s, which a loaded machine can miss.
#: The executor test starts a local Dask cluster, which on a loaded machine once left a pytest
#: warning (an error under the project's settings) with a mutant that cannot change any result.
TIMING_DEPENDENT = [
    "tests/test_fidelity.py::test_sweep_auto_fidelity_chooses_and_reports",
    "tests/test_time_loop.py::test_ctrl_c_interrupts_a_long_simulation_within_a_second",
    "tests/test_sweep.py::test_same_table_whatever_the_executor",
]
#: the fast suite: tests/ without the notebooks (the project's addopts add --nbmake), the slow
#: cases and the timing-dependent tests, stopping at the first failure
PYTEST_ARGS = ["-x", "-q", "-o", "addopts=-ra --strict-markers --strict-config", "-m", "not slow",
               "-p", "no:randomly", "-p", "no:cacheprovider",
               *(a for t in TIMING_DEPENDENT for a in ("--deselect", t)), "tests"]


@dataclasses.dataclass(frozen=True)
class Mutant:
    id: str
    file: str  #: path relative to the repository root
    old: str  #: exact text, must occur exactly once in ``file``
    new: str
    description: str
    #: why the mutant cannot change any result, if it is equivalent (then "survived" is expected)
    equivalent: str | None = None


M = Mutant
DYN = "cpp/dynamics.cpp"
SYS = "cpp/system.cpp"
SLIP = "cpp/slip.cpp"
GA = "cpp/ga_scheme.cpp"
RK4 = "cpp/explicit_rk4.cpp"
FULL = "cpp/full_path.cpp"
LOOP = "cpp/time_loop.cpp"
OUT = "cpp/output.cpp"
LBEAM = "cpp/linear_beam.cpp"
LIN = "cpp/linear_system.cpp"
ANCF = "cpp/ancf_cable.cpp"
CON = "cpp/contact.cpp"
ROLL = "cpp/rolling.cpp"
RAIL = "cpp/rail.cpp"
EIG = "cpp/eigen_analysis.cpp"
ANA = "python/trackwheel/study/analysis.py"
SHEAR = "cpp/ancf_shear.cpp"
WINDOW = "python/trackwheel/scene/window.py"
VEH = "cpp/vehicle.cpp"
VEHPY = "python/trackwheel/scene/vehicle.py"

#: The mutations. Keep the old texts short and specific: they must be unique in their file. The
#: kernel's shared pieces (contact law, generalized-alpha coefficients, time loop) are mutated
#: once: both paths see the bug.
MUTANTS: list[Mutant] = [
    # --- the two of issue 17
    M("slip-threshold", SLIP, "std::abs(lambda) > friction * ev.cf.N",
      "std::abs(lambda) > 1.1 * friction * ev.cf.N",
      "stick -> slide only when |lambda| > 1.1 mu N (Coulomb bound violated in stick)"),
    M("linear-support-damping", LBEAM, "Cy.at(a, b) = r.support_damping().at(i, j);",
      "Cy.at(a, b) = 0.0 * r.support_damping().at(i, j);",
      "linear path drops the support damping from its damping matrix"),
    # --- ANCF element: forces and Jacobians
    M("axial-geometric-stiffness", ANCF, "const double v = wl * eps * h.ns[i] * h.ns[j];",
      "const double v = 0.0 * wl * eps * h.ns[i] * h.ns[j];",
      "axial Jacobian without the geometric term eps S_s^T S_s"),
    M("bending-jacobian-term", ANCF, "3.75 * cr * g72 * dg * dg.transpose()",
      "3.0 * cr * g72 * dg * dg.transpose()",
      "exact-curvature Jacobian: wrong coefficient of the (dg dg^T) term"),
    M("bending-jacobian-d2g", ANCF, "- 1.5 * cr * g52 * d2g;", ";",
      "exact-curvature Jacobian without the d2g term"),
    M("fused-force-curvature", ANCF, "sb * (fa * a + fb * rs) + sa * rs",
      "sb * (fa * a) + sa * rs",
      "time-loop element force: exact curvature's |r_s|^-3 derivative dropped"),
    M("fused-force-axial", ANCF, "sa = wl * c.EA * eps;", "sa = 0.9 * wl * c.EA * eps;",
      "time-loop element force: axial force 10 % low (Jacobian path unchanged)"),
    # --- rail: supports, gravity (full path), and the linear path's rail
    M("full-support-damping", RAIL, "sup_.stiffness[j] * y + sup_.damping[j] * ydot",
      "sup_.stiffness[j] * y", "full path drops the support damping force"),
    M("rail-gravity", RAIL, "p_.rhoA * p_.gravity * nint[a]", "p_.rhoA * p_.gravity * 0.9 * nint[a]",
      "rail weight 10 % low"),
    M("rail-gravity-moments", RAIL, "l * l / 12.0, 0.5 * l, -l * l / 12.0",
      "0.0, 0.5 * l, 0.0", "consistent gravity load lumped (nodal moments dropped)"),
    M("linear-rail-gravity", LBEAM, "Qgy(a) = r.gravity_force()(full_of_y[a]);", "Qgy(a) = 0.0;",
      "linear path without the rail's weight"),
    M("linear-iteration-damping", LIN, "1.0, tr_.M, c_.cv, tr_.C", "1.0, tr_.M, 0.0, tr_.C",
      "linear path's iteration matrix M + cq K without cv C (its Newton stops after one "
      "iteration for the linear wheel models, so the matrix is part of the scheme there)"),
    M("linear-contact-damping-convection", LIN, "+ set_.speed * wc.ss.dot(st.e);", ";",
      "linear path's contact damper without the convected rate v y_s(X_A) of the rail"),
    # --- contact: the law shared by both paths, the distance and the running surface
    M("contact-stiffness", CON, "return k * delta;", "return 1.05 * k * delta;",
      "linear contact law 5 % stiff (force only, both paths)"),
    M("hertz-exponent", CON, "return k * delta * sq;", "return k * delta * std::cbrt(delta);",
      "Hertz law N ~ delta^(4/3) instead of delta^(3/2) (force only, both paths)"),
    M("contact-damping-sign", CON, "Ne + cp.damping * delta_dot", "Ne - cp.damping * delta_dot",
      "contact damper pushes the wrong way"),
    M("contact-damping-jacobian", CON,
      "dNe * out.grad_rho * out.grad_rho.transpose();\n    out.C = cp.damping *",
      "dNe * out.grad_rho * out.grad_rho.transpose();\n    out.C = 0.5 * cp.damping *",
      "contact damping matrix half the damping"),
    M("contact-hessian", CON, "+ (pt.rho / fs) * w * w.transpose()", "",
      "distance Hessian without the contact-point motion term"),
    M("surface-slope", CON, "pt.ps.y() += R.rx * pt.rs.x();", "pt.ps.y() += 0.0 * pt.rs.x();",
      "running surface's tangent without the profile slope r'(x) (surface_at)"),
    M("profile-curvature-hessian", CON, "-= pt.n.y() * pt.profile.rxx",
      "-= 0.0 * pt.profile.rxx",
      "distance Hessian without the profile's curvature term r''(x) S_x S_x^T"),
    # --- rolling constraint and slip
    M("rolling-radius", ROLL, "k.g = t.dot(u) - rho * thetadot;",
      "k.g = t.dot(u) - (rho + 1e-4) * thetadot;",
      "rolling radius 0.1 mm too large in the constraint (undeformed instead of deformed)"),
    M("slide-force-sign", SLIP, "return ws.sigma * friction * ev.cf.N;",
      "return -ws.sigma * friction * ev.cf.N;",
      "sliding friction drives the slip instead of opposing it"),
    M("landing-slip-direction", SLIP, "ws.sigma = ev.rk.g > 0 ? -1.0 : 1.0;",
      "ws.sigma = ev.rk.g > 0 ? 1.0 : -1.0;",
      "a wheel landing with slip slides with friction along its slip velocity"),
    M("slide-jacobian", SYS, "dN_ddelta * cq + model_.contact.damping * cv;", "dN_ddelta * cq;",
      "Newton matrix of the sliding row without dN/dqdot",
      equivalent="only the Newton matrix changes: the iteration converges to the same residual "
                 "tolerance (modified Newton), results agree to newton_tol; kept as a control"),
    M("out-of-round-moment", SLIP, "- ev.cf.N * ev.drho.rx;", ";",
      "an out-of-round wheel's normal force without its moment -N d(Delta rho)/d psi"),
    M("baumgarte-sign", SYS, "- set_.baumgarte * we.rk.g;", "+ set_.baumgarte * we.rk.g;",
      "Baumgarte stabilisation destabilises the constraint drift"),
    # --- integrators: generalized-alpha coefficients (shared by both paths), RK4
    M("alpha-gamma", GA, "gam = 0.5 - am + af;", "gam = 0.6 - am + af;",
      "generalized-alpha gamma off its second-order value (both paths)"),
    M("alpha-beta", GA, "bet = 0.25 * (1.0 - am + af)", "bet = 0.3 * (1.0 - am + af)",
      "generalized-alpha beta off its optimal value (both paths)"),
    M("alpha-position-factor", GA, "bp = bet * (1.0 - af) / (1.0 - am);",
      "bp = 1.1 * bet * (1.0 - af) / (1.0 - am);",
      "d q_{n+1} / d qdd_{n+1} 10 % off: the full path's Newton matrix, the linear path's "
      "position update"),
    M("rk4-weights", RK4, "2.0 * a3_.edd + a4_.edd", "1.0 * a3_.edd + 2.0 * a4_.edd",
      "RK4 weights (1,2,1,2)/6 on the rail velocities: consistent but first order"),
    M("rk4-last-stage", RK4, "stage(1.0, a3_, k3_, k4_);", "stage(0.5, a3_, k3_, k4_);",
      "RK4 fourth stage evaluated at half a step"),
    M("explicit-stability-limit", DYN, "return 2.0 * std::sqrt(2.0) / omega_max;",
      "return 4.0 * std::sqrt(2.0) / omega_max;",
      "predicted RK4 stability limit twice too long"),
    # --- time loop and outputs
    M("output-decimation", LOOP, "if (n % set.output_every == 0) s.record(n);",
      "if ((n - 1) % set.output_every == 0) s.record(n);",
      "every path records the step after the one it should (output_every > 1)"),
    M("energy-runaway-threshold", LOOP, "if (!(Ev <= wd.energy_cap))",
      "if (!(Ev <= 1e3 * wd.energy_cap))",
      "the energy-runaway watchdog fires only at 1000 times its cap"),
    M("output-field-order", OUT,
      '{"acc_A", "m/s^2", "rho cos(phi) theta\' v phi_s (docs: Model § Outputs)", true, false},\n'
      '      {"acc_B", "m/s^2", "rho cos(phi) theta\' phi_t", true, false},',
      '{"acc_B", "m/s^2", "rho cos(phi) theta\' phi_t", true, false},\n'
      '      {"acc_A", "m/s^2", "rho cos(phi) theta\' v phi_s (docs: Model § Outputs)", true, false},',
      "output table: acc_A and acc_B swapped (columns carry each other's values)"),
    M("energy-wheel-load", SYS, "E += model.wheels[w].total_load() * st.wheels[w].y;",
      "E += model.wheels[w].load * st.wheels[w].y;",
      "energy output: wheel-load potential without M g"),
    M("energy-torque", SYS, "E -= model.wheels[w].torque * st.wheels[w].theta;",
      "E += model.wheels[w].torque * st.wheels[w].theta;",
      "energy output: torque potential with the wrong sign"),
    M("reaction-friction", FULL, "lambda * we.rk.b(0)", "0.0 * we.rk.b(0)",
      "driving reaction output without the tangential force's horizontal part"),
    # --- analysis
    M("main-frequency-window", ANA, "w = np.hanning(x.size)", "w = np.ones(x.size)",
      "spectrum without the Hann window"),
    M("quasi-static-line", ANA, "quasi_static_line(one.scene, int(s.n_elements), x, linear)",
      "quasi_static_line(one.scene, int(s.n_elements), x + 0.005, linear)",
      "quasi-static line taken 5 mm ahead of the wheel"),
    M("eigen-wheel-position", EIG, "const MeshPoint mp = rail.locate(position);",
      "const MeshPoint mp = rail.locate(position + 0.05);",
      "eigen analysis attaches the wheel 5 cm from where it is asked"),
    # --- the shear-deformable rail, the axial end zones and the window's default zones
    M("shear-force-shear-term", SHEAR, "fs = wl * c.kGA * gamma;", "fs = 0.9 * wl * c.kGA * gamma;",
      "shear-deformable element's time-loop force: shear force 10 % low (Jacobian path unchanged)"),
    M("shear-jacobian-d2gamma", SHEAR, "*K += (sb * kappa) * d2k + (ss * gamma) * d2gam;",
      "*K += (sb * kappa) * d2k;",
      "shear-deformable element's Jacobian without the shear angle's Hessian term"),
    M("shear-rotary-inertia", SHEAR, "c.rhoI * P.transpose() * P",
      "0.0 * c.rhoI * P.transpose() * P",
      "shear-deformable element's mass without the rotary inertia rho I"),
    M("absorbing-axial", RAIL, "gw[g] * c_x * h.n[i] * h.n[k]", "gw[g] * 0.0 * c_x * h.n[i] * h.n[k]",
      "absorbing end zones without their axial dampers"),
    M("window-default-zones", WINDOW, "absorbing_length: float = 4.8",
      "absorbing_length: float = 0.0", "the travelling window without its default end zones"),
    M("shear-director-stretch", SHEAR, "const double ft = wl * c.kGA * stretch;",
      "const double ft = 0.0 * wl * c.kGA * stretch;",
      "shear-deformable element's time-loop force without the director's stretch term (the "
      "director's length free again: near-free axial modes at fine meshes)"),
    # --- the vehicle: suspensions and weight distribution
    M("vehicle-damper-absolute", VEH, "vm.C += s.damping * g * g.transpose();",
      "vm.C += s.damping * Eigen::MatrixXd(g.cwiseAbs2().asDiagonal());",
      "suspension dampers on each coordinate's absolute velocity instead of the extension rate "
      "(the diagonal of C_v kept, its coupling dropped)"),
    M("bogie-lever-arms", VEHPY,
      "shares = (total * (xk - b.centre) / (xk - xi), total * (b.centre - xi) / (xk - xi))",
      "shares = (total * (b.centre - xi) / (xk - xi), total * (xk - b.centre) / (xk - xi))",
      "a bogie's lever rule with its arms swapped (each wheel gets the other's share)"),
]


# ------------------------------------------------------------------------------------------
def copy_tree(dst: Path) -> None:
    """The working tree's tracked and untracked, non-ignored files (not build products)."""
    files = subprocess.run(["git", "ls-files", "-co", "--exclude-standard", "-z"], cwd=REPO,
                           check=True, capture_output=True).stdout.decode().split("\0")
    for f in filter(None, files):
        src = REPO / f
        if src.is_file():
            (dst / f).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(src, dst / f)


def configure(src: Path, build: Path) -> None:
    import pybind11

    version = re.search(r'^version = "([^"]+)"', (src / "pyproject.toml").read_text(), re.MULTILINE)
    subprocess.run(
        ["cmake", "-S", str(src), "-B", str(build), "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
         "-DSKBUILD_PROJECT_NAME=trackwheel",
         f"-DSKBUILD_PROJECT_VERSION={version.group(1) if version else '0.0.0'}",
         f"-Dpybind11_DIR={pybind11.get_cmake_dir()}", f"-DPython_EXECUTABLE={sys.executable}",
         f"-DCMAKE_LIBRARY_OUTPUT_DIRECTORY={src / 'python' / 'trackwheel'}"],
        check=True, capture_output=True)


def build_module(build: Path) -> tuple[bool, str]:
    p = subprocess.run(["cmake", "--build", str(build)], check=False, capture_output=True,
                       text=True)
    return p.returncode == 0, p.stdout[-3000:] + p.stderr[-3000:]


def make_venv(tmp: Path, src: Path) -> Path:
    """A bare virtual environment that sees the running environment's packages but not its
    .pth hooks (so not an editable install of trackwheel, which would import the developer's
    build, also in the subprocesses some tests start), with the scratch copy's python/ first.
    Returns its interpreter."""
    venv = tmp / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], check=True)
    py = venv / "bin" / "python"
    code = "import sysconfig; print(sysconfig.get_paths()['purelib'])"
    site = subprocess.run([str(py), "-c", code], check=True, capture_output=True, text=True)
    site = Path(site.stdout.strip())
    (site / "0_scratch.pth").write_text(f"{src / 'python'}\n")
    dev = [p for p in sys.path if p.endswith("site-packages") and Path(p).is_dir()]
    # a development set-up may put trackwheel's installed metadata (a dist-info directory, no
    # code) on sys.path instead of installing the package; importlib.metadata reads the version
    # from it (tests/test_cli.py checks it), so the scratch suite needs it too
    dev += [p for p in sys.path if p and p not in dev and Path(p).is_dir()
            and any(Path(p).glob("trackwheel-*.dist-info"))
            and not (Path(p) / "trackwheel").exists()]
    (site / "1_packages.pth").write_text("".join(f"{p}\n" for p in dev))
    return py


def run_suite(py: Path, src: Path, timeout: float) -> tuple[str, str, float]:
    """(status, first failing test, seconds)."""
    t0 = time.perf_counter()
    env = dict(os.environ, PYTHONDONTWRITEBYTECODE="1")
    env.pop("PYTHONPATH", None)
    try:
        p = subprocess.run([str(py), "-m", "pytest", *PYTEST_ARGS], cwd=src, env=env,
                           check=False, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return "timeout", "", time.perf_counter() - t0
    dt = time.perf_counter() - t0
    if p.returncode == 0:
        return "survived", "", dt
    # -ra summary line: "FAILED <node id> - <first line of the error>" (ids may hold spaces)
    m = re.search(r"^(?:FAILED|ERROR) (.+?)(?: - (.*))?$", p.stdout, re.MULTILINE)
    if not m:
        return "caught", f"pytest exit {p.returncode}", dt
    why = (m.group(2) or "").strip()
    return "caught", m.group(1) + (f" ({why[:90]})" if why else ""), dt


def run(mutants: list[Mutant], timeout: float, workdir: Path | None) -> list[dict]:
    tmp = Path(tempfile.mkdtemp(prefix="trackwheel-mutants-", dir=workdir))
    src, build = tmp / "src", tmp / "build"
    src.mkdir()
    print(f"scratch copy: {src}", flush=True)
    copy_tree(src)
    py = make_venv(tmp, src)
    t0 = time.perf_counter()
    configure(src, build)
    ok, log = build_module(build)
    if not ok:
        sys.exit(f"the unmutated code does not build:\n{log}")
    status, test, secs = run_suite(py, src, timeout)
    print(f"baseline: build + suite {time.perf_counter() - t0:.0f} s, suite {status} "
          f"({secs:.0f} s)", flush=True)
    if status != "survived":
        sys.exit(f"the unmutated suite does not pass ({status} {test}): nothing to measure")
    rows = []
    for mu in mutants:
        path = src / mu.file
        text = path.read_text()
        n = text.count(mu.old)
        row = {"id": mu.id, "file": mu.file, "description": mu.description, "status": "",
               "test": "", "seconds": 0.0, "equivalent": mu.equivalent or "",
               "run": _dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")}
        t1 = time.perf_counter()
        if n != 1:
            row["status"] = "pattern not found" if n == 0 else f"ambiguous ({n} matches)"
        else:
            path.write_text(text.replace(mu.old, mu.new))
            try:
                # every mutant, C++ or Python, runs against a module built from the tree as it is
                # now: the previous mutant's file has been restored, and a Python mutant after a
                # C++ one would otherwise import the C++ mutant's module (Ninja rebuilds only
                # what changed, so this is a no-op after a Python mutant)
                ok, log = build_module(build)
                if not ok:
                    row["status"] = "build error"
                else:
                    row["status"], row["test"], _ = run_suite(py, src, timeout)
            finally:
                path.write_text(text)
        row["seconds"] = round(time.perf_counter() - t1, 1)
        rows.append(row)
        print(f"{mu.id:28s} {row['status']:18s} {row['seconds']:6.0f} s  {row['test']}",
              flush=True)
    ok, log = build_module(build)  # leave the scratch build unmutated
    shutil.rmtree(tmp, ignore_errors=True)
    return rows


def report(rows: list[dict], total: float, out_md: Path, out_csv: Path, note: str = "") -> None:
    caught = sum(r["status"] == "caught" for r in rows)
    equiv = sum(r["status"] == "survived" and bool(r["equivalent"]) for r in rows)
    head = (f"{caught} of {len(rows)} mutants caught, {equiv} equivalent survived, "
            f"{len(rows) - caught - equiv} other; {total / 60:.0f} min.")
    print("\n" + head)
    lines = ["# Mutation check", "", "Generated by `python scripts/mutants.py`: " + head, note,
             "", "| mutant | file | status | first failing test (error) | s | run | description |",
             "|---|---|---|---|---|---|---|"]
    for r in rows:
        desc = r["description"] + (f" (equivalent: {r['equivalent']})" if r["equivalent"] else "")
        desc, test = (x.replace("|", "\\|") for x in (desc, r["test"]))
        lines.append(f"| {r['id']} | {r['file']} | {r['status']} | {test} | "
                     f"{float(r['seconds']):.0f} | {r['run']} | {desc} |")
    out_md.write_text("\n".join(lines) + "\n")
    with out_csv.open("w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print(f"written {out_md} and {out_csv}")


def merge(previous: Path, rows: list[dict]) -> list[dict]:
    """The rows of an earlier report (CSV) with the mutants run now replaced, in list order."""
    with previous.open(newline="") as f:
        by_id = {r["id"]: r for r in csv.DictReader(f)}
    for r in by_id.values():
        r.setdefault("run", "")
    by_id.update({r["id"]: r for r in rows})
    return [by_id[m.id] for m in MUTANTS if m.id in by_id]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--only", nargs="+", metavar="ID", help="run only these mutants")
    ap.add_argument("--list", action="store_true", help="list the mutants and exit")
    ap.add_argument("--timeout", type=float, default=900.0, help="per-mutant suite timeout [s]")
    ap.add_argument("--workdir", type=Path, default=None, help="parent of the scratch copy")
    ap.add_argument("--out", type=Path, default=REPO / "benchmarks" / "mutants.md",
                    help="markdown report (a CSV is written next to it)")
    ap.add_argument("--deselect", nargs="+", default=[], metavar="NODE",
                    help="also leave out these tests (e.g. tests/test_golden.py, to see which "
                         "physics test catches a mutant the golden regression catches first)")
    ap.add_argument("--update", action="store_true",
                    help="with --only: replace these mutants' rows in the existing report")
    a = ap.parse_args(argv)
    ids = [m.id for m in MUTANTS]
    if len(set(ids)) != len(ids):
        sys.exit("duplicate mutant ids")
    if a.list:
        for m in MUTANTS:
            print(f"{m.id:28s} {m.file:32s} {m.description}")
        return 0
    chosen = MUTANTS
    if a.only:
        unknown = set(a.only) - set(ids)
        if unknown:
            sys.exit(f"unknown mutant ids: {sorted(unknown)}; see --list")
        chosen = [m for m in MUTANTS if m.id in a.only]
    PYTEST_ARGS[-1:-1] = [x for node in a.deselect for x in ("--deselect", node)]
    t0 = time.perf_counter()
    rows = run(chosen, a.timeout, a.workdir)
    total = time.perf_counter() - t0
    csv_path = a.out.with_suffix(".csv")
    note = ""
    if a.update and csv_path.exists():
        rows = merge(csv_path, rows)
        total = sum(float(r["seconds"]) for r in rows)
        note = "(Rows re-run with --update carry their own date; the time is the sum of rows.)"
    report(rows, total, a.out, csv_path, note)
    bad = [r for r in rows if r["status"] != "caught" and not (r["status"] == "survived"
                                                                and r["equivalent"])]
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
