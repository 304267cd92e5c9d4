#!/usr/bin/env python3
"""Seed 000's study, end to end: every run of study.yaml, two at a time (one per core), then
the report (report.py).

    study.py run [--runs a,b] [--end-time T] [--jobs N] [--root DIR]
    study.py report [--end-time T] [--root DIR]
    study.py status [--root DIR]

A run that finished is skipped; one that was stopped resumes from its last checkpoint (a
killed study continues where it was). A run that fails is reported with its log's last lines
and the others go on; the command then exits non-zero. --end-time shortens every run (the
averaging windows scale with it), for a quick check of the whole pipeline.
"""
import argparse
import difflib
import os
import re
import shutil
import sys

import yaml

from tfdem import TUTORIALS, tfm_models
from tfdem.batch import BatchError, CaseRun, clock, run_batch
from tfdem.bed import DP_FROM, write_bed_probes
from tfdem.case import Case, CaseError, set_dict_entries
from tfdem.errors import Reported
from tfdem.packing import pour, set_atom_types
from tfdem.run import DEFAULT_GAS_LAYOUT, RunError, check_gas_layout, command, environment, prepare_gas, run

import tfm_mechanism  # noqa: E402  (this folder: the TFM peer's changes, the perturbed start)

STUDY_DIR = os.path.dirname(os.path.abspath(__file__))


class StudyError(Exception):
    """A study definition or run problem, named."""


RUN_KEYS = ("bed", "coupling", "refine_x", "refine_y", "gas_step", "tfm", "tfm_solids", "ranks", "gas", "dp_from")
# the TFM solids stress: the templates' kinetic theory (v1912's), the phase-pressure model (a file
# here), or the kinetic-theory peer that bubbles (tfm_mechanism.PEER: MFIX's slip production,
# Jenkins & Zhang's effective restitution and -grad P_s; tfm_README.md)
TFM_SOLIDS = ("kinetic_theory", "phase_pressure", "kinetic_theory_peer")
PHASE_PRESSURE = "tfm_phase_pressure.particles"


def load_study(path=os.path.join(STUDY_DIR, "study.yaml")):
    try:
        with open(path) as f:
            study = yaml.safe_load(f)
    except OSError as e:
        raise StudyError(f"{path}: cannot read the study definition ({e.strerror})") from None
    except yaml.YAMLError as e:
        raise StudyError(f"{path}: malformed YAML: {e}") from None
    for name, spec in study["runs"].items():
        if not isinstance(spec, dict) or spec.get("bed") not in study["beds"]:
            raise StudyError(f"{path}: run {name}: bed must be one of {sorted(study['beds'])}, got {spec.get('bed')!r}")
        for key in spec:
            if key not in RUN_KEYS:
                near = difflib.get_close_matches(key, RUN_KEYS, 1)
                raise StudyError(f"{path}: run {name}: unknown key '{key}'"
                                 + (f" (did you mean '{near[0]}'?)" if near else "") + f"; valid: {', '.join(RUN_KEYS)}")
        for key in ("refine_x", "refine_y"):
            if key in spec and not (isinstance(spec[key], int) and spec[key] >= 1):
                raise StudyError(f"{path}: run {name}: {key} must be a whole number of cells per template cell, "
                                 f"1 or more, got {spec[key]!r}")
        step = spec.get("gas_step")
        if "gas_step" in spec and (isinstance(step, bool) or not (isinstance(step, (int, float)) and step > 0)):
            raise StudyError(f"{path}: run {name}: gas_step must be a time step in seconds above 0, "
                             f"got {spec['gas_step']!r}")
        ranks = spec.get("ranks", 1)
        if isinstance(ranks, bool) or not (isinstance(ranks, int) and ranks >= 1):
            raise StudyError(f"{path}: run {name}: ranks must be a whole number of MPI ranks, 1 or more, got {ranks!r}")
        if "gas" in spec:
            try:
                check_gas_layout(spec["gas"])
            except ValueError as e:
                raise StudyError(f"{path}: run {name}: gas: {e}") from None
        if "tfm_solids" in spec and (not spec.get("tfm") or spec["tfm_solids"] not in TFM_SOLIDS):
            raise StudyError(f"{path}: run {name}: tfm_solids is for TFM runs (tfm: true) and one of "
                             f"{', '.join(TFM_SOLIDS)}, got {spec['tfm_solids']!r}")
        if spec.get("dp_from", "inlet") not in DP_FROM:
            raise StudyError(f"{path}: run {name}: dp_from is where Delta p's lower level is, one of "
                             f"{', '.join(DP_FROM)}, got {spec['dp_from']!r}")
        if spec.get("tfm") and ("ranks" in spec or "gas" in spec):
            raise StudyError(f"{path}: run {name}: ranks and gas are for the coupled runs; the TFM runs are serial")
        if spec.get("tfm") and (spec.get("refine_x", 1) != 1 or "gas_step" in spec):
            raise StudyError(f"{path}: run {name}: refine_x and gas_step are for the coupled runs; the TFM template "
                             "refines y only")
    study["runs"] = with_realizations(study, path)
    return study


