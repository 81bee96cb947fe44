"""The guided-wave simulation (dispersion/simulation/): loop, mesh, step, reference, bounds.

Default-run tests use tiny strips (one wavelength of travel, three elements per wavelength,
a few hundred steps). The slow test checks one setting fixed before it was run against the
exact reference.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.sparse as sp
from hypothesis import example, given, settings
from hypothesis import strategies as st

from dispersion.errors import ConvergenceError, InputError
from dispersion.simulation.central_difference import run_explicit
from dispersion.simulation.mass_operator import mass_operator
from dispersion.simulation.mesh_critical_step import mesh_critical_step, round_up
from dispersion.simulation.modal_synthesis import continue_signal
from dispersion.simulation.run_cost import RequestTooLarge, estimate_cost, check_cost
from dispersion.simulation.strip import Strip, plan_strip
from dispersion.simulation.strip_mesh import check_rule, strip_mesh, x_mass
from dispersion.simulation.tone_burst import ToneBurst
from dispersion.mass_rules.mass_rule import RULES

TINY = dict(travel=1, stations=2, elements_per_wavelength=3, kappa_c=1.0)


def _tiny(**kw):
    return strip_mesh(plan_strip(Strip(**{**TINY, **kw})))


def _energy_case(mass, p, mode, courant):
    """After the end load stops, E = v.Mv/2 + u_k.K u_{k+1}/2 is constant to round-off."""
    try:
        mesh = _tiny(p=p, mass=mass, mode=mode)
    except InputError as exc:  # a rule the strip cannot run says why
        assert str(exc)
        return
    op = mass_operator(mesh)
    dt = courant * mesh_critical_step(mesh, op).dt_crit
    n = 300
    t = np.arange(n) * dt
    force = np.where(t < 60 * dt, np.sin(np.pi * t / (60 * dt)) ** 2, 0.0)
    run = run_explicit(mesh, op, dt, force, energy_every=20)
    k, E = run.energy[:, 0], run.energy[:, 1]
    after = E[k > 62]
    assert after.size > 8 and after.min() > 0
    assert np.ptp(after) <= 1e-11 * after.max()


_ENERGY_DOMAIN = dict(mass=st.sampled_from(list(RULES)), p=st.integers(1, 4),
                      mode=st.sampled_from(["S0", "A0"]), courant=st.floats(0.05, 0.99))


def _one_rule_per_path() -> list[str]:
    """The first rule of the registry for each path through the loop: its stated explicit
    step, massless rows and basis (a new kind of rule brings its own path here)."""
    from dispersion.simulation.strip_mesh import explicit_step

    paths = {}
    for name, rule in RULES.items():
        key = (explicit_step(rule), rule.states.zero_rows, getattr(rule, "basis", "bspline"))
        paths.setdefault(key, name)
    return sorted(paths.values())


@pytest.mark.parametrize("mass", _one_rule_per_path())
def test_the_undamped_loop_conserves_its_discrete_energy(mass):
    """One rule for each path the registry's rules take (division, factorization,
    condensation of the massless DOFs, a banded inverse mass, a dense stiffness, the C0
    basis), p = 2, S0; every rule, p and load in the slow twin."""
    _energy_case(mass, 2, "S0", 0.9)


@pytest.mark.slow
@settings(max_examples=60, deadline=None)
@given(**_ENERGY_DOMAIN)
@example(mass="lumped", p=1, mode="S0", courant=0.05)
@example(mass="consistent", p=4, mode="A0", courant=0.99)
@example(mass="singular", p=4, mode="A0", courant=0.99)
def test_the_undamped_loop_conserves_its_discrete_energy_slow(mass, p, mode, courant):
    """The whole domain: every rule, p = 1..4, both loads, steps from 0.05 to 0.99 of the
    critical step (its ends as examples)."""
    _energy_case(mass, p, mode, courant)


def test_a_symmetric_load_gives_a_mirror_symmetric_field():
    """S0 load: u_x even and u_y odd in y (A0: the reverse), to round-off, on a mass that
    keeps the mirror (lumped and consistent)."""
    for mass in ("lumped", "consistent"):
        for mode, sign_x in (("S0", 1.0), ("A0", -1.0)):
            mesh = _tiny(p=2, mass=mass, mode=mode)
            op = mass_operator(mesh)
            dt = 0.8 * mesh_critical_step(mesh, op).dt_crit
            run = run_explicit(mesh, op, dt, np.sin(np.arange(200) * dt) ** 3, keep_field=True)
            n = mesh.plan.n
            u = run.field.reshape(-1, n, 2)        # (point along x, point through y, comp)
            mirror = u[:, ::-1, :]
            scale = np.abs(u).max()
            assert scale > 0
            assert np.abs(u[..., 0] - sign_x * mirror[..., 0]).max() <= 1e-12 * scale
            assert np.abs(u[..., 1] + sign_x * mirror[..., 1]).max() <= 1e-12 * scale


@pytest.mark.parametrize("mass", ["lumped", "consistent", "singular"])
def test_lanczos_finds_the_toolkits_dense_critical_step_and_the_loop_obeys_it(mass):
    """The Lanczos step equals the toolkit's dense matrix_critical_step (massless DOFs
    condensed) to 1e-10; 0.98 of it runs under either load, 1.05 of it blows up under one of
    them (the top mode belongs to one symmetry class; a mirror-symmetric mass keeps the
    other class free of it)."""
    from dispersion.time_stepping.timestep import matrix_critical_step

    kick = np.zeros(400)
    kick[0:3] = 1.0
    blew = []
    for mode in ("S0", "A0"):
        mesh = _tiny(p=2, mass=mass, mode=mode)
        op = mass_operator(mesh)
        step = mesh_critical_step(mesh, op)
        dense = matrix_critical_step(mesh.K, sp.kron(mesh.mass, sp.identity(2)))
        assert abs(2 / step.omega_lanczos - dense) <= 1e-10 * dense
        assert step.dt_crit <= 2 / step.omega_lanczos  # rounded up, to the stable side
        run_explicit(mesh, op, 0.98 * dense, kick)
        try:
            run_explicit(mesh, op, 1.05 * dense, kick)
            blew.append(False)
        except ConvergenceError:
            blew.append(True)
    assert any(blew)


def test_round_up_is_never_below():
    for x in (1.0, 2.0000001, 6.7523646474, 33.8253346, 1e-7 * math.pi):
        y = round_up(x)
        assert y >= x and (y - x) <= 1e-5 * x


def test_the_stiffness_is_the_contact_wings_galerkin_stiffness():
    """K of the strip equals the tangent at rest of the NURBS assembly of dispersion.contact
    (Gauss quadrature, St.Venant-Kirchhoff in plane strain with mu = 1) on the same
    B-spline rectangle: an independent assembly of the same bilinear form."""
    from dispersion.contact.assembly import discretize, internal_force
    from dispersion.contact.material import StVenantKirchhoff
    from dispersion.contact.nurbs import RingPatch
    from dispersion.splines.bspline import open_knot_vector

    mesh = _tiny(p=2, mass="lumped")
    plan = mesh.plan
    kv_x = open_knot_vector(2, plan.n_elements_x, 0, 1)
    kv_y = open_knot_vector(2, plan.n - 2, -1, 1)
    gx = np.array([float(g) for g in kv_x.greville()]) * plan.length
    gy = np.array([float(g) for g in kv_y.greville()])
    X, Y = np.meshgrid(gx, gy, indexing="ij")
    patch = RingPatch(kv_x, kv_y, np.column_stack([X.ravel(), Y.ravel()]),
                      np.ones(X.size))
    nu = plan.nu
    _, K = internal_force(discretize(patch), StVenantKirchhoff(2 * (1 + nu), nu, "strain"),
                          np.zeros((X.size, 2)))
    assert abs(K - mesh.K).max() <= 1e-10 * abs(K).max()


def test_a_non_dispersive_bar_receives_the_burst_unchanged():
    """Modal synthesis with kappa = Omega / c: the Hann burst arrives delayed by d / c and
    otherwise unchanged (closed form: the burst itself); exact for a whole number of samples,
    to the burst's sampling (band-limited interpolation) otherwise."""
    burst = ToneBurst(5, 1.0)
    dt = burst.duration / 400
    t = np.arange(4000) * dt
    source = burst.signal(t)
    c = 1.7
    for d, tol in ((c * 1000 * dt, 1e-12), (c * 1234.37 * dt, 1e-5)):
        moved = continue_signal(source, dt, d, lambda w: w / c, (0.0, math.pi / dt))
        assert np.abs(moved - burst.signal(t - d / c)).max() <= tol


