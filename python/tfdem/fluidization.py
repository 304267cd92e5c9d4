"""Fluidization curve of a case: the superficial inflow velocity stepped through levels (a YAML
schedule), the bed's pressure drop per level, the plateau and U_mf.

Schedule (a YAML file, e.g. tutorials/fluidization_curve/levels.yaml): `levels`, pairs
[velocity m/s, hold time s] in run order, up to the highest level (the rising branch) and back
down (the falling branch); optional `analysis` settings (defaults below) and `packing` (the
initial bed: variables for a LIGGGHTS packing script, by default
tutorials/bubbling_bed_packing/in.pack; leave it out to start from the case's own data file).

The case (as tutorials/fluidization_curve, whose files say the same):
  - coupling.yaml particles (d, rho_p: Wen-Yu's U_mf) and its DEM script (the script's
    `read_data` file is the bed; `variable floor` is the height of the DEM wall the bed rests
    on; `fix height_out ... print` writes t and the mean particle height; `fix forces_out ...
    ave/time` the particles' vertical forces from the gas, the plate, the two side walls, the
    lid and, in a bed more than one layer deep, the front and back walls);
  - constant/transportProperties (rho_g, mu), constant/g, system/blockMeshDict (column width
    and depth, the cellZone of the distributor's porous body), the distributor's
    Darcy-Forchheimer coefficients in fvOptions (f must be zero: its linear pressure drop
    mu d L U is subtracted; no fvOptions, no plate);
  - system/controlDict: endTime = the sum of the hold times; function objects `inletPressure`
    (surfaceFieldValue, area average of p on the inlet) and `abovePressure` (above the bed at
    every level: a surfaceFieldValue's area average over a cross-section, or probes, averaged). The inlet patch is `inlet`; this module writes 0/U (flow along
    +y).

Per level, once settled (after min(settling, half the hold time)): dp = p(inlet) - p(probe)
- rho_g g h - mu d L U; the bed voidage from the mean particle height above the floor (bed
height = 2 x (mean - floor)); the gas, plate and side-wall forces as fractions of the weight.
Plateau: mean of `batch`-long batch means of the levels >= `fluidized`, with its standard
error. U_mf: Ergun-form fit dp = a U + b U^2 through the falling branch's fixed-bed levels
(dp < fixed_bed_limit x plateau), intersected with the plateau.
"""
import math
import os
import re

import tfdem.run
from tfdem import TUTORIALS, outputs, physics, stats
from tfdem.case import Case, CaseError, _read, _strip_comments
from tfdem.frontdoor import write_text_atomic
from tfdem.inputs import InputError, Source, load_yaml, shown
from tfdem.packing import STAMP, verify_stamp

ANALYSIS_DEFAULTS = {
    "settling": 1.0,          # s: each level is averaged after min(settling, half its hold time)
    "batch": 0.5,             # s: plateau batch means, longer than the bubbling period
    "fluidized": None,        # m/s: levels at or above it make the plateau (required)
    "fixed_bed_limit": 0.85,  # falling-branch levels below this x plateau are the fixed bed
    "fixed_bed_check": None,  # m/s: falling level compared with Ergun (default: fastest fitted)
}
PACKING_SCRIPT = os.path.join(TUTORIALS, "bubbling_bed_packing", "in.pack")


class ScheduleError(InputError):
    """A schedule file is malformed; the message names the file and the key."""


SCHEDULE_KEYS = ("levels", "analysis", "packing")


