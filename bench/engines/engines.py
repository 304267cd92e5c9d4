"""The two particle engines side by side on seed 000's beds (issue 25): each of the study's
independent realizations of the uniform-inflow and the jet bed (studies/seed000,
runs/<bed>_m1_r<k>: LIGGGHTS' soft spheres from a poured packing) run again with the
hard-sphere engine from the same packing, the same gas, mesh and coupling, its collision laws
the LIGGGHTS contacts' equivalents (tfdem.engines.hard_sphere_laws: e_n from k_n and eta_n,
seed 001 eq. 27; beta_0 from k_t and eta_t, eq. 30; mu as given).

    engines.py run [--beds uniform jet] [--end-time 20] [--jobs 1]
    engines.py report

`report` compares the bed statistics of the two ensembles (tfdem.accuracy's metrics over
the study's window; every statistic as the mean over realizations with its standard error)
and their costs (processor seconds per simulated second; for the hard spheres collisions per
particle per second and microseconds per collision), and writes results/engines.json and
results/engines.md (the table of bench/README.md).
"""
import argparse
import json
import os
import re
import sys

import yaml

from tfdem import STUDIES
from tfdem.accuracy import scalar_metrics
from tfdem.batch import CaseRun, run_batch
from tfdem.bed import BedOutputs, l1_difference
from tfdem.engines import convert_to_hard_sphere
from tfdem.liggghts import read_data_file
from tfdem.run import run
from tfdem.stats import ensemble

HERE = os.path.dirname(os.path.abspath(__file__))
STUDY = os.path.join(STUDIES, "seed000")
BEDS = ("uniform", "jet")
REALIZATIONS = (1, 2, 3, 4)
METRICS = ("dp20_mean", "dp20_std", "mean_height", "dp20_frequency", "bulk_coordination", "multicontact")
COLLISIONS = re.compile(r"TFDEM hard spheres: (\d+) pair and (\d+) wall collisions")


class EngineError(Exception):
    """A missing study run or output, named."""


def study_settings():
    with open(os.path.join(STUDY, "study.yaml")) as f:
        return yaml.safe_load(f)


def soft_sphere_run(bed, k):
    """The study's LIGGGHTS realization k of a bed (method 1), which must have finished."""
    run_ = CaseRun(f"{bed}_m1_r{k}", os.path.join(STUDY, "runs", f"{bed}_m1_r{k}"))
    if not run_.done():
        raise EngineError(f"{run_.case.path}: the study's realization has not finished: "
                          f"run `studies/seed000/study.py run --runs {run_.name}` first")
    return run_


class HardSphereRun(CaseRun):
    """Realization k of a bed with the hard-sphere engine, in runs/<bed>_hs_r<k>/."""

    def __init__(self, bed, k, root=HERE):
        super().__init__(f"{bed}_hs_r{k}", os.path.join(root, "runs", f"{bed}_hs_r{k}"))
        self.bed, self.k = bed, k

    def prepare(self, end_time):
        source = soft_sphere_run(self.bed, self.k).case
        data = os.path.basename(source.dem().read_data())
        case = source.copy_to(self.case.path, extra=(data,))
        self.case = case
        self.set_status(state="preparing", end_time=end_time)  # "prepared" once all of it is done (run_batch)
        case.set_control(endTime=end_time, writeInterval=min(float(source.control("writeInterval")), end_time),
                         startFrom="startTime")
        convert_to_hard_sphere(case)
        run(["blockMesh"], case.path, "log.blockMesh")


# Report ------------------------------------------------------------------------------------
def run_metrics(run_, start, end, batch, band):
    """One run's statistics over [start, end] and its cost per simulated second."""
    d = BedOutputs(run_.case)
    t, h = d.mean_height()
    out = {k: v["value"] for k, v in scalar_metrics(d.p_t, d.dp, t, h, start, end, batch, band).items()}
    stats = d.particles
    window = [i for i, ti in enumerate(stats["t"]) if start - 1e-9 <= ti <= end + 1e-9]
    for key in ("bulk_coordination", "multicontact"):
        out[key] = sum(stats[key][i] for i in window) / len(window)
    simulated = float(run_.status().get("end_time") or run_.case.end_time())
    out["cpu_per_second"] = run_.cpu_seconds() / simulated
    collisions = [COLLISIONS.search(line) for log in run_.logs() for line in open(log, errors="replace")]
    found = [c for c in collisions if c]
    if found:
        count = sum(int(c.group(1)) + int(c.group(2)) for c in found)
        n = len(read_data_file(run_.case.file(yaml.safe_load(open(run_.case.file("coupling.yaml")))["dem"]["particles"]))["id"])
        out["collisions_per_particle_second"] = count / n / simulated
        out["us_per_collision"] = 1e6 * run_.cpu_seconds() / count
    out["_solids"] = d.field_average(d.solids, start, end)
    return out


