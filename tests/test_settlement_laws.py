"""The ballast settlement laws (docs: Model § Ballast settlement): Varandas et al. (2014)
against its definition and its closed form, Sato (1995) and Shenton (1985) against their curves
and their accumulation rules; cycle jumps against cycle-by-cycle steps; each sleeper of a
vectorised call against its own run, bit for bit; the state stored and resumed; bad input.

References are computed here independently of the code: partial sums of n^-beta by
``math.fsum`` (exact to one rounding), scipy's Hurwitz zeta and digamma where they apply, the
integral of Varandas' definition by ``scipy.integrate.quad``, and the equivalent cycles of a
strain-hardening law by ``scipy.optimize.brentq``.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy import integrate, optimize, special

import trackwheel as tw
from trackwheel.settlement import (
    MAX_CYCLES,
    Sato,
    SettlementState,
    Shenton,
    Varandas,
    law_from_dict,
    power_sum,
)

F0 = 50e3
GAMMA = 0.01
ALPHA, BETA = 0.6, 0.82
P = ALPHA + 1.0


def fsum_powers(beta, a, n):
    """sum_{k=0}^{n-1} (a + k)^-beta by math.fsum (correctly rounded sum of the terms)."""
    return math.fsum((a + np.arange(n, dtype=float)) ** -beta) if n else 0.0


Z_N0 = fsum_powers(BETA, 1.0, 10**6)  # sum_{k<=N0} k^-beta, N0 = 1e6


def varandas_closed_form(force, n):
    """S_N = gamma (F/F0)^(1+alpha) sum_{n<=N} n^-beta / sum_{k<=N0} k^-beta (constant F)."""
    return GAMMA * (force / F0) ** P * fsum_powers(BETA, 1.0, n) / Z_N0


# ---- partial sums ---------------------------------------------------------------------------
@pytest.mark.parametrize("s", [0.0, 0.3, 0.82, 1.0, 1.5, 3.0, 10.0])
def test_power_sums_equal_the_summed_terms(s):
    """To 1e-14: fsum is correctly rounded, and power_sum's Euler-Maclaurin remainder is below
    1e-15 of a term (module docstring), so what is left is a few roundings (measured 1.1e-15)."""
    for a in (1.0, 2.0, 17.5, 1234.0, 1e6):
        for n in (0, 1, 15, 16, 17, 18, 100, 12345, 200_000):
            expected = fsum_powers(s, a, n)
            got = float(power_sum(s, a, n))
            assert got == pytest.approx(expected, rel=1e-14, abs=0.0), (a, n)


@pytest.mark.parametrize("a", [1.0, 3.5, 1e5])
@pytest.mark.parametrize("n", [1000, 10**9, 10**12])
def test_power_sums_equal_hurwitz_zeta_and_digamma_differences(a, n):
    """Where scipy has them: zeta(s, a) - zeta(s, a + n) for s = 1.5 (scipy's zeta needs s > 1)
    and psi(a + n) - psi(a) for s = 1, up to n = 1e12 terms. 1e-12: the references are
    differences of two close numbers (at a = 1e5, n = 1e3 they cancel two digits)."""
    assert float(power_sum(1.5, a, n)) == pytest.approx(
        special.zeta(1.5, a) - special.zeta(1.5, a + n), rel=1e-12)
    assert float(power_sum(1.0, a, n)) == pytest.approx(
        special.digamma(a + n) - special.digamma(a), rel=1e-12)


def test_scipy_zeta_is_nan_below_one_so_the_sums_are_our_own():
    """Why the partial sums are not scipy.special.zeta differences: beta = 0.82 < 1."""
    assert math.isnan(special.zeta(BETA, 1.0))


def test_power_sums_add_up_over_any_split_of_the_range():
    """sum over [a, a + n1 + n2) = sum over [a, a + n1) + sum over [a + n1, a + n1 + n2), for
    splits that put either part in the direct terms or the Euler-Maclaurin tail: 1e-14."""
    for a in (1.0, 7.0):
        for n1, n2 in ((5, 10**9), (10**9, 5), (10**9, 3 * 10**11), (20, 30)):
            whole = float(power_sum(BETA, a, n1 + n2))
            parts = float(power_sum(BETA, a, n1)) + float(power_sum(BETA, a + n1, n2))
            assert whole == pytest.approx(parts, rel=1e-14)


def test_power_sums_of_nothing_are_zero_and_of_ones_count_the_terms():
    assert np.all(power_sum(BETA, np.array([1.0, 5.0, 1e9]), 0) == 0.0)
    n = np.array([1.0, 16.0, 17.0, 1e6, 1e12])
    assert power_sum(0.0, 3.0, n) == pytest.approx(n, rel=1e-14)  # expm1(log1p(.)) roundings


# ---- Varandas: closed form, definition, jumps -----------------------------------------------
def test_the_reference_test_settles_gamma():
    """N0 cycles of F0 on a fresh sleeper settle gamma (the law's normalisation): 1e-15."""
    law = Varandas()
    state, increment = law.advance(law.initial_state(1), [F0], law.reference_cycles)
    assert state.settlement[0] == pytest.approx(GAMMA, rel=1e-15)
    assert increment[0] == state.settlement[0]
    assert law.constant_load(F0, law.reference_cycles) == pytest.approx(GAMMA, rel=1e-15)


@pytest.mark.parametrize("force", [30e3, 50e3, 80e3])
@pytest.mark.parametrize("n", [1, 10, 1000, 123_457])
def test_a_constant_force_follows_the_closed_form(force, n):
    """S_N = gamma (F/F0)^(1+alpha) Z(N) / Z(N0), the sums by fsum: 1e-13 (a few roundings of
    the power and the products on top of the sums' 1e-14)."""
    law = Varandas()
    expected = varandas_closed_form(force, n)
    state, _ = law.advance(law.initial_state(1), [force], n)
    assert state.settlement[0] == pytest.approx(expected, rel=1e-13)
    assert law.constant_load(force, n) == pytest.approx(expected, rel=1e-13)


def test_the_law_follows_its_definition_cycle_by_cycle():
    """u_n = (gamma / M) int_0^{F_n} F^alpha (h_n(F) + 1)^-beta dF, h_n(F) the earlier cycles
    whose peak reached F, integrated by quad piece by piece for 40 cycles of random peaks (some
    repeated, some above, below and equal to earlier ones). 1e-10: quad's relative error."""
    rng = np.random.default_rng(3)
    peaks = rng.choice([30e3, 42e3, 55e3, 61e3, 75e3], size=40) * rng.choice([1.0, 1.01], 40)
    m_ab = F0 ** P / P * Z_N0
    law = Varandas(level_rtol=0.0)
    state = law.initial_state(1)
    for n, peak in enumerate(peaks):
        earlier = peaks[:n]
        edges = np.unique(np.concatenate([[0.0], earlier[earlier < peak], [peak]]))
        integral = sum(integrate.quad(
            lambda f, lo=lo: f ** ALPHA * (np.count_nonzero(earlier >= 0.5 * (lo + hi)) + 1.0)
            ** -BETA, lo, hi, epsrel=1e-13, epsabs=0.0)[0] for lo, hi in zip(edges, edges[1:]))
        state, increment = law.advance(state, [peak], 1)
        assert increment[0] == pytest.approx(GAMMA / m_ab * integral, rel=1e-10), n


def test_one_jump_equals_its_cycles_one_by_one():
    """2000 cycles in one jump against 2000 single cycles, on fresh sleepers and on sleepers
    with a history above, equal and below the force: 1e-12 (each single increment is exact to
    a few roundings; 2000 of them summed add at most 2000 eps of the total, 4.4e-13)."""
    law = Varandas(level_rtol=0.0)
    history = np.array([[0.0, 60e3, 50e3, 40e3]])
    force = np.full(4, 50e3)
    start, _ = law.advance(law.initial_state(4), history, 10**6)
    jumped, jump_increment = law.advance(start, force, 2000)
    stepped = start
    for _ in range(2000):
        stepped, _ = law.advance(stepped, force, 1)
    np.testing.assert_allclose(jumped.settlement, stepped.settlement, rtol=1e-12, atol=0.0)
    np.testing.assert_allclose(jump_increment, stepped.settlement - start.settlement,
                               rtol=1e-9)  # a difference of totals: 1e-12 of 1e-2 over 1e-6
    assert jumped.history["counts"].tolist() == stepped.history["counts"].tolist()


def test_jumps_of_millions_of_cycles_add_up():
    """3e6 + 7e6 cycles as two jumps equal 1e7 as one (and the closed form): 1e-14."""
    law = Varandas()
    one, _ = law.advance(law.initial_state(1), [60e3], 10**7)
    two, _ = law.advance(law.initial_state(1), [60e3], 3 * 10**6)
    two, _ = law.advance(two, [60e3], 7 * 10**6)
    assert two.settlement[0] == pytest.approx(one.settlement[0], rel=1e-14)
    assert one.settlement[0] == pytest.approx(
        GAMMA * (60e3 / F0) ** P * float(power_sum(BETA, 1.0, 1e7)) / Z_N0, rel=1e-13)


@pytest.mark.parametrize("later, expected_ratio", [
    (40e3, "below"), (60e3, "equal"), (80e3, "above")])
def test_the_load_history_effect(later, expected_ratio):
    """After N1 = 1e5 cycles at F1 = 60 kN, one cycle at F2 settles
    below (F2 < F1): gamma (F2/F0)^p (N1 + 1)^-beta / Z(N0), the fresh sleeper's times
    (N1 + 1)^-beta = 7.9e-5; equal: the same with F1; above: the history's part up to F1 plus a
    fresh part between F1 and F2: gamma / Z(N0) [(F1/F0)^p (N1+1)^-beta + (F2/F0)^p -
    (F1/F0)^p]. 1e-12."""
    law = Varandas()
    n1, f1 = 10**5, 60e3
    loaded, _ = law.advance(law.initial_state(2), [f1, 0.0], n1)
    _, increment = law.advance(loaded, [later, later], 1)
    fresh = GAMMA * (later / F0) ** P / Z_N0
    assert increment[1] == pytest.approx(fresh, rel=1e-12)
    decay = (n1 + 1.0) ** -BETA
    if expected_ratio == "above":
        expected = GAMMA / Z_N0 * ((f1 / F0) ** P * decay + (later / F0) ** P - (f1 / F0) ** P)
    else:
        expected = fresh * decay
    assert increment[0] == pytest.approx(expected, rel=1e-12)
    if expected_ratio == "below":
        assert increment[0] / increment[1] == pytest.approx(7.9e-5, rel=0.01)


def test_the_order_of_the_cycles_does_not_matter():
    """The settlement is a function of the load histogram (docs: Model § Ballast settlement):
    300 cycles of 4 levels one by one in random order, in sorted order and as one call of 4
    rows agree to 1e-12 (roundings of 300 summed increments) and keep the same histogram."""
    rng = np.random.default_rng(7)
    levels = np.array([35e3, 48e3, 52e3, 70e3])
    counts = np.array([120, 90, 60, 30])
    sequence = np.repeat(levels, counts)
    law = Varandas(level_rtol=0.0)
    results = []
    for order in (rng.permutation(sequence.size), np.argsort(sequence), None):
        state = law.initial_state(1)
        if order is None:
            state, _ = law.advance(state, levels[:, None], counts)
        else:
            for i in order:
                state, _ = law.advance(state, [sequence[i]], 1)
        results.append(state)
    for state in results[1:]:
        assert state.settlement[0] == pytest.approx(results[0].settlement[0], rel=1e-12)
        assert state.history["levels"].tolist() == results[0].history["levels"].tolist()
        assert state.history["counts"].tolist() == results[0].history["counts"].tolist()


def test_merging_close_levels_stays_within_its_bound():
    """300 single cycles of random peaks in [40, 60] kN: with level_rtol r the settlement is
    within a factor (1 -+ r)^(1+alpha) of the exact one (docs), and a new level is made only
    more than r away from every other, so at most ln(60/40) / ln(1 + r) + 1 levels."""
    rng = np.random.default_rng(11)
    peaks = rng.uniform(40e3, 60e3, 300)
    exact_law, merged_law = Varandas(level_rtol=0.0), Varandas(level_rtol=0.01)
    exact, merged = exact_law.initial_state(1), merged_law.initial_state(1)
    for peak in peaks:
        exact, _ = exact_law.advance(exact, [peak], 1)
        merged, _ = merged_law.advance(merged, [peak], 1)
    ratio = merged.settlement[0] / exact.settlement[0]
    assert 0.99 ** P <= ratio <= 1.01 ** P
    assert exact.history["levels"].shape[1] == 300
    assert merged.history["levels"].shape[1] <= math.log(1.5) / math.log(1.01) + 1
    assert merged.history["counts"].sum() == 300


def test_settlement_grows_with_cycles_and_force_and_shrinks_with_history():
    law = Varandas()
    forces = np.linspace(0.0, 150e3, 31)
    cycles = np.array([0, 1, 10, 10**3, 10**6, 10**8])
    curves = law.constant_load(forces[:, None], cycles[None, :])
    assert np.all(np.diff(curves[:, 1:], axis=0) > 0.0)
    assert np.all(np.diff(curves[1:], axis=1) > 0.0)
    assert np.all(curves[0] == 0.0) and np.all(curves[:, 0] == 0.0)
    rng = np.random.default_rng(5)
    state = law.initial_state(5)
    previous = None
    for _ in range(30):
        state, increment = law.advance(state, rng.uniform(0.0, 90e3, 5), rng.integers(0, 10**5))
        assert np.all(increment >= 0.0)
        # the same cycle settles less the more cycles came before it
        if previous is not None:
            _, now = law.advance(state, np.full(5, 45e3), 1)
            assert np.all(now <= previous)
        _, previous = law.advance(state, np.full(5, 45e3), 1)


# ---- Sato and Shenton -----------------------------------------------------------------------
SATO = dict(a=3e-3, b=2e-5, c=2e-9, reference_force=F0)
SHENTON = dict(k1=4e-4, k2=3e-10, reference_force=F0)


def sato_curve(force, n, a=3e-3, b=2e-5, c=2e-9):
    return (force / F0) * (a * (1.0 - np.exp(-b * n)) + c * n)


def shenton_curve(force, n, k1=4e-4, k2=3e-10):
    return (force / F0) * (k1 * n ** 0.2 + k2 * n)


@pytest.mark.parametrize("law, curve", [(Sato(**SATO), sato_curve),
                                        (Shenton(**SHENTON), shenton_curve)])
@pytest.mark.parametrize("hardening", ["strain", "time"])
def test_a_constant_force_follows_the_curve(law, curve, hardening):
    """S(N) of the published form at a constant force, as one jump and as 10 jumps: 1e-13 (one
    jump); 1e-12 (ten: each starts from an inverted curve, exact to a few roundings)."""
    from dataclasses import replace

    law = replace(law, hardening=hardening)
    for force in (20e3, 50e3, 90e3):
        for n in (1, 1000, 10**5, 10**7):
            state, _ = law.advance(law.initial_state(1), [force], n)
            assert state.settlement[0] == pytest.approx(curve(force, n), rel=1e-13)
            assert law.constant_load(force, n) == pytest.approx(curve(force, n), rel=1e-13)
            state = law.initial_state(1)
            if n % 10 == 0:
                for _ in range(10):
                    state, _ = law.advance(state, [force], n // 10)
                assert state.settlement[0] == pytest.approx(curve(force, n), rel=1e-12)


@pytest.mark.parametrize("law", [Sato(**SATO), Shenton(**SHENTON)])
def test_curve_laws_one_jump_equals_its_cycles_one_by_one(law):
    """1000 cycles in one jump against 1000 single cycles after a history at another force
    (strain hardening: each step inverts the curve): 1e-11, 1000 steps of a few roundings of
    the increment each, the increments 1e-4 of the total."""
    start, _ = law.advance(law.initial_state(2), [[70e3, 30e3]], 10**5)
    jumped, _ = law.advance(start, [50e3, 50e3], 1000)
    stepped = start
    for _ in range(1000):
        stepped, _ = law.advance(stepped, [50e3, 50e3], 1)
    np.testing.assert_allclose(jumped.settlement, stepped.settlement, rtol=1e-11, atol=0.0)


def test_strain_hardening_starts_at_the_equivalent_cycles():
    """N1 cycles at F1, then N2 at F2: the second stage adds S(N_eq + N2; F2) - S1 with
    S(N_eq; F2) = S1, N_eq by brentq (xtol 1e-6 cycles), for Sato and Shenton, the load
    going up and down: 1e-9. Closed forms without the linear terms: Sato
    N_eq = -ln(1 - (F1/F2)(1 - e^(-b N1))) / b; Shenton N_eq = N1 (F1/F2)^5: 1e-12."""
    n1, n2 = 2 * 10**5, 3 * 10**4
    for f1, f2 in ((70e3, 40e3), (40e3, 70e3)):
        for law, curve in ((Sato(**SATO), sato_curve), (Shenton(**SHENTON), shenton_curve)):
            s1 = curve(f1, n1)
            n_eq = optimize.brentq(lambda n: curve(f2, n) - s1, 0.0, 1e14, xtol=1e-6,
                                   rtol=1e-15)
            state, _ = law.advance(law.initial_state(1), [f1], n1)
            state, increment = law.advance(state, [f2], n2)
            assert increment[0] == pytest.approx(curve(f2, n_eq + n2) - s1, rel=1e-9)
        sato = Sato(a=3e-3, b=2e-5, c=0.0, reference_force=F0)
        state, _ = sato.advance(sato.initial_state(1), [f1], n1)
        state, _ = sato.advance(state, [f2], n2)
        n_eq = -math.log1p(-(f1 / f2) * -math.expm1(-2e-5 * n1)) / 2e-5 if f1 < f2 else math.inf
        expected = sato_curve(f2, n_eq + n2, c=0.0) if f1 < f2 else sato_curve(f1, n1, c=0.0)
        assert state.settlement[0] == pytest.approx(expected, rel=1e-12)
        shenton = Shenton(k1=4e-4, k2=0.0, reference_force=F0)
        state, _ = shenton.advance(shenton.initial_state(1), [f1], n1)
        state, _ = shenton.advance(state, [f2], n2)
        expected = 4e-4 * (f2 / F0) * (n1 * (f1 / f2) ** 5 + n2) ** 0.2
        assert state.settlement[0] == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("law, curve", [(Sato(**SATO, hardening="time"), sato_curve),
                                        (Shenton(**SHENTON, hardening="time"), shenton_curve)])
def test_time_hardening_continues_from_the_cycles_so_far(law, curve):
    """S = S(N1; F1) + S(N1 + N2; F2) - S(N1; F2): 1e-12."""
    n1, n2, f1, f2 = 10**5, 4 * 10**5, 65e3, 35e3
    state, _ = law.advance(law.initial_state(1), [f1], n1)
    state, _ = law.advance(state, [f2], n2)
    expected = curve(f1, n1) + curve(f2, n1 + n2) - curve(f2, n1)
    assert state.settlement[0] == pytest.approx(expected, rel=1e-12)


def test_a_curve_that_cannot_reach_the_settlement_adds_nothing():
    """Sato without a linear rate saturates at a(F): after a heavier load a lighter one whose
    curve stays below the settlement reached settles no more (N_eq infinite)."""
    law = Sato(a=3e-3, b=2e-5, c=0.0, reference_force=F0)
    state, _ = law.advance(law.initial_state(1), [90e3], 10**6)
    state, increment = law.advance(state, [30e3], 10**6)
    assert increment[0] == 0.0 and state.cycles[0] == 2 * 10**6


# ---- every law ------------------------------------------------------------------------------
LAWS = [Varandas(), Varandas(level_rtol=0.0), Sato(**SATO), Sato(**SATO, hardening="time"),
        Shenton(**SHENTON), Shenton(**SHENTON, hardening="time")]


@pytest.mark.parametrize("law", LAWS, ids=lambda law: f"{law.name}-{law.to_dict()}"[:40])
def test_each_sleeper_of_a_vectorised_call_is_its_own_run_bit_for_bit(law):
    """Seven sleepers with their own peaks (zeros among them) and cycles, over stages of one
    and of three kinds of cycle: every sleeper's settlement, increments and history equal the
    run of that sleeper alone, bit for bit."""
    rng = np.random.default_rng(1)
    n = 7
    stages = []
    for k in (1, 3, 1, 2, 3):
        force = rng.uniform(20e3, 90e3, (k, n)) * (rng.random((k, n)) > 0.15)
        force[:, 3] = force[:, 3].round(-3)  # repeated levels on one sleeper
        stages.append((force, rng.integers(0, 10**6, (k, n))))
    together = law.initial_state(n)
    increments = []
    for force, count in stages:
        together, increment = law.advance(together, force, count)
        increments.append(increment)
    for j in range(n):
        alone = law.initial_state(1)
        for (force, count), increment in zip(stages, increments):
            alone, own = law.advance(alone, force[:, j:j + 1], count[:, j:j + 1])
            assert own.tobytes() == increment[j:j + 1].tobytes()
        assert together.select(j).equals(alone), j


def test_a_long_history_sums_the_same_alone_and_in_a_batch():
    """Sleepers of 300 and of 150 distinct levels (a batch pads the shorter history with
    zeros): the pieces are summed in order, so each equals its own run bit for bit (numpy's
    pairwise sum would group the 300 and the 150 terms differently)."""
    rng = np.random.default_rng(2)
    law = Varandas(level_rtol=0.0)
    force = rng.uniform(30e3, 90e3, (300, 2))
    force[150:, 1] = 0.0
    count = rng.integers(1, 1000, (300, 2))
    together, _ = law.advance(law.initial_state(2), force, count)
    together, increment = law.advance(together, [95e3, 95e3], 10**4)
    for j in range(2):
        alone, _ = law.advance(law.initial_state(1), force[:, j:j + 1], count[:, j:j + 1])
        alone, own = law.advance(alone, [95e3], 10**4)
        assert own.tobytes() == increment[j:j + 1].tobytes()
        assert together.select(j).equals(alone)


@pytest.mark.parametrize("law", [Varandas(gamma=0.0), Sato(a=0.0, b=1e-4, c=0.0,
                                  reference_force=F0), Shenton(k1=0.0, k2=0.0,
                                                               reference_force=F0)])
def test_a_zero_law_never_settles(law):
    state, increment = law.advance(law.initial_state(3), [[50e3, 0.0, 120e3]], 10**6)
    state, increment = law.advance(state, [80e3, 10e3, 50e3], 10**5)
    assert np.all(state.settlement == 0.0) and np.all(increment == 0.0)
    assert state.cycles.tolist() == [1_100_000] * 3


@pytest.mark.parametrize("law", LAWS[::2], ids=lambda law: law.name)
def test_an_unloaded_sleeper_does_not_settle(law):
    state, increment = law.advance(law.initial_state(2), [0.0, 50e3], 10**6)
    assert increment[0] == 0.0 and increment[1] > 0.0
    assert state.cycles.tolist() == [10**6, 10**6]


@pytest.mark.parametrize("law", LAWS[::2], ids=lambda law: law.name)
def test_a_stored_state_resumes_bit_for_bit(law):
    """to_dict -> JSON -> from_dict gives the same state bit for bit, and advancing it gives
    what advancing the original gives; the law round-trips through its dict too."""
    state, _ = law.advance(law.initial_state(4), [[60e3, 0.0, 45e3, 80e3]], [12345])
    state, _ = law.advance(state, [30e3, 70e3, 45e3, 80e3], 999)
    restored = SettlementState.from_dict(json.loads(json.dumps(state.to_dict())))
    assert restored.equals(state)
    again = law_from_dict(json.loads(json.dumps(law.to_dict())))
    assert again == law
    a, da = law.advance(state, [50e3] * 4, 10**5)
    b, db = again.advance(restored, [50e3] * 4, 10**5)
    assert a.equals(b) and da.tobytes() == db.tobytes()


def test_states_are_immutable_and_advance_leaves_the_old_one_alone():
    law = Varandas()
    state, _ = law.advance(law.initial_state(2), [50e3, 60e3], 100)
    kept = SettlementState.from_dict(state.to_dict())
    law.advance(state, [90e3, 10e3], 10**6)
    assert state.equals(kept)
    with pytest.raises(ValueError):
        state.settlement[0] = 1.0
    with pytest.raises(ValueError):
        state.history["levels"][0, 0] = 1.0


def test_the_laws_are_trackwheel_settlement():
    import trackwheel.settlement as settlement

    assert tw.settlement is settlement
    assert settlement.Varandas is Varandas
    assert Varandas() == Varandas(alpha=0.6, beta=0.82, gamma=0.01, reference_cycles=10**6,
                                  reference_force=50e3)


# ---- bad input ------------------------------------------------------------------------------
@pytest.mark.parametrize("make, name", [
    (lambda: Varandas(alpha=-1.0), "alpha"),
    (lambda: Varandas(beta=-0.1), "beta"),
    (lambda: Varandas(beta=11.0), "beta"),
    (lambda: Varandas(gamma=-1e-3), "gamma"),
    (lambda: Varandas(gamma=10.0), "gamma"),  # 10 mm given as metres
    (lambda: Varandas(reference_cycles=0), "reference_cycles"),
    (lambda: Varandas(reference_force=0.0), "reference_force"),
    (lambda: Varandas(level_rtol=0.5), "level_rtol"),
    (lambda: Sato(a=-1e-3, b=1e-4, c=0.0, reference_force=F0), "a"),
    (lambda: Sato(a=1e-3, b=-1e-4, c=0.0, reference_force=F0), "b"),
    (lambda: Sato(a=1e-3, b=1e-4, c=-1e-9, reference_force=F0), "c"),
    (lambda: Sato(**SATO, hardening="plastic"), "hardening"),
    (lambda: Sato(**SATO, load_exponent=-1.0), "load_exponent"),
    (lambda: Shenton(k1=-1e-3, k2=0.0, reference_force=F0), "k1"),
    (lambda: Shenton(**SHENTON, exponent=1.0), "exponent"),
    (lambda: Shenton(k1=1e-3, k2=0.0, reference_force=-5.0), "reference_force"),
])
def test_bad_parameters_are_refused_by_name(make, name):
    with pytest.raises(ValueError, match=rf"^{name}\b.*(range|one of)"):
        make()


@pytest.mark.parametrize("force, cycles, match", [
    ([-1.0, 5e4], 1, r"peak_force = -1.0 is outside the allowed range \[0, inf\) N"),
    ([np.nan, 5e4], 1, r"peak_force = nan"),
    ([5e4, 5e4, 5e4], 1, r"peak_force must be .* shape \(2,\) or \(k, 2\)"),
    ([5e4, 5e4], -3, r"cycles = -3 is not a whole number in the allowed range \[0, "),
    ([5e4, 5e4], 2.5, r"cycles = 2.5 is not a whole number"),
    ([5e4, 5e4], MAX_CYCLES + 2, r"cycles = .* is not a whole number"),
    ([5e4, 5e4], [1, 2, 3], r"cycles has shape \(3,\)"),
])
def test_bad_inputs_to_advance_are_refused_by_name(force, cycles, match):
    law = Varandas()
    with pytest.raises(ValueError, match=match):
        law.advance(law.initial_state(2), force, cycles)


def test_a_state_is_refused_by_another_law_and_sleepers_are_counted():
    with pytest.raises(ValueError, match="state is a 'varandas' state; this law is 'sato'"):
        Sato(**SATO).advance(Varandas().initial_state(2), [5e4, 5e4], 1)
    with pytest.raises(TypeError, match="state must be a SettlementState"):
        Varandas().advance({"settlement": [0.0]}, [5e4], 1)
    with pytest.raises(ValueError, match=r"n_sleepers = 0 is outside the allowed range \[1, "):
        Varandas().initial_state(0)
    with pytest.raises(ValueError, match="law = 'hettler' is not one of"):
        law_from_dict({"law": "hettler"})
    law = Varandas()
    near_full, _ = law.advance(law.initial_state(1), [5e4], MAX_CYCLES - 1)
    with pytest.raises(ValueError, match="more than .* cycles"):
        law.advance(near_full, [5e4], 2)
