"""tfdem new's derivations against numbers worked by hand, and its refusals of bad input (each
message names the key and the fix). No simulation: the generated files are read back.

The bed: 800 glass beads of 1 mm (2500 kg/m^3, e_n 0.9) in a 4 x 12 cm column one layer deep,
on a plate taking 0.3 of the weight. By hand:
  Ar = 1.2 (2498.8) 9.81 (1e-9) / (1.8e-5)^2 = 90789.7; Re_mf = sqrt(33.7^2 + 0.0408 Ar) - 33.7
     = 35.870; U_mf = 35.870 (1.8e-5) / (1.2 (0.001)) = 0.53805 m/s (Wen and Yu)
  m = 2500 pi 1e-9 / 6 = 1.30900e-6 kg, m_ab = 6.54498e-7 kg
  k_n = m_ab (U_mf / (0.05 d))^2 = 6.54498e-7 (10761.0)^2 = 75.790 N/m
  eta_n = -2 ln(0.9) sqrt(m_ab k_n) / sqrt(pi^2 + ln^2 0.9) = 0.210721 (7.04304e-3) / 3.14336
        = 4.7214e-4 N s/m (seed 001 eq. 27); the wall's (m_ab = m, k = 2 k_n): twice that
  t_c = sqrt(m_ab (pi^2 + ln^2 0.9) / k_n) = 2.9211e-4 s; the rule for e_n 0.9:
        37 + 20 (0.9 - 0.86) / 0.11 = 44.273 steps, dt <= 6.5979e-6 s
  gas step 5e-4 s (the cap); 5e-4 / 6.5979e-6 = 75.78 -> 76 DEM steps of 6.5789e-6 s
  weight / area = 2498.8 (9.81) 800 (5.23599e-10) / (0.04 (0.001)) = 256.70 Pa
  plate: d = 0.3 (256.70) / (1.8e-5 (0.004) 0.53805) = 1.9879e9 1/m^2
  cells: 4 d = 4 mm -> 10 x 30 x 1
"""
import math
import os
import re
import sys
import tempfile

from tfdem.batch import end_time_change
from tfdem.case import Case, CaseError
from tfdem.liggghts import DemScript
from tfdem.newcase import BedError, derive, load_bed, main, write_case
from tfdem.packing import for_display, mixture, packing_settings

failures = []

BED = """
box: {width: 0.04, height: 0.12, depth: one_layer}
particles:
  density: 2500
  sizes: [{diameter: 0.001, number: 800}]
  restitution: 0.9
  friction: 0.1
gas: {density: 1.2, viscosity: 1.8e-5}
inflow: {velocity: 0.8, plate: {pressure_drop_fraction: 0.3}}
run: {end_time: 0.05, write_interval: 0.05}
"""


def check(name, condition, detail=""):
    print(("PASS " if condition else "FAIL ") + name + (f" {detail}" if detail else ""))
    if not condition:
        failures.append(name)


def close(name, value, expected, rel=1e-4):
    check(name, abs(value - expected) <= rel * abs(expected), f"({value:.6g} vs {expected:.6g} by hand)")


def write(root, name, text):
    path = os.path.join(root, name)
    with open(path, "w") as f:
        f.write(text)
    return path


