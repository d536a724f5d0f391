"""How a :class:`~ssi.scene.scene.Scene` adds its parts to the model it builds: the dead loads holding the
geostatic state, the plate strip on its contact interface, an embedded strip's side contact and a rigid
footing's base (a mixin the Scene inherits; ``Scene.build`` calls them in turn)."""

import math

import numpy as np

from ..core.assembly import scatter_vector
from ..core.mesh import foundation_contact, surface_pressure_forces
from ..core.protocol import K0_MATRIX
from ..core.shapes import lagrange3
from ..elements.interface import add_interface
from ..elements.plate import PlateStrip
from ..elements.side_interface import add_side_interface
from .checks import (
    _segment_at,
    _segments,
)


class SceneParts:
    """``_ground_loads``, ``_wall_forces``, ``_add_foundation``, ``_add_side_contact`` and
    ``_add_rigid_footing`` of a Scene (its fields and helpers are read through ``self``)."""

    def _ground_loads(self, built):
        """Dead loads that hold the geostatic state in place (without the soil's own weight, a body force of
        the soil group): the surcharge on the ground beside the strip and the horizontal geostatic stress on
        the walls of an embedded strip's trench."""
        mesh, model = built.mesh, built.model
        f_vec = np.zeros(model.n_dof)
        lo, hi = self.block()
        if self.surcharge:
            a, b = self.footprint()
            ranges = [(lo, hi)] if self.foundation is None else [(lo, a), (b, hi)]
            for a, b in ranges:
                if b - a > 1e-12:
                    nodes, f = surface_pressure_forces(mesh, a, b)
                    np.add.at(f_vec, model.dof(nodes, "w"), -self.surcharge * f)
        if self.embedment:
            for x_wall, normal in ((self.foundation.x0, 1.0), (self.foundation.x1, -1.0)):
                nodes, f = self._wall_forces(mesh, x_wall, normal)
                np.add.at(f_vec, model.dof(nodes, "u"), f)
        return f_vec

    def _wall_forces(self, mesh, x_wall, normal):
        """Nodal forces [N/m] of the traction sig_xx0 * n_x on a trench wall (3-point Gauss per edge)."""
        on = np.flatnonzero(
            (np.abs(mesh.xy[:, 0] - x_wall) < 1e-9) & (mesh.xy[:, 1] >= -self.embedment - 1e-9)
        )
        nodes = on[np.argsort(mesh.xy[on, 1])]
        z = mesh.xy[nodes, 1]
        f = np.zeros(len(nodes))
        xi = np.array([-math.sqrt(0.6), 0.0, math.sqrt(0.6)])
        wt = np.array([5.0, 8.0, 5.0]) / 9.0
        for i in range(0, len(nodes) - 2, 2):
            za = z[i : i + 3]
            for s, w in zip(xi, wt):
                n = lagrange3(s)[0]
                sxx = self.geostatic(np.array([n @ za]))[0, 0]
                f[i : i + 3] += n * sxx * normal * w * 0.5 * (za[2] - za[0])
        return nodes, f

    def _add_foundation(self, built):
        f, model, mesh = self.foundation, built.model, built.mesh
        z_base = -float(self.embedment)
        contact = foundation_contact(mesh, f.x0, f.x1, f.section.thickness, z=z_base)
        offset = -f.section.z_bottom  # plate nodes sit on the reference surface, this far above the base
        plate_xy = np.column_stack([contact.plate_xy[:, 0], np.full(len(contact.plate_xy), z_base + offset)])
        ids = model.add_nodes(plate_xy, ndof=3)
        built.geostatic_load = np.concatenate([built.geostatic_load, np.zeros(3 * len(ids))])
        conn = ids[contact.plate_conn]
        plate = PlateStrip(
            plate_xy[contact.plate_conn], model.element_dofs(conn), f.strip_section(), **f.strip_options()
        )
        model.add_group(plate)
        segments = _segments(self)
        x_mid = plate_xy[contact.plate_conn[:, 1], 0]
        params = np.array([_segment_at(segments, x).contact.params() for x in x_mid])
        # the strip starts carrying the geostatic vertical stress of its base level (surcharge, overburden):
        # contact traction and an equal dead load on the strip, so the initial state is in equilibrium
        p0 = -float(self.geostatic(np.array([z_base]))[0, 1]) if self.has_geostatic_stress() else 0.0
        iface = add_interface(
            model,
            conn,
            contact.soil_conn,
            params,
            offset=plate.bottom_offset,
            rule=segments[0].contact.rule,
            initial_traction=np.array([0.0, -p0]) if p0 else None,
        )
        built.plate, built.interface, built.plate_nodes = plate, iface, ids
        built.base_pressure = p0
        if all(seg.contact.kt == 0.0 for seg in segments):
            # frictionless contact everywhere: nothing resists a horizontal translation of the strip, so K0
            # is singular (strict pivoting used to factorise it on a round-off pivot). Hold u at the plate
            # node nearest the middle: the contact tractions are normal to the horizontal base, so the
            # support's reaction is zero while the strip carries no horizontal load (load_effect refuses one)
            built.slide_support = int(ids[np.argmin(np.abs(plate_xy[:, 0] - 0.5 * (f.x0 + f.x1)))])
            model.fix([built.slide_support], "u")
        if p0:
            scatter_vector(plate.edofs, plate.distributed_load(-p0, comp="w"), built.geostatic_load)
        if self.side_contact is not None:
            self._add_side_contact(built)

    def _add_side_contact(self, built):
        """Interfaces between each trench wall and the strip's side (:mod:`ssi.elements.side_interface`), the
        side moving with the strip's end node. They start with the wall's geostatic horizontal stress as
        their normal traction; the dead load that holds that state adds their internal force at rest to the
        wall loads: on the structure the earth pressure's resultant, on the soil (wall load + interface) a
        round-off residue, so the wall is traction-free once the contact opens."""
        model, mesh, ids = built.model, built.mesh, built.plate_nodes
        groups = []
        for x_wall, body, down in ((self.foundation.x0, ids[0], True), (self.foundation.x1, ids[-1], False)):
            on = np.flatnonzero(
                (np.abs(mesh.xy[:, 0] - x_wall) < 1e-9) & (mesh.xy[:, 1] >= -self.embedment - 1e-9)
            )
            # the structure on the left walking from node 0 to 2: down the left wall, up the right one
            nodes = on[np.argsort(-mesh.xy[on, 1] if down else mesh.xy[on, 1])]
            conn = np.column_stack([nodes[0:-2:2], nodes[1:-1:2], nodes[2::2]])
            group = add_side_interface(
                model, body, conn, self.side_contact.params(), rule=self.side_contact.rule,
                name=f"side_interface_{'left' if down else 'right'}",
            )  # fmt: skip
            if self.has_geostatic_stress():
                # sig_n of each point: the wall's sig_xx0, taken just inside its element (a point on a layer
                # boundary then reads its own element's layer)
                pts = group.ip_coords()[..., 1]
                centre = group.coords[:, 4:5, 1]
                z = pts + 1e-9 * (centre - pts)
                t0 = np.zeros(pts.shape + (2,))
                t0[..., 1] = self.geostatic(z)[..., 0]
                group.initial_traction = t0
                z0 = np.zeros(group.edofs.shape)
                scatter_vector(
                    group.edofs,
                    group.evaluate(z0, z0, group.initial_state(), K0_MATRIX)[0],
                    built.geostatic_load,
                )
            groups.append(group)
        built.side_interfaces = groups

    def _add_rigid_footing(self, built, soil_ids):
        """The soil nodes under a :class:`RigidFooting` are its base: held at rest (w = 0; rough: u = 0 too)
        until a Settlement prescribes their w (:meth:`BuiltScene.load_effect`)."""
        nodes = soil_ids[built.mesh.nodes_between(*self.footprint())]
        if self.foundation.rough:
            built.model.fix(nodes, "u")
        built.model.fix(nodes, "w")
        built.footing_nodes = nodes
