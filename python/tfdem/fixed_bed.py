"""A fixed bed with gas through it (tutorials/packed_bed_ergun): its Ergun reference read from
the case's own files, a run at a chosen superficial velocity, and what the run measured.

The case: spheres put on the DEM script's simple-cubic lattice in a block region (`lattice sc`,
`region bed block ...`, `create_atoms 1 region bed`) without time integration, in a column
one cell deep; the inlet is the patch `inlet` of 0/U (superficial velocity, flow along +y),
two pressure probes (function `pressure` of system/controlDict) below and above the bed, and
a `fix force_out ... print` file of the particles' summed fluid force, y.
"""
import math

import tfdem.run
from tfdem import outputs
from tfdem.case import Case
from tfdem.physics import ergun_gradient, sphere_volume

VELOCITIES = (0.3, 0.6, 1.0)  # m/s, superficial: tutorials/packed_bed_ergun's three runs


class FixedBed:
    """The bed of a case: gas fraction eps = 1 - N V_p / (region area x mesh depth), height
    of the region, Ergun's pressure drop plus the gas weight between the probes."""

    def __init__(self, case, region="bed", probes="pressure"):
        self.case = case if isinstance(case, Case) else Case(case)
        dem = self.case.dem()
        self.d, _ = self.case.particle_properties()
        self.rho_g, self.mu = self.case.gas()
        self.g = self.case.gravity_magnitude()
        self.particles = len(dem.lattice_sites(region))
        (x0, y0, _), (x1, y1, _) = dem.region(region)
        lo, hi = self.case.mesh_bounds()
        self.width, self.depth = hi[0] - lo[0], hi[2] - lo[2]
        self.height = y1 - y0
        self.eps = 1.0 - self.particles * sphere_volume(self.d) / ((x1 - x0) * self.height * self.depth)
        below, above = self.case.probe_locations(probes)[:2]
        self.probe_gap = above[1] - below[1]
        self.probes = probes

    def ergun_gradient(self, u):
        """Ergun's pressure drop per bed length (Pa/m) at superficial velocity u."""
        return ergun_gradient(u, self.eps, self.d, self.rho_g, self.mu)

    def expected_pressure_drop(self, u):
        """p(below) - p(above) (Pa): Ergun over the bed plus the gas weight between the probes."""
        return self.ergun_gradient(u) * self.height + self.rho_g * self.g * self.probe_gap

    def expected_particle_force(self, u):
        """Sum of the particles' fluid forces (N, up): Ergun's pressure drop over the column's
        cross-section (Newton's third law between the phases) plus the gas buoyancy rho_g g
        sum V_p."""
        return (self.ergun_gradient(u) * self.height * self.width * self.depth
                + self.rho_g * self.g * self.particles * math.pi * self.d ** 3 / 6)

    def measured_pressure_drop(self, case_path):
        """Last probe row of a finished run: p(below) - p(above) (Pa)."""
        _, p = outputs.probes(case_path, self.probes, "p")[-1]
        return p[0] - p[1]

    def measured_particle_force(self, case_path, fix_id="force_out"):
        """Last row of the DEM script's force file: the particles' summed fluid force, y (N)."""
        path = Case(case_path).file(Case(case_path).dem().fix_file(fix_id))
        return outputs.fix_print(path)[-1][1][0]

    def run(self, dest, u, runner=tfdem.run.run):
        """Copy the case to dest with inlet velocity (0 u 0), run blockMesh and tfdemFoam there
        via runner(args, cwd, log_name); return the measured pressure drop."""
        copy = self.case.copy_to(dest)
        copy.set_patch_value("U", "inlet", (0, u, 0))
        runner(["blockMesh"], dest, "log.blockMesh")
        runner(["tfdemFoam"], dest, "log.tfdemFoam")
        return self.measured_pressure_drop(dest)