def check_derived(root):
    source = write(root, "bed.yaml", BED)
    bed = load_bed(source)
    dv = derive(bed, source)
    close("U_mf (Wen-Yu)", dv["u_mf"], 0.53805)
    close("k_n", dv["stiffness"], 75.790)
    close("DEM step", dv["dem_step"], 6.5789e-6)
    check("coupling interval", dv["coupling_interval"] == 76, f"({dv['coupling_interval']})")
    close("gas step", dv["gas_step"], 5e-4, 1e-12)
    close("plate's Darcy coefficient", dv["plate_darcy"], 1.9879e9)
    check("cells", (dv["nx"], dv["ny"], dv["nz"]) == (10, 30, 1), f"({dv['nx']} x {dv['ny']} x {dv['nz']})")
    case_path = os.path.join(root, "case")
    write_case(case_path, bed, dv, source)
    script = DemScript(os.path.join(case_path, "in.bed"))
    close("in.bed: the pair's damping from e_n (eq. 27)", script.value("${eta11}"), 4.7214e-4)
    close("in.bed: the wall's damping", script.value("${eta1w}"), 2 * 4.7214e-4)
    close("in.bed: DEM step", script.value(script.command("timestep")[1]), 6.5789e-6)
    case = Case(case_path)
    close("controlDict deltaT = coupling_interval x DEM step", case.delta_t(),
          76 * script.value(script.command("timestep")[1]), 1e-14)
    lo, hi = case.mesh_bounds()
    check("mesh: the box of bed.yaml, one diameter deep", (lo, hi) == ((0, 0, 0), (0.04, 0.12, 0.001)), f"({lo}, {hi})")
    check("mesh: the windbox row is the distributor zone", case.block_bounds("distributor")[1][1] == 0.004)
    close("fvOptions: the plate's d", case.porosity()["d"][0], 1.9879e9)
    check("packing.yaml: count and floor", open(os.path.join(case_path, "packing.yaml")).read().count("count: 800") == 1
          and "floor: 0.004" in open(os.path.join(case_path, "packing.yaml")).read())
    check("a second write into the same folder is refused", _refused(lambda: write_case(case_path, bed, dv)))


def check_three_sizes(root):
    """Three sizes by number, 300 of 1 mm, 200 of 1.5 mm, 100 of 2 mm: mass fractions by hand
    n d^3 / sum = 300, 675, 800 of 1775; the damping of the 1.5-2 mm pair from its reduced
    mass (seed 001 eq. 16, 27); packing.yaml's mass_fractions and the pour's mixture from it;
    a packing.yaml with fractions of the wrong length or sum refused."""
    text = BED.replace("sizes: [{diameter: 0.001, number: 800}]",
                       "sizes: [{diameter: 0.002, number: 100}, {diameter: 0.001, number: 300}, "
                       "{diameter: 0.0015, number: 200}]")
    source = write(root, "three.yaml", text)
    bed = load_bed(source)
    dv = derive(bed, source)
    for got, expected in zip(dv["mass_fractions"], (300 / 1775, 675 / 1775, 800 / 1775)):
        close("three sizes: mass fraction", got, expected, 1e-12)
    case_path = os.path.join(root, "three_case")
    write_case(case_path, bed, dv, source)
    script = DemScript(os.path.join(case_path, "in.bed"))
    m2, m3 = (2500 * math.pi * d ** 3 / 6 for d in (0.0015, 0.002))
    m_ab, e, k = m2 * m3 / (m2 + m3), 0.9, script.value("${kn}")  # k_n as in.bed states it (6 digits)
    close("in.bed: the 1.5-2 mm pair's damping", script.value("${eta23}"),
          -2 * math.log(e) * math.sqrt(m_ab * k) / math.sqrt(math.pi ** 2 + math.log(e) ** 2), 1e-9)
    check("in.bed: four atom types (three sizes and the walls)", "peratomtypepair 4 " in open(script.path).read())
    case = Case(case_path)
    settings = packing_settings(case)
    fractions = mixture(case, case.particle_diameters(), settings.get("mass_fraction_small"),
                        settings.get("mass_fractions"))
    for got, expected in zip(fractions, (300 / 1775, 675 / 1775, 800 / 1775)):
        close("packing.yaml: the pour's mass fraction", got, expected, 1e-12)
    for bad, expected in (([0.5, 0.5], "expected 3 fractions"), ([0.5, 0.3, 0.1], "sum to 0.9, not 1")):
        try:
            mixture(case, case.particle_diameters(), None, bad)
            check(f"packing mass_fractions refused: {expected}", False)
        except CaseError as error:
            check(f"packing mass_fractions refused: {expected}", expected in str(error), str(error))