class Schedule:
    """Levels [(velocity, hold time)] and the analysis and packing settings of a YAML file."""

    def __init__(self, levels, analysis=None, packing=None, path="<schedule>"):
        self.path = path
        source = Source(path, ScheduleError)
        self.levels = [(source.number(f"levels[{k}] velocity", u, 0.0, low_open=True, what="a velocity in m/s above 0"),
                        source.number(f"levels[{k}] hold time", t, 0.0, low_open=True, what="a time in s above 0"))
                       for k, (u, t) in enumerate(levels)]
        if len(self.levels) < 2:
            source.fail("levels", "expected at least two [velocity, hold time] pairs")
        settings = dict(ANALYSIS_DEFAULTS)
        settings.update(source.mapping("analysis", analysis or {}, ANALYSIS_DEFAULTS))
        if settings["fluidized"] is None:
            source.fail("analysis.fluidized", "missing: give the velocity (m/s) from which levels make the plateau "
                        "(about 1.3 x U_mf)")
        for key, value in settings.items():
            if value is not None:
                settings[key] = source.number(f"analysis.{key}", value, 0.0, low_open=True, what="a number above 0")
        self.settling, self.batch = settings["settling"], settings["batch"]
        self.fluidized, self.fixed_bed_limit = settings["fluidized"], settings["fixed_bed_limit"]
        self.fixed_bed_check = settings["fixed_bed_check"]
        if not any(u >= self.fluidized for u, _ in self.levels):
            source.fail("analysis.fluidized", f"{shown((analysis or {})['fluidized'])}: no level at or above it; "
                        "give a velocity of the levels (about 1.3 x U_mf)")
        if packing is not None:
            source.mapping("packing", packing, what="a mapping of packing-script variables")
            for key, value in packing.items():
                if isinstance(value, (list, dict)) or value is None:
                    source.fail(f"packing.{key}", f"{shown(value)}: give one value (a packing-script variable)")
        self.packing = packing

    @classmethod
    def load(cls, path):
        source = Source(path, ScheduleError)
        data = source.mapping("", load_yaml(path, ScheduleError), SCHEDULE_KEYS)
        levels = []
        given = source.sequence("levels", source.required("", data, "levels", "[velocity m/s, hold time s] pairs"),
                                what="a list of [velocity m/s, hold time s] pairs")
        for k, level in enumerate(given):
            if isinstance(level, dict) and set(level) == {"velocity", "hold"}:
                level = [level["velocity"], level["hold"]]
            source.sequence(f"levels[{k}]", level, 2, 2, "[velocity m/s, hold time s]")
            levels.append(tuple(level))
        analysis = source.mapping("analysis", data.get("analysis") or {}, ANALYSIS_DEFAULTS)
        packing = data.get("packing")
        if isinstance(packing, dict) and "script" in packing:
            packing = dict(packing)
            script = source.text("packing.script", packing["script"], "the path of a LIGGGHTS packing script")
            packing["script"] = os.path.join(os.path.dirname(os.path.abspath(path)), script)
        return cls(levels, analysis, packing, path)

    def end_time(self):
        return sum(duration for _, duration in self.levels)

    @property
    def rising_count(self):
        """Levels of the rising branch: up to the (first) highest velocity, included."""
        top = max(u for u, _ in self.levels)
        return next(k for k, (u, _) in enumerate(self.levels) if u == top) + 1

    def rising(self, result):
        return result[:self.rising_count]

    def falling(self, result):
        """The falling branch, from the highest level on."""
        return result[self.rising_count - 1:]

    def windows(self):
        """(velocity, start, end) of each level's averaging window, in run order."""
        windows, t = [], 0.0
        for u, duration in self.levels:
            windows.append((u, t + min(self.settling, duration / 2), t + duration))
            t += duration
        return windows

    def inlet_table(self):
        """OpenFOAM table of the inlet velocity: each level held, switched over 10 ms."""
        rows, t = [], 0.0
        for u, duration in self.levels:
            rows.append(f"({t + (0.01 if t else 0):.4f} (0 {u} 0))")
            t += duration
            rows.append(f"({t:.4f} (0 {u} 0))")
        return "\n".join(rows)


# Case writing ---------------------------------------------------------------------------------
def _boundary_types(case):
    """[(patch, type)] of system/blockMeshDict's boundary, in order."""
    path = case.file("system", "blockMeshDict")
    text = _strip_comments(_read(path))
    found = re.search(r"\bboundary\s*\((.*)\)\s*;", text, flags=re.S)
    if not found:
        raise CaseError(f"{path}: no boundary list")
    return re.findall(r"(\w+)\s*\{\s*type\s+(\w+)\s*;", found.group(1))


