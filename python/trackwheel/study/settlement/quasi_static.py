"""The quasi-static stage of the settlement loop (``settle(..., stage_rule="quasi-static")``,
docs: Model § The settlement loop, "The quasi-static stage").

An explicit stage advances the law at the forces of the passage at its start. The feedback
from a void to the forces is stiff (a sleeper loaded above its history settles like fresh
ballast and sheds the excess to its neighbours within some ten cycles), so a long explicit
stage settles the newly loaded sleepers many times too much. The quasi-static stage keeps the
passage's *dynamic ratio* of each sleeper and axle fixed over the stage,

    r_ij = F_dyn,ij / F_st,ij(g_start),

and advances the law in sub-steps at F_ij(t) = r_ij F_st,ij(g(t)), F_st,ij(g) the peak static
ballast force of sleeper j under axle i of the item over the wheel positions of a passage on
the bed with the voids g (:class:`StaticBed`): the fast redistribution through the rail is
resolved inside the stage at the cost of statics, and only the dynamic ratio is frozen.

The statics: the rail an Euler-Bernoulli beam between its rigid end supports (cubic Hermite
elements from support to support: exact nodal displacements under point loads and the rail's
weight), each support a pad k_p on a sleeper of mass m_s on a ballast k_b with the void g_j,
which pushes only (closed while F_b > 0). A closed sleeper carries
F_b = k_pb (w_j - g_j) + m_s g k_b / (k_p + k_b), k_pb = k_p k_b / (k_p + k_b), w_j the rail's
deflection (down) at it; an open one hangs from the rail by its weight. Solved by an active set
per wheel position (the positions that share one are solved together, one banded Cholesky
factorisation each).
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import solveh_banded

from .passage import axle_peaks

#: wheel positions of the statics per sleeper bay [-]: the peak force's sampling error is
#: second order in the step and mostly cancels in the dynamic ratio
POSITIONS_PER_BAY = 4
#: active-set iterations before giving up [-]
MAX_ACTIVE_SET = 60


class StaticBed:
    """The track's statics for the quasi-static stage: each item's peak static ballast force
    per axle and settling sleeper on a bed of given voids (:meth:`peaks`)."""

    def __init__(self, scene, item_scenes, x_range, supports: np.ndarray,
                 sleepers: np.ndarray):
        if scene.window is not None:
            raise ValueError('stage_rule="quasi-static" needs a fixed rail (scene.window None)')
        values = scene.supports.values(supports) if hasattr(scene.supports, "values") else None
        n = supports.size
        sv = scene.supports

        def per(name):
            return (np.asarray(getattr(values, name), dtype=float) if values is not None
                    else np.full(n, float(getattr(sv, name))))

        kp, kb, ms = per("stiffness"), per("ballast_stiffness"), per("sleeper_mass")
        g = scene.gravity
        self.k = kp * kb / (kp + kb)  # (N,) closed sleeper's static stiffness [N/m]
        self.c = ms * g * kb / (kp + kb)  # (N,) closed sleeper's force at w = g_j [N]
        self.weight = ms * g  # (N,) [N]
        length = scene.rail.length
        self.nodes = np.concatenate([[0.0], supports, [length]])
        self.ei = scene.rail.bending_stiffness
        q = scene.rail.mass_per_length * g if scene.rail_gravity else 0.0
        self.n_dof = 2 * self.nodes.size
        self.band, self.dead = self._rail(q)
        self.support_dof = 2 * np.arange(1, n + 1)
        # the settling sleepers' support indices
        self.columns = np.argmin(np.abs(supports[None, :] - sleepers[:, None]), axis=1)
        self.sleepers = sleepers
        d = scene.supports.spacing
        self.items = []
        for s, (x0, x1) in zip(item_scenes, x_range):
            veh = s.active_vehicle
            offsets = np.asarray(veh.positions, dtype=float)
            loads = np.asarray(veh.static_loads(s.gravity), dtype=float)
            # the reference point over the passage, sleepers and the quarter points of each bay
            lo = max(x0, -offsets.min() + 1e-9)
            hi = min(x1, length - offsets.max() - 1e-9)
            step = d / POSITIONS_PER_BAY
            grid = np.arange(np.ceil(lo / step), np.floor(hi / step) + 1) * step
            refs = np.unique(np.concatenate([grid, (sleepers[:, None] - offsets[None, :]).ravel()]))
            refs = refs[(refs >= lo) & (refs <= hi)]
            self.items.append((refs, offsets, loads, self._loads(refs, offsets, loads)))
        self._closed = [None] * len(self.items)

    def _rail(self, q: float):
        """The rail's stiffness in upper band form (4, n_dof) with the end deflections fixed
        (identity rows) and its weight's consistent nodal loads (n_dof,)."""
        nd = self.n_dof
        band = np.zeros((4, nd))  # band[3 + i - j, j] = K[i, j], i <= j
        f = np.zeros(nd)
        for e, h in enumerate(np.diff(self.nodes)):
            ke = self.ei / h**3 * np.array([[12, 6 * h, -12, 6 * h],
                                            [6 * h, 4 * h * h, -6 * h, 2 * h * h],
                                            [-12, -6 * h, 12, -6 * h],
                                            [6 * h, 2 * h * h, -6 * h, 4 * h * h]])
            dofs = 2 * e + np.arange(4)
            for a in range(4):
                for b in range(a, 4):
                    band[3 + dofs[a] - dofs[b], dofs[b]] += ke[a, b]
            f[dofs] += q * np.array([h / 2, h * h / 12, h / 2, -h * h / 12])
        for dof in (0, nd - 2):  # rigid end supports: w = 0
            for off in range(1, 4):
                if dof + off < nd:
                    band[3 - off, dof + off] = 0.0
                if dof - off >= 0:
                    band[3 - off, dof] = 0.0
            band[3, dof] = 1.0
            f[dof] = 0.0
        return band, f

    def _loads(self, refs, offsets, loads) -> np.ndarray:
        """(n_dof, M) the wheels' consistent nodal loads at each reference position."""
        out = np.zeros((self.n_dof, refs.size))
        cols = np.arange(refs.size)
        for p, load in zip(offsets, loads):
            x = refs + p
            e = np.clip(np.searchsorted(self.nodes, x, side="right") - 1, 0, self.nodes.size - 2)
            h = self.nodes[e + 1] - self.nodes[e]
            xi = (x - self.nodes[e]) / h
            shape = (1 - 3 * xi**2 + 2 * xi**3, h * (xi - 2 * xi**2 + xi**3),
                     3 * xi**2 - 2 * xi**3, h * (-xi**2 + xi**3))
            for a, nval in enumerate(shape):
                np.add.at(out, (2 * e + a, cols), load * nval)
        out[[0, self.n_dof - 2], :] = 0.0
        return out

    def peaks(self, voids: np.ndarray) -> list[np.ndarray]:
        """Each item's (n_axles, n_sleepers) [N]: the largest static ballast force of each
        settling sleeper over the passage's wheel positions (several axles: while the axle is
        the one nearest the sleeper) on the bed with the voids (N,) [m]."""
        out = []
        for k, (refs, offsets, _, rhs) in enumerate(self.items):
            force, self._closed[k] = self._solve(voids, rhs, self._closed[k])
            out.append(axle_peaks(refs, offsets, self.sleepers, force[:, self.columns]))
        return out

    def _solve(self, voids, rhs, closed):
        """(M, N) ballast forces [N] and the closed sets (M, N) for the load columns rhs."""
        m, n = rhs.shape[1], self.k.size
        closed = np.ones((m, n), dtype=bool) if closed is None else closed.copy()
        force = np.zeros((m, n))
        todo = np.arange(m)
        for _ in range(MAX_ACTIVE_SET):
            if todo.size == 0:
                return force, closed
            patterns, inverse = np.unique(closed[todo], axis=0, return_inverse=True)
            left = []
            for p, pattern in enumerate(patterns):
                cols = todo[inverse.ravel() == p]
                band = self.band.copy()
                band[3, self.support_dof] += np.where(pattern, self.k, 0.0)
                base = self.dead.copy()
                base[self.support_dof] += self.weight - np.where(
                    pattern, self.c - self.k * voids, 0.0)
                w = solveh_banded(band, base[:, None] + rhs[:, cols])[self.support_dof]
                trial = self.k[:, None] * (w - voids[:, None]) + self.c[:, None]
                now = trial.T > 0.0
                force[cols] = np.where(now, trial.T, 0.0)
                changed = np.any(now != pattern[None, :], axis=1)
                closed[cols] = now
                left.append(cols[changed])
            todo = np.concatenate(left)
        raise ValueError("the quasi-static stage's statics found no equilibrium of the "
                         "unilateral ballast (active set not converged): a smaller increment")


