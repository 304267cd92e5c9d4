"""Bad input, one fault per case, as a demanding user meets them: each must stop non-zero,
without a crash or a hang, with a message holding its key words -- the file or key, the bad
value, the cause and the fix -- and lose nothing written before (probe.py classifies each
case: clear, unclear, crash, hang, silent; the counts go to outcomes.json and the README).

The base case is the settling tutorial (one 100 um sphere, 0.02 s, ~0.5 s a run) unless a row
names another; restart faults start from a copy of it that wrote checkpoints at 0.01 and
0.02 s (writePrecision 17) and is resumed to 0.03 s. Groups: coupling.yaml; the DEM script and
its data file; the gas case (controlDict, fields, mesh, layout); restart and checkpoints;
files, disk and locks; the DEM-only runner tfdem-liggghts.
"""
import os
import re
import shutil
import subprocess
import tempfile

from tfdem import SOURCE_DIR, TUTORIALS, BUILD_DIR
from tfdem.case import Case, remove_dict_entry
from tfdem.engines import use_hard_sphere
from tfdem.liggghts import write_data_file
from tfdem.run import write_decompose_dict, environment
import probe

SETTLING = os.path.join(TUTORIALS, "settling_particle")
BLOWOUT = os.path.join(SOURCE_DIR, "tests", "cases", "blowout")
POISEUILLE = os.path.join(TUTORIALS, "poiseuille_channel")
FREE_FALL = os.path.join(SOURCE_DIR, "tests", "cases", "dem_free_fall", "in.free_fall")
WHERE = os.path.join(BUILD_DIR, "test-runs", "bad_input")
CHECKPOINTED = os.path.join(WHERE, "template_checkpointed")




def append(path, text):
    with open(path, "a") as f:
        f.write(text)


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)


def in_case(relative, old, new):
    return lambda c: probe.edit(os.path.join(c, relative), old, new)


def yaml(old, new):
    return in_case("coupling.yaml", old, new)


def dem(old, new):
    return in_case("in.settling", old, new)


def dem_append(text):
    return lambda c: append(os.path.join(c, "in.settling"), text)


def control(**entries):
    return lambda c: Case(c).set_control(**entries)


def mesh_again(c):
    probe.run(["blockMesh"], c, "log.blockMesh")


# -- faults that need more than an edit -------------------------------------------------------

def hertz(case):
    """The settling case's linear contact replaced by a Hertz one too stiff for its 1e-4 s step."""
    script = os.path.join(case, "in.settling")
    text = re.sub(r"(?m)^fix\s+m[1-4] .*\n", "", open(script).read())
    text = text.replace("hooke/stiffness", "hertz").replace(
        "fix             m5", "fix             m1 all property/global youngsModulus peratomtype 5e6\n"
        "fix             m2 all property/global poissonsRatio peratomtype 0.3\n"
        "fix             m3 all property/global coefficientRestitution peratomtypepair 1 0.9\n"
        "fix             m5").replace(" absolute_damping on", "")
    open(script, "w").write(text)


def start_later(case):
    shutil.copytree(os.path.join(case, "0"), os.path.join(case, "0.01"))
    Case(case).set_control(startFrom="latestTime")


def included(name, text, replace=None):
    """The script includes file `name` holding `text` (replacing `replace` in the script)."""
    def fault(c):
        write(os.path.join(c, name), text)
        if replace:
            probe.edit(os.path.join(c, "in.settling"), replace, f"include {name}")
        else:
            append(os.path.join(c, "in.settling"), f"include {name}\n")
    return fault


def settling_from_data(c, atoms, velocities=None, box="0 0.06 xlo xhi\n0 0.4 ylo yhi\n0 0.02 zlo zhi\n"):
    """The settling case reading its particles from bed.data (atom lines 'id type d rho x y z')."""
    text = "settling particles\n\n%d atoms\n1 atom types\n\n%s\nAtoms # granular\n\n%s\n" % (
        len(atoms), box, "\n".join(atoms))
    if velocities:
        text += "\nVelocities\n\n" + "\n".join(velocities) + "\n"
    write(os.path.join(c, "bed.data"), text)
    script = os.path.join(c, "in.settling")
    t = open(script).read()
    t = re.sub(r"(?m)^region\s+box.*\n^create_box.*\n", "read_data       bed.data\n", t)
    t = re.sub(r"(?m)^(create_atoms|set|velocity)\s.*\n", "", t)
    open(script, "w").write(t)


def atoms_at(*positions, d=1.0e-4, rho=2500):
    return [f"{k + 1} 1 {d} {rho} {x} {y} {z}" for k, (x, y, z) in enumerate(positions)]


def coupling_renamed(new_name):
    return lambda c: os.rename(os.path.join(c, "coupling.yaml"), os.path.join(c, new_name))


def coupling_as_folder(c):
    os.remove(os.path.join(c, "coupling.yaml"))
    os.makedirs(os.path.join(c, "coupling.yaml"))


def script_as_folder(c):
    os.makedirs(os.path.join(c, "in.folder"))
    probe.edit(os.path.join(c, "coupling.yaml"), "script: in.settling", "script: in.folder")


def outlet_on_fixed_face(c):
    probe.edit(os.path.join(c, "coupling.yaml"), "  coupling_interval: 10\n", "  coupling_interval: 10\n  outlets: [top]\n")


# -- restart faults, on a copy of the checkpointed settling case --------------------------------

