"""The particle engines a case can run (coupling.yaml dem.engine): LIGGGHTS' soft spheres, the
case's DEM script, or the hard-sphere event-driven engine, the particles of a data file. What
turns a case from one to the other and writes the data file the hard-sphere engine reads.
"""
import yaml

from tfdem.case import Case


def write_data_file(path, lower, upper, diameters, densities, positions, velocities=None, types=None,
                    type_count=None, title="TFDEM particles"):
    """A LIGGGHTS data file (atom_style granular: id type diameter density x y z) of these
    particles in the box lower..upper, with a Velocities section when velocities are given."""
    n = len(positions)
    types = types or [1] * n
    lines = [title, "", f"{n} atoms", f"{type_count or max(types, default=1)} atom types", ""]
    lines += [f"{lower[a]!r} {upper[a]!r} {'xyz'[a]}lo {'xyz'[a]}hi" for a in range(3)]
    lines += ["", "Atoms # granular", ""]
    lines += [f"{k + 1} {types[k]} {diameters[k]!r} {densities[k]!r} {x!r} {y!r} {z!r}"
              for k, (x, y, z) in enumerate(positions)]
    if velocities:
        lines += ["", "Velocities", ""]
        lines += [f"{k + 1} {vx!r} {vy!r} {vz!r} 0 0 0" for k, (vx, vy, vz) in enumerate(velocities)]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def use_hard_sphere(case, particles, restitution, tangential_restitution, friction, wall=None, **options):
    """Make a case's coupling.yaml run the hard-sphere engine on the data file `particles`
    (relative to the case) with these collision coefficients (dem.hard_sphere; `wall`: a dict
    of the walls' own, `options`: elastic_within, contact_gap, move, ...). The LIGGGHTS keys
    (script, coupling_interval) go; the rest of the file stays."""
    case = case if isinstance(case, Case) else Case(case)
    path = case.file("coupling.yaml")
    with open(path) as f:
        config = yaml.safe_load(f)
    dem = config["dem"]
    for key in ("script", "coupling_interval"):
        dem.pop(key, None)
    dem["engine"] = "hard_sphere"
    dem["particles"] = particles
    hard = {"restitution": restitution, "tangential_restitution": tangential_restitution, "friction": friction}
    if wall:
        hard["wall"] = dict(wall)
    hard.update(options)
    dem["hard_sphere"] = hard
    with open(path, "w") as f:
        f.write("# the hard-sphere engine (tfdem.engines.use_hard_sphere)\n")
        yaml.safe_dump(config, f, sort_keys=False)
