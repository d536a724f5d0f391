"""The engine that knows no scene: ``Model`` (nodes, DOFs, groups, constraints, loads), ``System`` (the
assembled equations), the CSR assembly and the linear solvers, quadrature rules and shape functions, meshes,
the ``Result`` of an analysis, input validation, and the element-group protocol every group follows
(``protocol``: the array layout and the tangent flags)."""

from .model import Model, System
from .solution import Result

__all__ = ["Model", "Result", "System"]
