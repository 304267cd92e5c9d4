"""A fixed bed with gas through it (tutorials/packed_bed_ergun, tutorials/pseudo2d_packed_bed):
its Ergun reference read from the case's own files, a run at a chosen superficial velocity, and
what the run measured.

The case: spheres put on the DEM script's simple-cubic lattice in a block region (`lattice sc`,
`region bed block ...`, `create_atoms 1 region bed`) without time integration, in a column
one cell deep; the inlet is the patch `inlet` of 0/U (superficial velocity, flow along +y),
two pressure probes (function `pressure` of system/controlDict) below and above the bed, and
a `fix force_out ... print` file of the particles' summed fluid force, y.
"""
import math
import os
import statistics

import numpy

import tfdem.run
from tfdem import outputs
from tfdem.case import Case, CaseError
from tfdem.physics import beta_over_solid_fraction, ergun_gradient, slab_solid_fraction, sphere_volume

VELOCITIES = (0.3, 0.6, 1.0)  # m/s, superficial: tutorials/packed_bed_ergun's three runs


class FixedBed:
    """The bed of a case: gas fraction eps = 1 - N V_p / (region area x mesh depth), height
    of the region, Ergun's pressure drop plus the gas weight between the probes."""

    def __init__(self, case, region="bed", probes="pressure"):
        self._read_case(case, probes)
        dem = self.case.dem()
        self.particles = len(dem.lattice_sites(region))
        (x0, y0, _), (x1, y1, _) = dem.region(region)
        self.bottom, self.height = y0, y1 - y0
        self.eps = 1.0 - self.particles * sphere_volume(self.d) / ((x1 - x0) * self.height * self.depth)
        below, above = self.case.probe_locations(probes)[:2]
        self.probe_heights = (below[1], above[1])
        self.probe_gap = above[1] - below[1]

    def _read_case(self, case, probes):
        """What every fixed bed reads from its case: particle size, gas, gravity, the column's
        width and depth, the probes function's name."""
        self.case = case if isinstance(case, Case) else Case(case)
        self.d, _ = self.case.particle_properties()
        self.rho_g, self.mu = self.case.gas()
        self.g = self.case.gravity_magnitude()
        lo, hi = self.case.mesh_bounds()
        self.width, self.depth = hi[0] - lo[0], hi[2] - lo[2]
        self.probes = probes

    def extra_files(self):
        """Files a run's copy of the case needs besides its dictionaries and DEM scripts."""
        return ()

    def ergun_gradient(self, u):
        """Ergun's pressure drop per bed length (Pa/m) at superficial velocity u."""
        return ergun_gradient(u, self.eps, self.d, self.rho_g, self.mu)

    def expected_pressure_drop(self, u):
        """p(below) - p(above) (Pa): Ergun over the bed plus the gas weight between the probes."""
        return self.ergun_gradient(u) * self.height + self.rho_g * self.g * self.probe_gap

    def spread_pressure_drop(self, u, bandwidth, step=1e-5, heights=None):
        """p(below) - p(above) (Pa) between the probes (or the two `heights`, m) of the bed's
        particle fields spread by the diffusion smoothing
        of bandwidth b (coupling.void_fraction.diffusion_bandwidth) under the conservative
        per-particle transfer: a 1-D model along the flow, on its own fine line (`step`, m).

        The solids fraction phi is the bed's slab convolved with the Gaussian exp(-s^2/b^2) /
        (sqrt(pi) b) (mirrored at the column's ends: walls reflect); each particle's drag per
        unit volume is beta/eps_s (tfdem.physics: seed 000 eq. 30) at the spread eps = 1 - phi
        and the slip u_seen, the gas velocity U/eps convolved with the Gaussian, and the gas
        loses their drags per unit volume, phi_raw beta/eps_s u_seen, convolved with the same
        Gaussian: D(y). The steady gas momentum (UEqn.H: eps grad p = -D - eps rho g) gives
        the drop D / eps integrated between the probes plus the gas weight. For a bed whose
        edges are sharp on the grid this is below Ergun's for three reasons: the particles
        within ~b of an edge see the spread edge's higher gas fraction and the slower gas
        outside the bed, and the share of their drag spread beyond the edge acts on gas of
        eps ~ 1 (a drop D / eps for a drag D, where the bed has D / eps_bed)."""
        lo, hi = self.case.mesh_bounds()
        y = numpy.arange(lo[1] + step / 2, hi[1], step)
        inside = (y >= self.bottom) & (y <= self.bottom + self.height)
        phi_bed = 1.0 - self.eps
        kernel_s = numpy.arange(-4 * bandwidth, 4 * bandwidth + step / 2, step)
        kernel = numpy.exp(-(kernel_s / bandwidth) ** 2) * step / (math.sqrt(math.pi) * bandwidth)
        pad = len(kernel_s) // 2

        def spread(field):
            """`field` convolved with the Gaussian, mirrored at the column's ends."""
            padded = numpy.concatenate([field[pad - 1::-1], field, field[:-pad - 1:-1]])
            return numpy.convolve(padded, kernel, mode="valid")

        eps = 1.0 - spread(numpy.where(inside, phi_bed, 0.0))
        seen = spread(u / eps)  # the gas velocity the particles see: spread as well
        drag = numpy.array([phi_bed * beta_over_solid_fraction(e, v, self.d, self.rho_g, self.mu) * v if k else 0.0
                            for e, v, k in zip(eps, seen, inside)])
        gradient = spread(drag) / eps
        low, high = heights or self.probe_heights
        between = (y >= low) & (y <= high)
        return float(gradient[between].sum() * step) + self.rho_g * self.g * (high - low)

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
        copy = self.case.copy_to(dest, extra=self.extra_files())
        copy.set_patch_value("U", "inlet", (0, u, 0))
        runner(["blockMesh"], dest, "log.blockMesh")
        runner(["tfdemFoam"], dest, "log.tfdemFoam")
        return self.measured_pressure_drop(dest)


