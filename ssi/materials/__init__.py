"""Constitutive laws as pure numba point kernels: (strain or slip, committed history, parameters) in,
(stress, tangent, new history) out. They never mutate the committed history."""
