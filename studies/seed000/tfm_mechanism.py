#!/usr/bin/env python3
"""Why the kinetic-theory TFM peer of the uniform-inflow bed stays laterally uniform (issue 52):
the template `tfm_bubbling_bed` run with one change at a time, each change one term of the
model, and OpenFOAM's own kinetic-theory `fluidisedBed` tutorial (which bubbles) beside it, as
shipped and with seed 000's restitution; the same measures read from every run.

    tfm_mechanism.py run [--variants NAME ...] [--end-time T] [--jobs 2]
    tfm_mechanism.py report
    tfm_mechanism.py measure
    tfm_mechanism.py snapshots NAME ...
    tfm_mechanism.py figure NAME ... --out PNG

`run` copies the variant's template to runs/tfm_mechanism/<variant>, makes its one change
(VARIANTS below), writes the fields every WRITE_INTERVAL, runs Allprepare and Allsolve to the
end time (END_TIME or DEFAULT_END_TIME unless given), and keeps the run's measures in
results/tfm_mechanism/<variant>.csv (one row per write). `report` reads those files and writes
results/tfm_mechanism.md (tfm_README.md quotes it); `measure` reads the measures again from the
runs as they stand, then reports. `snapshots` keeps alpha_s of six writes of a finished run's
second half (results/tfm_mechanism/snapshots/<variant>.csv) and `figure` draws those files, a
row of panels per variant (figures/tfm_bridge.png).

Measures at each write, over the bed's rows of cells (those whose initial mean solids fraction
is at least half the densest row's):
  lateral std   the standard deviation of alpha_s across a row, averaged over the rows
                (the walls' steady profile counts in it)
  departure     the same of alpha_s less its cell's mean over the run's second half: 0 for
                a steady profile and for horizontal layers moving as one (1-D waves and
                slugs), large for 2-D bubbles
  min alpha_s   the least solids fraction of those rows' cells (a void has alpha_s < 0.1)
  bed Theta     the granular temperature, alpha_s-weighted over those rows (m^2/s^2)
and from the solver's function objects where the case has them (seed 000's): the pressure
drop over the 20 cm above the bottom cell centre, and the whole bed's (the inlet's p less the
outlet's and the gas column's) as a fraction of the solids' weight per area. The report averages each over the second half of the run.
"""
import argparse
import concurrent.futures
import csv
import glob
import math
import os
import random
import re
import shutil
import subprocess
import sys
import tarfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "python"))
from tfdem.case import Case, dict_entry  # noqa: E402
from tfdem.errors import Reported  # noqa: E402
from tfdem.outputs import OutputError, field, joined_series, pressure_series, probes, times  # noqa: E402
from tfdem import tfm_models  # noqa: E402
from tfdem.physics import jenkins_zhang_effective_restitution, wen_yu_minimum_fluidization  # noqa: E402

TEMPLATE = os.path.join(HERE, "tfm_bubbling_bed")
JET_TEMPLATE = os.path.join(HERE, "tfm_jet_bed")
CACHE = os.environ.get("TFDEM_CACHE", os.path.join(HERE, "..", "..", ".cache"))
# OpenFOAM's own kinetic-theory bed (300 um, e 0.8, 5 mm cells), which bubbles: taken from the
# OpenFOAM source tarball that scripts/setup.sh downloads (Debian ships no tutorials)
FLUIDISED_BED = "tutorials/multiphase/twoPhaseEulerFoam/RAS/fluidisedBed"
RUNS = os.path.join(HERE, "runs", "tfm_mechanism")
RESULTS = os.path.join(HERE, "results", "tfm_mechanism")
KINETIC = "constant/turbulenceProperties.particles"
PHASES = "constant/phaseProperties"
WRITE_INTERVAL = {"seed000": 0.1, "seed000_jet": 0.1, "fluidised_bed": 0.02}  # s, per template
# Jenkins & Zhang (2002): the effective restitution of rough spheres, e - 3/2 mu exp(-3 mu),
# for Table 1's e and the DEM's friction mu: 0.97 and 0.1 (uniform bed), 0.86 and 0.2 (jet bed)
E_EFFECTIVE = jenkins_zhang_effective_restitution(0.97, 0.1)
E_EFFECTIVE_JET = jenkins_zhang_effective_restitution(0.86, 0.2)
# The conservative granular pressure force, -grad P_s (tfm_models/kineticTheoryConservative.H)
KINETIC_THEORY_LIBRARY = tfm_models.LIBRARY
LOAD_LIBRARY = ("system/controlDict", *tfm_models.load_library_edit())
CONSERVATIVE = [(KINETIC, pattern, replacement) for pattern, replacement in tfm_models.CONSERVATIVE_PRESSURE_EDITS] \
    + [LOAD_LIBRARY]


def slip_production(production):
    """The edits that replace v1912's production of Theta by gas-particle slip (Gidaspow's, with
    beta^2) by `production`, KochSangani (MFIX's) or none (tfm_models/granularSlipProduction.H):
    a new constant/fvOptions (an edit whose pattern is None writes the file)."""
    return [LOAD_LIBRARY, ("constant/fvOptions", None, tfm_models.slip_production_options(production))]


def restitution(e, template_e="0.97"):
    """The edit that sets the particle-particle restitution, from the template's value."""
    return (KINETIC, rf"(\n\s*e\s+){re.escape(template_e)};", rf"\g<1>{e};")


# OpenFOAM's fluidisedBed gas: air as a perfect gas at 600 K and 1e5 Pa (molar mass 28.9 g/mol)
HOT_AIR_DENSITY = 1e5 * 0.0289 / (8.314 * 600)  # kg/m3, 0.579
HOT_AIR_VISCOSITY = 1.84e-5  # Pa s
U_SEED000 = 1.92  # m/s, Table 1: 1.5 U_mf
# The inflow that puts seed 000's air at the tutorial's hot air's U/U_mf (1.92 m/s over its U_mf)
U_AT_HOT_AIR_RATIO = U_SEED000 / wen_yu_minimum_fluidization(0.0025, 2500, HOT_AIR_DENSITY, HOT_AIR_VISCOSITY, 9.81) \
    * wen_yu_minimum_fluidization(0.0025, 2526, 1.2, 1.8e-5, 9.81)
# The tutorial's bed is at 600 K but its inflow at 300 K: heated in the bed, the gas doubles its
# volume, so its superficial velocity in the bed is 1.92 m/s times the densities' ratio
COLD_AIR_DENSITY = 1e5 * 0.0289 / (8.314 * 300)  # kg/m3, 1.159
U_HEATED = U_SEED000 * COLD_AIR_DENSITY / HOT_AIR_DENSITY
U_AT_HEATED_RATIO = U_HEATED / wen_yu_minimum_fluidization(0.0025, 2500, HOT_AIR_DENSITY, HOT_AIR_VISCOSITY, 9.81) \
    * wen_yu_minimum_fluidization(0.0025, 2526, 1.2, 1.8e-5, 9.81)
AIR = "constant/thermophysicalProperties.air"
HOT_AIR_VISCOSITY_EDIT = (AIR, r"mu\s+1\.8e-05;", f"mu          {HOT_AIR_VISCOSITY:g};")
HOT_AIR = [(AIR, r"\n(\s*)rho\s+1\.2;", rf"\n\g<1>rho         {HOT_AIR_DENSITY:.4f};"), HOT_AIR_VISCOSITY_EDIT]
PERFECT_GAS = (AIR, r"equationOfState rhoConst;", "equationOfState perfectGas;")


