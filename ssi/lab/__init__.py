"""Verification and research tools: closed-form references (``analytical``, ``analytical_soil``,
``bearing_capacity``), the scenes of the chapters (``examples``, ``zoo``, ``rc_beam``), finite-difference and
convergence checks (``verify``, ``element_test``), digitised reference data (``digitize``), the property-based
input study (``fuzz``), and the chapters' report rows and figure folders (``report``, ``paths``).

Nothing in the rest of ``ssi`` imports this package (a test reads the imports to keep it so), and its files
are outside the numba cache key. Some modules need the ``test`` extra (``fuzz``: hypothesis) or a checkout of
the repository (``paths``, ``report``, ``digitize``: its ``figures/`` and ``reference_data/`` folders).
"""
