"""Hard cases, as a demanding user runs them: each must run to its end with every particle and
its mass accounted for (and its own check holding), or -- where the scene cannot be simulated
-- stop with a message naming the cause and the fix; a set-up that deserves a warning must
print it. Nothing may crash or hang (probe.py classifies each: handled, unclear, crash, hang,
silent; the counts go to outcomes.json and the README).

Seed 000's beds run briefly from packings made once: the uniform bed (4000 spheres of 2.5 mm)
and the central-jet bed (2400 of 4 mm). Groups: speeds and time steps; contacts; mapping and
drag; particles in and out; restart and outputs; ranks and layouts; set-up warnings.
"""
import math
import os
import re
import shutil
import signal
import subprocess
import time

from tfdem import BUILD_DIR, SOURCE_DIR, TUTORIALS
from tfdem.case import Case
from tfdem.outputs import joined_series, particle_statistics
from tfdem.run import write_decompose_dict, environment
import probe

WHERE = os.path.join(BUILD_DIR, "test-runs", "stability")
BED = os.path.join(TUTORIALS, "bubbling_bed")
JET = os.path.join(TUTORIALS, "jet_bed")
SETTLING = os.path.join(TUTORIALS, "settling_particle")
BLOWOUT = os.path.join(SOURCE_DIR, "tests", "cases", "blowout")
POISEUILLE = os.path.join(TUTORIALS, "poiseuille_channel")
ZERO = os.path.join(SOURCE_DIR, "tests", "cases", "zero_particles")
PACKED = os.path.join(TUTORIALS, "packed_bed_ergun")
BED_MASS = 2526 * math.pi * 0.0025 ** 3 / 6
JET_MASS = 2700 * math.pi * 0.004 ** 3 / 6


def pack(name, variables):
    where = os.path.join(WHERE, name)
    if os.path.isfile(os.path.join(where, "done")):
        return where
    shutil.rmtree(where, ignore_errors=True)
    os.makedirs(where)
    code, output, _ = probe.run(["tfdem-liggghts", "-in", os.path.join(TUTORIALS, "bubbling_bed_packing", "in.pack")]
                                + variables + ["-log", "log.liggghts"], where, "log.screen", timeout=600)
    assert code == 0, output[-3000:]
    open(os.path.join(where, "done"), "w").close()
    return where




def set_damping(case, particles, walls):
    script = case.file("in.bed")
    text = open(script).read()
    for prop in ("gamman_abs", "gammat_abs"):
        text = re.sub(rf"(fix\s+m\d all property/global {prop} peratomtypepair 2) \S+ \S+ \S+ \S+",
                      rf"\1 {particles} {walls} {walls} {walls}", text)
    open(script, "w").write(text)


class Hard:
    """A hard case: a template, what to change, how long to run, what must hold after."""

    def __init__(self, group, name, template, data=None, end_time=0.05, change=None, check=None, ranks=1,
                 gas="whole", stop_words=None, warn_words=(), particle_mass=None, statistics=True, timeout=300,
                 write_interval=None):
        self.__dict__.update(locals())
        del self.__dict__["self"]


def accounted(case, output, particle_mass):
    """Every particle and its mass at the end as at the start, from the statistics series."""
    start = int(re.search(r"TFDEM coupling: (\d+) particles", output).group(1))
    stats = particle_statistics(case.path)
    left = sum(int(v[1]) for _, v in joined_series(case.path, "tfdemOutlets", "outlets.dat")) \
        if os.path.isdir(case.file("postProcessing", "tfdemOutlets")) else 0
    count = int(stats["particles"][-1])
    if count + left != start:
        return False, f"{count} particles in the bed + {left} left through outlets, {start} at the start"
    if particle_mass and start and abs(stats["mass"][-1] - (start - left) * particle_mass) > 1e-12 * start * particle_mass:
        return False, f"mass {stats['mass'][-1]!r} kg, expected {(start - left) * particle_mass!r}"
    return True, f"{count} in the bed + {left} left = {start} at the start"