def with_realizations(study, path):
    """The runs, and each one of study.yaml's realizations list again once per seed, as
    <run>_r<k> from a poured packing of that seed (realizations.lattice checked: see
    realizations_only)."""
    spec = study.get("realizations")
    if not spec:
        return study["runs"]
    runs = dict(study["runs"])
    seeds = spec.get("seeds") or []
    if not seeds or any(not isinstance(s, int) or s <= 10000 for s in seeds):
        raise StudyError(f"{path}: realizations.seeds must list primes above 10000 (LIGGGHTS' insertion seeds), "
                         f"got {seeds!r}")
    realized, lattice = spec.get("runs") or [], spec.get("lattice") or []
    for key, names in (("runs", realized), ("lattice", lattice)):
        for name in names:
            if name not in study["runs"]:
                near = difflib.get_close_matches(name, list(study["runs"]), 1)
                raise StudyError(f"{path}: realizations.{key}: no run '{name}'"
                                 + (f" (did you mean '{near[0]}'?)" if near else ""))
    strays = [name for name in lattice if name not in realized]
    if strays:
        raise StudyError(f"{path}: realizations.lattice: {', '.join(strays)} not in realizations.runs (a run "
                         "without realizations runs from the lattice packing anyway)")
    for name in realized:
        for k, seed in enumerate(seeds, 1):
            runs[f"{name}_r{k}"] = dict(study["runs"][name], seed=seed)
    return runs