def check_hard_sphere(root):
    """dem.engine: hard_sphere: no DEM script; coupling.yaml's dem names the engine, the data
    file and the collision laws: e_n and mu of bed.yaml and beta_0 by hand from the soft
    contacts tfdem new writes for LIGGGHTS (k_t = 2/7 k_n, eta_t = eta_n, tangential mass
    2/7 m_ab; seed 001 eq. 30): with c = -2 ln 0.9 / sqrt(pi^2 + ln^2 0.9) = 0.0670373,
    beta_0 = exp(-pi c / sqrt(16/49 - c^2)) = exp(-0.371118) = 0.689963, whatever m_ab and
    k_n; a given beta_0 (0.33) is written as given."""
    for text, beta in ((BED + "dem: {engine: hard_sphere}\n", 0.689963),
                       (BED + "dem: {engine: hard_sphere, tangential_restitution: 0.33}\n", 0.33)):
        source = write(root, "hard.yaml", text)
        bed = load_bed(source)
        dv = derive(bed, source)
        case_path = os.path.join(root, f"hard_case_{beta}")
        write_case(case_path, bed, dv, source)
        case = Case(case_path)
        hard = case.coupling_value("dem.hard_sphere")
        check(f"hard spheres (beta_0 {beta}): engine and data file", case.hard_sphere()
              and case.particles_file() == "bed.data" and case.coupling_value("dem.script") is None)
        close(f"hard spheres: beta_0 {beta}", hard["tangential_restitution"], beta, 2e-6)
        close("hard spheres: the walls' beta_0", hard["wall"]["tangential_restitution"], beta, 2e-6)
        check("hard spheres: e_n and mu of bed.yaml", (hard["restitution"], hard["friction"], hard["wall"]["restitution"])
              == (0.9, 0.1, 0.9), f"({hard})")
        check("hard spheres: no DEM script written", not os.path.exists(os.path.join(case_path, "in.bed")))
        check("hard spheres: no DEM step derived", not any(n.startswith("DEM step") for n in dv["notes"]))
    case.set_time_steps(gas=2.5e-4)
    check("hard spheres: a sweep's gas step is set alone", case.delta_t() == 2.5e-4)
    try:
        case.set_time_steps(dem=1e-5)
        check("hard spheres: a DEM step is refused", False)
    except CaseError as error:
        check("hard spheres: a DEM step is refused", "which has none" in str(error), str(error))


WIDE = """
box: {width: 0.08, height: 0.30, depth: 0.08}
particles:
  density: 2500
  sizes: [{diameter: 0.002, number: 8000}]
  restitution: 0.9
  friction: 0.3
inflow: {velocity: 2.0}
run: {end_time: 0.05, write_interval: 0.05}
"""


def check_shallow_bed(root):
    """Issue 48's 8 x 8 x 30 cm box with 8000 beads of 2 mm, by hand: solid volume 8000 pi
    (0.002)^3 / 6 = 3.35103e-5 m^3, packed 3.35103e-5 / (0.6 (0.0064)) = 8.7266e-3 m deep;
    cells 4 d = 8 mm across (10 x 10), 0.30 m / 8 mm = 37.5 rows -> 38 of 7.8947 mm (not
    cubes: 38 x 8 mm = 0.304 m would make them so); the bed 8.7266 / 7.8947 = 1.1054 cells
    deep, 3 cells at 3 / 1.1054 = 2.7140 times as many particles, 21713 (8000 x 2.7140 rounded
    up), or a cross-section 2.7140 times smaller, 0.08 / sqrt(2.7140) = 0.0486 m a side."""
    source = write(root, "wide.yaml", WIDE)
    dv = derive(load_bed(source), source)
    warning = "".join(dv["warnings"])
    check("a bed 1.1 cells deep: warned", len(dv["warnings"]) == 1 and "1.1 gas cells of 7.89 mm" in warning,
          str(dv["warnings"]))
    check("... with the count and the box for 3 cells", "21713 particles" in warning
          and "0.0486 x 0.0486 m in cross-section" in warning, warning)
    cells = next(n for n in dv["notes"] if n.startswith("gas cells"))
    check("cells of 8 x 7.89 x 8 mm are not called cubic, and the height that makes them cubes is named",
          "not cubic" in cells and "height 0.3 m is not a whole number" in cells and "height 0.304 m" in cells, cells)
    case_path = os.path.join(root, "wide_case")
    write_case(case_path, load_bed(source), dv, source)
    check("the warning kept in derived.txt", "Warnings:\n  the bed is about 0.873 cm" in
          open(os.path.join(case_path, "derived.txt")).read())