def run_hard(suite, h):
    case_dir = os.path.join(WHERE, probe.slug(h.group + "_" + h.name))
    case = Case(h.template).copy_to(case_dir)
    if h.data:
        os.symlink(h.data, case.file(os.path.basename(h.data)))
    case.set_control(endTime=h.end_time, writeControl="runTime", writeInterval=h.write_interval or h.end_time)
    if h.statistics:
        case.set_coupling("output.statistics_interval", h.end_time / 10)
    if h.change:
        h.change(case)
    probe.run(["blockMesh"], case.path, "log.blockMesh")
    if h.ranks > 1 and h.gas == "split":
        write_decompose_dict(case.path, (h.ranks, 1, 1))
        probe.run(["decomposePar", "-force"], case.path, "log.decomposePar")
    (code, output, timed_out), seconds = probe.timed(probe.run, ["tfdemFoam"], case.path, "log.tfdemFoam", h.ranks,
                                                     h.gas, h.timeout)
    if h.stop_words is not None:
        verdict, missing = probe.verdict_of_failure(code, output, timed_out, h.stop_words)
        suite.record(h.group, h.name, "handled" if verdict == "clear" else verdict, seconds,
                     output if verdict != "clear" else "", missing)
        return
    if timed_out or probe.crashed(code, output):
        suite.record(h.group, h.name, "hang" if timed_out else "crash", seconds, output)
        return
    if code != 0 or not re.search(r"(?m)^End$", output):
        suite.record(h.group, h.name, "unclear", seconds, output)
        return
    missing = [w for w in h.warn_words if w not in output]
    ok, detail = accounted(case, output, h.particle_mass) if h.statistics else (True, "")
    if ok and h.check:
        ok, detail = h.check(case, output)
    suite.record(h.group, h.name, "handled" if ok and not missing else "silent", seconds,
                 "" if ok and not missing else detail + "\n" + output[-3000:], missing)


# -- changes and checks ------------------------------------------------------------------------

def inflow(speed, field="U", old="value uniform (0 39 0)"):
    return lambda case: probe.edit(case.file("0", field), old, f"value uniform (0 {speed} 0)")


def coupling(**entries):
    def change(case):
        for key, value in entries.items():
            case.set_coupling(key.replace("__", "."), value)
    return change


def small_cells(method):
    def change(case):
        case.scale_cells(0, 5)  # 1 cm -> 2 mm
        case.scale_cells(1, 5)
        case.set_coupling("coupling.void_fraction.method", method)
    return change


def squeezed(fraction):
    """The packing's heights scaled by `fraction`: overlaps far deeper than its weight makes."""
    def change(case):
        source = os.path.realpath(case.file("bed.data"))
        os.remove(case.file("bed.data"))
        lines, out, atoms = open(source).read().split("\n"), [], False
        for line in lines:
            words = line.split()
            if line.startswith("Atoms"):
                atoms = True
            elif line.startswith("Velocities"):
                atoms = False
            elif atoms and len(words) >= 7:
                words[5] = repr(float(words[5]) * fraction)
                line = " ".join(words)
            out.append(line)
        open(case.file("bed.data"), "w").write("\n".join(out))
    return change


def no_gravity_in_dem(case):
    probe.edit(case.file("in.bed"), "fix             grav all gravity 9.81 vector 0 -1 0\n", "")


def coupling_fix_included(case):
    probe.edit(case.file("in.bed"), "fix             fluid all tfdem/coupling\n", "include coupling.in\n")
    open(case.file("coupling.in"), "w").write("fix             fluid all tfdem/coupling\n")