def check_end_time(case, schedule, set_it=False):
    """system/controlDict's endTime must be the schedule's total hold time (set it if asked)."""
    path = case.file("system", "controlDict")
    try:
        value = case.end_time()
    except CaseError:
        value = None
    if value is not None and abs(value - schedule.end_time()) <= 1e-9:
        return
    if set_it:
        case.set_control(endTime=f"{schedule.end_time():g}")
        print(f"{path}: endTime set to {schedule.end_time():g} s, the sum of the hold times")
        return
    if value is None:
        raise CaseError(f"{path}: no endTime entry; expected endTime {schedule.end_time():g};")
    raise CaseError(f"{path}: endTime {value:g} differs from the sum of the hold times of"
                    f" {schedule.path}, {schedule.end_time():g} s; make them equal (or pass --set-end-time)")


def write_velocity_file(case, schedule, set_end_time=False):
    """0/U: the schedule's table on the patch `inlet` (superficial velocity, +y), and for the
    other patches of the mesh pressureInletOutletVelocity (patch), noSlip (wall) or empty."""
    check_end_time(case, schedule, set_end_time)
    patches = _boundary_types(case)
    if "inlet" not in [name for name, _ in patches]:
        raise CaseError(f"{case.file('system', 'blockMeshDict')}: no patch 'inlet' for the inflow")
    conditions = {"patch": "type pressureInletOutletVelocity; value uniform (0 0 0);",
                  "wall": "type noSlip;", "empty": "type empty;", "symmetryPlane": "type symmetryPlane;"}
    lines = []
    for name, kind in patches:
        if name == "inlet":
            lines.append("    // superficial inflow velocity (eps = 1 at the inlet face), stepped up then down")
            lines.append(f"    {name:<12} {{ type uniformFixedValue; uniformValue table\n(\n"
                         f"{schedule.inlet_table()}\n); }}")
        elif kind in conditions:
            lines.append(f"    {name:<12} {{ {conditions[kind]} }}")
        else:
            raise CaseError(f"{case.file('system', 'blockMeshDict')}: patch {name} of type {kind}:"
                            " no velocity condition for it")
    text = ("FoamFile { version 2.0; format ascii; class volVectorField; object U; }\n"
            "dimensions      [0 1 -1 0 0 0 0];\ninternalField   uniform (0 0 0);\nboundaryField\n{\n"
            + "\n".join(lines) + "\n}\n")
    write_text_atomic(case.file("0", "U"), text)


def packing_command(case, schedule):
    """tfdem-liggghts arguments that pack the bed into the DEM script's data file: the packing
    script's variables dp, rho (coupling.yaml), width, height (the mesh), floor (the DEM
    script's variable) and out, then the schedule's packing variables."""
    settings = dict(schedule.packing)
    script = settings.pop("script", PACKING_SCRIPT)
    d, rho = case.particle_properties()
    lo, hi = case.mesh_bounds()
    dem = case.dem()
    variables = {"dp": f"{d:.12g}", "rho": f"{rho:.12g}", "width": f"{hi[0] - lo[0]:.12g}",
                 "height": f"{hi[1] - lo[1]:.12g}", "floor": dem.variable("floor"),
                 "out": os.path.basename(dem.read_data())}
    variables.update({k: str(v) for k, v in settings.items()})
    args = ["tfdem-liggghts", "-in", script, "-log", "log.packing"]
    for name, value in variables.items():
        args += ["-var", name, value]
    return args


def require_soft_spheres(case):
    """The curve reads the DEM script's height and wall-force outputs: refuse a hard-sphere case."""
    if case.hard_sphere():
        raise CaseError(f"{case.file('coupling.yaml')}: dem.engine: hard_sphere; the fluidization curve reads the "
                        "DEM script's height and wall-force outputs (fix height_out, forces_out): run it with the "
                        "soft spheres (dem.engine: liggghts; in bed.yaml leave dem out)")