def map_l1s(soft, hard):
    """The solids maps' L1 between realizations: within each engine (pairs of realizations,
    the noise floor) and across the engines (every soft-hard pair)."""
    pairs = lambda runs: [l1_difference(a, b) for i, a in enumerate(runs) for b in runs[i + 1:]]
    within = pairs(soft) + pairs(hard)
    across = [l1_difference(a, b) for a in soft for b in hard]
    return {"within": ensemble(within), "across": ensemble(across)}


def report(beds, end_time=20.0, out=os.path.join(HERE, "results")):
    """The study's longer window (study.yaml windows, fractions of the end time) and batch."""
    study = study_settings()
    start, end = (f * end_time for f in study["windows"][-1])
    batch, band = study["batch"], 0.05
    results = {}
    for bed in beds:
        soft = [run_metrics(soft_sphere_run(bed, k), start, end, batch, band) for k in REALIZATIONS]
        hard_runs = [HardSphereRun(bed, k) for k in REALIZATIONS]
        missing = [r.name for r in hard_runs if not r.done()]
        if missing:
            print(f"{bed}: {', '.join(missing)} not finished; run `engines.py run --beds {bed}`")
            continue
        hard = [run_metrics(r, start, end, batch, band) for r in hard_runs]
        keys = [k for k in soft[0] if not k.startswith("_")]
        results[bed] = {
            "liggghts": {k: ensemble([m[k] for m in soft]) for k in keys},
            "hard_sphere": {k: ensemble([m[k] for m in hard]) for k in hard[0] if not k.startswith("_")},
            "solids_map_l1": map_l1s([m["_solids"] for m in soft], [m["_solids"] for m in hard]),
            "window": [start, end],
        }
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "engines.json"), "w") as f:
        json.dump(results, f, indent=1)
    table = markdown_table(results)
    with open(os.path.join(out, "engines.md"), "w") as f:
        f.write(table)
    print(table)
    return results


LABELS = {"dp20_mean": ("Δp(20 cm) mean (Pa)", 1, 0), "dp20_std": ("Δp(20 cm) std (Pa)", 1, 0),
          "mean_height": ("mean height (cm)", 100, 2), "dp20_frequency": ("Δp frequency (Hz)", 1, 2),
          "bulk_coordination": ("N_c", 1, 3), "multicontact": ("multicontact ratio", 1, 3),
          "cpu_per_second": ("processor s per simulated s", 1, 1),
          "collisions_per_particle_second": ("collisions per particle per s", 1, 0),
          "us_per_collision": ("µs per collision", 1, 3)}


def markdown_table(results):
    lines = []
    for bed, r in results.items():
        start, end = r["window"]
        lines += [f"**{bed} bed**, {start:g}-{end:g} s, mean ± standard error of {r['liggghts']['dp20_mean']['n']} "
                  "realizations:", "", "| | LIGGGHTS (soft spheres) | hard spheres | difference / its error |",
                  "|---|---|---|---|"]
        for key, (label, scale, digits) in LABELS.items():
            soft, hard = r["liggghts"].get(key), r["hard_sphere"].get(key)
            cell = lambda s: f"{s['mean'] * scale:.{digits}f} ± {s['error'] * scale:.{digits}f}" if s else "-"
            ratio = "-"
            if soft and hard and key in METRICS:
                sigma = (soft["error"] ** 2 + hard["error"] ** 2) ** 0.5
                ratio = f"{(hard['mean'] - soft['mean']) / sigma:+.1f}"
            lines.append(f"| {label} | {cell(soft)} | {cell(hard)} | {ratio} |")
        l1 = r["solids_map_l1"]
        lines += [f"| solids map L1 | within an engine {l1['within']['mean']:.4f} ± {l1['within']['error']:.4f} | "
                  f"across {l1['across']['mean']:.4f} ± {l1['across']['error']:.4f} | |", ""]
    return "\n".join(lines)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="action", required=True)
    run_parser = sub.add_parser("run")
    run_parser.add_argument("--beds", nargs="+", choices=BEDS, default=list(BEDS))
    run_parser.add_argument("--end-time", type=float, default=20.0)
    run_parser.add_argument("--jobs", type=int, default=1)
    report_parser = sub.add_parser("report")
    report_parser.add_argument("--beds", nargs="+", choices=BEDS, default=list(BEDS))
    args = parser.parse_args(argv)
    try:
        if args.action == "run":
            runs = [HardSphereRun(bed, k) for bed in args.beds for k in REALIZATIONS]
            if not run_batch(runs, args.end_time, args.jobs):
                return 1
        report(args.beds)
    except EngineError as e:
        print(f"engines.py: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
