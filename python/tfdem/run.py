"""Running TFDEM's programs and OpenFOAM's tools: environment, MPI, gas layout, decomposition."""
import os
import re
import subprocess

from tfdem import BUILD_DIR, SOURCE_DIR
from tfdem.case import CaseError
from tfdem.errors import Reported
from tfdem.frontdoor import run_command, write_text_atomic
from tfdem.outputs import times


class RunError(Reported):
    """A program exited non-zero; the message names it, its exit code and its log."""


def environment():
    """Environment with build/ and scripts/bin/ on PATH, the package on PYTHONPATH and what
    Debian's OpenFOAM and Open MPI need (as scripts/tfdem-env.sh)."""
    env = dict(os.environ)
    env["WM_PROJECT_DIR"] = "/usr/share/openfoam"
    env["PATH"] = os.pathsep.join([os.path.join(SOURCE_DIR, "scripts", "bin"),
                                   os.path.join(BUILD_DIR, "openfoam_solver"),
                                   os.path.join(BUILD_DIR, "engines"),
                                   os.path.join(BUILD_DIR, "engines", "liggghts"),
                                   os.path.join(BUILD_DIR, "coupling"), env.get("PATH", "")])
    env["PYTHONPATH"] = os.pathsep.join(p for p in (os.path.join(SOURCE_DIR, "python"),
                                                    env.get("PYTHONPATH", "")) if p)
    if os.geteuid() == 0:
        env["OMPI_ALLOW_RUN_AS_ROOT"] = "1"
        env["OMPI_ALLOW_RUN_AS_ROOT_CONFIRM"] = "1"
    env["OMPI_MCA_rmaps_base_oversubscribe"] = "1"
    return env


# How tfdemFoam's ranks share the gas mesh (openfoam_solver/tfdemRanks.H); the particles are
# always split by LIGGGHTS.
GAS_LAYOUTS = {
    "whole": "every rank solves the whole mesh (mpirun without -parallel, no decomposition)",
    "split": "the mesh decomposed in x (decomposePar, mpirun ... -parallel)",
}
# On the tutorials' meshes (<= a few thousand cells) whole is the faster: bench/README.md.
DEFAULT_GAS_LAYOUT = "whole"


def check_gas_layout(gas):
    if gas not in GAS_LAYOUTS:
        raise ValueError(f"gas layout '{gas}': use " + " or ".join(f"'{k}' ({v})" for k, v in GAS_LAYOUTS.items()))
    return gas


def command(args, ranks=1, gas=DEFAULT_GAS_LAYOUT):
    """args under mpirun -np ranks when ranks > 1, with -parallel when the gas is split."""
    if ranks <= 1:
        return list(args)
    return ["mpirun", "-np", str(ranks)] + list(args) + (["-parallel"] if check_gas_layout(gas) == "split" else [])


def run(args, cwd, log_name, ranks=1, expect_success=True, gas=DEFAULT_GAS_LAYOUT, show_progress=False):
    """Run a program in cwd (under mpirun when ranks > 1, with -parallel when the gas is
    split), its output to cwd/log_name as it comes (with `show_progress`, its TFDEM progress
    lines on the terminal too); return (exit code, output). RunError when it fails and success
    was expected."""
    full = command(args, ranks, gas)
    log = os.path.join(cwd, log_name)
    # errors="replace": LIGGGHTS 3.8.0, aborting on 2 ranks, sometimes echoes an error line
    # from a freed buffer (bytes that are not UTF-8) on the second rank.
    env = dict(environment(), PWD=os.path.abspath(cwd))  # as a shell there has it: OpenFOAM compares the two
    proc = subprocess.Popen(full, cwd=cwd, env=env, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True, errors="replace")
    lines = []
    with open(log, "w") as out:
        for line in proc.stdout:
            out.write(line)
            lines.append(line)
            if show_progress and line.startswith("TFDEM progress"):
                print(line, end="", flush=True)
    proc.wait()
    output = "".join(lines)
    if expect_success and proc.returncode != 0:
        raise RunError(f"'{' '.join(full)}' exited with {proc.returncode} (log: {log}):\n" + output[-3000:])
    return proc.returncode, output


def start(args, cwd, log_name, ranks=1, gas=DEFAULT_GAS_LAYOUT):
    """Start a program in the background (its own process group), output to cwd/log_name."""
    log = open(os.path.join(cwd, log_name), "w")
    return subprocess.Popen(command(args, ranks, gas), cwd=cwd, env=dict(environment(), PWD=os.path.abspath(cwd)),
                            stdout=log, stderr=subprocess.STDOUT, start_new_session=True)