def checkpointed_template():
    """The settling case run to 0.02 s, checkpoints at 0.01 and 0.02 s, set to resume to 0.03."""
    if os.path.isfile(os.path.join(CHECKPOINTED, "0.02", "tfdem.checkpoint")):
        return CHECKPOINTED
    case = Case(SETTLING).copy_to(CHECKPOINTED)
    case.set_control(endTime=0.02, writeInterval=0.01, writePrecision=17)
    probe.run(["blockMesh"], case.path, "log.blockMesh")
    code, output, _ = probe.run(["tfdemFoam"], case.path, "log.tfdemFoam")
    assert code == 0, output[-2000:]
    case.set_control(endTime=0.03, startFrom="latestTime")
    return CHECKPOINTED


def cut(path, keep_fraction=0.5):
    data = open(path, "rb").read()
    open(path, "wb").write(data[:int(len(data) * keep_fraction)])


def flip_byte(path, offset=None):
    data = bytearray(open(path, "rb").read())
    k = len(data) // 2 if offset is None else offset
    data[k] ^= 0x01
    open(path, "wb").write(bytes(data))


def in_checkpoint(name, action):
    return lambda c: action(os.path.join(c, "0.02", name))


def emptied(path):
    open(path, "w").close()


def removed(path):
    os.remove(path)


def marker_edit(old, new):
    def fault(c):
        marker = os.path.join(c, "0.02", "tfdem.checkpoint")
        text = open(marker).read()
        assert re.search(old, text), old
        open(marker, "w").write(re.sub(old, new, text, count=1))
    return fault


def restart_fresh_over_checkpoints(c):
    Case(c).set_control(startFrom="startTime", startTime=0)


def resume_earlier(c):
    Case(c).set_control(startFrom="startTime", startTime=0.01)


def split_after_serial(c):
    """Serial checkpoints; decomposePar of time 0 only; a split run from latestTime."""
    write_decompose_dict(c, (1, 2, 1))
    probe.run(["decomposePar", "-force", "-time", "0"], c, "log.decomposePar")
    return {"ranks": 2, "gas": "split"}


def serial_after_split(c):
    """Checkpoints of a 2-rank split run (fields in processor*/), resumed by a serial run."""
    shutil.rmtree(os.path.join(c, "0.01"))
    shutil.rmtree(os.path.join(c, "0.02"))
    for name in os.listdir(c):
        if name.startswith("log."):
            os.remove(os.path.join(c, name))
    Case(c).set_control(endTime=0.02, startFrom="startTime")
    write_decompose_dict(c, (1, 2, 1))
    probe.run(["decomposePar", "-force"], c, "log.decomposePar")
    code, output, _ = probe.run(["tfdemFoam"], c, "log.split", ranks=2, gas="split")
    assert code == 0, output[-2000:]
    Case(c).set_control(endTime=0.03, startFrom="latestTime")
    # a serial run sees case/0.02 with the marker and the DEM restart, but no gas fields


def killed_while_writing(c):
    """What a run killed while writing its DEM restart leaves: the partial file, no marker."""
    os.rename(os.path.join(c, "0.02", "dem.restart"), os.path.join(c, "0.02", "dem.restart.tmp"))
    os.remove(os.path.join(c, "0.02", "tfdem.checkpoint"))


def processor_time_deleted(c):
    """The settling case run split on 2 ranks to 0.02 s (checkpoints at 0.01 and 0.02 s), then
    processor1/0.02 deleted and the case set to resume to 0.03 s."""
    case = Case(c)
    case.set_control(endTime=0.02, writeInterval=0.01, writePrecision=17)
    write_decompose_dict(c, (1, 2, 1))
    probe.run(["decomposePar", "-force"], c, "log.decomposePar")
    code, output, _ = probe.run(["tfdemFoam"], c, "log.split", 2, "split")
    assert code == 0, output[-2000:]
    shutil.rmtree(os.path.join(c, "processor1", "0.02"))
    case.set_control(endTime=0.03, startFrom="latestTime")
    return {"ranks": 2, "gas": "split"}


# -- files, disk and locks -----------------------------------------------------------------------

class NeedsRoot(Exception):
    """The fault needs root (mounting a small disk or a read-only view)."""


def as_root():
    if os.geteuid() != 0:
        raise NeedsRoot()


def on_small_disk(kilobytes, fill_to_free_kb=None):
    """The case moved onto a tmpfs of `kilobytes` (root can mount one), optionally filled until
    `fill_to_free_kb` is free; the run there writes checkpoints every 5 ms."""
    def fault(c):
        as_root()
        mount = tempfile.mkdtemp(prefix="tfdem_disk_", dir=WHERE)
        subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={kilobytes}k", "tmpfs", mount], check=True)
        target = os.path.join(mount, "case")
        shutil.copytree(c, target)
        Case(target).set_control(endTime=0.05, writeInterval=0.005)
        if fill_to_free_kb is not None:
            free = os.statvfs(mount).f_bavail * os.statvfs(mount).f_frsize // 1024
            with open(os.path.join(mount, "filler"), "wb") as f:
                f.write(b"\0" * max(0, (free - fill_to_free_kb)) * 1024)
        return {"cwd": target, "cleanup": lambda: subprocess.run(["umount", "-l", mount])}
    return fault


def read_only_case(c):
    as_root()
    mount = tempfile.mkdtemp(prefix="tfdem_ro_", dir=WHERE)
    subprocess.run(["mount", "--bind", c, mount], check=True)
    subprocess.run(["mount", "-o", "remount,ro,bind", mount], check=True)
    return {"cwd": mount, "cleanup": lambda: subprocess.run(["umount", "-l", mount])}


def case_path_with_space(c):
    spaced = os.path.join(WHERE, "my bed")
    shutil.rmtree(spaced, ignore_errors=True)
    shutil.copytree(c, spaced)
    return {"cwd": spaced}