JETS = """
box: {width: 0.072, height: 0.3, depth: one_layer}
particles:
  density: 2700
  sizes: [{diameter: 0.002, number: 600}]
  restitution: 0.9
  friction: 0.3
inflow: {jets: [%s]}
run: {end_time: 0.05, write_interval: 0.05}
"""


def check_jets(root):
    """Jets of 8 mm (a cell) through a closed bottom 72 mm wide, 2 mm beads of 2700 kg/m^3:
    Ar = 1.2 (2698.8) 9.81 (0.002)^3 / (1.8e-5)^2 = 784450, Re_mf = sqrt(33.7^2 + 0.0408 Ar)
    - 33.7 = 148.35, U_mf = 148.35 (1.8e-5) / (1.2 (0.002)) = 1.1126 m/s (Wen-Yu).
    One jet of 20 m/s: 20 (0.008) / 0.072 = 2.22 m/s over the bottom, 2.0 U_mf: a note, no
    warning. Five of 30 m/s: 5 (30) (0.008) / 0.072 = 16.7 m/s = 15.0 U_mf, above the spheres'
    terminal velocity (about 11 m/s): the bed is lifted to the lid, warned; and 30 / 1.1126
    = 26.96 U_mf a jet, past the 18.1 U_mf the tests cover, warned (once for the five)."""
    one = write(root, "one_jet.yaml", JETS % "{centre: 0.036, width: 0.008, velocity: 20}")
    dv = derive(load_bed(one), one)
    note = next((n for n in dv["notes"] if n.startswith("mean superficial velocity")), "")
    check("one jet: the mean over the bottom, 2.22 m/s = 2.0 U_mf", "2.22 m/s" in note and ": 2 U_mf" in note, note)
    check("one jet: no warning", not dv["warnings"], str(dv["warnings"]))
    jets = next((n for n in dv["notes"] if n.startswith("jets")), "")
    check("one jet: its velocity 20 m/s = 18 U_mf (20 / 1.1126 = 17.98) and the rest of the bottom closed",
          "20 m/s = 18 U_mf" in jets and "the rest of the bottom closed" in jets, jets)
    fed = write(root, "jet_fed.yaml", JETS.replace("inflow: {jets:", "inflow: {velocity: 1.0, jets:")
                % "{centre: 0.036, width: 0.008, velocity: 20}")
    jets = next((n for n in derive(load_bed(fed), fed)["notes"] if n.startswith("jets")), "")
    check("a jet over a bottom fed at 1 m/s: the rest 1 m/s = 0.899 U_mf (1 / 1.1126)",
          "the rest of the bottom 1 m/s = 0.899 U_mf" in jets, jets)
    five = write(root, "five_jets.yaml", JETS % ", ".join(
        f"{{centre: {0.004 + 0.016 * k:.3f}, width: 0.008, velocity: 30}}" for k in range(5)))
    dv = derive(load_bed(five), five)
    lifted = [w for w in dv["warnings"] if "pinned under the lid" in w]
    check("five jets: the bed pinned under the lid, warned with the mean 16.7 m/s = 15 U_mf",
          len(lifted) == 1 and "16.7 m/s = 15 U_mf" in lifted[0], str(dv["warnings"]))
    check("five jets: 26.96 U_mf a jet, outside the tested range (18.1 U_mf)",
          any("jet velocity / U_mf 26.96 is outside" in w and "0 to 18.1" in w for w in dv["warnings"]),
          str(dv["warnings"]))


def check_untested(root):
    """BED (1 mm glass, e_n 0.9, friction 0.1, air, 0.8 m/s = 1.49 U_mf) is inside every tested
    range; steel beads (7800 kg/m^3) with friction 0.5 are outside two (2500-2700 kg/m^3 and
    0.1-0.3)."""
    source = write(root, "bed.yaml", BED)
    check("the tutorial's bed: no warning", not derive(load_bed(source), source)["warnings"])
    steel = write(root, "steel.yaml", BED.replace("density: 2500", "density: 7800").replace("friction: 0.1",
                                                                                          "friction: 0.5"))
    warnings = derive(load_bed(steel), steel)["warnings"]
    names = [w.split(" ")[0] for w in warnings]
    check("steel beads with friction 0.5: density and friction named with the tested ranges",
          "particles.density" in names and "particles.friction" in names
          and any("2500 to 2700 kg/m^3" in w for w in warnings) and any("0.1 to 0.3" in w for w in warnings),
          str(warnings))