def hertz_bed(case):
    """The uniform bed with Hertz contacts (E 5 MPa, nu 0.3, e 0.9) at its DEM step."""
    text = open(case.file("in.bed")).read()
    text = re.sub(r"(?m)^fix\s+m[1-4] .*\n", "", text)
    text = text.replace("fix             m5", "fix             m1 all property/global youngsModulus peratomtype 5e6 5e6\n"
                        "fix             m2 all property/global poissonsRatio peratomtype 0.3 0.3\n"
                        "fix             m3 all property/global coefficientRestitution peratomtypepair 2 0.9 0.9 0.9 0.9\n"
                        "fix             m5")
    text = text.replace("hooke/stiffness", "hertz").replace(" absolute_damping on", "")
    open(case.file("in.bed"), "w").write(text)


def falling_fast(case):
    probe.edit(case.file("in.bed"), "fix             fluid all tfdem/coupling",
               "velocity        all set 0 -3 0\nfix             fluid all tfdem/coupling")


def frozen_bed(case):
    probe.edit(case.file("in.bed"), "fix             integr all nve/sphere\n", "")


def dem_step_at_limit(case):
    """t_c/12: above the rule's 57 steps (advice printed), below the t_c/10 refusal."""
    probe.edit(case.file("in.bed"), "timestep        6.25e-6", "timestep        2.5e-5")
    case.set_coupling("dem.coupling_interval", 20)  # the same gas step, 5e-4 s


def courant_above_rule(case):
    probe.edit(case.file("0", "U"), "value uniform (0 5 0)", "value uniform (0 50 0)")


def lighter_particles(case):
    """Half-density particles in the uniform bed's gas: fluidized far above U_mf."""
    source = os.path.realpath(case.file("bed.data"))
    os.remove(case.file("bed.data"))
    out, atoms = [], False
    for line in open(source).read().split("\n"):
        words = line.split()
        atoms = (atoms or line.startswith("Atoms")) and not line.startswith("Velocities")
        if atoms and len(words) >= 7:
            words[3] = repr(float(words[3]) / 2)
            line = " ".join(words)
        out.append(line)
    open(case.file("bed.data"), "w").write("\n".join(out))
    case.set_coupling("particles.density", 1263)


def empty_domain(case):
    for name in ("coupling.yaml", "in.empty", os.path.join("0", "voidFraction")):
        shutil.copy(os.path.join(ZERO, name), case.file(name))


def all_blown_out(case):
    probe.edit(case.file("0", "U"), "value uniform (0 5 0)", "value uniform (0 12 0)")


def check_emptied_and_resumed(case, output):
    """All particles left; the run carried on from its last checkpoint (an empty bed) to 0.3 s."""
    stats = particle_statistics(case.path)
    if stats["particles"][-1] != 0:
        return False, f"{stats['particles'][-1]} particles still in the bed"
    case.set_control(endTime=0.3, startFrom="latestTime")
    code, resumed, _ = probe.run(["tfdemFoam"], case.path, "log.resumed")
    if code != 0 or "resuming gas and particles from t = 0.2 s (no particles" not in resumed:
        return False, "the emptied bed did not resume:\n" + resumed[-2000:]
    left = sum(int(v[1]) for _, v in joined_series(case.path, "tfdemOutlets", "outlets.dat"))
    return left == 16, f"{left} of 16 left over both segments"