def constant_density(rho):
    """The edits that make the tutorial's perfect gas one of constant density rho (kg/m3)."""
    return [(AIR, r"equationOfState perfectGas;", "equationOfState rhoConst;"),
            (AIR, r"(\n\s*thermodynamics\s*\{)", rf"\n    equationOfState\n    {{\n        rho         {rho};\n    }}\g<1>")]


def inflow(u):
    """The edits that set the template's inflow (superficial, m/s) from U_SEED000."""
    return [("0.orig/U.air", rf"uniform \(0 {re.escape(str(U_SEED000))} 0\)", f"uniform (0 {u:.4f} 0)", 2)]


PERTURBATION = 0.02  # relative, uniform per cell, of the packed bed's alpha_s
INLET_PERTURBATION = 0.1  # relative, uniform per inlet face, of the inflow velocity (held in time)
# A bed of bubbles: the rows' lateral std of alpha_s's departure from its cell's time mean
# above this (1-D waves and slugs, and a steady lateral profile, give 0)
BUBBLING = 0.02

# The shallow 2.5 mm tutorial with all of the template's settings (chain_8 below) forms voids;
# what else differs from the template is added to the template with the tutorial's gas at e 0.8:
# a perfect gas with its viscosity, the bed at 600 K (and its inflow too, or at 300 K as the
# tutorial's)
TUTORIAL_GAS_AT_E08 = [PERFECT_GAS, HOT_AIR_VISCOSITY_EDIT, restitution("0.8")]
BED_AND_INFLOW_AT_600K = [(f"0.orig/T.{phase}", r"uniform 300;", "uniform 600;", 4) for phase in ("air", "particles")]
BED_AT_600K_INFLOW_AT_300K = [(f"0.orig/T.{phase}", r"internalField\s+uniform 300;", "internalField   uniform 600;")
                              for phase in ("air", "particles")]
TUTORIAL_GAS = TUTORIAL_GAS_AT_E08 + BED_AND_INFLOW_AT_600K
TUTORIAL_START = [("0.orig/U.air", r"internalField\s+uniform \(0 1\.28 0\);", "internalField   uniform (0 1.92 0);"),
                  ("0.orig/Theta.particles", r"internalField\s+uniform 1e-4;", "internalField   uniform 0;")]
PARTICLE_DENSITY_2500 = [("constant/thermophysicalProperties.particles", r"(\n\s*rho\s+)2526;", r"\g<1>2500;")]
DEPTH_2CM = [("system/blockMeshDict", r"\ndepth\s+0\.0025;", "\ndepth   0.02;")]
TUTORIAL_REST = {
    "start": ("the tutorial's start: the gas at 1.92 m/s in every cell (not 1.28) and Theta 0 inside (plus the "
              "1e-4 reference level both add)", TUTORIAL_START),
    "particle_density_2500": ("the tutorial's particle density, 2500 kg/m3 (not 2526)", PARTICLE_DENSITY_2500),
    "depth_2cm": ("the tutorial's slab depth, 2 cm (not 2.5 mm; one cell deep, front and back empty)", DEPTH_2CM),
    "start_density_depth": ("all three: the tutorial's start, particle density and slab depth",
                            TUTORIAL_START + PARTICLE_DENSITY_2500 + DEPTH_2CM),
}

# Seed 000's solids stresses as it prints them (eqs. 7-11; MFIX's, Syamlal, Rogers & O'Brien
# 1993): P = K1 alpha_s^2 Theta with no kinetic alpha_s rho_s Theta term, lambda and mu of
# K2 and K3, and above alpha_s* = 0.58 the plastic regime of Schaeffer (1987), whose pressure
# 1e24 (alpha_s - 0.58)^10 Pa is MFIX's: 1e7 Pa at the template's packing 0.6, so that bed is
# laid down at 0.58
SEED000_VISCOUS_CLOSURES = [(KINETIC, r"granularPressureModel\s+Lun;", "granularPressureModel   SyamlalRogersOBrien;"),
                            (KINETIC, r"viscosityModel\s+Gidaspow;", "viscosityModel          Syamlal;"),
                            (KINETIC, r"conductivityModel\s+Gidaspow;", "conductivityModel       Syamlal;")]
SEED000_CLOSURES = SEED000_VISCOUS_CLOSURES + [
    (KINETIC, r"frictionalStressModel\s+JohnsonJacksonSchaeffer;", "frictionalStressModel   Schaeffer;"),
    (KINETIC, r"JohnsonJacksonSchaefferCoeffs", "SchaefferCoeffs"),
    ("Allprepare", r"\nalpha_s0=0\.6 ", "\nalpha_s0=0.58 ")]

# MFIX's production of Theta by slip and Jenkins & Zhang's effective restitution of the bed's
# Table 1 e and friction, per bed: what makes v1912's kinetic theory bubble (tfm_README.md, "The
# gas heats the solids")
SLIP_AND_RESTITUTION = {"uniform": slip_production("KochSangani") + [restitution(f"{E_EFFECTIVE:.4f}")],
                        "jet": slip_production("KochSangani") + [restitution(f"{E_EFFECTIVE_JET:.4f}", "0.86")]}
# The kinetic-theory peer, per study bed (study.py's tfm_solids: kinetic_theory_peer): those, with
# the solids pressure force as seed 000 eqs. 4 and 7 write it, -grad P_s (CONSERVATIVE; the
# library is loaded by the slip production's edits)
PEER = {bed: edits + CONSERVATIVE[:2] for bed, edits in SLIP_AND_RESTITUTION.items()}