def prepare_run(source, dest, schedule, runner=tfdem.run.run, set_end_time=False):
    """Copy the case from source to dest (unless they are the same), pack its bed (when the
    schedule has `packing`; else a bed tfdem pack poured must match its stamp), write 0/U and
    run blockMesh and tfdemFoam there via runner(args, cwd, log_name), the solver's progress
    lines shown (runner's show_progress)."""
    case = Case(source)
    require_soft_spheres(case)
    if os.path.abspath(source) != os.path.abspath(dest):
        case = case.copy_to(dest)
    if schedule.packing is not None:
        runner(packing_command(case, schedule), case.path, "log.packing.screen")
    elif not os.path.exists(case.dem().read_data()):
        raise CaseError(f"{case.dem().read_data()}: no bed, and {schedule.path} has no 'packing'")
    elif os.path.exists(case.dem().read_data() + STAMP):  # a bed tfdem pack poured: the one it finished
        verify_stamp(case)
    write_velocity_file(case, schedule, set_end_time)
    runner(["blockMesh"], case.path, "log.blockMesh")
    runner(["tfdemFoam"], case.path, "log.tfdemFoam", show_progress=True)


# The bed and its outputs ----------------------------------------------------------------------
class Bed:
    """What the analysis needs of a case, from its own files."""

    def __init__(self, case):
        self.case = case if isinstance(case, Case) else Case(case)
        c = self.case
        require_soft_spheres(c)
        self.d, self.rho_p = c.particle_properties()
        self.rho_g, self.mu = c.gas()
        self.g = c.gravity_magnitude()
        dem = c.dem()
        particles = c.particles(dem.read_data())
        self.particles = len(particles["id"])
        self.solid_volume = math.fsum(physics.sphere_volume(d) for d in particles["diameter"])
        if len(set(particles["density"])) > 1:
            raise CaseError(f"{dem.read_data()}: particles of several densities; the analysis takes one")
        lo, hi = c.mesh_bounds()
        self.width, self.depth = hi[0] - lo[0], hi[2] - lo[2]
        self.floor = dem.value(dem.variable("floor"))
        self.probe_height = c.pressure_height("abovePressure") - lo[1]
        plate = c.porosity()
        if plate is None:
            self.darcy, self.plate_thickness = 0.0, 0.0
        else:
            if any(v != 0 for v in plate["f"]):
                raise CaseError(f"{c.path}/fvOptions: f {plate['f']} is not zero; the analysis subtracts a"
                                " linear (Darcy) plate's pressure drop only: set f (0 0 0);")
            zone_lo, zone_hi = c.block_bounds(plate["zone"])
            self.darcy, self.plate_thickness = plate["d"][1], zone_hi[1] - zone_lo[1]
        self.height_file = c.file(dem.fix_file("height_out"))
        self.forces_file = c.file(dem.fix_file("forces_out"))
        self.dem_step = dem.time_step()

    def distributor_pressure_drop(self, u):
        """The plate's porous body at superficial velocity u (Pa): mu d L u (Darcy)."""
        return self.mu * self.darcy * self.plate_thickness * u

    def weight(self):
        """Weight of the particles (N)."""
        return self.solid_volume * self.rho_p * self.g

    def weight_per_area(self):
        """Net weight (weight less buoyancy) of the particles per cross-section (Pa)."""
        return self.solid_volume * (self.rho_p - self.rho_g) * self.g / (self.width * self.depth)

    def voidage(self, mean_height):
        """Bed voidage and height from the mean particle height (bed height = 2 x (mean - floor))."""
        height = 2 * (mean_height - self.floor)
        return 1 - self.solid_volume / (self.width * self.depth * height), height

    def ergun_pressure_drop(self, u, eps, height):
        """Ergun (tfdem.physics.ergun_gradient) over a bed of voidage eps and height (Pa)."""
        return physics.ergun_gradient(u, eps, self.d, self.rho_g, self.mu) * height

    def wen_yu(self):
        return physics.wen_yu_minimum_fluidization(self.d, self.rho_p, self.rho_g, self.mu, self.g)

    def ergun_u_mf(self, eps):
        return physics.ergun_minimum_fluidization(eps, self.d, self.rho_p, self.rho_g, self.mu, self.g)

    def pressure_drops(self):
        """(t, dp) of p(inlet, area average) - p(probe) - rho_g g h (Pa), the plate's drop
        still included."""
        inlet = outputs.joined_series(self.case.path, "inletPressure", "surfaceFieldValue.dat")
        # the two function objects print their times at different precisions (the probes at
        # writePrecision): samples are matched on the time rounded to well below the gas step
        above = {round(t, 9): p for t, p in outputs.pressure_series(self.case.path, "abovePressure")}
        return [(t, p[0] - above[round(t, 9)] - self.rho_g * self.g * self.probe_height) for t, p in inlet
                if round(t, 9) in above]