def second_solver(c):
    """A first run of the case holds it, slow enough (1 us steps) to outlast the probed run's
    10 s wait for the lock; the probed run, of the same case, never starts its steps."""
    probe.edit(os.path.join(c, "in.settling"), "timestep        1e-4", "timestep        1e-6")
    probe.edit(os.path.join(c, "coupling.yaml"), "coupling_interval: 10", "coupling_interval: 1")
    Case(c).set_control(deltaT=1e-6, endTime=0.5, writeInterval=0.5)
    first = subprocess.Popen(["tfdemFoam"], cwd=c, env=environment(), stdout=open(os.path.join(c, "log.first"), "w"),
                             stderr=subprocess.STDOUT, start_new_session=True)
    deadline = 0
    while deadline < 100 and "Starting time loop" not in open(os.path.join(c, "log.first")).read():
        probe.time.sleep(0.1)
        deadline += 1

    def stop():
        os.killpg(first.pid, 9)
        first.wait()
    return {"cleanup": stop}


def interval_left_out_and_uneven(c):
    """coupling.yaml without dem.coupling_interval (the solver derives it) and a gas step of
    15.5 DEM steps."""
    probe.edit(os.path.join(c, "coupling.yaml"), "  coupling_interval: 10\n", "")
    probe.edit(os.path.join(c, "system", "controlDict"), "deltaT          1e-3;", "deltaT          1.55e-3;")


def record_forces_unwritable(c):
    return {"command": ["tfdemFoam", "-recordForces", "/nonexistent/forces.bin"]}


def no_mesh(c):
    shutil.rmtree(os.path.join(c, "constant", "polyMesh"))


def unknown_option(c):
    return {"command": ["tfdemFoam", "-recordForce", "f.bin"]}


def missing_case(c):
    return {"command": ["tfdemFoam", "-case", os.path.join(c, "nothing-here")]}


def split_without_decomposition(c):
    return {"ranks": 2, "gas": "split"}


# ------------------------------------------------------------------------------------------------