# name: (what changes, [(file, pattern, replacement[, matches])]); patterns are regular
# expressions that must match exactly once in the template (or `matches` times)
SEED000_VARIANTS = {
    "template": ("nothing: e 0.97, Gidaspow viscosity and conductivity, Lun pressure, "
                 "Carnahan-Starling g0, friction from 0.58, Theta fixed at the inlet, zero gradient at the walls", []),
    "pressure_conservative": ("the solids pressure force as -grad P_s (MFIX's form), not -p' grad alpha_s: "
                              "adds -(P_s/Theta) grad Theta (tfm_models/kineticTheoryConservative)", CONSERVATIVE),
    "pressure_conservative_restitution_0.6": ("-grad P_s (as pressure_conservative) at e = 0.6, where the template bubbles "
                                              "(a diagnosis: does MFIX's form steady a bed that bubbles?)",
                                              CONSERVATIVE + [restitution("0.6")]),
    "restitution_0.859": (f"e = {E_EFFECTIVE:.3f}, Jenkins & Zhang's effective e of Table 1's e and mu",
                          [restitution(f"{E_EFFECTIVE:.4f}")]),
    "restitution_0.8": ("e = 0.8, OpenFOAM's fluidisedBed tutorial's value (a diagnosis)",
                        [restitution("0.8")]),
    "restitution_0.7": ("e = 0.7 (a diagnosis: where the bed starts to bubble)",
                        [restitution("0.7")]),
    "restitution_0.6": ("e = 0.6 (a diagnosis)", [restitution("0.6")]),
    "restitution_0.5": ("e = 0.5 (a diagnosis)", [restitution("0.5")]),
    "no_viscosity": ("solids shear viscosity off (viscosityModel none)",
                     [(KINETIC, r"viscosityModel\s+Gidaspow;", "viscosityModel          none;")]),
    "pressure_syamlal": ("granular pressure of Syamlal, Rogers & O'Brien (no kinetic alpha rho Theta term)",
                         [(KINETIC, r"granularPressureModel\s+Lun;", "granularPressureModel   SyamlalRogersOBrien;")]),
    "radial_sinclair_jackson": ("radial distribution of Sinclair & Jackson (the tutorial's)",
                                [(KINETIC, r"radialModel\s+CarnahanStarling;", "radialModel             SinclairJackson;")]),
    "conductivity_syamlal": ("conductivity of Syamlal, Rogers & O'Brien",
                             [(KINETIC, r"conductivityModel\s+Gidaspow;", "conductivityModel       Syamlal;")]),
    "equilibrium": ("algebraic Theta (equilibrium on: production = dissipation in each cell)",
                    [(KINETIC, r"equilibrium\s+off;", "equilibrium             on;")]),
    "friction_from_0.5": ("frictional stress from alpha_s 0.5 (the tutorial's onset)",
                          [(KINETIC, r"alphaMinFriction\s+0\.58;", "alphaMinFriction        0.5;")]),
    "drag_syamlal_obrien": ("drag of Syamlal & O'Brien (no switch at alpha_g 0.8)",
                            [(PHASES, r"type\s+GidaspowErgunWenYu;", "type            SyamlalOBrien;")]),
    "drag_ergun": ("Ergun's drag at every solids fraction (no Wen-Yu branch)",
                   [(PHASES, r"type\s+GidaspowErgunWenYu;", "type            Ergun;")]),
    "inlet_theta_zero_gradient": ("Theta zero gradient at the inlet (not held at 1e-4 m^2/s^2)",
                                  [("0.orig/Theta.particles", r"inlet\s*\{\s*type\s+fixedValue;\s*value\s+uniform 1e-4;",
                                    "inlet\n    {\n        type            zeroGradient;")]),
    "walls_johnson_jackson_theta": ("Johnson & Jackson's wall Theta (e_w 0.9, specularity 0.5): walls take up fluctuation energy",
                                    [("0.orig/Theta.particles", r"walls\s*\{\s*type\s+zeroGradient;",
                                      "walls\n    {\n        type            JohnsonJacksonParticleTheta;\n"
                                      "        restitutionCoefficient 0.9;\n        specularityCoefficient 0.5;\n"
                                      "        value           uniform 1e-4;")]),
    "perturbed": (f"start with alpha_s perturbed by +-{PERTURBATION:.0%} at random per cell (inventory kept)", []),
    "inlet_perturbed": (f"the inflow varied by +-{INLET_PERTURBATION:.0%} at random across the inlet's faces (its "
                        "mean kept), held in time: the distributor's symmetry broken", []),
    "explicit_phase_pressure": ("the solids pressure explicit in the phase-fraction equation (implicitPhasePressure no): "
                                "the numerics' own damping of alpha_s", [("system/fvSolution", r"implicitPhasePressure\s+yes;",
                                                                         "implicitPhasePressure no;")]),
    "deep_bed": ("a bed 0.5 m deep, as the fluidisedBed tutorial's (13,750 spheres in a column 1 m tall, "
                 "1 cm cells): the bed's aspect (a diagnosis)",
                 [("Allprepare", r"\nn_particles=4000 ", "\nn_particles=13750 "),
                  ("Allprepare", r"\nheight=0\.45 ", "\nheight=1.0 "),
                  ("system/blockMeshDict", r"(\(0(?:\.15)?\s+)0\.45(\s)", r"\g<1>1.0\g<2>", 4),
                  ("system/blockMeshDict", r"\nny\s+45;", "\nny      100;")]),
    "wide_bed": ("a bed 0.45 m wide, three times seed 000's (12,000 spheres, the same depth, 1 cm cells): "
                 "room for bubbles narrower than the column (a diagnosis)",
                 [("Allprepare", r"\nn_particles=4000 ", "\nn_particles=12000 "),
                  ("Allprepare", r"\nwidth=0\.15 ", "\nwidth=0.45 "),
                  ("system/blockMeshDict", r"\(0\.15(\s)", r"(0.45\g<1>", 4),
                  ("system/blockMeshDict", r"\nnx\s+15;", "\nnx      45;"),
                  ("system/controlDict", r"\(0\.075 ", "(0.225 ", 2)]),
    "walls_free_slip": ("solids slip freely at the walls (slip, not noSlip): no wall shear holds the dense layers",
                        [("0.orig/U.particles", r"walls\s*\{\s*type\s+noSlip;", "walls\n    {\n        type            slip;")]),
    "no_friction": ("no frictional stress (Fr 1e-12 Pa, the frictional pressure and viscosity vanish): dense layers "
                    "are not held as plugs", [(KINETIC, r"(\n\s*Fr\s+)0\.05;", r"\g<1>1e-12;")]),
    "time_step_1e-4": ("the time step held at 1e-4 s or below (maxDeltaT 1e-4, not 1e-3): the time integration's own damping",
                       [("system/controlDict", r"\nmaxDeltaT\s+1e-3;", "\nmaxDeltaT       1e-4;")]),
    "air_600K": (f"the gas of OpenFOAM's fluidisedBed: {HOT_AIR_DENSITY:.2f} kg/m3 and {HOT_AIR_VISCOSITY:g} Pa s "
                 "(air at 600 K), not 1.2 kg/m3 and 1.8e-5 Pa s, at the same 1.92 m/s (1.13 U_mf of that gas)", HOT_AIR),
    "air_600K_restitution_0.8": ("the fluidisedBed tutorial's gas (as air_600K) at its e = 0.8 (a diagnosis: the two "
                                 "settings in which the shallow tutorial differs from restitution_0.8)",
                                 HOT_AIR + [restitution("0.8")]),
    "air_compressible": ("the air a perfect gas (1.17 kg/m3 at 300 K and 1 atm), as the fluidisedBed tutorial's gas, "
                         "not of constant density",
                         [PERFECT_GAS]),
    "air_compressible_restitution_0.8": ("the air a perfect gas (as air_compressible) at e = 0.8",
                                         [PERFECT_GAS, restitution("0.8")]),
    "air_600K_compressible_restitution_0.8": ("the fluidisedBed tutorial's gas as it is there: a perfect gas at 600 K "
                                              "(0.58 kg/m3), 1.84e-5 Pa s, both phases at 600 K, at e = 0.8",
                                              TUTORIAL_GAS),
    "tutorial_gas_cold_inflow": ("the fluidisedBed tutorial's gas at e 0.8 (as air_600K_compressible_restitution_0.8) "
                                 "fed at 300 K as the tutorial's is (the bed at 600 K): the gas heats and expands "
                                 f"in the bed to {U_HEATED:.2f} m/s",
                                 TUTORIAL_GAS_AT_E08 + BED_AT_600K_INFLOW_AT_300K),
    "inflow_heated_tutorial_umf": (f"the inflow at {U_AT_HEATED_RATIO:.2f} m/s: the U/U_mf of the tutorial's heated gas "
                                   f"({U_HEATED:.2f} m/s at 600 K), not 1.5", inflow(U_AT_HEATED_RATIO)),
    "inflow_heated_tutorial_umf_restitution_0.8": (f"the inflow at {U_AT_HEATED_RATIO:.2f} m/s (as "
                                                   "inflow_heated_tutorial_umf) at e = 0.8",
                                                   inflow(U_AT_HEATED_RATIO) + [restitution("0.8")]),
    **{f"tutorial_gas_{name}": (f"the fluidisedBed tutorial's gas at e 0.8 (as air_600K_compressible_restitution_0.8) "
                                f"with {what}", TUTORIAL_GAS + changes)
       for name, (what, changes) in TUTORIAL_REST.items()},
    "slip_production_koch_sangani": ("Theta's production by gas-particle slip as MFIX's (Koch & Sangani 1999, "
                                     "81 alpha mu^2 |du|^2 / (g0 d^3 rho_s sqrt(pi Theta))), not v1912's Gidaspow form "
                                     "(beta^2 d |du|^2 / (4 alpha rho_s sqrt(pi Theta)))",
                                     slip_production("KochSangani")),
    "slip_production_koch_sangani_restitution_0.859": (f"MFIX's slip production (as slip_production_koch_sangani) at "
                                                       f"e = {E_EFFECTIVE:.3f}, Jenkins & Zhang's effective e of Table 1's "
                                                       "e and mu", SLIP_AND_RESTITUTION["uniform"]),
    "slip_production_koch_sangani_restitution_0.859_conservative": ("the peer: as slip_production_koch_sangani_"
                                                                    "restitution_0.859 with the solids pressure as "
                                                                    "-grad P_s (as pressure_conservative), MFIX's "
                                                                    "form", PEER["uniform"]),
    "slip_production_koch_sangani_perturbed": (f"MFIX's slip production (as slip_production_koch_sangani), the start "
                                               f"perturbed by +-{PERTURBATION:.0%} per cell (as perturbed)",
                                               slip_production("KochSangani")),
    "slip_production_none": ("no production of Theta by gas-particle slip (v1912's Gidaspow form taken away)",
                             slip_production("none")),
    "seed000_viscous_closures": ("seed 000's viscous-regime stresses as printed (eqs. 8-11, MFIX's): Syamlal-Rogers-O'Brien "
                                 "pressure K1 alpha^2 Theta, Syamlal viscosity and conductivity (friction the template's)",
                                 SEED000_VISCOUS_CLOSURES),
    "seed000_closures": ("seed 000's solids stresses as printed (eqs. 7-11): as seed000_viscous_closures with "
                         "Schaeffer's plastic regime above 0.58 (MFIX's), the bed laid down at 0.58",
                         SEED000_CLOSURES),
    "inflow_1.13_umf": (f"the inflow at {U_AT_HOT_AIR_RATIO:.2f} m/s, the hot-air tutorial's U/U_mf, not 1.5 U_mf",
                        inflow(U_AT_HOT_AIR_RATIO)),
    "fine_grid": ("cells of 0.5 cm (30 x 90)",
                  [("system/blockMeshDict", r"\nnx\s+15;", "\nnx      30;"),
                   ("system/blockMeshDict", r"\nny\s+45;", "\nny      90;")]),
}
# The jet bed (Tsuji's, tfm_jet_bed): its steady spout against the same measures
SEED000_JET_VARIANTS = {
    "jet_template": ("the jet bed's template: e 0.86 (Table 1), otherwise as the uniform bed's", []),
    "jet_slip_production_koch_sangani_restitution_0.695": (f"the jet bed with MFIX's slip production at e = "
                                                           f"{E_EFFECTIVE_JET:.3f} (Jenkins & Zhang's effective e)",
                                                           SLIP_AND_RESTITUTION["jet"]),
    "jet_slip_production_koch_sangani_restitution_0.695_perturbed": (
        f"as jet_slip_production_koch_sangani_restitution_0.695 from a start perturbed by "
        f"+-{PERTURBATION:.0%} per cell (as the study's realizations)", SLIP_AND_RESTITUTION["jet"]),
    "jet_slip_production_koch_sangani_restitution_0.695_conservative": (
        "the jet bed's peer: as jet_slip_production_koch_sangani_restitution_0.695 with the solids pressure as "
        "-grad P_s (as pressure_conservative), MFIX's form", PEER["jet"]),
    "jet_restitution_0.695": (f"the jet bed at e = {E_EFFECTIVE_JET:.3f}, Jenkins & Zhang's effective e of Table 1's e and "
                              "mu (0.86, 0.2)", [restitution(f"{E_EFFECTIVE_JET:.4f}", "0.86")]),
}
PARTICLES_2_5_MM = [(PHASES, r"(\n\s*d\s+)3e-4;", r"\g<1>0.0025;"),
                    ("0/U.air", r"internalField\s+uniform \(0 0\.25 0\);", "internalField   uniform (0 1.92 0);"),
                    ("0/U.air", r"inletVelocity\s+uniform \(0 0\.25 0\);", "inletVelocity      uniform (0 1.92 0);")]
