"""A :class:`~ssi.scene.site.Site` built into a model (``BuiltSite``): the soil group with its materials and
initial stress, the strips (plate and interface, or a rigid base), the supports and the loads."""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np

from ..core.geometry import GeometryError
from ..core.model import Model
from ..core.quadrature import gauss_2d
from ..elements.interface import add_interface
from ..elements.plate import PlateStrip
from ..elements.side_interface import add_side_interface
from ..elements.soil_q8 import SoilQ8, q8_points
from ..elements.soil_q8_points import SoilQ8Points
from ..materials.soil_laws import SoilLayer, geostatic_stress, material_table
from .site_parts import DepthVarying, RigidStrip, Strip
from .site_view import SiteResult, pushed_nodes

if TYPE_CHECKING:  # for annotations only: the site module imports this one
    from .site import Site

__all__ = ["BuiltSite"]


@dataclass
class BuiltSite:
    """A site built into a model: ``mesh`` (SoilMesh or UnstructuredMesh), ``soil`` group, per strip a dict
    (``plate``, ``interface``, ``plate_nodes`` model ids ordered by x, ``soil_nodes``; of a RigidStrip:
    ``rigid``, ``soil_nodes``, ``width``, ``body`` the side contact's rigid body node or None),
    ``element_layer`` (n_el,) layer index, ``initial_stress_method`` "K0", "gravity" or "none" (weightless
    soil), ``mesher`` "structured" or "gmsh", ``quality`` of the mesh
    (:func:`ssi.core.gmsh_mesh.check_quality`)."""

    site: Site
    model: Model
    mesh: object
    soil: SoilQ8
    strips: list
    element_layer: np.ndarray
    initial_stress_method: str
    mesher: str
    quality: dict

    @classmethod
    def assemble(cls, site: Site, mesh, method: str, mesher: str, quality: dict) -> BuiltSite:
        model = Model()
        model.info["site"] = site
        ids = model.add_nodes(mesh.xy, ndof=2)
        centre = mesh.xy[mesh.conn].mean(axis=1)
        coords = mesh.xy[mesh.conn]
        kinds, params, mat, weights = _materials(site, mesh, centre, _gauss_points(coords, site.mesh.n_gauss))
        soil = _soil_group(
            coords, model.element_dofs(ids[mesh.conn]), mat, kinds, params, site.mesh.n_gauss,
            weights if weights.any() else None,
        )  # fmt: skip
        model.add_group(soil)
        _fix_sides(model, mesh.xy, site)
        built = cls(site, model, mesh, soil, [], np.asarray(mesh.el_layer, np.int64), method, mesher, quality)
        if weights.any():
            soil.initial_stress = built._initial_stress()
        else:  # weightless soil: no initial stress, whatever the method asked for
            built.initial_stress_method = "none"
        for s in site.strips:
            built._add_strip(s)
            if s.side_contact is not None:
                built._add_side_contact(len(built.strips) - 1)
        built._add_loads()
        return built

    def ground_nodes(self, x0: float, x1: float, z: float | None = None, chain: bool = True) -> np.ndarray:
        """Soil node ids on the ground between x0 and x1 [m], ordered by x; at elevation ``z`` [m] if given
        (an embedded strip's trench bottom). ``chain``: they must form a chain of element edges (refused
        otherwise); False: any such nodes (the ground on both sides of a trench)."""
        xy = self.mesh.xy
        scale = max(1.0, self.site.width)
        z_on = self.site.ground_z(xy[:, 0]) if z is None else z
        on = np.abs(xy[:, 1] - z_on) < 1e-7 * scale
        on &= (xy[:, 0] >= x0 - 1e-9 * scale) & (xy[:, 0] <= x1 + 1e-9 * scale)
        ids = np.flatnonzero(on)
        ids = ids[np.argsort(xy[ids, 0])]
        if chain and (len(ids) < 3 or len(ids) % 2 == 0):
            raise GeometryError(
                f"the range ({x0:g}, {x1:g}) m does not start and end on element edges of the ground"
            )
        return ids

    def _initial_stress(self) -> np.ndarray:
        """(n_el, n_ip, 4) initial effective stress [Pa] by the method of the build."""
        site, soil = self.site, self.soil
        if self.initial_stress_method == "K0":
            layers = [lay.layer if isinstance(lay, DepthVarying) else lay for lay in site.layers]
            layers = [replace(lay, thickness=t) for lay, t in zip(layers, site.layer_thicknesses())]
            wt = -float(site.water_z(0.0)) if site.has_water else None
            return geostatic_stress(
                soil.integration_points()[..., 1], layers, water_table=wt, gamma_w=site.gamma_w
            )
        # gravity loading: the weight on the soil alone, elastic (every law's E and nu), one linear solve; or
        # with the soil's own laws, the weight ramped up as the reference load of an incremental solve
        plastic = self.initial_stress_method == "gravity_plastic"
        model = Model()
        ids = model.add_nodes(self.mesh.xy, ndof=2)
        if plastic:
            kinds, params = soil.kinds, soil.params
        else:
            elastic = []
            for k in range(len(soil.kinds)):
                e, nu = soil.params[k, 0], soil.params[k, 1]
                elastic.append(SoilLayer(1.0, E=e, nu=nu).law())
            kinds, params = material_table(elastic)
        mat = np.column_stack(soil.point_mat) if isinstance(soil, SoilQ8Points) else soil.el_mat
        g = _soil_group(
            soil.coords, model.element_dofs(ids[self.mesh.conn]), mat, kinds, params, site.mesh.n_gauss,
            soil.unit_weight,
        )  # fmt: skip
        model.add_group(g)
        _fix_sides(model, self.mesh.xy, site)
        if plastic:
            from ..solver import NonConvergence
            from .stages import _run_phase

            weight = model.load_vectors()[1]
            g.unit_weight = None  # the weight becomes the reference load, ramped from zero
            try:
                res = _run_phase(model, [1.0], None, loads=(weight, np.zeros(model.n_dof)))
            except NonConvergence as err:  # the soil cannot carry its own weight: the input's fault, named
                raise ValueError(
                    f'Site.initial_stress = "gravity_plastic": the soil does not carry its own weight under '
                    f"its own laws (the gravity phase stopped at {err.result.load_factor[-1]:.3g} of the "
                    f"weight: {err.report.get('reason')}); a slope steeper than its soil's friction angle "
                    "(without cohesion) cannot stand -- flatten it or give the soil a cohesion c > 0"
                ) from err
        else:
            res = model.solve_linear()
        self.gravity_displacement = res.u[-1]
        return np.ascontiguousarray(g.stress(res.states[-1][0]))

    def _add_strip(self, s: Strip | RigidStrip):
        if isinstance(s, RigidStrip):
            z_base = self.site.base_z(len(self.strips))
            nodes = self.ground_nodes(s.x0, s.x1, None if s.level is None else z_base)
            if s.rough:
                self.model.fix(nodes, "u")
            self.model.prescribe(nodes, "w", -s.settle)
            body = None
            if s.side_contact is not None:
                # the structure side of the wall interfaces: one rigid body (u, w, alpha) at the base's
                # middle, settling with the base, not rotating, held sideways (a Push prescribes its u)
                body = int(self.model.add_nodes(np.array([[0.5 * (s.x0 + s.x1), z_base]]), ndof=3)[0])
                self.model.prescribe([body], "w", -s.settle)
                self.model.fix([body], "u")
                self.model.fix([body], "alpha")
            self.strips.append({"rigid": True, "soil_nodes": nodes, "width": s.x1 - s.x0, "body": body})
            return
        f, model = s.foundation, self.model
        z_base = self.site.base_z(len(self.strips))
        soil_nodes = self.ground_nodes(f.x0, f.x1, z_base)
        xs = self.mesh.xy[soil_nodes, 0]
        if abs(xs[0] - f.x0) > 1e-9 * self.site.width or abs(xs[-1] - f.x1) > 1e-9 * self.site.width:
            raise GeometryError(f"the strip ({f.x0:g}, {f.x1:g}) m ends are not mesh nodes of the ground")
        local = np.arange(0, len(soil_nodes) - 2, 2)
        plate_conn = np.column_stack([local, local + 1, local + 2])
        plate_xy = np.column_stack([xs, np.full(len(xs), z_base - f.section.z_bottom)])
        ids = model.add_nodes(plate_xy, ndof=3)
        plate = PlateStrip(
            plate_xy[plate_conn], model.element_dofs(ids[plate_conn]), f.strip_section(), **f.strip_options()
        )
        model.add_group(plate)
        iface = add_interface(
            model, ids[plate_conn], soil_nodes[plate_conn], np.tile(s.contact.params(), (len(plate_conn), 1)),
            offset=plate.bottom_offset, rule=s.contact.rule,
        )  # fmt: skip
        held = None
        if s.contact.kt == 0.0:
            held = int(ids[np.argmin(np.abs(xs - 0.5 * (f.x0 + f.x1)))])
            model.fix([held], "u")
        self.strips.append(
            {
                "plate": plate,
                "interface": iface,
                "plate_nodes": ids,
                "soil_nodes": soil_nodes,
                "slide_support": held,
            }
        )

    def _add_side_contact(self, i: int):
        """Interfaces between the trench walls of the embedded strip ``i`` and its vertical sides
        (:func:`ssi.elements.side_interface.add_side_interface`), each side moving rigidly with the strip's
        end node (a RigidStrip: its one rigid body node, both walls). They start without traction: the
        initial stress is that of gravity loading with the trench open, so the walls are free faces (the
        strip cast against them presses on them only as it moves)."""
        s, st, site = self.site.strips[i], self.strips[i], self.site
        xy = self.mesh.xy
        z_base, scale = site.base_z(i), max(1.0, site.width)
        if st.get("rigid"):
            x0, x1, left, right = s.x0, s.x1, st["body"], st["body"]
        else:
            ids = st["plate_nodes"]
            x0, x1, left, right = s.foundation.x0, s.foundation.x1, ids[0], ids[-1]
        groups = []
        for x_wall, body, down in ((x0, left, True), (x1, right, False)):
            top = float(site.ground_z(x_wall))
            on = np.flatnonzero(
                (np.abs(xy[:, 0] - x_wall) < 1e-9 * scale)
                & (xy[:, 1] >= z_base - 1e-9 * scale)
                & (xy[:, 1] <= top + 1e-9 * scale)
            )
            # the structure on the left walking from node 0 to 2: down the left wall, up the right one
            nodes = on[np.argsort(-xy[on, 1] if down else xy[on, 1])]
            if len(nodes) < 3 or len(nodes) % 2 == 0:
                raise GeometryError(
                    f"strips[{i}]: the trench wall at x={x_wall:g} m is not a chain of element edges "
                    f"({len(nodes)} nodes from z={z_base:g} to {top:g} m)"
                )
            conn = np.column_stack([nodes[0:-2:2], nodes[1:-1:2], nodes[2::2]])
            groups.append(
                add_side_interface(
                    self.model,
                    body,
                    conn,
                    s.side_contact.params(),
                    rule=s.side_contact.rule,
                    name=f"side_interface_{i}_{'left' if down else 'right'}",
                )  # fmt: skip
            )
        st["side_interfaces"] = groups

    def _add_loads(self):
        """Every load through its own ``effect(self)`` (:mod:`ssi.scene.loads`), as a scene's: its reference
        force vector and the DOFs it prescribes."""
        for ld in self.site.loads:
            f_vec, held = ld.effect(self)
            nz = np.flatnonzero(f_vec)
            if nz.size:
                self.model.add_element_load(nz[None], f_vec[nz][None])
            self.model.prescribe_dofs(np.array(list(held), np.int64), list(held.values()))

    # ---- what a load's effect asks of a built model (as BuiltScene answers it) ---------------------------
    def plate_node_at(self, x: float) -> int:
        """Model id of the plate node at ``x`` [m] of the strip under it (a GeometryError if none is
        there)."""
        ids = self.strips[self.site._strip_at(x)]["plate_nodes"]
        i = int(np.argmin(np.abs(self.model.coords[ids, 0] - x)))
        if abs(self.model.coords[ids[i], 0] - x) > 1e-6:
            raise GeometryError(f"ColumnLoad at x={x:g} m is not a node of its strip")
        return int(ids[i])

    def slides_freely_at(self, x: float) -> bool:
        """True if the plate strip under ``x`` [m] has no shear stiffness (Contact.kt = 0: its middle node's u
        held)."""
        return self.strips[self.site._strip_at(x)]["slide_support"] is not None

    def foundation_spans(self) -> list[tuple[float, float]]:
        """(x0, x1) [m] of every strip: a ground pressure must stay clear of them."""
        return [s.ends for s in self.site.strips]

    def ground_weights(self, x0: float, x1: float) -> tuple[np.ndarray, np.ndarray]:
        """(ground node ids from ``x0`` to ``x1`` [m], their share [m] of the loaded length): L/6, 4L/6, L/6
        of each quadratic edge of length L (a vertical pressure per horizontal metre of ground)."""
        nodes = self.ground_nodes(x0, x1)
        xs = self.mesh.xy[nodes, 0]
        w = np.zeros(len(nodes))
        for i in range(0, len(nodes) - 2, 2):
            w[i : i + 3] += np.array([1.0, 4.0, 1.0]) * (xs[i + 2] - xs[i]) / 6.0
        return nodes, w

    def push_held(self, push) -> dict[int, float]:
        """{dof: prescribed increment [m]} of a :class:`~ssi.scene.loads.Push` (its ``effect``): the pushed
        strip's nodes' u (a plate's rotations held; a RigidStrip's base and side body)."""
        st = self.strips[self.site.pushed_strip(push)]
        nodes, model = pushed_nodes(st), self.model
        held = {int(d): float(push.u) for d in model.dof(nodes, "u")}
        if not st.get("rigid"):
            if st["slide_support"] is not None:
                raise GeometryError(
                    f"{push!r} on a frictionless contact (Contact.kt = 0): nothing but the held middle "
                    "node resists the push; give Contact.kt > 0"
                )
            held.update({int(d): 0.0 for d in model.dof(nodes, "alpha")})
        return held

    @property
    def is_linear(self) -> bool:
        layers = [lay.layer if isinstance(lay, DepthVarying) else lay for lay in self.site.soils()]
        return all(lay.c is None for lay in layers) and all(
            (s.side_contact is None or s.side_contact.phi_deg is None)
            and (
                isinstance(s, RigidStrip)
                or (s.contact.phi_deg is None and bool(np.all(st["plate"].section.kind == 0)))
            )
            for s, st in zip(self.site.strips, self.strips)
        )

    @property
    def scene(self) -> Site:
        """The site (the name a BuiltScene gives its input: the error estimate refines either)."""
        return self.site

    def result_view(self, solver_result) -> SiteResult:
        """The view of a solver result of this site (a NonConvergence's converged steps, a stored result)."""
        return SiteResult(self, solver_result)

    def solve(self, n_steps: int | None = None, settings=None, load_factors=None) -> SiteResult:
        """Apply the loads to load factor 1 from the initial stress: one linear solve for a linear site, else
        the solver's automatic increments (``n_steps``, ``settings`` as for a scene; ``load_factors``: the
        levels themselves, e.g. a graded push of a RigidStrip). With ``site.phases``: the geostatic phase,
        then ``site.loads`` (if any, as a phase named "loads") and each phase in turn
        (:func:`ssi.scene.stages.solve_site_phases`); ``out.phases`` lists them."""
        from ..solver import Settings
        from .stages import _load_levels, _run_phase, solve_site_phases

        if self.site.phases:
            if load_factors is not None:
                raise ValueError(
                    f"load_factors={load_factors!r}: a phased site steps each phase by its own n_steps"
                )
            return solve_site_phases(self, n_steps, settings)
        if self.is_linear and load_factors is None:
            return SiteResult(self, self.model.solve_linear(backend=(settings or Settings()).backend))
        levels = _load_levels(n_steps) if load_factors is None else np.asarray(load_factors, np.float64)
        return SiteResult(self, _run_phase(self.model, levels, settings))