CONFIG = [
    ("misspelt key", yaml("  transfer:", "  transfr:"),
     ["coupling.yaml:12:3: coupling.transfr: unknown key (did you mean 'transfer'?)"]),
    ("malformed YAML", yaml("density: 1.2 ", "density: [1.2 "), ["malformed YAML"]),
    ("key given twice", yaml("  coupling_interval: 10\n", "  coupling_interval: 10\n  coupling_interval: 20\n"),
     ["dem.coupling_interval: given twice (first at", "keep one"]),
    ("dem.script missing", yaml("  script: in.settling\n", ""), ["dem.script: missing (required)"]),
    ("coupling_interval not a number", yaml("coupling_interval: 10", "coupling_interval: ten"),
     ["dem.coupling_interval: must be a whole number, got 'ten'"]),
    ("coupling_interval 0", yaml("coupling_interval: 10", "coupling_interval: 0"),
     ["dem.coupling_interval: value 0 is out of range [1, 1000000]"]),
    ("coupling_interval 2.5", yaml("coupling_interval: 10", "coupling_interval: 2.5"),
     ["dem.coupling_interval: must be a whole number, got '2.5'"]),
    ("density .nan", yaml("density: 2500 ", "density: .nan "),
     ["particles.density: must be a number, got '.nan' (not a number)"]),
    ("viscosity .inf", yaml("viscosity: 1.8e-5", "viscosity: .inf"), ["gas.viscosity: value inf is out of range"]),
    ("diameter .NaN in a list", yaml("diameter: 1.0e-4", "diameter: [1.0e-4, .NaN]"),
     ["particles.diameter: must be a number or a list of numbers, got '.NaN' (not a number)"]),
    ("diameter an empty list", yaml("diameter: 1.0e-4", "diameter: []"), ["particles.diameter: is an empty list"]),
    ("diameter negative", yaml("diameter: 1.0e-4", "diameter: -1.0e-4"),
     ["particles.diameter: value -0.0001 is out of range"]),
    ("gas density 0", yaml("density: 1.2 ", "density: 0 "), ["gas.density: value 0 is out of range"]),
    ("unclosed quote in dem.script", yaml("script: in.settling", 'script: "in.settling'),
     ["coupling.yaml:9: a quote (\") opens here and is not closed on this line", "close the quote"]),
    ("unknown drag law", yaml("drag_law: ergun_wen_yu", "drag_law: wen_yu"),
     ["coupling.drag_law: unknown value 'wen_yu'", "'ergun_wen_yu'"]),
    ("drag law misspelt", yaml("drag_law: ergun_wen_yu", "drag_law: beetstr"),
     ["unknown value 'beetstr' (did you mean 'beetstra'?)"]),
    ("unknown transfer method", yaml("transfer: per_particle", "transfer: perparticle"),
     ["coupling.transfer: unknown value 'perparticle' (did you mean 'per_particle'?)"]),
    ("unknown void fraction method", yaml("method: centroid", "method: centroids"),
     ["coupling.void_fraction.method: unknown value 'centroids' (did you mean 'centroid'?)"]),
    ("cube factor below the sphere's volume", yaml("method: centroid", "method: porous_cube\n    cube_factor: 0.7"),
     ["coupling.void_fraction.cube_factor: value 0.7 is out of range [0.805996"]),
    ("cube factor not a number", yaml("method: centroid", "method: porous_cube\n    cube_factor: big"),
     ["coupling.void_fraction.cube_factor: must be a number, got 'big'"]),
    ("void fraction floor 1", yaml("method: centroid", "method: centroid\n    floor: 1"),
     ["coupling.void_fraction.floor: value 1 leaves no room for particles"]),
    ("void fraction floor negative", yaml("method: centroid", "method: centroid\n    floor: -0.1"),
     ["coupling.void_fraction.floor: value -0.1 is out of range [0, 1]"]),
    ("interpolated gas velocity with averaged transfer",
     yaml("transfer: per_particle", "transfer: averaged\n  gas_velocity_at_particle: interpolated"),
     ["'interpolated' applies to the per-particle transfers"]),
    ("polydisperse drag with averaged transfer",
     yaml("transfer: per_particle", "transfer: averaged\n  polydisperse_drag: beetstra_2007"),
     ["coupling.polydisperse_drag", "use transfer: per_particle_conservative"]),
    ("viscous force asked for", yaml("drag_law: ergun_wen_yu", "drag_law: ergun_wen_yu\n  viscous_force: true"),
     ["coupling.viscous_force: not modelled"]),
    ("misspelt output key", lambda c: append(os.path.join(c, "coupling.yaml"), "output:\n  statistic_interval: 0.01\n"),
     ["output.statistic_interval: unknown key (did you mean 'statistics_interval'?)"]),
    ("misspelt section", lambda c: append(os.path.join(c, "coupling.yaml"), "outputs:\n  particles_vtk: false\n"),
     ["outputs: unknown key (did you mean 'output'?)"]),
    ("statistics interval negative",
     lambda c: append(os.path.join(c, "coupling.yaml"), "output:\n  statistics_interval: -0.01\n"),
     ["output.statistics_interval: value -0.01 is out of range"]),
    ("statistics interval not a whole number of gas steps",
     lambda c: append(os.path.join(c, "coupling.yaml"), "output:\n  statistics_interval: 0.0015\n"),
     ["output.statistics_interval = 0.0015 s is not a whole number of gas steps of 0.001 s"]),
    ("particles_vtk not a boolean", lambda c: append(os.path.join(c, "coupling.yaml"), "output:\n  particles_vtk: maybe\n"),
     ["output.particles_vtk: must be true or false, got 'maybe'"]),
    ("outlet patch misspelt", yaml("  coupling_interval: 10\n", "  coupling_interval: 10\n  outlets: [topp]\n"),
     ["dem.outlets: no patch 'topp' (did you mean 'top'?)"]),
    ("outlets a mapping", yaml("  coupling_interval: 10\n", "  coupling_interval: 10\n  outlets: {top: 1}\n"),
     ["dem.outlets: must be a name or a list of names"]),
    ("outlet where the DEM box drops particles", outlet_on_fixed_face,
     ["dem.outlets: patch 'top' lies at y = 0.4 m", "boundary f", "beyond the outlet"]),
    ("coupling.yaml a list", lambda c: write(os.path.join(c, "coupling.yaml"), "- gas\n- particles\n"),
     ["the file must be a mapping of keys to values"]),
    ("coupling.yaml empty", lambda c: write(os.path.join(c, "coupling.yaml"), ""),
     ["gas: missing (required)", "particles: missing (required)", "dem: missing (required)"]),
    ("tab indentation", yaml("  density: 2500 ", "\tdensity: 2500 "), ["coupling.yaml:", "malformed YAML"]),
    ("coupling.yaml a folder", coupling_as_folder, ["coupling.yaml is a folder, not a file", "restore coupling.yaml"]),
    ("coupling.yaml named coupling.yml", coupling_renamed("coupling.yml"),
     ["'coupling.yml' (a misnamed coupling.yaml?)", "the gas would run alone"]),
    ("coupling.yaml named Coupling.yaml", coupling_renamed("Coupling.yaml"), ["'Coupling.yaml' (a misnamed coupling.yaml?)"]),
    ("coupling.yaml deleted beside the DEM script", lambda c: os.remove(os.path.join(c, "coupling.yaml")),
     ["no coupling.yaml in", "the DEM script 'in.settling' (it has a tfdem/coupling fix)", "restore coupling.yaml"]),
    ("gas properties disagree", yaml("density: 1.2 ", "density: 1.25 "), ["gas properties disagree", "gas.density = 1.25"]),
    ("particle diameter disagrees", yaml("diameter: 1.0e-4", "diameter: 1.2e-4"),
     ["particles disagree", "diameters 0.0001 to 0.0001 m", "particles.diameter = 0.00012 m"]),
    ("particle density disagrees", yaml("density: 2500 ", "density: 2600 "),
     ["particles disagree", "densities 2500 to 2500 kg/m^3", "particles.density = 2600 kg/m^3"]),
]