class Run(CaseRun):
    """One run of the study: its template, the changes, and its folder under runs/."""

    def __init__(self, name, spec, study, root):
        super().__init__(name, os.path.join(root, "runs", name))
        self.spec, self.study = spec, study
        bed = study["beds"][spec["bed"]]
        self.bed = spec["bed"]
        self.tfm = bool(spec.get("tfm", False))
        template = bed["tfm_template"] if self.tfm else bed["template"]
        self.template = os.path.join(STUDY_DIR if self.tfm else TUTORIALS, template)
        self.solver = "twoPhaseEulerFoam" if self.tfm else "tfdemFoam"
        self.dp_from = spec.get("dp_from", "inlet")

    def command(self):
        if self.tfm:
            return ["./Allsolve"]
        return command([self.solver], self.spec.get("ranks", 1), self.spec.get("gas", DEFAULT_GAS_LAYOUT))

    def complete_fields(self):
        if self.tfm:
            return ("U.air", "U.particles", "alpha.particles", "p", "Theta.particles")
        if self.spec.get("ranks", 1) > 1 and self.spec.get("gas") == "split":
            return ("no-resume",)  # as tfdem.bedstats: a split run's checkpoints are per processor
        return super().complete_fields()

    # Preparation -------------------------------------------------------------------------
    def prepare(self, end_time):
        """A fresh run folder: the template with the study's changes, mesh and initial state."""
        if os.path.isdir(self.case.path):
            shutil.rmtree(self.case.path)
        Case(self.template).copy_to(self.case.path, extra=("Allprepare", "Allsolve", "0.orig"))
        self.set_status(state="preparing", end_time=end_time)  # "prepared" once all of it is done (run_batch)
        self.case.set_control(endTime=end_time, writeInterval=self.write_interval(end_time), startFrom="startTime",
                              writePrecision=17)
        if self.tfm:
            self._prepare_tfm(self.spec.get("refine_y", 1))
        else:
            self._prepare_coupled(end_time)
        self._write_probes()

    def refinement(self):
        """(x, y) factors of the template's cells (1 x 2 cm jet: (2, 4) gives 0.5 x 0.5 cm)."""
        return self.spec.get("refine_x", 1), self.spec.get("refine_y", 1)

    def _prepare_coupled(self, end_time):
        case = self.case
        refine = max(self.refinement())
        for axis, factor in enumerate(self.refinement()):
            if factor != 1:
                case.scale_cells(axis, factor)
        if refine != 1 or "gas_step" in self.spec:
            # the same Courant number on the finer cells (the gas step rule, scene_check.h), or
            # the run's own gas_step, rounded down to a whole number of DEM steps that divides
            # the statistics interval
            target = self.spec.get("gas_step", case.delta_t() / refine)
            case.set_time_steps(gas=whole_gas_step(target, case.dem_time_step(), self.study["statistics_interval"]))
        for key, value in self.spec.get("coupling", {}).items():
            case.set_coupling(key, value)
        case.set_coupling("output.statistics_interval", self.study["statistics_interval"])
        case.set_coupling("output.particles_vtk", True)
        self._set_initial_gas(case.file("0", "U"))
        run(["blockMesh"], case.path, "log.blockMesh")
        data = self._packing()
        shutil.copy(data, case.file(os.path.basename(data).replace("poured_", "")))
        prepare_gas(case.path, self.spec.get("ranks", 1), self.spec.get("gas", DEFAULT_GAS_LAYOUT))

    def _prepare_tfm(self, refine):
        case = self.case
        path = case.file("system", "blockMeshDict")
        if refine != 1:
            set_dict_entries(path, ny=int(round(float(re.search(r"(?m)^ny\s+(\d+);", open(path).read()).group(1)) * refine)))
        self._set_initial_gas(case.file("0.orig", "U.air"))
        solids = self.spec.get("tfm_solids", "kinetic_theory")
        if solids == "phase_pressure":
            shutil.copy(os.path.join(STUDY_DIR, PHASE_PRESSURE), case.file("constant", "turbulenceProperties.particles"))
        elif solids == "kinetic_theory_peer":
            tfm_models.check_library()
            tfm_mechanism.apply_edits(case.path, tfm_mechanism.PEER[self.bed])
        run(["./Allprepare"], case.path, "log.Allprepare")
        if "seed" in self.spec:
            # a realization of a TFM run: the packed bed's alpha_s perturbed per cell, its seed
            tfm_mechanism.perturb(case.path, self.spec["seed"])

    def _set_initial_gas(self, path):
        """Seed 000 Table 1: the gas starts at v_g = U_mf (upward) in the whole domain."""
        u = self.study["beds"][self.bed]["initial_gas_velocity"]
        text = open(path).read()
        text, n = re.subn(r"(?m)^internalField\s+uniform\s+\([^)]*\);", f"internalField   uniform (0 {u} 0);", text)
        if n != 1:
            raise StudyError(f"{path}: no 'internalField uniform (...)' to set the initial gas velocity in")
        open(path, "w").write(text)

    def _packing(self):
        """The initial packing: the template's lattice one, made once in the tutorial folder,
        or for a realization (a seed) one poured in the run folder with as many particles
        and the template's friction."""
        if self.spec["bed"] == "jet":
            run(["./Allpack"], os.path.join(TUTORIALS, "jet_bed"), "log.Allpack")
            lattice = os.path.join(TUTORIALS, "jet_bed", "packed_bed.data")
        else:
            lattice = os.path.join(TUTORIALS, "bubbling_bed_packing", "bed.data")
            if not os.path.isfile(lattice):
                run(["./Allrun"], os.path.join(TUTORIALS, "bubbling_bed_packing"), "log.Allrun")
        if "seed" not in self.spec:
            return lattice
        header = open(lattice).read()
        count = int(re.search(r"(?m)^\s*(\d+)\s+atoms\s*$", header).group(1))
        types = int(re.search(r"(?m)^\s*(\d+)\s+atom types\s*$", header).group(1))
        script = open(self.case.file("in.bed")).read()
        friction = float(re.search(r"coefficientFriction peratomtypepair \d+ (\S+)", script).group(1))
        poured = self.case.file("poured_" + os.path.basename(lattice))
        print(f"{self.name}: {pour(self.case, count, out=os.path.basename(poured), seed=self.spec['seed'], friction=friction)}")
        set_atom_types(poured, types)
        return poured

    def write_interval(self, end_time):
        return self.study["write_interval"] * self._scale(end_time)

    def _scale(self, end_time):
        """A shortened run writes checkpoints and particle files as often, relative to its
        length (the sampling intervals stay)."""
        return min(1.0, end_time / self.study["end_time"])

    def _write_probes(self):
        """The study's function objects (tfdem.bed): the maps at every cell centre and p on
        the rows of cells either side of Delta p's levels (at 20 cm, Fig. 3; from the run's
        dp_from)."""
        write_bed_probes(self.case, self.study["field_interval"], self.study["statistics_interval"], self.tfm,
                         dp_from=self.dp_from)