def _columns(rows, column):
    return [r[0] for r in rows], [r[1][column - 1] for r in rows]


def side_columns(forces):
    """The columns of forces_out that are walls beside the bed: x0 and x1 (3, 4), and in a bed
    more than one layer deep the front and back walls z0 and z1 (6, 7; 5 is the lid)."""
    return (3, 4, 6, 7) if forces and len(forces[0][1]) >= 7 else (3, 4)


def levels(bed, schedule):
    """One dict per level, in run order: u, dp (Pa), eps and bed height, Ergun's dp at that
    voidage, and the mean vertical forces on the particles as fractions of their weight (gas,
    plate, side walls)."""
    drops = bed.pressure_drops()
    t_dp, dp = [t for t, _ in drops], [v for _, v in drops]
    t_h, h = _columns(outputs.fix_print(bed.height_file), 1)
    forces = [(step * bed.dem_step, values) for step, values in outputs.fix_print(bed.forces_file)]
    weight = bed.weight()
    result = []
    for u, start, end in schedule.windows():
        eps, height = bed.voidage(stats.interval_mean(t_h, h, start, end))

        def force(column):
            return stats.interval_mean(*_columns(forces, column), start, end)

        result.append({
            "u": u,
            "dp": stats.interval_mean(t_dp, dp, start, end) - bed.distributor_pressure_drop(u),
            "eps": eps,
            "height": height,
            "ergun": bed.ergun_pressure_drop(u, eps, height),
            "gas": force(1) / weight,
            "plate": force(2) / weight,
            "side": sum(force(k) for k in side_columns(forces)) / weight,
        })
    return result


def plateau(bed, schedule):
    """Mean and standard error (Pa) of the batch means of the bed's pressure drop in the
    averaging windows of the levels >= schedule.fluidized (a window's remainder shorter than a
    batch is left out), and the number of batches."""
    drops = bed.pressure_drops()
    t, dp = [t for t, _ in drops], [v for _, v in drops]
    batches = []
    for u, start, end in schedule.windows():
        if u < schedule.fluidized:
            continue
        count = int((end - start) / schedule.batch + 1e-9)
        batches += [stats.interval_mean(t, dp, start + k * schedule.batch, start + (k + 1) * schedule.batch)
                    - bed.distributor_pressure_drop(u) for k in range(count)]
    if len(batches) < 2:
        raise ValueError(f"{schedule.path}: {len(batches)} plateau batch(es) of {schedule.batch} s in the"
                         f" levels >= {schedule.fluidized} m/s: hold them at least 2 x batch beyond settling")
    mean, error = stats.mean_and_error(batches)
    return mean, error, len(batches)


def minimum_fluidization(branch, top, limit):
    """Ergun-form fit of the branch's fixed-bed levels (dp < limit x top) intersected with the
    plateau top: (U_mf, a, b, fitted levels)."""
    fixed = [r for r in branch if r["dp"] < limit * top]
    a, b = stats.fit_linear_quadratic([r["u"] for r in fixed], [r["dp"] for r in fixed])
    return (-a + math.sqrt(a * a + 4 * b * top)) / (2 * b), a, b, fixed