def check_hard_sphere_keys(root):
    """The hard-sphere keys of coupling.yaml's dem.hard_sphere given in bed.yaml reach it as
    given; left out, the solver's defaults stand (not written)."""
    source = write(root, "keys.yaml", BED + "dem: {engine: hard_sphere, elastic_within: 0, "
                   "max_collisions_per_particle: 500, contact_gap: 0.02, move: false}\n")
    bed = load_bed(source)
    case_path = os.path.join(root, "keys_case")
    write_case(case_path, bed, derive(bed, source), source)
    hard = Case(case_path).coupling_value("dem.hard_sphere")
    check("elastic_within, max_collisions_per_particle, contact_gap, move written as given",
          (hard.get("elastic_within"), hard.get("max_collisions_per_particle"), hard.get("contact_gap"),
           hard.get("move")) == (0, 500, 0.02, False), str(hard))
    check("left out, not written", "elastic_within" not in Case(os.path.join(root, "hard_case_0.33"))
          .coupling_value("dem.hard_sphere"))


def check_small_ones():
    """The batch's message for a lower end time; tfdem pack's summary line rounded for display
    (0.012779559550864403802 -> 0.01278, 0.0028906183994024999689 -> 0.002891)."""
    check("a lower end time is not 'carried on'", end_time_change(2.0, 1.25, True).startswith(
        "end time lowered from 2 s to 1.25 s: its last checkpoint is at or past 1.25 s, so it is done"))
    check("... nor when it runs on to it", end_time_change(2.0, 1.25, False) ==
          "end time lowered from 2 s to 1.25 s: runs on to 1.25 s from its last checkpoint")
    check("a later end time is carried on", end_time_change(1.0, 2.0, False) == "carried on from 1 s to 2 s")
    line = for_display("TFDEM packed bed: 2000 particles, mean height 0.012779559550864403802 m, rms speed "
                       "0.0028906183994024999689 m/s")
    check("tfdem pack's numbers rounded for display", line == "TFDEM packed bed: 2000 particles, mean height "
          "0.01278 m, rms speed 0.002891 m/s", line)


def _refused(action):
    try:
        action()
    except BedError:
        return True
    return False


