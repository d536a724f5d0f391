"""Uniaxial laws of the plate strip's layers (axial stress sig from axial strain eps, shear stress tau
from shear strain gam), at one integration point of one layer.

Law kinds (``kind``) and their parameter vectors ``params`` (length <= N_LAYER_PARAMS):

* ``ELASTIC`` (0): [E, nu]; sig = E/(1-nu^2) eps (cylindrical bending), tau = E/(2(1+nu)) gam.
* ``CONCRETE`` (1): [E0, nu, fc, eps_c, eps_cu, fr, Gf, ls, alpha_ts, eps_y, beta0, beta_floor] --
  eq. (5.1) in compression with irreversible strain (5.3), crack-band softening (5.4), tension
  stiffening and cracked shear retention (Figs. 5-6). Uniaxial unless its plane-strain flag (index 13) is set.
  See ``concrete``.
* ``STEEL`` (2): [Es, 0, fy, EH] -- bilinear with hardening EH, unloading Es, no shear. See ``steel``.

Build the vectors with ``ssi.materials.rc.concrete_params`` / ``steel_params`` (they validate).
For every kind params[0] is the initial (K0) modulus.

The plate element applies the shear correction factor kappa to tau; laws return the unfactored tau.

Crack band width (for the plate element): ``params[P_LS]`` (index 7 of a CONCRETE vector) is the width ls
of eq. (5.4). The element size entering eq. (5.4) should be the length the integration point
represents, ``crack_band_width(L_e, w_i) = w_i L_e / 2`` for Gauss weight w_i on [-1, 1] of an element
of length L_e, so that a point that cracks through dissipates exactly Gf per unit crack area.
A model builder sets it per element and point (the params array may be per point); if a single ls is
given for all elements the law is a plain (mesh-dependent) strain-softening law.

Numba cache: ``cache=True`` alone keys a kernel's cache on its *own* file, but ``layer_update`` and the plate
kernels inline ``concrete_update`` / ``steel_update``. ``import ssi`` therefore points ``NUMBA_CACHE_DIR`` at
a folder keyed on a hash of all package sources (``ssi/__init__.py``): any edit recompiles, nothing stale
runs.

History: N_LAYER_HIST = 4 floats per layer point (concrete uses 2: max compressive strain, max crack
strain; steel uses 1: plastic strain). Unused entries are copied through.
"""

from numba import njit

from .concrete import (
    H_EMAX,
    H_XMAX,
    N_CONCRETE_CONSTANTS,
    N_CONCRETE_PARAMS,
    P_LS,
    concrete_constants,
    concrete_update_with,
)
from .steel import H_EPS_P, steel_update

ELASTIC = 0
CONCRETE = 1
STEEL = 2
N_LAYER_HIST = 4  # history variables per layer point (laws may use fewer)
# the history slots by name, each named by the law that writes it (a slot's meaning depends on the layer's
# law: slot 0 is concrete's x_max and steel's eps_p)
LAYER_HIST_FIELDS = {"x_max": H_XMAX, "e_max": H_EMAX, "eps_p": H_EPS_P}
N_LAYER_PARAMS = N_CONCRETE_PARAMS  # longest parameter vector of any kind
N_LAYER_CONSTANTS = N_CONCRETE_CONSTANTS  # a layer's precomputed constants (only concrete has any)
_NO_CONSTANTS = (0.0,) * N_LAYER_CONSTANTS

__all__ = [
    "CONCRETE",
    "ELASTIC",
    "N_LAYER_CONSTANTS",
    "LAYER_HIST_FIELDS",
    "N_LAYER_HIST",
    "N_LAYER_PARAMS",
    "P_LS",
    "STEEL",
    "crack_band_width",
    "layer_constants",
    "layer_update",
    "layer_update_with",
]


@njit(cache=True)
def crack_band_width(element_length: float, weight: float) -> float:
    """Length represented by a Gauss point of weight ``weight`` (on [-1, 1]) in an element of length
    ``element_length``: the crack band width ls of eq. (5.4) for that point. A numba kernel, callable from
    Python as well (the plate strip's kernels and its snap-back check both use it)."""
    return 0.5 * weight * element_length


@njit(cache=True)
def layer_update(kind, params, eps, gam, hist_old, hist_new, tangent):
    """Return ``(sig, tau, e_t, g_t)``: stresses and the tangent (``tangent`` CONSISTENT) or initial
    (K0_MATRIX) moduli d sig/d eps and d tau/d gam. Writes ``hist_new`` (N_LAYER_HIST,)."""
    const = concrete_constants(params) if kind == CONCRETE else _NO_CONSTANTS
    return layer_update_with(kind, params, const, eps, gam, hist_old, hist_new, tangent)


@njit(cache=True)
def layer_constants(kind, params, out):
    """Write the law's constants (functions of ``params`` alone) to ``out`` (N_LAYER_CONSTANTS,), for
    :func:`layer_update_with`: a kernel that updates one layer at many points computes them once."""
    if kind == CONCRETE:
        const = concrete_constants(params)
        for i in range(N_LAYER_CONSTANTS):
            out[i] = const[i]


@njit(cache=True)
def layer_update_with(kind, params, const, eps, gam, hist_old, hist_new, tangent):
    """:func:`layer_update` with the law's constants ``const`` (from :func:`layer_constants`) given."""
    for i in range(hist_old.size):  # a loop, not hist_new[:] = hist_old: numba compiles an array-to-slice
        hist_new[i] = hist_old[i]  # copy with its shape-checking error path, seconds per signature
    if kind == CONCRETE:
        return concrete_update_with(const, params, eps, gam, hist_old, hist_new, tangent)
    if kind == STEEL:
        return steel_update(params, eps, gam, hist_old, hist_new, tangent)
    E, nu = params[0], params[1]
    e1 = E / (1.0 - nu * nu)
    g = 0.5 * E / (1.0 + nu)
    return e1 * eps, g * gam, e1, g