FLUIDISED_BED_VARIANTS = {
    "fluidised_bed": ("OpenFOAM's RAS/fluidisedBed as shipped: 300 um, U 0.25 m/s, e 0.8, Sinclair-Jackson g0, "
                      "friction from 0.5, 5 mm cells", []),
    "fluidised_bed_restitution_0.97": ("the same with e = 0.97, seed 000's",
                                       [restitution("0.97", "0.8")]),
    "fluidised_bed_slip_production_koch_sangani": ("the same with MFIX's production of Theta by slip (Koch & Sangani "
                                                   "1999), not v1912's Gidaspow form: does the tutorial still bubble?",
                                                   slip_production("KochSangani")),
    "fluidised_bed_slip_production_koch_sangani_conservative": (
        "the same with the peer's closures: MFIX's slip production and -grad P_s (the tutorial's own e 0.8)",
        slip_production("KochSangani") + CONSERVATIVE[:2]),
    "fluidised_bed_particles_2.5mm": ("the same with seed 000's particles and inflow: d 2.5 mm, U 1.92 m/s",
                                      PARTICLES_2_5_MM),
    "fluidised_bed_particles_2.5mm_restitution_0.97": ("the same with d 2.5 mm, U 1.92 m/s and e = 0.97",
                                                       PARTICLES_2_5_MM + [restitution("0.97", "0.8")]),
}
# The 2.5 mm tutorial at its own e 0.8 with seed 000's inventory (a bed 15.9 cm deep, not 50 cm:
# it forms voids), then changed one setting at a time towards seed 000's template at e 0.8
# (restitution_0.8, flat layers): which difference keeps our bed in layers?
SEED000_INVENTORY_HEIGHT = 4000 * math.pi * 0.0025 ** 2 / 6 / (0.15 * 0.55)  # m: 4000 spheres at the tutorial's 0.55
SHALLOW = [("system/setFieldsDict", r"\(0\.15 0\.5 0\.1\)", f"(0.15 {SEED000_INVENTORY_HEIGHT:.4f} 0.1)"),
           ("Allprepare", r"(blockMesh > log\.blockMesh 2>&1\n)",
            r"\g<1>for a in air particles; do cp 0/alpha.$a.orig 0/alpha.$a; done\nsetFields > log.setFields 2>&1\n")]