def whole_gas_step(target, dem_step, interval):
    """The longest gas step up to `target` that is a whole number of DEM steps and divides the
    statistics interval (0.25 ms target, 0.02 ms DEM steps, 10 ms interval: 0.2 ms)."""
    steps_per_interval = round(interval / dem_step)
    most = max(1, int(target / dem_step + 1e-9))
    return dem_step * max(n for n in range(1, most + 1) if steps_per_interval % n == 0)


def realizations_only(study):
    """The runs that have realizations and are not run themselves (their entries stay, as the
    configurations the report groups the realizations by): all but those realizations.lattice
    names, which also run once from the template's lattice packing."""
    spec = study.get("realizations") or {}
    return set(spec.get("runs") or []) - set(spec.get("lattice") or [])


def selected_runs(study, names, root):
    runnable = {name: spec for name, spec in study["runs"].items() if name not in realizations_only(study)}
    runs = [Run(name, spec, study, root) for name, spec in runnable.items()]
    if names:
        unknown = [n for n in names if n not in study["runs"]]
        if unknown:
            raise StudyError(f"unknown run(s) {', '.join(unknown)}; study.yaml has: {', '.join(runnable)}")
        realized = [n for n in names if n not in runnable]
        if realized:
            raise StudyError(f"{', '.join(realized)}: run only as realizations ({realized[0]}_r1, {realized[0]}_r2, "
                             "...); list it under realizations.lattice in study.yaml to run it once from the "
                             "lattice packing too")
        runs = [r for r in runs if r.name in names]
    # the longest first, so the two cores finish together: the jet bed's (fine grid first, its
    # TFM as long as its coarse TF-DEM), then the uniform bed's (its TFM the shortest)
    return sorted(runs, key=lambda r: (r.bed != "jet", -r.refinement()[0] * r.refinement()[1], r.tfm and r.bed != "jet"))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("command", choices=("run", "report", "status"))
    parser.add_argument("--runs", default="", help="comma-separated run names (default: all)")
    parser.add_argument("--end-time", type=float, default=None, help="simulated seconds per run (default: study.yaml's)")
    parser.add_argument("--jobs", type=int, default=2, help="runs side by side (default 2: one per core)")
    parser.add_argument("--root", default=STUDY_DIR,
                        help="folder for runs/, report/ and results/ (the runs' records; default: the study's)")
    parser.add_argument("--study", default=os.path.join(STUDY_DIR, "study.yaml"), help="study definition")
    args = parser.parse_args(argv)
    try:
        study = load_study(args.study)
        end_time = args.end_time or study["end_time"]
        if not end_time > 0:
            raise StudyError(f"--end-time must be positive, got {end_time}")
        runs = selected_runs(study, [n for n in args.runs.split(",") if n], args.root)
        if args.command == "status":
            for r in runs:
                s = r.status()
                print(f"{r.name:<26} {s.get('state')}  {clock(s.get('wall_seconds', 0))}")
            return 0
        if args.command == "run":
            if shutil.which("twoPhaseEulerFoam", path=environment()["PATH"]) is None and any(r.tfm for r in runs):
                raise StudyError("twoPhaseEulerFoam is not on PATH: the TFM runs need Debian's openfoam package "
                                 "(./tfdem setup installs it)")
            ok = run_batch(runs, end_time, args.jobs)
            if not ok:
                print("some runs failed (above); the others' results are kept. Fix the cause and run again: "
                      "finished runs are skipped, stopped ones resume.", file=sys.stderr)
                return 1
            return 0
        import report
        from record import RecordError
        from replicates import ReplicatesError
        readme = os.path.join(args.root, "README.md")
        try:
            report.write_report(study, runs, end_time, os.path.join(args.root, "report"),
                                os.path.join(args.root, "results"),
                                readme if end_time == study["end_time"] and os.path.isfile(readme) else None)
        except (RecordError, ReplicatesError) as e:
            raise StudyError(str(e)) from None
        return 0
    except (StudyError, BatchError, CaseError, RunError, Reported, tfm_mechanism.MechanismError) as e:
        print(f"study.py: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        return 130


if __name__ == "__main__":
    sys.exit(main())
