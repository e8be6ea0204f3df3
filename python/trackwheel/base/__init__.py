"""The bottom layer: limits, units, argument checks and the package's exceptions.

Nothing here knows the physics or the compiled kernel, so every layer above (excitation, scene,
run, study and the faces) may use it, and a Scene can be built without importing ``_core``.
"""