class PouredBed(FixedBed):
    """A poured bed (the DEM script's read_data file, particles not integrated) in a column of
    any depth: Ergun at the solid fraction measured between two rows of pressure probes.

    The slab between the rows (heights of the probes function) holds the exact volume of the
    spheres inside it (spherical caps of those cut by its planes); eps = 1 - that / slab volume.
    The measured pressure drop is the mean over the lower row minus the mean over the upper.
    """

    def __init__(self, case, probes="pressure"):
        self._read_case(case, probes)
        heights = sorted({round(p[1], 9) for p in self.case.probe_locations(probes)})
        if len(heights) != 2:
            raise CaseError(f"{self.case.file('system', 'controlDict')}: probes '{probes}' must lie in two"
                            f" rows (heights), found {len(heights)}")
        self.below, self.above = heights
        self.height = self.probe_gap = self.above - self.below
        self.eps = 1.0 - slab_solid_fraction(self.case.particles(), self.below, self.above, self.width * self.depth)

    def measured_pressure_drop(self, case_path):
        """Last probe row of a finished run: mean p of the lower row minus that of the upper (Pa)."""
        locations = self.case.probe_locations(self.probes)
        _, p = outputs.probes(case_path, self.probes, "p")[-1]
        lower = [v for v, x in zip(p, locations) if abs(x[1] - self.below) < 1e-9]
        upper = [v for v, x in zip(p, locations) if abs(x[1] - self.above) < 1e-9]
        return statistics.fmean(lower) - statistics.fmean(upper)

    def extra_files(self):
        return data_file_of(self.case)

    def expected_particle_force(self, u):
        raise CaseError("a poured bed's total particle force is not Ergun's: its solid fraction varies with"
                        " height; compare the pressure drop between the probe rows")


def data_file_of(case):
    """(name,) of the data file the case's DEM script reads, for Case.copy_to's extra."""
    return (os.path.basename(case.dem().read_data()),)


def deep_variant(case, dest, cells_in_depth, front_and_back="type noSlip;"):
    """A copy of a one-cell-deep column case at dest with `cells_in_depth` cells across its depth
    and the gas condition `front_and_back` on the patch frontAndBack (the 3-D variant)."""
    source = case if isinstance(case, Case) else Case(case)
    copy = source.copy_to(dest, extra=data_file_of(source))
    copy.scale_cells(2, cells_in_depth)
    copy.set_patch_condition("U", "frontAndBack", front_and_back)
    return copy


DEEP_CELLS = 3  # cells across the depth in tutorials/pseudo2d_packed_bed's 3-D variant


def poured_bed_runs(case, runs_dir, runner=tfdem.run.run, velocities=VELOCITIES):
    """The runs of tutorials/pseudo2d_packed_bed (or a case built like it) under runs_dir: the
    case as it is (one cell deep, front and back slip) and its 3-D variant (DEEP_CELLS cells in
    depth, noSlip front and back) at each velocity, and the 3-D variant with slip walls at the
    middle one. Returns {(variant, u): (measured, expected)} pressure drops (Pa)."""
    case = case if isinstance(case, Case) else Case(case)
    variants = {"one_cell": case,
                "deep_noslip": deep_variant(case, os.path.join(runs_dir, "deep_noslip"), DEEP_CELLS),
                "deep_slip": deep_variant(case, os.path.join(runs_dir, "deep_slip"), DEEP_CELLS, "type slip;")}
    results = {}
    for name, variant in variants.items():
        bed = PouredBed(variant)
        for u in velocities if name != "deep_slip" else velocities[len(velocities) // 2:][:1]:
            dp = bed.run(os.path.join(runs_dir, f"{name}_U{u}"), u, runner)
            results[(name, u)] = (dp, bed.expected_pressure_drop(u))
    return results