def killed_and_resumed(case, output):
    """Run again to 0.1 s after the straight run, killed at 0.06 s and resumed from its 0.05 s
    checkpoint: the side outputs (fix print, fix ave/time, a dump, the DEM log) end as the
    straight run's, bit for bit (the log holds both segments)."""
    straight = {n: open(case.file(n), "rb").read() for n in ("mean_height.txt", "averages.txt", "snap.dump")}
    resumed = Case(case.path).copy_to(case.path + "_resumed")
    os.symlink(os.path.realpath(case.file("bed.data")), resumed.file("bed.data"))
    probe.run(["blockMesh"], resumed.path, "log.blockMesh")
    proc = subprocess.Popen(["tfdemFoam"], cwd=resumed.path, env=environment(),
                            stdout=open(resumed.file("log.killed"), "w"), stderr=subprocess.STDOUT,
                            start_new_session=True)
    while proc.poll() is None and "\nTime = 0.06\n" not in open(resumed.file("log.killed")).read():
        time.sleep(0.1)
    os.killpg(proc.pid, signal.SIGKILL)
    proc.wait()
    resumed.set_control(startFrom="latestTime")
    code, text, _ = probe.run(["tfdemFoam"], resumed.path, "log.resumed")
    if code != 0 or "resuming gas and particles from t = 0.05 s" not in text:
        return False, "did not resume from 0.05 s:\n" + text[-2000:]
    differ = [n for n, b in straight.items() if open(resumed.file(n), "rb").read() != b]
    if differ:
        return False, f"differ from the straight run: {differ}"
    log = open(resumed.file("log.liggghts")).read()
    first_segment = re.search(r"(?m)^\s*0\s+4000\s", log)  # the thermo line of step 0
    return bool(first_segment) and "TFDEM: the DEM resumes from" in log, "the DEM log holds both segments"


def side_outputs(case):
    probe.edit(case.file("in.bed"), "fix             height_out",
               "fix             avg all ave/time 1 1 80 c_height file averages.txt\n"
               "dump            snap all custom 800 snap.dump id x y vx vy\n"
               "dump_modify     snap sort id\n"
               "fix             height_out")
    case.set_control(writeInterval=0.05, writePrecision=17)


def check_purged(case, output):
    kept = sorted(n for n in os.listdir(case.path) if re.fullmatch(r"0\.\d+", n))
    return kept == ["0.08", "0.1"], f"time folders kept {kept} (purgeWrite 2 of 0.02 ... 0.1)"


def legacy_marker(case):
    """A checkpoint written before markers listed their files, resumed."""
    case.set_control(endTime=0.02, writeInterval=0.01)


def check_legacy(case, output):
    marker = case.file("0.02", "tfdem.checkpoint")
    text = open(marker).read()
    kept = [l for l in text.splitlines() if l.split()[:1] and l.split()[0] in
            ("time", "demRestart", "demStep", "particles", "particleMass", "removedParticles", "removedMass")]
    open(marker, "w").write("// TFDEM checkpoint, written after the fields and dem.restart\n" + "\n".join(kept) + "\n")
    case.set_control(endTime=0.03, startFrom="latestTime")
    code, resumed, _ = probe.run(["tfdemFoam"], case.path, "log.resumed")
    return (code == 0 and "was written before checkpoints listed their files" in resumed,
            resumed[-1500:])


def low_precision(case):
    case.set_control(writePrecision=8, writeInterval=0.01)


def check_low_precision_resume(case, output):
    case.set_control(endTime=0.03, startFrom="latestTime")
    code, resumed, _ = probe.run(["tfdemFoam"], case.path, "log.resumed")
    return (code == 0 and "written at writePrecision 8: this run continues close to, not bit for bit" in resumed,
            resumed[-1500:])


def check_from_elsewhere(case, output):
    """The settling case run again, started from inside another case folder (the blow-out's)
    with -case: it writes its dump and logs in its own folder and nothing in the other."""
    shutil.rmtree(case.file("0.02"))
    os.remove(case.file("particle.dump"))
    other = Case(BLOWOUT).copy_to(case.path + "_other")
    before = sorted(os.listdir(other.path))
    code, text, _ = probe.run(["tfdemFoam", "-case", case.path], other.path, "../" + os.path.basename(case.path) +
                              "/log.from_elsewhere")
    after = sorted(n for n in os.listdir(other.path))
    dump = case.file("particle.dump")
    return (code == 0 and before == after and os.path.getsize(dump) > 0,
            f"other folder before {before}, after {after}; exit {code}")