def advance_stage(su, last, static_bed: StaticBed):
    """The quasi-static stage from the stage ``last`` (its law state and its passages'
    forces): (cycles at the stage's end, the law's state there, sub-steps taken).

    Each sub-step is the longest (bisection on the whole number of cycles, at least one
    passage) whose largest change of a settling sleeper's void is at most
    SUBSTEP_INCREMENT x w0 and keeps the stage's own change within ``increment`` x w0
    (adaptive; with ``stages`` the schedule's end instead); the stage ends where that limit
    or the schedule stops it. Each sub-step's forces are r F_st(g) on the bed it starts from.
    """
    from . import stages as sg

    w0 = su.static_deflection
    sub_limit = min(sg.SUBSTEP_INCREMENT, su.increment) * w0
    if su.stages is not None:
        k = last.index + 1
        end = su.cycles if k >= su.stages else int(round(su.cycles ** (k / su.stages)))
        end, stage_limit = min(su.cycles, max(end, last.cycles + 1)), np.inf
    else:
        end, stage_limit = su.cycles, su.increment * w0
    state, done = last.state, last.cycles
    passages = np.asarray(last.passages, dtype=np.int64)
    start_zone, start_all = sg.bed(su, state.settlement)
    static0 = static_bed.peaks(start_all)
    dynamic = [f.peaks for f in last.forces]
    static, zone = static0, start_zone
    substeps = 0
    while done < end:
        # the dynamic ratio F_dyn / F_st(g_start) times the statics now; exactly the passage's
        # peaks where the statics have not changed (ratio 1.0)
        rows = np.concatenate([np.where(s0 > 0.0, d * (s / np.where(s0 > 0.0, s0, 1.0)), d)
                               for d, s, s0 in zip(dynamic, static, static0)], axis=0)

        def change(total, rows=rows, zone=zone, state=state, passages=passages):
            dp = su.traffic.passages(su.scene, total) - passages
            counts = np.concatenate([np.full(f.peaks.shape[0], c, dtype=np.int64)
                                     for f, c in zip(last.forces, dp)])
            after = sg.bed(su, su.law.advance(state, rows, counts)[0].settlement)[0]
            return (float(np.max(np.abs(after - zone))),
                    float(np.max(np.abs(after - start_zone))))

        def fits(total):
            a, b = change(total)
            return a <= sub_limit and b <= stage_limit

        stage_bound = False
        if fits(end):
            lo = end
        else:
            lo, hi = done, end
            while hi - lo > 1:
                mid = (lo + hi) // 2
                if fits(mid):
                    lo = mid
                else:
                    hi = mid
            if np.all(su.traffic.passages(su.scene, lo) == passages):
                lo = hi  # even the first passage changes the voids by more than the limit
            stage_bound = change(hi)[1] > stage_limit
        dp = su.traffic.passages(su.scene, lo) - passages
        counts = np.concatenate([np.full(f.peaks.shape[0], c, dtype=np.int64)
                                 for f, c in zip(last.forces, dp)])
        state, _ = su.law.advance(state, rows, counts)
        passages, done = passages + dp, lo
        substeps += 1
        if done >= end or stage_bound:
            break
        zone, voids_all = sg.bed(su, state.settlement)
        static = static_bed.peaks(voids_all)
    return done, state, substeps