def summary(case, schedule):
    """The figures of a finished run, as a dict."""
    bed = Bed(case)
    result = levels(bed, schedule)
    (top, top_error, batches), weight = plateau(bed, schedule), bed.weight_per_area()
    u_mf, a, b, fixed = minimum_fluidization(schedule.falling(result), top, schedule.fixed_bed_limit)
    u_mf_rising = minimum_fluidization(schedule.rising(result), top, schedule.fixed_bed_limit)[0]
    # voidage of the defluidized bed: the falling branch's fixed-bed levels
    eps_mf = sum(r["eps"] for r in fixed) / len(fixed)
    check = schedule.fixed_bed_check
    if check is None:
        check_level = max(fixed, key=lambda r: r["u"])
    else:
        matches = [r for r in schedule.falling(result) if abs(r["u"] - check) < 1e-9]
        if not matches:
            raise ValueError(f"{schedule.path}: analysis.fixed_bed_check: no falling level at {check} m/s")
        check_level = matches[0]
    fluidized = [r for r in result if r["u"] >= schedule.fluidized]
    return {
        "particles": bed.particles, "levels": result, "plateau": top, "plateau_error": top_error,
        "plateau_batches": batches, "weight": weight, "bed": bed,
        "u_mf": u_mf, "u_mf_rising": u_mf_rising, "fit": (a, b), "fitted": fixed,
        "wen_yu": bed.wen_yu(), "eps_mf": eps_mf, "ergun_u_mf": bed.ergun_u_mf(eps_mf),
        "fixed_bed_check": check_level,
        "gas_share": sum(r["gas"] for r in fluidized) / len(fluidized),
        "plate_share": sum(r["plate"] for r in fluidized) / len(fluidized),
        "side_share": sum(r["side"] for r in fluidized) / len(fluidized),
    }


def report(s, schedule):
    """The summary as the lines the tutorial prints."""
    def pct(value, reference):
        return f"{100 * (value / reference - 1):+.2f} %"

    lines = [f"{s['particles']} particles; net bed weight / cross-section {s['weight']:.1f} Pa",
             "branch   U (m/s)  dp (Pa)   eps    Ergun(eps) (Pa)  force on particles / weight:"
             " gas  plate  side walls"]
    for k, r in enumerate(s["levels"]):
        branch = "rising " if k < schedule.rising_count else "falling"
        lines.append(f"{branch}  {r['u']:5.2f}  {r['dp']:7.1f}  {r['eps']:.3f}  {r['ergun']:9.1f}"
                     f"            {r['gas']:.3f}  {r['plate']:.3f}  {r['side']:+.3f}")
    top, weight = s["plateau"], s["weight"]
    lines.append(f"plateau (U >= {schedule.fluidized} m/s) {top:.1f} Pa vs bed weight {weight:.1f} Pa:"
                 f" {pct(top, weight)} +- {100 * s['plateau_error'] / weight:.2f} % (standard error of"
                 f" {s['plateau_batches']} {schedule.batch} s batch means)  [gas carries {s['gas_share']:.3f},"
                 f" plate {s['plate_share']:.3f}, side walls {s['side_share']:+.3f} of the weight]")
    lines.append(f"U_mf (falling branch, Ergun-form fit of {len(s['fitted'])} fixed-bed levels x plateau)"
                 f" {s['u_mf']:.3f} m/s vs Wen-Yu {s['wen_yu']:.3f} m/s: {pct(s['u_mf'], s['wen_yu'])};"
                 f" vs Ergun at the bed's eps_mf = {s['eps_mf']:.3f}: {s['ergun_u_mf']:.3f} m/s,"
                 f" {pct(s['u_mf'], s['ergun_u_mf'])}")
    lines.append(f"U_mf (rising branch, same method) {s['u_mf_rising']:.3f} m/s:"
                 f" {pct(s['u_mf_rising'], s['wen_yu'])} on Wen-Yu")
    r1 = s["fixed_bed_check"]
    lines.append(f"fixed bed at {r1['u']:g} m/s (falling): {r1['dp']:.1f} Pa vs Ergun {r1['ergun']:.1f} Pa"
                 f" at eps = {r1['eps']:.3f}, H = {100 * r1['height']:.2f} cm: {pct(r1['dp'], r1['ergun'])}")
    return lines
