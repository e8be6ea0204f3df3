# The one place the version is written: pyproject.toml reads it (scikit-build-core's regex
# metadata provider), the package and the sweep store's records use it.
__version__ = "0.1.0"