TOWARDS_SEED000 = {
    "fluidised_bed_2.5mm_shallow_bed": (f"the 2.5 mm tutorial with seed 000's inventory: the bed "
                                        f"{SEED000_INVENTORY_HEIGHT * 100:.1f} cm deep at alpha_s 0.55, not 50 cm", []),
    "fluidised_bed_2.5mm_shallow_air_seed000": ("the shallow 2.5 mm tutorial with seed 000's air: 1.2 kg/m3 and "
                                                "1.8e-5 Pa s, not a perfect gas at 600 K and 1 bar (0.58 kg/m3, 1.84e-5 Pa s)",
                                                constant_density(1.2) + [(AIR, r"mu\s+1\.84e-05;", "mu          1.8e-05;")]),
    "fluidised_bed_2.5mm_shallow_air_incompressible": ("the shallow 2.5 mm tutorial with its hot air of constant density "
                                                       "(0.579 kg/m3, rhoConst), not a perfect gas",
                                                       constant_density(f"{HOT_AIR_DENSITY:.4f}")),
    "fluidised_bed_2.5mm_shallow_laminar_gas": ("the shallow 2.5 mm tutorial with the gas laminar, not k-epsilon "
                                                "(seed 000's template's)",
                                                [("constant/turbulenceProperties.air", r"simulationType\s+RAS;",
                                                  "simulationType  laminar;")]),
    "fluidised_bed_2.5mm_shallow_radial_carnahan_starling": ("the shallow 2.5 mm tutorial with Carnahan & Starling's g0 "
                                                             "(the template's)",
                                                             [(KINETIC, r"radialModel\s+SinclairJackson;",
                                                               "radialModel             CarnahanStarling;")]),
    "fluidised_bed_2.5mm_shallow_friction_seed000": ("the shallow 2.5 mm tutorial with the template's friction: "
                                                     "Johnson-Jackson-Schaeffer from alpha_s 0.58",
                                                     [(KINETIC, r"alphaMinFriction\s+0\.5;", "alphaMinFriction        0.58;"),
                                                      (KINETIC, r"JohnsonJackson;", "JohnsonJacksonSchaeffer;"),
                                                      (KINETIC, r"JohnsonJacksonCoeffs", "JohnsonJacksonSchaefferCoeffs")]),
    "fluidised_bed_2.5mm_shallow_time_step_adjustable": ("the shallow 2.5 mm tutorial with the template's time step: "
                                                         "adjusted to Courant 0.5, at most 1 ms (not fixed at 0.2 ms)",
                                                         [("system/controlDict", r"\nadjustTimeStep\s+no;",
                                                           "\nadjustTimeStep  yes;"),
                                                          ("system/controlDict", r"\nmaxCo\s+0\.9;", "\nmaxCo           0.5;"),
                                                          ("system/controlDict", r"\nmaxDeltaT\s+1e-05;",
                                                           "\nmaxDeltaT       1e-3;")]),
    "fluidised_bed_2.5mm_shallow_face_momentum": ("the shallow 2.5 mm tutorial with faceMomentum yes (the template's)",
                                                  [("system/fvSolution", r"(\n\s*nOuterCorrectors\s+3;)",
                                                    r"\g<1>\n    faceMomentum     yes;")]),
    "fluidised_bed_2.5mm_shallow_packed_0.6": ("the shallow 2.5 mm tutorial packed at alpha_s 0.6 (the template's), "
                                               f"{SEED000_INVENTORY_HEIGHT * 0.55 / 0.6 * 100:.1f} cm deep, not at 0.55",
                                               [("system/setFieldsDict", rf"\(0\.15 {SEED000_INVENTORY_HEIGHT:.4f} 0\.1\)",
                                                 f"(0.15 {SEED000_INVENTORY_HEIGHT * 0.55 / 0.6:.4f} 0.1)"),
                                                ("system/setFieldsDict", r"alpha\.air 0\.45", "alpha.air 0.4"),
                                                ("system/setFieldsDict", r"alpha\.particles 0\.55", "alpha.particles 0.6")]),
    "fluidised_bed_2.5mm_shallow_column_0.45m": ("the shallow 2.5 mm tutorial in a column 0.45 m tall (the template's), "
                                                 "not 1 m, on the same 5 mm cells",
                                                 [("system/blockMeshDict", r"\((0(?:\.15)?) 1 (-?0\.01)\)", r"(\g<1> 0.45 \g<2>)", 4),
                                                  ("system/blockMeshDict", r"\(30 200 1\)", "(30 90 1)")]),
    "fluidised_bed_2.5mm_shallow_cells_1cm": ("the shallow 2.5 mm tutorial on seed 000's 1 cm cells (15 x 100), not 5 mm",
                                              [("system/blockMeshDict", r"\(30 200 1\)", "(15 100 1)")]),
}
# two of those changes together (each alone leaves the voids)
for first, second in (("cells_1cm", "time_step_adjustable"), ("cells_1cm", "face_momentum")):
    TOWARDS_SEED000[f"fluidised_bed_2.5mm_shallow_{first}_{second}"] = (
        f"the shallow 2.5 mm tutorial with both {first} and {second} (as the two variants)",
        TOWARDS_SEED000[f"fluidised_bed_2.5mm_shallow_{first}"][1] + TOWARDS_SEED000[f"fluidised_bed_2.5mm_shallow_{second}"][1])
# the template's settings added one after another (the first two are cells_1cm_face_momentum):
# where do the slugs become layers? On 1 cm cells the 0.45 m column is 45 rows.
CHAIN = ("cells_1cm", "face_momentum", "time_step_adjustable", "laminar_gas", "radial_carnahan_starling",
         "friction_seed000", "packed_0.6", "column_0.45m")
CHAIN_EDITS = {name: TOWARDS_SEED000[f"fluidised_bed_2.5mm_shallow_{name}"][1] for name in CHAIN}
CHAIN_EDITS["column_0.45m"] = [CHAIN_EDITS["column_0.45m"][0], ("system/blockMeshDict", r"\(15 100 1\)", "(15 45 1)")]
for last in range(3, len(CHAIN) + 1):
    TOWARDS_SEED000[f"fluidised_bed_2.5mm_shallow_chain_{last}"] = (
        f"the shallow 2.5 mm tutorial with the template's first {last} settings: {', '.join(CHAIN[:last])}",
        [change for name in CHAIN[:last] for change in CHAIN_EDITS[name]])
LONG_CHAIN = f"fluidised_bed_2.5mm_shallow_chain_{len(CHAIN)}_to_6s"
TOWARDS_SEED000[LONG_CHAIN] = (f"the shallow 2.5 mm tutorial with all {len(CHAIN)} of the template's settings (as "
                               f"chain_{len(CHAIN)}) run to 6 s as the template's runs (measured over 3-6 s, not 1-2 s)",
                               TOWARDS_SEED000[f"fluidised_bed_2.5mm_shallow_chain_{len(CHAIN)}"][1])
FLUIDISED_BED_VARIANTS.update({name: (what, PARTICLES_2_5_MM + SHALLOW + changes) for name, (what, changes) in TOWARDS_SEED000.items()})
VARIANTS = {**{name: ("seed000",) + v for name, v in SEED000_VARIANTS.items()},
            **{name: ("seed000_jet",) + v for name, v in SEED000_JET_VARIANTS.items()},
            **{name: ("fluidised_bed",) + v for name, v in FLUIDISED_BED_VARIANTS.items()}}
