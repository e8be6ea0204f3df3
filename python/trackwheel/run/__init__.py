"""Running the kernel: a scene in, results out (docs: Model § Equations of motion, § Outputs,
§ Eigen analysis, § Receptance and decay rate).

Layer 3: it knows the base layer, the excitation and the scene, and is the only layer that
calls the compiled kernel (``trackwheel._core``).

- :mod:`.kernel` -- the scene as the kernel's parameter structs (rail model, wheels, contact,
  vehicle) and the vehicle matrices read back; :mod:`.profile` -- the rail profile and the
  wheel's out-of-roundness as the kernel's spline tables (streamed over long runs);
- :mod:`.defaults` -- every rule that derives a setting from a scene: the mesh of a call, the
  derived mesh and time step, the frequency-domain mesh, the start and end, stability limits;
- :mod:`.plan`, :mod:`.passage`, :mod:`.start`, :mod:`.simulate` -- a time simulation:
  arguments resolved into a plan, where it starts and ends, its start state, the kernel call;
- :mod:`.results` -- what the kernel returns, as tables: the output fields, the run settings,
  the static fields;
- :mod:`.statics`, :mod:`.eigen`, :mod:`.frequency` -- static equilibrium and the quasi-static
  line, natural frequencies and modes, receptance and decay rate.
"""
