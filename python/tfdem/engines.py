"""The particle engines a case can run (coupling.yaml dem.engine): LIGGGHTS' soft spheres, the
case's DEM script, or the hard-sphere event-driven engine, the particles of a data file. What
turns a case from one to the other and writes the data file the hard-sphere engine reads.
"""
import math
import os

import yaml

from tfdem.case import Case, sphere_volume
from tfdem.liggghts import ScriptError, contact_properties, read_data_file, wall_type

def restitution_of_damping(stiffness, damping, mass):
    """The restitution of a linear spring-dashpot contact, seed 001 eq. 27 solved for e_n
    (normal: stiffness k_n, damping eta_n, mass m_ab) or eq. 30 for beta_0 (tangential: k_t,
    eta_t and the mass 2/7 m_ab): e = exp(-pi eta / sqrt(4 m k - eta^2)); 0 at or past critical
    damping (eta >= 2 sqrt(m k))."""
    discriminant = 4 * mass * stiffness - damping ** 2
    return math.exp(-math.pi * damping / math.sqrt(discriminant)) if discriminant > 0 else 0.0


def hard_sphere_laws(script, masses):
    """Seed 001's hard-sphere coefficients (e_n, beta_0, mu; eqs. 17, 19, 21) equivalent to a
    LIGGGHTS script's (a DemScript) linear spring-dashpot contacts (eqs. 24-30): e_n from k_n, eta_n and m_ab
    (eq. 27), beta_0 from k_t, eta_t and 2/7 m_ab (eq. 30, a sticking contact), mu as given.
    `masses`: one particle mass per particle type (types 1..n); the walls' type (wall_type)
    has infinite mass: m_ab = m_a; types the tables declare beyond the particles' hold none
    and need no law. Returns the keyword arguments of use_hard_sphere: matrices over the
    particle types and the walls' lists."""
    tables = contact_properties(script)
    n = len(masses)
    declared = len(tables["kn"])
    wall = wall_type(script, declared) - 1
    if declared < n + 1 or wall < n:
        raise ScriptError(f"{script.path}: {declared} atom types in its contact tables, the walls' type "
                          f"{wall + 1}: expected {n} particle types before the walls'")

    def laws(pairs):
        e, beta, mu = [], [], []
        for a, b, m_ab in pairs:
            e.append(restitution_of_damping(tables["kn"][a][b], tables["gamman_abs"][a][b], m_ab))
            beta.append(restitution_of_damping(tables["kt"][a][b], tables["gammat_abs"][a][b], 2 / 7 * m_ab))
            mu.append(tables["coefficientFriction"][a][b])
        one = lambda v: v[0] if len(set(v)) == 1 else v  # the same for every pair: one value
        return {"restitution": one(e), "tangential_restitution": one(beta), "friction": one(mu)}

    pair = laws([(a, b, masses[a] * masses[b] / (masses[a] + masses[b])) for a in range(n) for b in range(n)])
    pair["wall"] = laws([(a, wall, masses[a]) for a in range(n)])
    return pair


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


def type_masses(data_file):
    """The mass of one particle of each atom type (1, 2, ...) of a data file; refuses a type
    whose particles differ in mass (the laws are per pair of types)."""
    atoms = read_data_file(data_file)
    masses = {}
    for t, d, rho in zip(atoms["type"], atoms["diameter"], atoms["density"]):
        m = rho * sphere_volume(d)
        if abs(masses.setdefault(t, m) - m) > 1e-9 * m:
            raise ScriptError(f"{data_file}: atom type {t} holds particles of different masses: "
                              "the hard-sphere laws are per pair of types")
    return [masses[t] for t in sorted(masses)]


# A tutorial's variants run again with the hard-sphere engine are named <variant>_hard_sphere
HARD_SPHERE = "_hard_sphere"


def with_hard_sphere(variants):
    """A tutorial's variants {name: coupling.yaml settings}, and each again as
    <name>_hard_sphere with the same settings (run by convert_to_hard_sphere)."""
    return {**variants, **{name + HARD_SPHERE: settings for name, settings in variants.items()}}


def convert_to_hard_sphere(case):
    """Turn a LIGGGHTS case into the same bed with the hard-sphere engine: the particles of its
    DEM script's data file, the laws equivalent to the script's contacts (hard_sphere_laws);
    the script goes (the engine reads the data file only)."""
    case = case if isinstance(case, Case) else Case(case)
    script = case.dem()
    data = os.path.relpath(script.read_data(), case.path)
    use_hard_sphere(case, data, **hard_sphere_laws(script, type_masses(case.file(data))))
    os.remove(script.path)