DEFAULT_END_TIME = {"seed000": 6.0, "seed000_jet": 6.0, "fluidised_bed": 0.6}  # s, unless a variant's own below
END_TIME = {"fluidised_bed_particles_2.5mm": 2.0, "fluidised_bed_particles_2.5mm_restitution_0.97": 2.0,
            **{name: 2.0 for name in TOWARDS_SEED000}, LONG_CHAIN: 6.0}
CHANGES_AFTER_PREPARE = {"perturbed", "slip_production_koch_sangani_perturbed",
                         "jet_slip_production_koch_sangani_restitution_0.695_perturbed"}
CHANGES_BEFORE_PREPARE = {"inlet_perturbed"}


class MechanismError(Exception):
    """A variant that cannot be made or run, named."""


def edit(path, pattern, replacement, expected=1):
    with open(path) as f:
        text = f.read()
    new, count = re.subn(pattern, replacement, text)
    if count != expected:
        raise MechanismError(f"{path}: pattern {pattern!r} matched {count} times, not {expected}")
    with open(path, "w") as f:
        f.write(new)


def apply_edits(case, edits):
    """A variant's edits in the case folder: (file, pattern, replacement[, matches]) each, a
    pattern of None writing the file."""
    for path, pattern, replacement, *expected in edits:
        if pattern is None:
            with open(os.path.join(case, path), "w") as f:
                f.write(replacement)
        else:
            edit(os.path.join(case, path), pattern, replacement, *expected)


def set_control(case, end_time, write_interval):
    edit(os.path.join(case, "system/controlDict"), r"\nendTime\s[^;]*;", f"\nendTime {end_time:g};")
    edit(os.path.join(case, "system/controlDict"), r"\nwriteInterval\s[^;]*;", f"\nwriteInterval {write_interval:g};")


def grid(case):
    """(nx, ny) of the case's cells."""
    counts = Case(case).grid().counts
    return counts[0], counts[1]


def fluidised_bed_template():
    """OpenFOAM's RAS/fluidisedBed, extracted once from the source tarball into runs/."""
    folder = os.path.join(RUNS, "openfoam_fluidised_bed")
    if os.path.isdir(folder):
        return folder
    tarballs = sorted(glob.glob(os.path.join(CACHE, "download", "openfoam_1912*.orig.tar.*")))
    if not tarballs:
        raise MechanismError(f"no OpenFOAM source tarball in {CACHE}/download: run scripts/setup.sh "
                             "(it fetches it with apt-get source openfoam)")
    with tarfile.open(tarballs[0]) as tar:
        members = [m for m in tar.getmembers() if f"/{FLUIDISED_BED}/" in m.name]
        if not members:
            raise MechanismError(f"{tarballs[0]}: no {FLUIDISED_BED}")
        prefix = members[0].name.split(f"/{FLUIDISED_BED}/")[0] + f"/{FLUIDISED_BED}/"
        os.makedirs(folder + ".part", exist_ok=True)
        for member in members:
            member.name = member.name[len(prefix):]
            tar.extract(member, folder + ".part")
    shutil.copy(os.path.join(TEMPLATE, "Allsolve"), folder + ".part")
    with open(os.path.join(folder + ".part", "Allprepare"), "w") as f:
        f.write("#!/usr/bin/env bash\n# As the tutorial runs: its 0/ holds the initial bed already\n"
                "set -e\ncd \"$(dirname \"$0\")\"\nblockMesh > log.blockMesh 2>&1\n")
    os.chmod(os.path.join(folder + ".part", "Allprepare"), 0o755)
    os.rename(folder + ".part", folder)
    return folder


def perturb(case, seed=1):
    """alpha_s of the packed rows (at their initial value) times 1 + PERTURBATION u, u uniform
    on [-1, 1] per cell, then scaled so the rows hold what they held."""
    path = os.path.join(case, "0", "alpha.particles")
    with open(path) as f:
        text = f.read()
    found = re.search(r"internalField\s+nonuniform\s+List<scalar>\s*(\d+)\s*\((.*?)\)\s*;", text, flags=re.S)
    if not found:
        raise MechanismError(f"{path}: no nonuniform internalField to perturb")
    alpha = [float(v) for v in found.group(2).split()]
    packed = max(alpha)
    cells = [k for k, a in enumerate(alpha) if a == packed]
    rng = random.Random(seed)
    factors = [1 + PERTURBATION * rng.uniform(-1, 1) for _ in cells]
    scale = len(cells) / sum(factors)
    for k, factor in zip(cells, factors):
        alpha[k] = packed * factor * scale
    body = "\n".join(f"{a:.9g}" for a in alpha)
    text = text[:found.start()] + f"internalField   nonuniform List<scalar>\n{len(alpha)}\n(\n{body}\n)\n;" + text[found.end():]
    with open(path, "w") as f:
        f.write(text)


def perturb_inlet(case, seed=1):
    """0.orig/U.air's inletVelocity (0 U 0), uniform, made one value per inlet face (the
    bottom row's nx): U (1 + INLET_PERTURBATION u), u uniform on [-1, 1], scaled to keep the
    mean U."""
    path = os.path.join(case, "0.orig", "U.air")
    with open(path) as f:
        text = f.read()
    found = re.search(r"inletVelocity\s+uniform\s+\(\s*0\s+(\S+)\s+0\s*\)\s*;", text)
    if not found:
        raise MechanismError(f"{path}: no 'inletVelocity uniform (0 U 0);' to perturb")
    u, (nx, _) = float(found.group(1)), grid(case)
    rng = random.Random(seed)
    factors = [1 + INLET_PERTURBATION * rng.uniform(-1, 1) for _ in range(nx)]
    scale = nx / sum(factors)
    values = " ".join(f"(0 {u * f * scale:.9g} 0)" for f in factors)
    text = text[:found.start()] + f"inletVelocity   nonuniform List<vector> {nx} ({values});" + text[found.end():]
    with open(path, "w") as f:
        f.write(text)


def is_output(name):
    """A run's output in the template folder (a time folder, a log, postProcessing)."""
    try:
        float(name)
        return True
    except ValueError:
        return name.startswith("log.") or name == "postProcessing"


def run_variant(name, end_time):
    case = os.path.join(RUNS, name)
    os.makedirs(RUNS, exist_ok=True)
    run_case(name, case, end_time)
    write_measures(case, os.path.join(RESULTS, name + ".csv"), VARIANTS[name][0])
    return name


def run_case(name, case, end_time=None):
    """Variant `name` made afresh in the folder `case` (its template, its edits, its writes) and
    run to end_time (its own END_TIME or DEFAULT_END_TIME when None)."""
    template, _, edits = VARIANTS[name]
    if LOAD_LIBRARY in edits:
        tfm_models.check_library()  # before the earlier run is removed
    shutil.rmtree(case, ignore_errors=True)
    source = {"seed000": TEMPLATE, "seed000_jet": JET_TEMPLATE}.get(template) or fluidised_bed_template()
    shutil.copytree(source, case, ignore=lambda folder, names: [n for n in names if is_output(n) and n != "0"])
    apply_edits(case, edits)
    set_control(case, end_time or END_TIME.get(name, DEFAULT_END_TIME[template]), WRITE_INTERVAL[template])
    if name in CHANGES_BEFORE_PREPARE:
        perturb_inlet(case)
    for step in ("Allprepare", "Allsolve"):
        if step == "Allsolve" and name in CHANGES_AFTER_PREPARE:
            perturb(case)
        with open(os.path.join(case, f"log.{step}"), "w") as log:
            if subprocess.run([f"./{step}"], cwd=case, stdout=log, stderr=subprocess.STDOUT).returncode:
                raise MechanismError(f"{name}: {step} failed; see {case}/log.{step}")


