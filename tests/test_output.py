"""The output table (cpp/output.cpp): one definition drives the recording, the binding's dict,
``_core.OUTPUT_FIELDS`` and :class:`trackwheel.Result`."""

from __future__ import annotations

import dataclasses as dc

import numpy as np

import trackwheel as tw
from trackwheel import _core


def test_result_exposes_exactly_the_table_fields_with_units_in_its_doc():
    table = _core.OUTPUT_FIELDS
    names = [f[0] for f in table]
    assert len(set(names)) == len(names)
    result_arrays = [f.name for f in dc.fields(tw.Result)
                     if f.name not in {"scene", "settings", "steps", "newton_iterations",
                                       "state_changes", "stability_limit", "wall_time",
                                       "final_state", "body_z", "body_phi", "support_envelope",
                                       "ballast_events", "ballast_contact_time"}]
    assert result_arrays == names + [f[0] for f in _core.SUPPORT_FIELDS]
    doc = tw.Result.__doc__
    for name, unit, text, _per_wheel, dtype in table:
        kind = "int" if dtype == "int32" else f"[{unit}]"
        assert f"``{name}`` {kind}: {text}" in doc, name


def test_binding_returns_every_field_with_its_shape_and_dtype():
    """Per-wheel fields come as (n_samples, n_wheels), the others as (n_samples,)."""
    r = tw.simulate(tw.Scene.kato2005(), tw.kmh(100), x_end=0.3, dt=1e-5, n_elements=20,
                    energy=True, progress=False)
    n = len(r.t)
    for name, _unit, _doc, _per_wheel, dtype in _core.OUTPUT_FIELDS:
        a = getattr(r, name)
        assert a.shape == (n,) and a.dtype == np.dtype(dtype), name
    assert n == r.steps + 1  # every step kept (output_every = 1) plus t = 0


def test_energy_is_recorded_only_on_request():
    r = tw.simulate(tw.Scene.kato2005(), tw.kmh(100), x_end=0.3, dt=1e-5, n_elements=20,
                    progress=False)
    assert r.energy is None