BAD = [
    ("a box narrower than a particle", ("width: 0.04", "width: 0.0008"), r"box\.width: 0\.0008 m is narrower than a particle"),
    ("e_n above 1", ("restitution: 0.9", "restitution: 1.2"), r"particles\.restitution: 1\.2 is outside \(0, 1\]"),
    ("e_n of 0", ("restitution: 0.9", "restitution: 0"), r"particles\.restitution: 0 is outside \(0, 1\]"),
    ("e_n of 1 (no damping)", ("restitution: 0.9", "restitution: 1.0"), r"particles\.restitution: e_n = 1"),
    ("mass fractions not summing to 1",
     ("sizes: [{diameter: 0.001, number: 800}]",
      "sizes: [{diameter: 0.001, mass_fraction: 0.5}, {diameter: 0.002, mass_fraction: 0.4}]\n  count: 800"),
     r"particles\.sizes: the mass fractions sum to 0\.9, not 1"),
    ("a jet wider than the box", ("inflow: {velocity: 0.8, plate: {pressure_drop_fraction: 0.3}}",
                                  "inflow: {jets: [{centre: 0.02, width: 0.05, velocity: 20}]}"),
     r"inflow\.jets\[0\]: x = -0\.005 to 0\.045 m reaches past the box"),
    ("a jet off the cells' faces", ("inflow: {velocity: 0.8, plate: {pressure_drop_fraction: 0.3}}",
                                    "inflow: {jets: [{centre: 0.02, width: 0.004, velocity: 20}]}"),
     r"inflow\.jets\[0\]: its edges x = 0\.018 and 0\.022 m are not on the gas cells' faces .*e\.g\. 0\.004"),
    ("a misspelt key", ("width: 0.04", "widht: 0.04"), r"box\.widht: unknown key \(did you mean 'width'\?\)"),
    ("an unknown drag law (the core's list)", ("run:", "coupling: {drag_law: ergun_wenyu}\nrun:"),
     r"bad\.yaml: coupling\.drag_law: unknown value 'ergun_wenyu' \(did you mean 'ergun_wen_yu'\?\)"),
    ("a column too short for its bed", ("height: 0.12", "height: 0.03"), r"box\.height: 0\.03 m leaves the bed"),
    ("a misspelt engine", ("run:", "dem: {engine: hardsphere}\nrun:"),
     r"dem\.engine: unknown value 'hardsphere' \(did you mean 'hard_sphere'\?\)"),
    ("beta_0 for soft spheres", ("run:", "dem: {tangential_restitution: 0.4}\nrun:"),
     r"dem\.tangential_restitution: only the hard-sphere engine takes beta_0"),
    ("beta_0 above 1", ("run:", "dem: {engine: hard_sphere, tangential_restitution: 1.5}\nrun:"),
     r"dem\.tangential_restitution: 1\.5 is outside \[0, 1\]"),
    ("a hard-sphere key for soft spheres", ("run:", "dem: {elastic_within: 0}\nrun:"),
     r"dem\.elastic_within: only the hard-sphere engine takes it"),
    ("a misspelt hard-sphere key", ("run:", "dem: {engine: hard_sphere, elastic_whithin: 0}\nrun:"),
     r"dem\.elastic_whithin: unknown key \(did you mean 'elastic_within'\?\)"),
    ("move not true or false", ("run:", "dem: {engine: hard_sphere, move: 1}\nrun:"),
     r"dem\.move: 1 is not true or false"),
    ("collisions per particle not whole", ("run:", "dem: {engine: hard_sphere, max_collisions_per_particle: 2.5}\nrun:"),
     r"dem\.max_collisions_per_particle: 2\.5 is not a whole number"),
    ("a contact gap above 1", ("run:", "dem: {engine: hard_sphere, contact_gap: 2}\nrun:"),
     r"dem\.contact_gap: 2 is outside \[0, 1\]"),
    ("ten sizes", ("sizes: [{diameter: 0.001, number: 800}]",
                   "sizes: [" + ", ".join(f"{{diameter: {0.0005 + 0.0001 * k:g}, number: 8}}" for k in range(10)) + "]"),
     r"particles\.sizes: expected a list of 1 to 9 sizes"),
    ("a size given twice", ("sizes: [{diameter: 0.001, number: 800}]",
                            "sizes: [{diameter: 0.001, number: 8}, {diameter: 0.0008, number: 8}, "
                            "{diameter: 0.001, number: 8}]"),
     r"particles\.sizes: two sizes have diameter 0\.001; give each size once"),
]


def check_refusals(root):
    for name, (old, new), pattern in BAD:
        assert old in BED, old
        source = write(root, "bad.yaml", BED.replace(old, new, 1))
        dest = os.path.join(root, "bad_case")
        code = None
        stderr = sys.stderr
        with tempfile.TemporaryFile("w+") as err:
            sys.stderr = err
            try:
                code = main([dest, "--from", source])
            finally:
                sys.stderr = stderr
            err.seek(0)
            message = err.read().strip()
        check(f"refused: {name}", code == 2 and re.search(pattern, message) and not os.path.exists(dest),
              f"({message})")


def main_test():
    with tempfile.TemporaryDirectory() as root:
        check_derived(root)
        check_three_sizes(root)
        check_hard_sphere(root)
        check_refusals(root)
        check_shallow_bed(root)
        check_jets(root)
        check_untested(root)
        check_hard_sphere_keys(root)
    check_small_ones()
    if failures:
        print(f"{len(failures)} check(s) failed: {', '.join(failures)}")
        sys.exit(1)


if __name__ == "__main__":
    main_test()
