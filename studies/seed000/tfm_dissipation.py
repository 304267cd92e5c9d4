"""How much a TF-DEM bed's contacts dissipate, against kinetic theory: the effective restitution.

    tfm_dissipation.py [RUN ...] [--from 5] [--csv results/tfm_dissipation.csv]

RUN: run folders under runs/ (default: the jet bed's b = 1.2 cm realizations, jet_diff12_r*).

Over a run's particle files (VTK/particles_<t>.vtk, one per write interval), the power that the
gas and gravity put into the particles,

    P = sum_p (F_fluid,p + m_p g) . v_p        (F_fluid: seed 000 eq. 28's total fluid force)

averages to the rate D at which the contacts (particle-particle and walls) dissipate, since the
particles' kinetic and potential energy return over the run. Kinetic theory's collisional
dissipation for the same particles (seed 000 eq. 5's J_sm,coll, in the form of Lun et al. 1984,
J. Fluid Mech. 140, the gamma of twoPhaseEulerFoam's kineticTheory) is, per unit volume,

    Gamma = 12 (1 - e^2) g0(alpha) rho_s alpha^2 Theta^(3/2) / (d sqrt(pi)),

g0 Carnahan-Starling's (2 - alpha) / (2 (1 - alpha)^3) as in the TFM template. alpha and Theta
(seed 000 eq. 6, Theta = <|v - v_cell|^2> / 3, here with n/(n-1) for the cell's own mean) come
from the particles binned into the run's cells by their centres; a cell with fewer than two
particles has no Theta and adds nothing. With S = sum_cells 12 g0 rho_s alpha^2 Theta^(3/2) V /
(d sqrt(pi)), the restitution at which kinetic theory dissipates what the DEM does is

    e_eff = sqrt(1 - D / <S>).

Each sample is one particle file; D and <S> are means over the files from --from on, and
over the realizations given; D's error is the realizations' standard error, or that of their
own samples where larger. e_eff2d repeats it with the 2-D temperature (|v - v_cell|^2) / 2
of these one-layer beds, whose particles move in x and y only. e_eff_fields takes alpha and
Theta instead from the fields the coupler wrote at the same times (voidFraction, filtered with
the run's bandwidth; granularTemperature, eq. 6 with the 3-D convention): a check on the
binning by centres.
"""
import argparse
import csv
import math
import os
import re
import statistics
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "python"))
from tfdem.case import Case  # noqa: E402
from tfdem.errors import Reported  # noqa: E402
from tfdem.outputs import OutputError, field, vtk_particles  # noqa: E402

DEFAULT_RUNS = ["jet_diff12_r1", "jet_diff12_r2", "jet_diff12_r3", "jet_diff12_r4"]
DEFAULT_FROM = 5.0  # s: seed 000's averaging window starts here
RESULTS = os.path.join(HERE, "results", "tfm_dissipation.csv")


def carnahan_starling(alpha):
    return (2 - alpha) / (2 * (1 - alpha) ** 3)


def input_power(particles, density, gravity):
    """P = sum (F_fluid + m g) . v over the particles (W); gravity along -y."""
    total = 0.0
    for d, v, f in zip(particles["diameter"], particles["velocity"], particles["fluidForce"]):
        mass = density * math.pi * d ** 3 / 6
        total += f[0] * v[0] + (f[1] - mass * gravity) * v[1] + f[2] * v[2]
    return total