DEM = [
    ("DEM script not found", yaml("script: in.settling", "script: in.missing"),
     ["dem.script: DEM input script 'in.missing' not found"]),
    ("DEM script a folder", script_as_folder, ["DEM input script 'in.folder' is not a file (a directory?)"]),
    ("DEM script empty", lambda c: write(os.path.join(c, "in.settling"), ""), ["no 'fix ID all tfdem/coupling'"]),
    ("syntax error on the terminal", dem("timestep        1e-4", "timestep        1e-4 extra"),
     ["[DEM rank 0] LIGGGHTS ERROR: Illegal timestep command", "full LIGGGHTS output:", "log.liggghts.screen"]),
    ("data file missing", lambda c: None, ["[DEM rank 0] LIGGGHTS ERROR on proc 0: Cannot open file bed.data",
                                           "log.liggghts.screen"], {"base": os.path.join(TUTORIALS, "bubbling_bed")}),
    ("run in the script", dem_append("run 10\n"), ["in.settling:31: 'run' in a coupled DEM script", "remove the command"]),
    ("run in an included file", included("extra.in", "run 10\n"), ["extra.in:1: 'run' in a coupled DEM script"]),
    ("rerun in the script", dem_append("rerun dump.x dump x y z\n"), ["'rerun' in a coupled DEM script"]),
    ("minimize in the script", dem_append("minimize 0 0 10 10\n"), ["'minimize' in a coupled DEM script"]),
    ("clear in the script", dem_append("clear\n"), ["'clear' drops TFDEM's fix styles"]),
    ("jump in the script", dem_append("jump SELF loop\n"), ["in.settling:31: 'jump' in a coupled DEM script",
                                                              "use 'include'"]),
    ("include of a missing file", dem_append("include parts/walls.in\n"),
     ["in.settling:31: include 'parts/walls.in': DEM input script 'parts/walls.in' not found"]),
    ("include cycle", included("loop.in", "include loop.in\n"), ["include 'loop.in' includes itself"]),
    ("include named by a variable", dem_append("variable part string walls\ninclude ${part}.in\n"),
     ["include '${part}.in'", "write the file name itself"]),
    ("two coupling fixes", dem_append("fix fluid2 all tfdem/coupling\n"),
     ["2 'fix ... tfdem/coupling' (in.settling:26, in.settling:31)", "keep exactly one"]),
    ("coupling fix twice through an include", included("again.in", "fix fluid2 all tfdem/coupling\n"),
     ["2 'fix ... tfdem/coupling' (in.settling:26, again.in:1)"]),
    ("no coupling fix", dem("fix             fluid all tfdem/coupling", ""), ["no 'fix ID all tfdem/coupling'"]),
    ("gravity disagrees", dem("gravity 9.81 vector 0 -1 0", "gravity 9.7 vector 0 -1 0"),
     ["gravity disagrees", "(0 -9.7 0)"]),
    ("particle of diameter 0", dem("diameter 1.0e-4 density 2500", "diameter 0 density 2500"),
     ["has diameter 0 m; every DEM particle needs a positive diameter"]),
    ("DEM step above t_c/10", dem("kn peratomtypepair 1 1e-3", "kn peratomtypepair 1 1e3"),
     ["contact of atom types 1 and 1", "DEM step dt = 0.0001 s is above t_c/10", "use dt <= t_c/57"]),
    ("overdamped contact", dem("gamman_abs peratomtypepair 1 1e-8", "gamman_abs peratomtypepair 1 1e-3"),
     ["the contact is overdamped", "e_n is undefined"]),
    ("Hertz contact too stiff for the DEM step", hertz, ["Hertz, E* =", "is above t_c/10"]),
    ("stiffness property missing", dem("fix             m1 all property/global kn peratomtypepair 1 1e-3", ""),
     ["LIGGGHTS ERROR", "kn"]),
    ("particles lost (DEM box smaller than the mesh)",
     dem("region          box block 0 0.06 0 0.4 0 0.02", "region          box block 0 0.06 0.3499 0.4 0 0.02"),
     ["particles were lost in the DEM between t =", "id 1 at (0.03 ", "dem.outlets"], {"end_time": 0.05}),
    ("processors 1 1 1 on 2 ranks", dem("units           si", "units           si\nprocessors      1 1 1"),
     ["processors 1 1 1 asks for 1 rank of the DEM on a run of 2 ranks", "mpirun -np 1"], {"ranks": 2}),
    ("processors * 2 1 on 3 ranks", dem("units           si", "units           si\nprocessors      * 2 1"),
     ["processors * 2 1 fixes 2 ranks of the DEM on its given axes on a run of 3 ranks", "a multiple of 2"], {"ranks": 3}),
    ("fix print into a folder that does not exist",
     dem_append('fix out all print 10 "x" file no/such/folder/x.txt\n'),
     ["LIGGGHTS ERROR", "Cannot open fix print file no/such/folder/x.txt"]),
    ("two particles at one point",
     lambda c: settling_from_data(c, atoms_at((0.03, 0.35, 0.01), (0.03, 0.35, 0.01))),
     ["pair(s) with their centres at one point", "ids 1 and 2 both at (0.03 0.35 0.01) m"]),
    ("velocity not a number in the data file",
     lambda c: settling_from_data(c, atoms_at((0.03, 0.35, 0.01)), ["1 0 nan 0 0 0 0"]),
     ["not a finite number", "id 1: position (0.03 0.35 0.01) m, velocity (0 nan 0) m/s"]),
    ("position not a number in the data file", lambda c: settling_from_data(c, atoms_at((0.03, "nan", 0.01))),
     ["bed.data", "id 1 (line", "its diameter or position is not a finite number"]),
    ("particle outside the DEM box in the data file",
     lambda c: settling_from_data(c, atoms_at((0.03, 0.35, 0.01), (0.03, 0.45, 0.01))),
     ["bed.data: 1 atom(s) LIGGGHTS cannot place", "id 2 at (0.03, 0.45, 0.01) m (line 13): y is above yhi = 0.4 m",
      "widen the box"]),
    ("data file cut short",
     probe.all_of(lambda c: settling_from_data(c, atoms_at((0.03, 0.35, 0.01), (0.03, 0.3, 0.01))),
          in_case("bed.data", "2 1 0.0001 2500 0.03 0.3 0.01\n", "")),
     ["LIGGGHTS ERROR", "log.liggghts.screen"]),
]