def bed_rows(alpha, nx):
    """The rows whose initial mean solids fraction is at least half the densest row's."""
    means = [sum(alpha[j * nx:(j + 1) * nx]) / nx for j in range(len(alpha) // nx)]
    return [j for j, m in enumerate(means) if m >= 0.5 * max(means)]


def lateral_std(alpha, nx, rows):
    """The standard deviation of alpha across each row, averaged over the rows."""
    total = 0.0
    for j in rows:
        row = alpha[j * nx:(j + 1) * nx]
        mean = sum(row) / nx
        total += math.sqrt(sum((a - mean) ** 2 for a in row) / nx)
    return total / len(rows)


def bed_theta(alpha, theta, nx, rows):
    cells = range(rows[0] * nx, (rows[-1] + 1) * nx)
    return sum(alpha[k] * theta[k] for k in cells) / sum(alpha[k] for k in cells)


def whole_bed_support(case):
    """(t, whole-bed dp / bed weight per area): the area-averaged p on the inlet less the
    outlet's 101325 Pa and the gas column, over the solids' weight (their volume sum alpha_s V,
    less buoyancy) per inlet area; [] for a case without those function objects."""
    try:
        inlet = pressure_series(case, "pInlet")
        solids = joined_series(case, "solidsVolume", "volFieldValue.dat")
    except OutputError:
        return []
    c = Case(case)
    rho_s, rho_g = (float(dict_entry(c.file("constant", f"thermophysicalProperties.{phase}"), "rho"))
                    for phase in ("particles", "air"))
    lo, hi = c.mesh_bounds()
    g = c.gravity_magnitude()
    weight = solids[-1][1][0] * (rho_s - rho_g) * g / ((hi[0] - lo[0]) * (hi[2] - lo[2]))
    return [(t, (p - 101325 - rho_g * g * (hi[1] - lo[1])) / weight) for t, p in inlet]


def pressure_drop(case):
    """(t, dp) of the pressure probes: p(bottom cell centre) - p(20 cm above); [] without them."""
    try:
        return [(t, values[0] - values[1]) for t, values in probes(case)]
    except OutputError:
        return []


def row_major(case):
    """The cells' indices ordered row by row, left to right: a mesh of several blocks side by
    side (the jet bed's) numbers its cells block by block, each block row by row, so sorting
    by the cell centre's height (0/Cy, which Allprepare writes) and then by index gives that
    order; None (the cells' own order) for a case without 0/Cy."""
    if not os.path.exists(os.path.join(case, "0", "Cy")):
        return None
    cy = field(case, "0", "Cy")
    return sorted(range(len(cy)), key=lambda k: (round(cy[k], 9), k))


def rows_of(values, order):
    return values if order is None or len(values) == 1 else [values[k] for k in order]


def write_measures(case, path, template):
    """One row per write: the measures of the module's doc. The departure from the cells' mean
    is alpha_s less its cell's time mean over the run's second half: a steady lateral profile
    (the walls') and horizontal layers moving as one (1-D waves, slugs) both give 0 there. The
    jet bed's inlet is its jet alone, so its whole-bed support is left out (nan)."""
    write_interval = WRITE_INTERVAL[template]
    nx, ny = grid(case)
    order = row_major(case)
    rows = bed_rows(rows_of(field(case, "0", "alpha.particles"), order), nx)
    written = [name for name in times(case) if float(name) > 0]
    alpha = {name: rows_of(field(case, name, "alpha.particles"), order) for name in written}
    end = float(written[-1])
    late = [name for name in written if float(name) >= end / 2 - 1e-9]
    cell_mean = [sum(alpha[name][k] for name in late) / len(late) for k in range(nx * ny)]
    dp = pressure_drop(case)
    support = whole_bed_support(case) if template != "seed000_jet" else []
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", newline="") as f:
        out = csv.writer(f)
        out.writerow(["t (s)", "lateral std of alpha_s", "lateral std of alpha_s less its cell's mean",
                      "min alpha_s", "bed Theta (m2/s2)",
                      "dp 20 cm (Pa), mean over the write interval", "dp 20 cm (Pa), std over the write interval",
                      "whole-bed dp / bed weight, mean over the write interval"])
        for name in written:
            t, a = float(name), alpha[name]
            theta = rows_of(field(case, name, "Theta.particles"), order)
            theta = theta * len(a) if len(theta) == 1 else theta
            departure = [x - m for x, m in zip(a, cell_mean)]
            least = min(a[k] for k in range(rows[0] * nx, (rows[-1] + 1) * nx))
            window = [p for s, p in dp if t - write_interval < s <= t + 1e-9] or [math.nan]
            mean = sum(window) / len(window)
            spread = math.sqrt(sum((p - mean) ** 2 for p in window) / len(window))
            held = [w for s, w in support if t - write_interval < s <= t + 1e-9] or [math.nan]
            out.writerow([f"{t:g}", f"{lateral_std(a, nx, rows):.6g}", f"{lateral_std(departure, nx, rows):.6g}",
                          f"{least:.6g}", f"{bed_theta(a, theta, nx, rows):.6g}", f"{mean:.6g}", f"{spread:.6g}",
                          f"{sum(held) / len(held):.6g}"])


def read_measures(name):
    with open(os.path.join(RESULTS, name + ".csv")) as f:
        rows = list(csv.reader(f))[1:]
    return [[float(v) for v in row] for row in rows]


def summary(name):
    """Second-half means: lateral std, min alpha_s, bed Theta, dp mean, dp std (from the
    write intervals' means and spreads)."""
    rows = read_measures(name)
    end = rows[-1][0]
    late = [r for r in rows if r[0] >= end / 2 - 1e-9]
    mean = lambda k: sum(r[k] for r in late) / len(late)  # noqa: E731
    dp_mean = mean(5)
    dp_var = sum(r[6] ** 2 + (r[5] - dp_mean) ** 2 for r in late) / len(late)
    return {"end": end, "from": end / 2, "lateral_std": mean(1), "departure_std": mean(2),
            "min_alpha": min(r[3] for r in late), "theta": mean(4), "dp_mean": dp_mean, "dp_std": math.sqrt(dp_var),
            "support": mean(7)}


def report_text():
    """The table of the variants whose measures are in results/tfm_mechanism/, and the names of
    those that are not."""
    lines = ["| variant | change | lateral std of α_s | of its departure from the cell's mean | least α_s "
             "| bed Θ (m²/s²) | Δp 20 cm (Pa) | Δp std (Pa) | whole-bed Δp / weight | span (s) | 2-D bubbles |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    done = [name for name in VARIANTS if os.path.exists(os.path.join(RESULTS, name + ".csv"))]
    for name in done:
        s = summary(name)
        dp = "–" if math.isnan(s["dp_mean"]) else f"{s['dp_mean']:.0f} | {s['dp_std']:.0f}"
        lines.append(f"| `{name}` | {VARIANTS[name][1]} | {s['lateral_std']:.4f} | {s['departure_std']:.4f} | "
                     f"{s['min_alpha']:.3f} | {s['theta']:.2e} | {dp if dp != '–' else '– | –'} | "
                     f"{'–' if math.isnan(s['support']) else format(s['support'], '.3f')} | {s['from']:g}–{s['end']:g} | {'yes' if s['departure_std'] > BUBBLING else 'no'} |")
    head = ("Kinetic-theory TFM, one change at a time: seed 000's uniform-inflow bed (`tfm_bubbling_bed`) "
            "and OpenFOAM's `fluidisedBed` tutorial (`tfm_mechanism.py`). Averages over the second half of "
            "each run of the fields written every "
            + ", ".join(f"{v:g} s ({k})" for k, v in WRITE_INTERVAL.items())
            + f", over the bed's rows. 2-D bubbles: the rows' mean lateral std of α_s's departure from its "
            f"cell's mean above {BUBBLING}.\n\n")
    return head + "\n".join(lines) + "\n", [n for n in VARIANTS if n not in done]


def report():
    text, missing = report_text()
    with open(os.path.join(HERE, "results", "tfm_mechanism.md"), "w") as f:
        f.write(text)
    print(text, end="")
    if missing:
        print("not run: " + " ".join(missing))


SNAPSHOTS = os.path.join(RESULTS, "snapshots")


def write_snapshots(name, count=6):
    """alpha_s of `count` writes evenly spread over the run's second half, one line per row of
    cells (bottom first): results/tfm_mechanism/snapshots/<variant>.csv, the figure's input."""
    case = os.path.join(RUNS, name)
    if not os.path.isdir(case):
        raise MechanismError(f"{case}: no run of {name} here: `tfm_mechanism.py run --variants {name}` first")
    nx, ny = grid(case)
    written = [t for t in times(case) if float(t) > 0]
    if len(written) < count:
        raise MechanismError(f"{case}: {len(written)} writes, fewer than the {count} snapshots: an unfinished run")
    late = [t for t in written if float(t) >= float(written[-1]) / 2 - 1e-9]
    chosen = [late[round(k * (len(late) - 1) / (count - 1))] for k in range(count)]
    lo, hi = Case(case).mesh_bounds()
    os.makedirs(SNAPSHOTS, exist_ok=True)
    path = os.path.join(SNAPSHOTS, name + ".csv")
    with open(path + ".tmp", "w", newline="") as f:
        out = csv.writer(f)
        out.writerow(["t (s)", "row", f"alpha_s of the row's {nx} cells, left to right; cells "
                      f"{(hi[0] - lo[0]) / nx * 100:g} x {(hi[1] - lo[1]) / ny * 100:g} cm"])
        order = row_major(case)
        for t in chosen:
            alpha = rows_of(field(case, t, "alpha.particles"), order)
            for j in range(ny):
                out.writerow([t, j] + [f"{a:.4g}" for a in alpha[j * nx:(j + 1) * nx]])
    os.replace(path + ".tmp", path)


def read_snapshots(name):
    """{t: rows of alpha_s} and (cell width, cell height) in cm, from the snapshot file."""
    with open(os.path.join(SNAPSHOTS, name + ".csv")) as f:
        rows = list(csv.reader(f))
    found = re.search(r"cells (\S+) x (\S+) cm", ",".join(rows[0]))
    frames = {}
    for row in rows[1:]:
        frames.setdefault(row[0], []).append([float(a) for a in row[2:]])
    return frames, (float(found.group(1)), float(found.group(2)))


def draw_snapshots(names, path, height_cm=30):
    """One column of panels per variant, alpha_s at each snapshot, the lowest height_cm shown."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    data = [read_snapshots(name) for name in names]
    count = max(len(frames) for frames, _ in data)
    fig, axes = plt.subplots(len(names), count, figsize=(1.3 * count, 2.9 * len(names)), squeeze=False)
    for row, (name, (frames, (dx, dy))) in enumerate(zip(names, data)):
        for col, (t, alpha) in enumerate(frames.items()):
            ax = axes[row][col]
            shown = alpha[:max(1, round(height_cm / dy))]
            image = ax.imshow(shown, origin="lower", vmin=0, vmax=0.62, cmap="viridis",
                              extent=(0, dx * len(shown[0]), 0, dy * len(shown)))
            ax.set_title(f"{float(t):g} s", fontsize=8)
            ax.tick_params(labelsize=7)
            if col == 0:
                ax.set_ylabel(f"{name}\nheight (cm)", fontsize=7)
    fig.colorbar(image, ax=axes, shrink=0.6, label="solids fraction α_s")
    fig.savefig(path, dpi=90, bbox_inches="tight")
    plt.close(fig)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="run variants (all by default)")
    run.add_argument("--variants", nargs="+", default=list(VARIANTS), choices=list(VARIANTS), metavar="NAME")
    run.add_argument("--end-time", type=float, default=None,
                     help="s; default " + ", ".join(f"{v:g} s for {k}" for k, v in DEFAULT_END_TIME.items()))
    run.add_argument("--jobs", type=int, default=2)
    sub.add_parser("report", help="the table of the variants run")
    snap = sub.add_parser("snapshots", help="keep alpha_s of six writes of the second half of runs in "
                                            "results/tfm_mechanism/snapshots/")
    snap.add_argument("variants", nargs="+", choices=list(VARIANTS), metavar="NAME")
    figure = sub.add_parser("figure", help="draw kept snapshots, one row of panels per variant")
    figure.add_argument("variants", nargs="+", choices=list(VARIANTS), metavar="NAME")
    figure.add_argument("--out", required=True, help="PNG to write")
    sub.add_parser("measure", help="read the measures again from the runs in runs/tfm_mechanism/")
    args = parser.parse_args(argv)
    if args.command == "snapshots":
        try:
            for name in args.variants:
                write_snapshots(name)
        except (MechanismError, OutputError) as error:
            print(f"tfm_mechanism.py: {error}", file=sys.stderr)
            return 1
        return 0
    if args.command == "figure":
        missing = [n for n in args.variants if not os.path.exists(os.path.join(SNAPSHOTS, n + ".csv"))]
        if missing:
            print(f"tfm_mechanism.py: no snapshots of {' '.join(missing)}: run `tfm_mechanism.py snapshots` "
                  "on a finished run first", file=sys.stderr)
            return 1
        try:
            draw_snapshots(args.variants, args.out)
        except OSError as error:
            print(f"tfm_mechanism.py: --out {args.out}: cannot write it ({error.strerror}). Fix: a PNG path in a "
                  "writable folder", file=sys.stderr)
            return 1
        return 0
    if args.command == "measure":
        for name in VARIANTS:
            case = os.path.join(RUNS, name)
            if os.path.isdir(case) and len(times(case)) > 1:
                write_measures(case, os.path.join(RESULTS, name + ".csv"), VARIANTS[name][0])
    if args.command in ("measure", "report"):
        report()
        return 0
    if any(VARIANTS[name][0] == "fluidised_bed" for name in args.variants):
        fluidised_bed_template()  # once, before the runs that copy it
    failed = 0
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futures = {pool.submit(run_variant, name, args.end_time): name for name in args.variants}
        for future in concurrent.futures.as_completed(futures):
            try:
                print(f"{future.result()}: done", flush=True)
            except (MechanismError, Reported) as error:
                print(error, file=sys.stderr, flush=True)
                failed += 1
    report()
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