def dissipation_scale(particles, grid, density, components=3):
    """S = sum over cells of 12 g0 rho_s alpha^2 Theta^(3/2) V / (d sqrt(pi)) (W per unit
    1 - e^2), Theta = sum |v - v_cell|^2 / (components (n - 1)) over a cell's n >= 2 particles."""
    volume = grid.spacing[0] * grid.spacing[1] * grid.spacing[2]
    cells = {}
    for x, d, v in zip(particles["position"], particles["diameter"], particles["velocity"]):
        key = tuple(min(max(int((x[a] - grid.origin[a]) // grid.spacing[a]), 0), grid.counts[a] - 1)
                    for a in range(3))
        cells.setdefault(key, []).append((d, v))
    total = 0.0
    for members in cells.values():
        n = len(members)
        if n < 2:
            continue
        mean = [sum(v[a] for _, v in members) / n for a in range(3)]
        theta = sum(sum((v[a] - mean[a]) ** 2 for a in range(3)) for _, v in members) / (components * (n - 1))
        alpha = sum(math.pi * d ** 3 / 6 for d, _ in members) / volume
        d = sum(d for d, _ in members) / n
        total += 12 * carnahan_starling(alpha) * density * alpha ** 2 * theta ** 1.5 * volume / (d * math.sqrt(math.pi))
    return total


def dissipation_scale_fields(run, time_name, grid, density, diameter):
    """S from the coupler's fields at a write time: alpha = 1 - voidFraction, Theta =
    granularTemperature, each cell of volume V; nan for a run that did not write them (particle
    statistics off)."""
    volume = grid.spacing[0] * grid.spacing[1] * grid.spacing[2]
    if not all(os.path.isfile(os.path.join(run, time_name, n)) for n in ("voidFraction", "granularTemperature")):
        return math.nan
    void, theta = field(run, time_name, "voidFraction"), field(run, time_name, "granularTemperature")
    return sum(12 * carnahan_starling(1 - eps) * density * (1 - eps) ** 2 * max(t, 0.0) ** 1.5 * volume
               / (diameter * math.sqrt(math.pi)) for eps, t in zip(void, theta))


def particle_files(run, since):
    folder = os.path.join(run, "VTK")
    if not os.path.isdir(folder):
        raise Reported(f"{run}: no VTK/ folder of particle files. Fix: give a finished TF-DEM run")
    found = []
    for name in os.listdir(folder):
        match = re.fullmatch(r"particles_([0-9.eE+-]+)\.vtk", name)
        if match and float(match.group(1)) >= since - 1e-9:
            found.append((float(match.group(1)), os.path.join(folder, name)))
    if len(found) < 2:
        raise Reported(f"{run}: fewer than two particle files from {since:g} s. Fix: a run that reached past it")
    return sorted(found)


def samples(run, since):
    """[(t, P, S, S_2d, S_fields)] of the run's particle files from `since` on."""
    files = particle_files(run, since)
    case = Case(run)
    grid, density, gravity = case.grid(), case.particle_density(), case.gravity_magnitude()
    out = []
    for t, path in files:
        try:
            p = vtk_particles(path)
        except (OSError, OutputError) as error:
            raise Reported(f"{path}: {error}")
        missing = [name for name in ("diameter", "velocity", "fluidForce") if name not in p]
        if missing:
            raise Reported(f"{path}: no {', '.join(missing)} in this particle file (a coupler older than its "
                           "fluidForce output). Fix: run the case again with this TFDEM")
        written = f"{t:g}"
        mean_d = sum(p["diameter"]) / len(p["diameter"])
        out.append((t, input_power(p, density, gravity), dissipation_scale(p, grid, density),
                    dissipation_scale(p, grid, density, components=2),
                    dissipation_scale_fields(run, written, grid, density, mean_d)))
    return out


def effective(d, s):
    """sqrt(1 - d / s); nan where no restitution in [0, 1] gives it (or s is unknown)."""
    return math.sqrt(1 - d / s) if 0 <= d <= s else math.nan


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("runs", nargs="*", default=DEFAULT_RUNS)
    parser.add_argument("--from", dest="since", type=float, default=DEFAULT_FROM)
    parser.add_argument("--csv", default=RESULTS)
    args = parser.parse_args(argv)
    try:
        per_run = {name: samples(name if os.path.isdir(name) else os.path.join(HERE, "runs", name), args.since)
                   for name in args.runs}
    except Reported as error:
        print(error, file=sys.stderr)
        return 1
    rows = []
    for path, values in per_run.items():
        name = os.path.basename(os.path.normpath(path))
        d, s, s2, sf = ([v[k] for v in values] for k in (1, 2, 3, 4))
        rows.append([name, len(values), statistics.mean(d), statistics.stdev(d) / math.sqrt(len(d)),
                     statistics.mean(s), effective(statistics.mean(d), statistics.mean(s)),
                     effective(statistics.mean(d), statistics.mean(s2)),
                     effective(statistics.mean(d), statistics.mean(sf))])
    means_d = [r[2] for r in rows]
    d_all = statistics.mean(means_d)
    # the realizations' scatter, or their own samples' errors where that is larger (two runs)
    within = math.sqrt(sum(r[3] ** 2 for r in rows)) / len(rows)
    d_err = max(statistics.stdev(means_d) / math.sqrt(len(means_d)), within) if len(means_d) > 1 else within
    s_all, s2_all, sf_all = (statistics.mean(v[k] for values in per_run.values() for v in values)
                             for k in (2, 3, 4))
    rows.append(["all", sum(r[1] for r in rows), d_all, d_err, s_all, effective(d_all, s_all),
                 effective(d_all, s2_all), effective(d_all, sf_all)])
    try:
        os.makedirs(os.path.dirname(os.path.abspath(args.csv)), exist_ok=True)
        with open(args.csv + ".tmp", "w", newline="") as f:
            out = csv.writer(f)
            out.writerow(["run", "particle files", "D = <P> (W)", "D standard error (W)",
                          "<S> (W per unit 1 - e^2)", "e_eff", "e_eff2d", "e_eff_fields"])
            for r in rows:
                out.writerow([r[0], r[1]] + [f"{x:.6g}" for x in r[2:]])
        os.replace(args.csv + ".tmp", args.csv)
    except OSError as error:
        if os.path.isfile(args.csv + ".tmp"):
            os.remove(args.csv + ".tmp")
        print(f"--csv {args.csv}: cannot write it ({error.strerror}). Fix: a file path in a writable folder",
              file=sys.stderr)
        return 1
    for r in rows:
        print(f"{r[0]:<16} {r[1]:3d} files  D = {r[2]:.4g} ± {r[3]:.2g} W  <S> = {r[4]:.4g} W  "
              f"e_eff = {r[5]:.3f}  (2-D Theta: {r[6]:.3f}; the coupler's fields: {r[7]:.3f})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