GAS = [
    ("a processor's newest time deleted", processor_time_deleted,
     ["processor0/0.02 is the newest, processor1 has nothing after 0.01", "tfdem resume", "restore processor1/0.02"]),
    ("coupling interval does not divide the gas step",
     in_case(os.path.join("system", "controlDict"), "deltaT          1e-3;", "deltaT          1.5e-3;"),
     ["deltaT = 0.0015 s must equal dem.coupling_interval x DEM timestep = 10 x 0.0001 = 0.001 s"]),
    ("coupling_interval left out, deltaT not a whole number of DEM steps", interval_left_out_and_uneven,
     ["deltaT = 0.00155 s is not a whole number of DEM steps of 0.0001 s", "use deltaT = 15 x 0.0001 = 0.0015 s"]),
    ("deltaT 0", in_case(os.path.join("system", "controlDict"), "deltaT          1e-3;", "deltaT          0;"),
     ["deltaT must be a positive time step"]),
    ("writeInterval 0", control(writeInterval=0), ["writeInterval 0", "it must be positive"]),
    ("writeInterval negative", control(writeInterval=-1), ["writeInterval -1", "it must be positive"]),
    ("writeInterval 0 time steps", control(writeControl="timeStep", writeInterval=0),
     ["writeInterval 0 (writeControl timeStep)", "a whole number of steps, at least 1"]),
    ("writeInterval 2.5 time steps", control(writeControl="timeStep", writeInterval=2.5),
     ["writeInterval 2.5 (writeControl timeStep)", "a whole number of steps"]),
    ("adjustable time step", control(adjustTimeStep="yes"), ["adjustTimeStep must be 'no'"]),
    ("2-D rule with a deep mesh", yaml("    method: centroid", "    method: centroid\n    two_dimensional: true"),
     ["coupling.void_fraction.two_dimensional is true", "depth = particles.diameter = 0.0001 m", "1 cell(s) of depth 0.02 m"]),
    ("graded mesh", probe.all_of(in_case(os.path.join("system", "blockMeshDict"), "simpleGrading (1 1 1)", "simpleGrading (1 2 1)"),
                         mesh_again), ["needs a uniform Cartesian mesh"]),
    ("no mesh", no_mesh, ["polyMesh", "points"]),
    ("particle outside the mesh",
     probe.all_of(in_case(os.path.join("system", "blockMeshDict"), "0.4", "0.3"), mesh_again),
     ["particle 0 at (0.03, 0.35, 0.01) m is outside the mesh"]),
    ("particle outside the mesh on 2 ranks, split",
     probe.all_of(in_case(os.path.join("system", "blockMeshDict"), "0.4", "0.3"), mesh_again),
     ["at t = 0 s: particle 0 at (0.03, 0.35, 0.01) m is outside the mesh"], {"ranks": 2, "gas": "split"}),
    ("particle outside the mesh on 2 ranks, whole",
     probe.all_of(in_case(os.path.join("system", "blockMeshDict"), "0.4", "0.3"), mesh_again),
     ["at t = 0 s: particle 0 at (0.03, 0.35, 0.01) m is outside the mesh"], {"ranks": 2}),
    ("re-read controlDict with the gas whole on 2 ranks", control(runTimeModifiable="true"),
     ["the gas is solved whole on each of 2 ranks", "runTimeModifiable true", "Fix: runTimeModifiable false"],
     {"ranks": 2}),
    ("clock-time writes with the gas whole on 2 ranks", control(writeControl="clockTime", writeInterval=1),
     ["writeControl clockTime", "writeControl timeStep or runTime"], {"ranks": 2}),
    ("split run without decomposition", split_without_decomposition, ["Cannot read decomposeParDict"]),
    ("later start time without a checkpoint", start_later,
     ["the gas starts at t = 0.01 s but", "has no TFDEM checkpoint", "startFrom latestTime"]),
    ("inlet without 0/voidFraction", lambda c: os.remove(os.path.join(c, "0", "voidFraction")),
     ["gas flows in through patch 'inlet'", '"0/voidFraction"', "fixedValue; value uniform 1;"], {"base": BLOWOUT}),
    ("0/U missing", lambda c: os.remove(os.path.join(c, "0", "U")), ["0/U"]),
    ("constant/g missing", lambda c: os.remove(os.path.join(c, "constant", "g")), ["constant/g"]),
    ("nu missing from transportProperties",
     lambda c: remove_dict_entry(os.path.join(c, "constant", "transportProperties"), "nu"),
     ["Entry 'nu' not found", "constant/transportProperties"]),
    ("system/controlDict missing", lambda c: os.remove(os.path.join(c, "system", "controlDict")),
     ["system/controlDict"]),
    ("case folder missing", missing_case, ["nothing-here"]),
    ("unknown command-line option", unknown_option, ["recordForce"]),
    ("force record to a folder that does not exist", record_forces_unwritable, ["/nonexistent/forces.bin"]),
    ("gas-only case with a void fraction but no coupling.yaml",
     lambda c: shutil.copy(os.path.join(SOURCE_DIR, "tests", "cases", "zero_particles", "0", "voidFraction"),
                           os.path.join(c, "0", "voidFraction")),
     ["no coupling.yaml in", "0/voidFraction (the gas fraction of particles)"], {"base": POISEUILLE}),
]

