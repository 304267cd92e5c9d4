"""The fixed bed of tutorials/packed_bed_ergun on gas cells smaller than a particle (2.04 mm
against d = 2.5 mm, 30 x 100 cells), its particle fields spread by the diffusion smoothing
(coupling.void_fraction.diffusion_bandwidth 7.5 mm = 3 d, per_particle_conservative).

Unspread, the centroid map of this lattice (2.55 mm apart) on these cells is a pattern of
cells holding one sphere (eps_g = 0.21) and empty ones (eps_g = 1). Spread, the test asserts:
- the run ends, with no cell floored;
- the pressure drop between the probes equals tfdem.fixed_bed's 1-D model of the spread bed
  (FixedBed.spread_pressure_drop: the slab's solids and drag convolved with the Gaussian of
  bandwidth b, from seed 000 eq. 30 in tfdem.physics, the gas momentum of UEqn.H integrated),
  within 0.5 % at 0.3 and 1.0 m/s;
  (measured 2026-12-07: +0.06 % and -0.06 %);
- inside the bed, farther than 2.5 b from both edges (the Gaussian's tail there e^-6.25 =
  0.2 %), the pressure gradient is Ergun's within 0.5 % (two more probes at cell centres,
  6.3 cm apart; measured 2026-12-07: -0.10 % and -0.20 %): the spread keeps a uniform bed's drag on cells
  smaller than a particle;
- and what the spread costs against Ergun over the whole bed, named: the spheres within ~b of the
  bed's two sharp edges see the spread edge's gas fraction and the slower gas beyond it, and the
  drag spread beyond the edges acts on gas of eps ~ 1 (model -10.4 % at both velocities, about
  -1.4 % per mm of b for this 10.2 cm bed; measured -10.37 % and -10.42 %): 8-11 % below Ergun,
  not within 0.5 % of it. Unspread, the same cells give 4.6 Pa against Ergun's 60.8 (-92 %).

A bandwidth wider than the column, or a particle-field block that does not divide the mesh,
stops the solver at start with the key, the axis and the fix.

Cost (the solver's timing line, three alternated pairs, 400 coupling steps, 3000 cells): map and
forces 0.82 s spread against 0.06 s unspread, 1.9 ms per coupling step against a gas step of
10 ms.
"""
import os

from tfdem import TUTORIALS, outputs
from tfdem.fixed_bed import FixedBed
from tfdem_testlib import Checks, run, scratch

TUTORIAL = os.path.join(TUTORIALS, "packed_bed_ergun")
BANDWIDTH = 0.0075  # m, 3 d
REFINE = 5  # the tutorial's 10.2 mm cells into 2.04 mm ones
INTERIOR_MARGIN = 2.5 * BANDWIDTH  # m from each bed edge: the spread edge's Gaussian tail is e^-6.25 there


def main():
    checks = Checks()
    bed = FixedBed(TUTORIAL)
    for u in (0.3, 1.0):
        dest = scratch(f"packed_bed_fine_U{u}")
        copy = bed.case.copy_to(dest)
        copy.scale_cells(0, REFINE)
        copy.scale_cells(1, REFINE)
        copy.set_coupling("coupling.transfer", "per_particle_conservative")
        copy.set_coupling("coupling.void_fraction.diffusion_bandwidth", BANDWIDTH)
        copy.set_patch_value("U", "inlet", (0, u, 0))
        below, above = copy.probe_locations("pressure")[:2]
        interior = [copy.grid().centre_of_cell_at(1, y)
                    for y in (bed.bottom + INTERIOR_MARGIN, bed.bottom + bed.height - INTERIOR_MARGIN)]
        copy.set_probe_locations("pressure", [below, above] + [(below[0], y, below[2]) for y in interior])
        run(["blockMesh"], dest, "log.blockMesh")
        run(["tfdemFoam"], dest, "log.tfdemFoam")
        log = open(os.path.join(dest, "log.tfdemFoam")).read()
        checks.true(f"U = {u} m/s: cells of {bed.width / 30 * 1e3:.2f} mm, smaller than d = {bed.d * 1e3} mm",
                    copy.grid().spacing[1] < bed.d)
        checks.true(f"U = {u} m/s: the spread named at start", "TFDEM diffusion smoothing: the particle fields spread "
                    f"with bandwidth b = {BANDWIDTH}" in log)
        checks.true(f"U = {u} m/s: no cell floored", "floored" not in log.lower())
        measured = FixedBed(dest).measured_pressure_drop(dest)
        checks.close(f"U = {u} m/s: pressure drop (Pa) against the 1-D model of the spread bed", measured,
                     bed.spread_pressure_drop(u, BANDWIDTH), 0.005)
        _, p = outputs.probes(dest, "pressure", "p")[-1]
        span = interior[1] - interior[0]
        checks.close(f"U = {u} m/s: pressure drop (Pa) over the bed's interior {span * 100:.1f} cm against Ergun's",
                     p[2] - p[3], (bed.ergun_gradient(u) + bed.rho_g * bed.g) * span, 0.005)
        ergun = bed.expected_pressure_drop(u)
        checks.true(f"U = {u} m/s: the spread's cost against Ergun, 8-11 % below it",
                    -0.11 < measured / ergun - 1 < -0.08, f"({measured:.2f} Pa against Ergun {ergun:.2f} Pa: "
                    f"{measured / ergun - 1:+.2%})")
    # A bandwidth wider than the column (0.5 m against 0.0612 m wide, 0.204 m high) stops the
    # solver at start, non-zero, naming the key, the first axis it exceeds and the fix
    dest = scratch("packed_bed_fine_too_wide")
    copy = bed.case.copy_to(dest)
    copy.set_coupling("coupling.transfer", "per_particle_conservative")
    copy.set_coupling("coupling.void_fraction.diffusion_bandwidth", 0.5)
    run(["blockMesh"], dest, "log.blockMesh")
    code, _ = run(["tfdemFoam"], dest, "log.tfdemFoam", expect_success=False)
    log = open(os.path.join(dest, "log.tfdemFoam")).read()
    checks.true("a bandwidth wider than the column is refused at start", code != 0 and
                "coupling.void_fraction.diffusion_bandwidth: 0.5 m is larger than the domain along x (0.0612 m)" in log
                and "give a bandwidth below 0.0612 m" in log, f"(exit code {code})")
    # A particle-field block that does not divide the mesh (4 of this copy's 6 cells across) likewise
    copy.set_coupling("coupling.void_fraction.diffusion_bandwidth", 0.005)
    copy.set_coupling("coupling.void_fraction.particle_field_block", [4, 1, 1])
    code, _ = run(["tfdemFoam"], dest, "log.tfdemFoam", expect_success=False)
    log = open(os.path.join(dest, "log.tfdemFoam")).read()
    checks.true("a particle-field block that does not divide the mesh is refused at start", code != 0 and
                "coupling.void_fraction.particle_field_block: 4 gas cells along x is not a whole divisor of the gas "
                "grid's 6 cells there: give one of 1 2 3 6" in log, f"(exit code {code})")
    checks.finish()


if __name__ == "__main__":
    main()