HARD = [
    Hard("speeds and time steps", "jet at 42 m/s", JET, "jet", 0.1, inflow(42), particle_mass=JET_MASS),
    Hard("speeds and time steps", "jet at 80 m/s", JET, "jet", 0.1, inflow(80), particle_mass=JET_MASS),
    Hard("speeds and time steps", "jet at 150 m/s, centroid mapping", JET, "jet", 0.1, inflow(150),
         stop_words=["fill it: gas fraction", "before any floor", "divided or porous_cube"]),
    Hard("speeds and time steps", "jet at 150 m/s, porous cube", JET, "jet", 0.1,
         probe.all_of(inflow(150), coupling(coupling__void_fraction__method="porous_cube")), particle_mass=JET_MASS),
    Hard("speeds and time steps", "gas Courant number above the measured 3.2", BLOWOUT, None, 0.01,
         courant_above_rule, warn_words=["TFDEM warning: the gas Courant number reached", "(> 3.2"]),
    Hard("speeds and time steps", "DEM step at t_c/12", BED, "bed", 0.05, dem_step_at_limit, particle_mass=BED_MASS,
         warn_words=["advice: contact of atom types 1 and 1"]),
    Hard("speeds and time steps", "particles thrown down at 3 m/s", BED, "bed", 0.05, falling_fast,
         particle_mass=BED_MASS),
    Hard("speeds and time steps", "light particles far above U_mf", BED, "bed", 0.05, lighter_particles,
         particle_mass=BED_MASS / 2),
    Hard("speeds and time steps", "no inflow (a defluidizing bed)", BED, "bed", 0.05,
         inflow(0, old="value uniform (0 1.92 0)"), particle_mass=BED_MASS),
    Hard("contacts", "e_n = 1", BED, "bed", 0.1, lambda c: set_damping(c, 0, 0), particle_mass=BED_MASS),
    Hard("contacts", "e_n = 0.01", BED, "bed", 0.1, lambda c: set_damping(c, 0.15, 0.15), particle_mass=BED_MASS),
    Hard("contacts", "Hertz contacts", BED, "bed", 0.05, hertz_bed, particle_mass=BED_MASS),
    Hard("contacts", "frozen bed (no time integration)", BED, "bed", 0.05, frozen_bed, particle_mass=BED_MASS,
         warn_words=["a frozen bed, contact time not checked"]),
    Hard("mapping and drag", "cells smaller than particles, centroid", BED, "bed", 0.02, small_cells("centroid"),
         stop_words=["fill it: gas fraction", "before any floor", "Particles with a share in it",
                     "divided or porous_cube"]),
    Hard("mapping and drag", "cells smaller than particles, porous cube", BED, "bed", 0.02,
         small_cells("porous_cube"), particle_mass=BED_MASS),
    Hard("mapping and drag", "divided volume", BED, "bed", 0.05, coupling(coupling__void_fraction__method="divided"),
         particle_mass=BED_MASS),
    Hard("mapping and drag", "per-particle transfer", BED, "bed", 0.05, coupling(coupling__transfer="per_particle"),
         particle_mass=BED_MASS),
    Hard("mapping and drag", "conservative transfer, interpolated gas velocity", BED, "bed", 0.05,
         coupling(coupling__transfer="per_particle_conservative",
                  coupling__gas_velocity_at_particle="interpolated"), particle_mass=BED_MASS),
    Hard("mapping and drag", "Beetstra drag", BED, "bed", 0.05, coupling(coupling__drag_law="beetstra"),
         particle_mass=BED_MASS),
    Hard("mapping and drag", "Hill-Koch-Ladd drag", BED, "bed", 0.05, coupling(coupling__drag_law="hill_koch_ladd"),
         particle_mass=BED_MASS),
    Hard("mapping and drag", "Koch-Hill drag", BED, "bed", 0.05, coupling(coupling__drag_law="koch_hill"),
         particle_mass=BED_MASS),
    Hard("mapping and drag", "Di Felice drag", BED, "bed", 0.05, coupling(coupling__drag_law="di_felice"),
         particle_mass=BED_MASS),
    Hard("mapping and drag", "no void fraction floor", BED, "bed", 0.05,
         coupling(coupling__void_fraction__floor=0), particle_mass=BED_MASS),
    Hard("particles in and out", "10 of 16 blown out through the outlet", BLOWOUT, None, 0.05,
         check=lambda case, out: (0 < sum(int(v[1]) for _, v in joined_series(case.path, "tfdemOutlets",
                                                                                 "outlets.dat")) < 16, "some left")),
    Hard("particles in and out", "all blown out, the empty bed resumed", BLOWOUT, None, 0.2, all_blown_out,
         check=check_emptied_and_resumed, write_interval=0.1),
    Hard("particles in and out", "an empty DEM domain", POISEUILLE, None, 0.05, empty_domain, statistics=False),
    Hard("restart and outputs", "killed and resumed: side outputs bit for bit", BED, "bed", 0.1, side_outputs,
         check=killed_and_resumed, particle_mass=BED_MASS, write_interval=0.05),
    Hard("restart and outputs", "purgeWrite 2 keeps the two newest checkpoints", BED, "bed", 0.1,
         lambda case: case.set_control(purgeWrite=2), check=check_purged, write_interval=0.02,
         particle_mass=BED_MASS),
    Hard("restart and outputs", "checkpoint of an earlier version resumed", SETTLING, None, 0.02, legacy_marker,
         check=check_legacy, statistics=False, write_interval=0.01),
    Hard("restart and outputs", "resumed from writePrecision 8", SETTLING, None, 0.02, low_precision,
         check=check_low_precision_resume, statistics=False,
         warn_words=["writePrecision 8 (ascii): a run resumed from these checkpoints continues close to"]),
    Hard("restart and outputs", "-case from inside another case", SETTLING, None, 0.02,
         check=check_from_elsewhere, statistics=False),
    Hard("ranks and layouts", "2 ranks, gas whole", BED, "bed", 0.05, ranks=2, particle_mass=BED_MASS),
    Hard("ranks and layouts", "2 ranks, gas split", BED, "bed", 0.05, ranks=2, gas="split", particle_mass=BED_MASS),
    Hard("ranks and layouts", "2 ranks, jet at 80 m/s", JET, "jet", 0.05, inflow(80), ranks=2,
         particle_mass=JET_MASS),
    Hard("set-up warnings", "bed squeezed to 0.85 of its height", BED, "bed", 0.05, squeezed(0.85),
         particle_mass=BED_MASS, warn_words=["TFDEM warning: the initial packing stores more elastic energy",
                                             "will be thrown apart"]),
    Hard("set-up warnings", "DEM without gravity", BED, "bed", 0.02, no_gravity_in_dem, particle_mass=BED_MASS,
         warn_words=["TFDEM warning: the DEM script has no fix gravity"]),
    Hard("set-up warnings", "coupling fix in an included file", BED, "bed", 0.02, coupling_fix_included,
         particle_mass=BED_MASS),
]


def main():
    """All cases, or those whose names contain the command line's words."""
    import sys
    wanted = sys.argv[1:]
    suite = probe.Suite("stability", WHERE)
    os.makedirs(WHERE, exist_ok=True)
    data = {
        "bed": os.path.join(pack("packing_bed", ["-var", "steps", "20000", "-var", "out", "bed.data"]), "bed.data"),
        "jet": os.path.join(pack("packing_jet", ["-var", "dp", "0.004", "-var", "rho", "2700", "-var", "mu", "0.2",
                                                 "-var", "spacing", "0.005", "-var", "width", "0.15", "-var", "height",
                                                 "0.9", "-var", "fill_top", "0.41", "-var", "steps", "30000",
                                                 "-var", "out", "packed_bed.data"]), "packed_bed.data"),
    }
    for h in HARD:
        if wanted and not any(w in h.name for w in wanted):
            continue
        h.data = data.get(h.data, h.data)
        run_hard(suite, h)
    suite.finish()


if __name__ == "__main__":
    main()