RESTART = [
    ("DEM restart empty", in_checkpoint("dem.restart", emptied),
     ["the checkpoint at t = 0.02 s is not as it was written", "0.02/dem.restart: 0 bytes, written with",
      "The newest earlier checkpoint that verifies is t = 0.01 s"]),
    ("DEM restart cut short", in_checkpoint("dem.restart", cut), ["0.02/dem.restart:", "bytes, written with",
                                                                   "t = 0.01 s"]),
    ("DEM restart with a flipped bit", in_checkpoint("dem.restart", flip_byte),
     ["0.02/dem.restart: its content changed since it was written", "t = 0.01 s"]),
    ("DEM restart missing", in_checkpoint("dem.restart", removed), ["0.02/dem.restart: No such file or directory"]),
    ("gas field cut short", in_checkpoint("U", cut), ["0.02/U:", "bytes, written with"]),
    ("gas field with a flipped bit", in_checkpoint("p", flip_byte), ["0.02/p: its content changed"]),
    ("flux phi missing", in_checkpoint("phi", removed), ["0.02/phi: No such file or directory"]),
    ("momentum pressure gradient missing", in_checkpoint("momentumPressureGradient", removed),
     ["0.02/momentumPressureGradient: No such file or directory"]),
    ("marker empty", in_checkpoint("tfdem.checkpoint", emptied),
     ["the checkpoint marker cannot be read", "not a TFDEM checkpoint marker", "t = 0.01 s"]),
    ("marker cut short", in_checkpoint("tfdem.checkpoint", lambda p: cut(p, 0.33)),
     ["the checkpoint marker cannot be read", "tfdem.checkpoint:"]),
    ("marker garbage", in_checkpoint("tfdem.checkpoint", lambda p: open(p, "wb").write(os.urandom(200))),
     ["the checkpoint marker cannot be read"]),
    ("marker's DEM step edited", marker_edit(r"demStep\s+\d+;", "demStep          150;"),
     ["LIGGGHTS resumes at step 200", "written at step 150"]),
    ("marker's particle count edited", marker_edit(r"particles\s+1;", "particles        2;"),
     ["holds 1 particles", "written with 2 particles", "The newest earlier checkpoint that verifies is t = 0.01 s"]),
    ("marker's DEM part switched off", marker_edit(r"demRestart\s+true;", "demRestart       false;"),
     ["demRestart: false", "its files list the DEM restart file", "edited or damaged",
      "The newest earlier checkpoint that verifies is t = 0.01 s"]),
    ("marker's removed count negative", marker_edit(r"removedParticles\s+0;", "removedParticles -3;"),
     ["removedParticles: -3: a count cannot be negative", "edited or damaged"]),
    ("marker's engine misspelt", marker_edit(r"engine\s+liggghts;", "engine           liggghts2;"),
     ["engine: liggghts2: the engines are", "hard_sphere", "liggghts"]),
    ("killed while writing the DEM restart", killed_while_writing,
     ["the checkpoint at t = 0.02 s is incomplete", "tfdem resume <case> moves it aside", "start from the time before"]),
    ("fresh start over checkpoints", restart_fresh_over_checkpoints,
     ["this run starts afresh at t = 0 s but the case holds TFDEM checkpoints up to t = 0.02 s",
      "to resume it, set startFrom latestTime", "foamListTimes -rm"]),
    ("resume from an earlier checkpoint with later ones", resume_earlier,
     ["this run resumes from t = 0.01 s but the case holds later checkpoints (0.02 s)", "move those time folders"]),
    ("serial checkpoints, split run decomposed at time 0", split_after_serial,
     ["this run starts afresh at t = 0 s but the case holds TFDEM checkpoints up to t = 0.02 s",
      "decomposePar -time 0.02"]),
    ("split checkpoints, resumed serially", serial_after_split,
     ["the gas fields to resume from are missing", "written split over 2 ranks", "reconstructPar -time 0.02"]),
]

FILES = [
    ("disk full before the first checkpoint", on_small_disk(1200, 40),
     ["were not written whole", "MB free", "the run had written no checkpoint yet"]),
    ("disk full after some checkpoints", on_small_disk(1200, 110),
     ["the last good checkpoint is t = 0.0", "MB free"]),
    ("read-only case", read_only_case, ["cannot create", "tfdem.lock", "Read-only file system", "must be writable"]),
    ("case path with a space", case_path_with_space,
     ["the case path", "my bed", "holds a space, which OpenFOAM strips", "rename the case folder"]),
    ("second solver in the same case", second_solver,
     ["another tfdemFoam is running in", "waited 10 s", "two runs in one case would write the same checkpoints"]),
]

DEM_ONLY = [  # tfdem-liggghts, the DEM-only runner (packing, benchmarks)
    ("script not found", "missing", ["'missing.in' not found"]),
    ("unknown fix argument", ("weight_fraction ${weight_fraction}", "wieght_fraction 0.5"),
     ["unknown argument 'wieght_fraction'", "did you mean 'weight_fraction'?"]),
    ("non-numeric fix argument on 2 ranks", ("weight_fraction ${weight_fraction}", "weight_fraction abc"),
     ["'weight_fraction' must be a number, got 'abc'"], 2),
]
DEM_VARS = ["-var", "steps", "10", "-var", "dumpfile", "dump.final", "-var", "weight_fraction", "1"]

def hard_spheres(positions=((0.03, 0.35, 0.01),), box=((0, 0, 0), (0.06, 0.4, 0.02)), edit=None, velocities=None,
                 **laws):
    """The settling case with the hard-sphere engine on bed.data (100 um glass spheres at
    these centres, with these velocities), its laws changed by `laws`, then coupling.yaml
    edited by `edit` (old, new)."""
    def fault(c):
        n = len(positions)
        write_data_file(os.path.join(c, "bed.data"), box[0], box[1], [1e-4] * n, [2500] * n, list(positions),
                        velocities=list(velocities) if velocities else None)
        use_hard_sphere(c, "bed.data", **{"restitution": 0.9, "tangential_restitution": 0.33, "friction": 0.1, **laws})
        if edit:
            probe.edit(os.path.join(c, "coupling.yaml"), *edit)
    return fault


def hard_sphere_checkpoint_resumed_with_liggghts(c):
    """The hard-sphere settling case run to its end (0.02 s, written), then set to resume it
    to 0.03 s with coupling.yaml's LIGGGHTS engine."""
    hard_spheres()(c)
    code, output, _ = probe.run(["tfdemFoam"], c, "log.hard_sphere")
    assert code == 0, output[-2000:]
    shutil.copy(os.path.join(SETTLING, "coupling.yaml"), os.path.join(c, "coupling.yaml"))
    Case(c).set_control(endTime=0.03, startFrom="latestTime")