def _gauss_points(coords, n_gauss):
    """(n_el, n_ip, 2) coordinates [m] of the soil elements' Gauss points (the group's order)."""
    gp, _ = gauss_2d(n_gauss)
    out = np.empty((len(coords), len(gp), 2))
    q8_points(np.ascontiguousarray(coords, np.float64), gp, out)
    return out


def _soil_group(coords, edofs, mat, kinds, params, n_gauss, unit_weight):
    """The soil group: element-wise (``mat`` (n_el,)) or with a material row per Gauss point (``mat``
    (n_el, n_ip))."""
    cls = SoilQ8Points if np.ndim(mat) == 2 else SoilQ8
    return cls(coords, edofs, mat, kinds, params, n_gauss=n_gauss, unit_weight=unit_weight)


def _materials(site: Site, mesh, centre, points):
    """(kinds, params, material index, unit weights) of the soil: one row per layer, or, in a layer whose
    properties vary with depth, one per Gauss point (``points`` (n_el, n_ip, 2); site.depth_varying
    "gauss": the index is (n_el, n_ip)) or per element (evaluated at its ``centre``; "centroid")."""
    rows, el_mat, weights = [], np.zeros(len(mesh.conn), np.int64), []
    per_point = site.depth_varying == "gauss" and any(isinstance(lay, DepthVarying) for lay in site.soils())
    point_mat = np.zeros(points.shape[:2], np.int64)
    layer_of = np.asarray(mesh.el_layer, np.int64)
    wet = centre[:, 1] < site.water_z(centre[:, 0])
    for k, lay in enumerate(site.soils()):  # the layers, then the lenses (region n_layers + j)
        base = lay.layer if isinstance(lay, DepthVarying) else lay
        sat = base.unit_weight if base.unit_weight_sat is None else base.unit_weight_sat
        for is_wet in (False, True):
            els = np.flatnonzero((layer_of == k) & (wet == is_wet))
            if not len(els):
                continue
            gamma = max(sat - site.gamma_w, 0.0) if is_wet else base.unit_weight
            if isinstance(lay, DepthVarying) and per_point:
                p = points[els]
                z_ref = site.ground_z(p[..., 0]) if lay.z_ref is None else np.full(p.shape[:2], lay.z_ref)
                for e, depths in zip(els, z_ref - p[..., 1]):
                    for q, d in enumerate(depths):
                        point_mat[e, q] = len(rows)
                        rows.append(lay.at(d).law())
                        weights.append(gamma)
            elif isinstance(lay, DepthVarying):
                z_ref = site.ground_z(centre[els, 0]) if lay.z_ref is None else np.full(len(els), lay.z_ref)
                for e, d in zip(els, z_ref - centre[els, 1]):
                    el_mat[e] = len(rows)
                    rows.append(lay.at(d).law())
                    weights.append(gamma)
            else:
                el_mat[els] = len(rows)
                point_mat[els] = len(rows)
                rows.append(base.law())
                weights.append(gamma)
    kinds, params = material_table(rows)
    return kinds, params, (point_mat if per_point else el_mat), np.array(weights)


def _fix_sides(model, xy, site):
    """Bottom fixed (u, w), sides on vertical rollers (u)."""
    tol = 1e-9 * max(1.0, site.width)
    bottom = np.flatnonzero(np.abs(xy[:, 1] - site.z_bottom) < tol)
    sides = np.flatnonzero((np.abs(xy[:, 0] - site.x_left) < tol) | (np.abs(xy[:, 0] - site.x_right) < tol))
    model.fix(bottom, "u")
    model.fix(bottom, "w")
    model.fix(sides, "u")