def test_the_burst_spectrum_is_the_transform_of_the_burst():
    burst = ToneBurst(5, 0.8)
    t = np.linspace(0, burst.duration, 40001)
    for w in (0.2, 0.8, 1.3):
        numeric = np.trapezoid(burst.signal(t) * np.exp(-1j * w * t), t)
        assert abs(numeric - burst.spectrum(w)) <= 1e-8 * abs(burst.spectrum(0.8))


def test_requests_over_the_bounds_are_refused_before_any_work():
    plan = plan_strip(Strip(p=4, mass="consistent", elements_per_wavelength=64, travel=200))
    with pytest.raises(RequestTooLarge, match="DOF"):
        check_cost(estimate_cost(plan), "simulation")
    for bad, name in ((dict(p=5), "p"), (dict(courant=1.0), "courant"),
                      (dict(mode="S1"), "mode"), (dict(elements_per_wavelength=1), "elements"),
                      (dict(mass=3), "mass"), (dict(travel=math.nan), "travel")):
        with pytest.raises(InputError, match=name):
            Strip(**bad)


def test_a_rule_the_strip_cannot_run_is_refused_with_its_reason():
    from types import SimpleNamespace

    from dispersion.mass_rules.mass_rule import user_rule

    stated = SimpleNamespace(name="odd", states=SimpleNamespace(
        as_dict=lambda: {"symmetric": True, "diagonal": False, "dense_stiffness": True}))
    with pytest.raises(InputError, match="dense_stiffness"):
        check_rule(stated)

    def dense(space):  # the consistent mass plus a rank-one coupling of every function
        import sympy

        n = space.n
        return space.M + sympy.Matrix(n, n, lambda i, j: sympy.Rational((-1) ** (i + j),
                                                                          100 * n))

    with pytest.raises(InputError, match="banded"):
        x_mass(user_rule("dense-coupled", dense), 2, 100, 1.0)
    assert x_mass("nodal-greville", 3, 100, 0.5).sum() == pytest.approx(50.0, rel=1e-14)


