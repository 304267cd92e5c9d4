"""Hand-made runs for the tests of the Python readers: a case written by `tfdem new` (any layout,
one to nine sizes, either engine) and output files in the formats the solver and LIGGGHTS write
(postProcessing probes and surfaceFieldValue files, particles.dat, the VTK particle files,
forces.txt, mean_height.txt, a data file), with values the test chooses. No simulation.
"""
import math
import os

from tfdem.case import Case
from tfdem.newcase import derive, load_bed, write_case

RHO, RHO_GAS, G = 2500.0, 1.2, 9.81


def bed_yaml(depth, diameters, engine="liggghts", width=0.04, height=0.16, cell=0.01):
    """A bed.yaml of `diameters` (ten spheres each) in a width x height column `depth` deep
    (a length in m or 'one_layer'), gas cells `cell` wide."""
    sizes = ", ".join(f"{{diameter: {d!r}, number: 10}}" for d in diameters)
    dem = "" if engine == "liggghts" else f"dem: {{engine: {engine}}}\n"
    return (f"box: {{width: {width}, height: {height}, depth: {depth}}}\n"
            f"particles:\n  density: {RHO}\n  sizes: [{sizes}]\n  restitution: 0.9\n  friction: 0.1\n"
            f"gas: {{density: {RHO_GAS}, viscosity: 1.8e-5}}\ninflow: {{velocity: 0.5}}\n"
            f"run: {{end_time: 1.0, write_interval: 0.5}}\nmesh: {{cell_size: {cell}}}\n" + dem)


def make_case(root, name, text):
    """tfdem new of the bed `text` into root/name: (Case, bed, derived values)."""
    os.makedirs(root, exist_ok=True)
    source = os.path.join(root, f"{name}.yaml")
    with open(source, "w") as f:
        f.write(text)
    bed = load_bed(source)
    dv = derive(bed, source)
    path = os.path.join(root, name)
    write_case(path, bed, dv, source)
    return Case(path), bed, dv


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)


def write_data_file(path, atoms, box):
    """A LIGGGHTS data file (atom style granular) of atoms [(type, diameter, x, y, z)] in the
    box ((xlo, ylo, zlo), (xhi, yhi, zhi)), as tfdem pack writes it."""
    lo, hi = box
    types = max(t for t, *_ in atoms) + 1
    lines = ["LIGGGHTS data file (hand-made)", "", f"{len(atoms)} atoms", f"{types} atom types", ""]
    lines += [f"{lo[a]!r} {hi[a]!r} {axis}lo {axis}hi" for a, axis in enumerate("xyz")]
    lines += ["", "Atoms", ""]
    lines += [f"{k + 1} {t} {d!r} {RHO!r} {x!r} {y!r} {z!r}" for k, (t, d, x, y, z) in enumerate(atoms)]
    lines += ["", "Velocities", ""] + [f"{k + 1} 0 0 0 0 0 0" for k in range(len(atoms))]
    write(path, "\n".join(lines) + "\n")


def write_probes(case, name, field, locations, rows, start="0"):
    """postProcessing/<name>/<start>/<field> as OpenFOAM's probes write it: a header line per
    probe location, then `t value value ...` rows ([(t, [values])])."""
    header = "".join(f"# Probe {k} ({x!r} {y!r} {z!r})\n" for k, (x, y, z) in enumerate(locations))
    header += "#" + " " * 17 + "Probe" + "".join(f"{k:>25}" for k in range(len(locations))) + "\n"
    header += "#" + " " * 18 + "Time\n"
    body = "".join(f"{t!r:>24}" + "".join(f"{v!r:>25}" for v in values) + "\n" for t, values in rows)
    write(case.file("postProcessing", name, start, field), header + body)


def write_surface_average(case, name, patch, faces, area, rows, start="0"):
    """postProcessing/<name>/<start>/surfaceFieldValue.dat of an areaAverage of p on a patch,
    as OpenFOAM's surfaceFieldValue writes it ([(t, value)])."""
    header = (f"# Region type : patch {patch}\n# Faces : {faces}\n# Area : {area!r}\n"
              "# Scale factor : 1.00000000000000000e+00\n# Time                   \tareaAverage(p)\n")
    write(case.file("postProcessing", name, start, "surfaceFieldValue.dat"),
          header + "".join(f"{t!r:<25}\t{v!r}\n" for t, v in rows))


def write_particles_dat(case, rows, bidisperse, start="0"):
    """postProcessing/tfdemParticles/<start>/particles.dat as the coupler writes it: rows of
    (t, particles, mass, mean height, bulk coordination, multicontact[, segregation])."""
    header = ("# t (s)  particles  mass (kg)  mean height (m)  bulk coordination number  multicontact ratio"
              + ("  segregation degree" if bidisperse else "") + "\n")
    write(case.file("postProcessing", "tfdemParticles", start, "particles.dat"),
          header + "".join(" ".join(repr(v) for v in row) + "\n" for row in rows))


def write_vtk_particles(path, t, particles):
    """A VTK particle file as the coupler writes it (VTK/particles_<t>.vtk): particles
    [(id, diameter, (x, y, z))] with zero velocities and forces."""
    n = len(particles)
    lines = ["# vtk DataFile Version 3.0", f"TFDEM particles at t = {t:g} s", "ASCII", "DATASET POLYDATA",
             f"POINTS {n} double"]
    lines += [f"{x!r} {y!r} {z!r}" for _, _, (x, y, z) in particles]
    lines += [f"VERTICES {n} {2 * n}"] + [f"1 {i}" for i in range(n)] + [f"POINT_DATA {n}"]
    lines += ["SCALARS id int 1", "LOOKUP_TABLE default"] + [str(i) for i, _, _ in particles]
    lines += ["SCALARS diameter double 1", "LOOKUP_TABLE default"] + [repr(d) for _, d, _ in particles]
    for vector in ("velocity", "contactForce", "dragForce", "fluidForce"):
        lines += [f"VECTORS {vector} double"] + ["0 0 0"] * n
        if vector == "velocity":
            lines += ["SCALARS coordination int 1", "LOOKUP_TABLE default"] + ["0"] * n
    write(path, "\n".join(lines) + "\n")


def buoyant_weight_per_area(diameters, width, depth):
    """sum (rho - rho_gas) g pi d^3 / 6 over the spheres, per width x depth (Pa)."""
    return sum((RHO - RHO_GAS) * G * math.pi * d ** 3 / 6 for d in diameters) / (width * depth)


def write_forces(case, rows):
    """forces.txt as LIGGGHTS' `fix forces_out ... ave/time` of a generated in.bed writes it:
    rows of (DEM step, gas, plate, wall x0, wall x1, lid[, wall z0, wall z1]) in N."""
    columns = "c_f_gas c_f_plate c_f_side[1] c_f_side[2] c_f_lid" + (" c_f_depth[1] c_f_depth[2]" if len(rows[0]) > 6
                                                                     else "")
    write(case.file("forces.txt"), "# Time-averaged data for fix forces_out\n# TimeStep " + columns + "\n"
          + "".join(f"{row[0]} " + " ".join(f"{v:.9g}" for v in row[1:]) + "\n" for row in rows))