def write_decompose_dict(case_path, split):
    """system/decomposeParDict: simple decomposition into split = (nx, ny, nz)."""
    nx, ny, nz = split
    write_text_atomic(os.path.join(case_path, "system", "decomposeParDict"),
                      "FoamFile { version 2.0; format ascii; class dictionary; object decomposeParDict; }\n"
                      f"numberOfSubdomains {nx * ny * nz};\nmethod          simple;\n"
                      f"coeffs          {{ n ({nx} {ny} {nz}); }}\n")


def split_times(case_path):
    """The time folders a split run wrote (processor0's after 0), oldest first."""
    folder = os.path.join(case_path, "processor0")
    return [t for t in times(folder) if float(t) > 0] if os.path.isdir(folder) else []


def mesh_cells(case_path):
    """The mesh's cell count from its polyMesh/owner header (blockMesh writes it), or None."""
    try:
        with open(os.path.join(case_path, "constant", "polyMesh", "owner"), errors="replace") as f:
            found = re.search(r"nCells:\s*(\d+)", f.read(4096))
    except OSError:
        return None
    return int(found.group(1)) if found else None


def decompose(case_path, ranks):
    """Decompose the case's mesh and fields for `ranks` ranks, the gas split in x in equal
    parts (as LIGGGHTS' `processors * 1 1` cuts the particles). A case a split run has written
    is first reconstructed (reconstructPar of every time: each checkpoint's gas fields kept whole
    before decomposePar -force deletes the old processor*/), then its newest time is decomposed
    anew: that checkpoint resumes on the new count (startFrom latestTime)."""
    cells = mesh_cells(case_path)
    if cells is not None and ranks > cells:
        raise RunError(f"{case_path}: {ranks} ranks for a mesh of {cells} cells: a rank would own no gas cell. "
                       f"Fix: at most {cells} ranks split, or the gas whole on each rank (no decomposition, "
                       "mpirun without -parallel)")
    resumed = bool(split_times(case_path))
    if resumed:
        run(["reconstructPar"], case_path, "log.reconstructPar")
    write_decompose_dict(case_path, (ranks, 1, 1))
    run(["decomposePar", "-force"] + (["-latestTime"] if resumed else []), case_path, "log.decomposePar")


def reconstruct(case_path):
    """A case whose newest time a split run wrote (its gas fields in processor*/ alone; the
    checkpoint's DEM restart and marker are at the top) made whole for a whole or serial run
    (reconstructPar -latestTime); True when it did."""
    names = split_times(case_path)
    if not names or os.path.isfile(os.path.join(case_path, names[-1], "p")):
        return False
    run(["reconstructPar", "-latestTime"], case_path, "log.reconstructPar")
    return True


def prepare_gas(case_path, ranks, gas=DEFAULT_GAS_LAYOUT):
    """What the gas layout needs before the run: the decomposition when split on > 1 rank."""
    if ranks > 1 and check_gas_layout(gas) == "split":
        decompose(case_path, ranks)


USAGE = "usage: python3 -m tfdem.run decompose CASE RANKS(>= 2) | reconstruct CASE"


def main(argv=None):
    """python3 -m tfdem.run decompose CASE RANKS: split a case's gas over RANKS ranks, for
    `mpirun -np RANKS tfdemFoam -parallel` (a split checkpoint re-decomposed for the new count);
    python3 -m tfdem.run reconstruct CASE: a split checkpoint made whole, for a whole or
    serial run."""
    return run_command("tfdem.run", _run, argv)


def _run(argv):
    args = [a for a in argv if a != "--debug"]
    if len(args) == 3 and args[0] == "decompose":
        if not (args[2].isdigit() and int(args[2]) >= 2):
            raise CaseError(f"RANKS {args[2]!r}: give a whole number of 2 or more ({USAGE})")
        _case_folder(args[1])
        decompose(args[1], int(args[2]))
        print(f"gas split on {args[2]} ranks")
    elif len(args) == 2 and args[0] == "reconstruct":
        _case_folder(args[1])
        print("newest time reconstructed" if reconstruct(args[1]) else "nothing to reconstruct")
    else:
        raise CaseError(f"{' '.join(args) or 'no arguments'}: {USAGE}")
    return 0


def _case_folder(path):
    if not os.path.isdir(os.path.join(path, "system")):
        raise CaseError(f"{path}: not a case folder (no system/): give the case's folder")


if __name__ == "__main__":
    raise SystemExit(main())