def test_the_nodal_gll_space_has_the_spectra_of_the_c0_bernstein_space():
    """C0 Lagrange elements in the nodal GLL basis (the spectral-element comparator) against
    the same space as B-splines with p-fold interior knots (Bernstein basis): the pencils
    (stiffness, consistent mass) and (stiffness, GLL-quadrature mass, the registry's
    nodal-lobatto matrix of that knot vector) are congruent, so their eigenvalues agree."""
    import scipy.linalg as sla
    import sympy

    from dispersion.simulation.lagrange_space import NodalSpace1D
    from dispersion.simulation.strip_mesh import spline_grams
    from dispersion.splines.bspline import KnotVector, SplineBasis1D
    from dispersion.splines.spline_mass import lobatto_matrix

    for p in (1, 2, 3, 4):
        ne = 3
        inner = [sympy.Rational(e, ne) for e in range(1, ne) for _ in range(p)]
        kv = KnotVector(tuple([0] * (p + 1) + inner + [1] * (p + 1)), p)
        bern = spline_grams(SplineBasis1D.from_knots(kv))
        node = NodalSpace1D(p, ne, 0.0, 1.0)
        G = node.grams()
        gll = np.array(lobatto_matrix(kv).tolist(), dtype=float)
        for (Kb, Mb), (Kn, Mn) in (((bern["11"], bern["00"]), (G["11"], G["00"])),
                                   ((bern["11"], gll), (G["11"], node.lumped()))):
            lb = sla.eigh(Kb.toarray(), Mb if isinstance(Mb, np.ndarray) else Mb.toarray(),
                          eigvals_only=True)
            ln = sla.eigh(Kn.toarray(), Mn.toarray(), eigvals_only=True)
            assert np.allclose(lb, ln, rtol=1e-10, atol=1e-10)
        assert np.count_nonzero(node.lumped().toarray() - np.diag(node.lumped().diagonal())) == 0


