"""Former home of the element-group protocol, now :mod:`ssi.core.protocol` (kept so that old imports work).

The tangent flags were renamed there so that they cannot be mistaken for law kinds: ``ELASTIC`` (flag 0)
is ``K0_MATRIX`` and ``NO_MATRIX`` (flag -1) is ``FORCES_ONLY``. Nothing in the tree imports this module;
new code imports :mod:`ssi.core.protocol`.
"""

from ..core.protocol import CONSISTENT, FORCES_ONLY, K0_MATRIX, TANGENT_FLAGS, ElementGroup

ELASTIC = K0_MATRIX  # deprecated alias of the tangent flag K0_MATRIX
NO_MATRIX = FORCES_ONLY  # deprecated alias of the tangent flag FORCES_ONLY

__all__ = ["CONSISTENT", "ELASTIC", "FORCES_ONLY", "K0_MATRIX", "NO_MATRIX", "TANGENT_FLAGS", "ElementGroup"]
