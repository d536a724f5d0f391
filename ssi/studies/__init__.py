"""Studies over many scenes: parameter sweeps on a dask cluster (``sweep``). They solve scenes; no scene calls
them. (A scene's error estimate is a property of its answer and lives with it: :mod:`ssi.scene.estimate`.)"""