def test_simulate_command_writes_signals_with_their_inputs(tmp_path, capsys):
    """``dispersion simulate``: CSV with # input lines and one column pair per station, a
    figure, JSON on stdout; bad input is one line and exit 2."""
    import json

    from dispersion.cli import main

    csv_path, fig = tmp_path / "s.csv", tmp_path / "s.png"
    args = ["simulate", "--p", "1", "--elements-per-wavelength", "3", "--travel", "1",
            "--stations", "2", "--kappa", "1", "--csv", str(csv_path), "--figure", str(fig),
            "--format", "json"]
    assert main(args) == 0
    out = json.loads(capsys.readouterr().out)
    summary = out["summary"]
    assert summary["strip"]["mass"] == "lumped" and summary["dofs"] > 0 and "failures" in out
    assert out["columns"][:2] == ["t [H/c_T]", "t [us]"] and len(out["rows"]) == \
        summary["n_steps"]
    lines = csv_path.read_text().splitlines()
    header = [ln for ln in lines if ln.startswith("#")]
    assert any(ln.startswith("# material: steel") for ln in header)
    columns = lines[len(header)].split(",")
    assert columns[:2] == ["t [H/c_T]", "t [us]"] and len(columns) == 2 + 2 * 2
    assert len(lines) - len(header) - 1 == summary["n_steps"]
    assert fig.stat().st_size > 0
    assert main(["simulate", "--courant", "1.5"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "courant" in err[0]


@pytest.mark.slow
def test_the_simulation_meets_the_exact_reference_at_the_verification_setting():
    """One setting fixed before it was run (the default study's verification: S0, p = 3,
    consistent, 8 elements per wavelength, 0.3 of the critical step, 40 wavelengths): the
    burst after 40 wavelengths arrives within 0.1 % of the exact modal synthesis by both
    measures, its phase velocity is the fully discrete branch's to 1e-5, its arrival time the
    predicted one within 20 %, and its L2 error is at most 0.05 (four times the predicted
    phase error of about 0.011 rad)."""
    from dispersion.simulation.wave_run import simulate

    run = simulate(Strip(p=3, mass="consistent", elements_per_wavelength=8, courant=0.3))
    e, pred = run.far, run.prediction
    assert not run.failures and run.phase_certain
    assert abs(e.arrival_error) <= 1e-3 and abs(e.energy_arrival_error) <= 1e-3
    assert abs(e.phase_velocity_error - pred.phase_velocity_error) <= 1e-5
    assert abs(e.energy_arrival_error - pred.arrival_error) <= 0.2 * abs(pred.arrival_error)
    assert e.l2_error <= 0.05


@pytest.mark.slow
def test_the_study_runs_every_rule_and_renders_from_its_json(tmp_path):
    """A tiny size through the whole pipeline: every rule of the registry run or refused with
    a reason, the front and the cheapest from the points, JSON strict, page and figures."""
    import json

    from dispersion.report.wave_simulation import FIGURES, render
    from dispersion.results import dumps
    from dispersion.studies.wave_simulation import WaveSimulationSize, wave_simulation

    size = WaveSimulationSize("tiny", ("S0",), (1,), (3, 4), 10**7,
                              {"p": 1, "mass": "lumped", "elements_per_wavelength": 4,
                               "courant": 0.5},
                              {"travel": 2, "stations": 2, "kappa_c": 1.0})
    study = wave_simulation(size, jobs=1)
    ran = {pt.mass for pt in study.points} | {r.mass for r in study.refused}
    assert ran == set(RULES)
    assert all(r.reason for r in study.refused)
    data = json.loads(dumps(study))
    page = render(data, tmp_path)
    for name in FIGURES:
        assert (tmp_path / name).stat().st_size > 0 and name in page
    assert f"{len(study.points)} runs" in page


def _point(N, energy, peak=None, predicted=None, seconds=1.0, failures=()):
    from dispersion.studies.wave_simulation import SweepPoint

    peak = energy if peak is None else peak
    return SweepPoint("S0", 2, "lumped", N, 4, 100, "diagonal", 10, 0.1, 0.11, 0.11, seconds,
                      (0.1, 0.1, 0.1), 0.0, 1.0, 1e3, 1e4, 10, max(abs(peak), abs(energy)), peak,
                      energy, 0.0, 0.0, 0.0, 0.0, predicted, 0.0, 0.0, None, None, failures,
                      "w")


def test_the_cheapest_choice_and_the_stated_reasons_follow_the_numbers():
    """The cheapest run meeting a target is the one of least loop time without a failure; a
    sign change of the error next to it is flagged as a cancellation; the prediction verdict
    gives the first stated reason that applies."""
    from dispersion.studies.wave_simulation import (STRONG_DISPERSION, _cheapest, _verdict)

    pts = [_point(4, 0.05, seconds=1.0), _point(8, 0.004, seconds=2.0),
           _point(12, -0.0008, seconds=4.0), _point(16, 0.0009, seconds=0.5, failures=("x",))]
    c = _cheapest(pts, "S0", 1e-2, "measured")
    assert (c.elements_per_wavelength, c.cancellation) == (8, False)
    c = _cheapest(pts, "S0", 1e-3, "measured")
    assert (c.elements_per_wavelength, c.cancellation) == (12, True)  # 16 has a failure
    assert _cheapest(pts, "S0", 1e-4, "measured").p is None
    v = _verdict(0, _point(8, 0.0101, predicted=0.01), "energy arrival", "energy_arrival_error",
                 "predicted_arrival_error")
    assert v.holds and v.reason is None
    v = _verdict(0, _point(8, 0.02, predicted=2 * STRONG_DISPERSION), "energy arrival",
                 "energy_arrival_error", "predicted_arrival_error")
    assert not v.holds and v.reason.startswith("strong discrete dispersion")
    v = _verdict(0, _point(8, 0.01, peak=0.02, predicted=0.01), "envelope-peak arrival",
                 "peak_arrival_error", "predicted_arrival_error")
    assert not v.holds and v.reason.startswith("the envelope is distorted")
    v = _verdict(0, _point(8, 0.01), "energy arrival", "energy_arrival_error",
                 "predicted_arrival_error")
    assert not v.holds and v.reason.startswith("no prediction")