HARD_SPHERE = [
    ("e_n above 1", hard_spheres(restitution=1.2),
     ["dem.hard_sphere.restitution", "1.2", "out of range [0, 1]"]),
    ("friction negative", hard_spheres(friction=-0.1), ["dem.hard_sphere.friction", "-0.1", "out of range"]),
    ("engine name misspelt", hard_spheres(edit=("engine: hard_sphere", "engine: hardsphere")),
     ["dem.engine: unknown value 'hardsphere'", "did you mean 'hard_sphere'?"]),
    ("a LIGGGHTS key left in", hard_spheres(edit=("engine: hard_sphere", "engine: hard_sphere\n  script: in.settling")),
     ["dem.script: applies to the liggghts engine, not to dem.engine: hard_sphere"]),
    ("particles file missing", hard_spheres(edit=("particles: bed.data", "particles: beds.data")),
     ["beds.data"]),
    ("a centre outside the box", hard_spheres(positions=((0.03, 0.35, 0.01), (0.07, 0.2, 0.01))),
     ["id 2", "x = 0.07", "the centre outside the box", "Fix: move them inside, or widen the box"]),
    ("two spheres at one point", hard_spheres(positions=((0.03, 0.35, 0.01), (0.03, 0.35, 0.01))),
     ["1 pair(s) with their centres at one point", "ids 1 and 2 both at (0.03 0.35 0.01) m"]),
    ("laws that do not fit the types", hard_spheres(restitution=[0.9, 0.8, 0.8], wall={"restitution": 0.9, "tangential_restitution": 0.33, "friction": 0.1}),
     ["dem.hard_sphere.restitution does not fit", "3 values"]),
    ("on 2 ranks", hard_spheres(), ["dem.engine: hard_sphere runs on one rank", "without mpirun"], {"ranks": 2}),
    ("e_n zero", hard_spheres(restitution=0),
     ["dem.hard_sphere.restitution", "e_n = 0", "cannot part", "give e_n above 0"]),
    ("a NaN velocity", hard_spheres(velocities=((0, float("nan"), 0),)),
     ["id 1", "velocity", "not a finite number", "bed.data"]),
    ("its checkpoint resumed with LIGGGHTS", hard_sphere_checkpoint_resumed_with_liggghts,
     ["written by the hard_sphere engine", "dem.engine: liggghts", "resume it with dem.engine: hard_sphere"]),
]

GROUPS = [("coupling.yaml", CONFIG), ("DEM script and data", DEM), ("gas case", GAS),
          ("restart and checkpoints", RESTART), ("files, disk, locks", FILES), ("hard-sphere engine", HARD_SPHERE)]


def probe_case(suite, group, name, fault, words, options):
    base = options.get("base", SETTLING)
    case_dir = os.path.join(WHERE, probe.slug(group + "_" + name))
    if group == "restart and checkpoints":
        probe.fresh_copy(checkpointed_template(), case_dir)
    else:
        shutil.rmtree(case_dir, ignore_errors=True)
        Case(base).copy_to(case_dir)
        Case(case_dir).set_control(endTime=options.get("end_time", 0.02))
        probe.run(["blockMesh"], case_dir, "log.blockMesh")
    try:
        overrides = fault(case_dir)
    except NeedsRoot:
        print(f"SKIP [{group}] {name}: needs root (a tmpfs or a read-only mount); not counted", flush=True)
        return
    overrides = overrides if isinstance(overrides, dict) else {}
    ranks = overrides.get("ranks", options.get("ranks", 1))
    gas = overrides.get("gas", options.get("gas", "whole"))
    cwd = overrides.get("cwd", case_dir)
    if ranks > 1 and gas == "split" and "ranks" not in overrides:
        write_decompose_dict(cwd, (1, 2, 1))
        probe.run(["decomposePar", "-force"], cwd, "log.decomposePar")
    command = overrides.get("command", ["tfdemFoam"])
    try:
        # the log in the case's own folder, also when the run is moved (a small disk, a
        # read-only view, a path with a space)
        (code, output, timed_out), seconds = probe.timed(probe.run, command, cwd, os.path.join(case_dir, "log.probe"),
                                                         ranks, gas, 120)
    finally:
        if "cleanup" in overrides:
            overrides["cleanup"]()
    verdict, missing = probe.verdict_of_failure(code, output, timed_out, words)
    suite.record(group, name, verdict, seconds, output if verdict != "clear" else "", missing)


def probe_dem_only(suite, name, fault, words, ranks=1):
    where = os.path.join(WHERE, "dem_only")
    os.makedirs(where, exist_ok=True)
    if fault == "missing":
        script = "missing.in"
    else:
        script = os.path.join(where, probe.slug(name) + ".in")
        text = open(FREE_FALL).read()
        assert fault[0] in text
        open(script, "w").write(text.replace(*fault))
    (code, output, timed_out), seconds = probe.timed(probe.run, ["tfdem-liggghts", "-in", script] + DEM_VARS, where,
                                                     "log." + probe.slug(name), ranks, "whole", 60)
    verdict, missing = probe.verdict_of_failure(code, output, timed_out, words)
    suite.record("tfdem-liggghts", name, verdict, seconds, output if verdict != "clear" else "", missing)


def main():
    suite = probe.Suite("bad_input", WHERE)
    os.makedirs(WHERE, exist_ok=True)
    for group, rows in GROUPS:
        for row in rows:
            name, fault, words = row[:3]
            probe_case(suite, group, name, fault, words, row[3] if len(row) > 3 else {})
    for row in DEM_ONLY:
        probe_dem_only(suite, *row)
    suite.finish()


if __name__ == "__main__":
    main()
