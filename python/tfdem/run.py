"""Running TFDEM's programs and OpenFOAM's tools: environment, MPI, decomposition."""
import os
import re
import subprocess

from tfdem import BUILD_DIR, SOURCE_DIR


class RunError(Exception):
    """A program exited non-zero; the message names it, its exit code and its log."""


def environment():
    """Environment with build/ on PATH, the package on PYTHONPATH and what Debian's OpenFOAM
    and Open MPI need (as scripts/tfdem-env.sh)."""
    env = dict(os.environ)
    env["WM_PROJECT_DIR"] = "/usr/share/openfoam"
    env["PATH"] = os.pathsep.join([os.path.join(BUILD_DIR, "openfoam_solver"),
                                   os.path.join(BUILD_DIR, "liggghts_fixes"),
                                   os.path.join(BUILD_DIR, "coupling"), env.get("PATH", "")])
    env["PYTHONPATH"] = os.pathsep.join(p for p in (os.path.join(SOURCE_DIR, "python"),
                                                    env.get("PYTHONPATH", "")) if p)
    if os.geteuid() == 0:
        env["OMPI_ALLOW_RUN_AS_ROOT"] = "1"
        env["OMPI_ALLOW_RUN_AS_ROOT_CONFIRM"] = "1"
    env["OMPI_MCA_rmaps_base_oversubscribe"] = "1"
    return env


def command(args, ranks=1):
    """args under mpirun -np ranks (with -parallel for OpenFOAM solvers) when ranks > 1."""
    if ranks <= 1:
        return list(args)
    return ["mpirun", "-np", str(ranks)] + list(args) + ["-parallel"]


def run(args, cwd, log_name, ranks=1, expect_success=True, parallel_flag=True):
    """Run a program in cwd (under mpirun when ranks > 1), its output to cwd/log_name; return
    (exit code, output). RunError when it fails and success was expected."""
    full = command(args, ranks) if parallel_flag else (["mpirun", "-np", str(ranks)] + list(args)
                                                       if ranks > 1 else list(args))
    # errors="replace": LIGGGHTS 3.8.0, aborting on 2 ranks, sometimes echoes an error line
    # from a freed buffer (bytes that are not UTF-8) on the second rank.
    proc = subprocess.run(full, cwd=cwd, env=environment(), stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True, errors="replace")
    log = os.path.join(cwd, log_name)
    with open(log, "w") as out:
        out.write(proc.stdout)
    if expect_success and proc.returncode != 0:
        raise RunError(f"'{' '.join(full)}' exited with {proc.returncode} (log: {log}):\n"
                       + proc.stdout[-3000:])
    return proc.returncode, proc.stdout


def start(args, cwd, log_name, ranks=1):
    """Start a program in the background (its own process group), output to cwd/log_name."""
    log = open(os.path.join(cwd, log_name), "w")
    return subprocess.Popen(command(args, ranks), cwd=cwd, env=environment(), stdout=log,
                            stderr=subprocess.STDOUT, start_new_session=True)


def mesh_cell_count(case_path):
    """Cells of the case's constant/polyMesh (the note OpenFOAM writes in its owner file)."""
    path = os.path.join(case_path, "constant", "polyMesh", "owner")
    try:
        with open(path, errors="replace") as f:
            head = f.read(2000)
    except OSError:
        raise RunError(f"{path} is missing: make the mesh (blockMesh) before decomposing") from None
    found = re.search(r"nCells:\s*(\d+)", head)
    if not found:
        raise RunError(f"{path}: no 'nCells:' in its header note; decompose it by hand (decomposePar)")
    return int(found.group(1))


def write_decompose_dict(case_path, split):
    """system/decomposeParDict: simple decomposition into split = (nx, ny, nz)."""
    nx, ny, nz = split
    with open(os.path.join(case_path, "system", "decomposeParDict"), "w") as out:
        out.write("FoamFile { version 2.0; format ascii; class dictionary; object decomposeParDict; }\n"
                  f"numberOfSubdomains {nx * ny * nz};\nmethod          simple;\n"
                  f"coeffs          {{ n ({nx} {ny} {nz}); }}\n")


def write_whole_gas_dict(case_path, ranks):
    """system/decomposeParDict and constant/cellDecomposition putting every cell on the first
    of `ranks` ranks (the others get an empty mesh)."""
    cells = mesh_cell_count(case_path)
    with open(os.path.join(case_path, "constant", "cellDecomposition"), "w") as out:
        out.write("FoamFile { version 2.0; format ascii; class labelList; object cellDecomposition; }\n"
                  f"{cells}\n(\n" + "0\n" * cells + ")\n")
    with open(os.path.join(case_path, "system", "decomposeParDict"), "w") as out:
        out.write("FoamFile { version 2.0; format ascii; class dictionary; object decomposeParDict; }\n"
                  f"numberOfSubdomains {ranks};\nmethod          manual;\n"
                  "coeffs          { dataFile \"cellDecomposition\"; }\n")


def decompose(case_path, ranks, layout="split"):
    """Decompose the case's mesh and fields for `ranks` ranks: the gas split in x in equal
    parts (as LIGGGHTS' `processors * 1 1` cuts the particles), or `whole` on the first rank
    (the other ranks run only their part of the DEM; on the 675-cell jet bed no faster than
    split, bench/README.md). Returns the layout."""
    if layout == "whole":
        write_whole_gas_dict(case_path, ranks)
    elif layout == "split":
        write_decompose_dict(case_path, (ranks, 1, 1))
    else:
        raise ValueError(f"gas layout '{layout}': use 'whole' or 'split'")
    run(["decomposePar", "-force"], case_path, "log.decomposePar")
    return layout


def main(argv=None):
    """python3 -m tfdem.run decompose CASE RANKS [split|whole]: decompose a case (Allrun scripts)."""
    import sys
    args = sys.argv[1:] if argv is None else argv
    if len(args) not in (3, 4) or args[0] != "decompose" or not args[2].isdigit() or int(args[2]) < 2:
        sys.exit("usage: python3 -m tfdem.run decompose CASE RANKS(>= 2) [split|whole]")
    try:
        layout = decompose(args[1], int(args[2]), *args[3:])
    except (RunError, ValueError) as e:
        sys.exit(f"tfdem.run: {e}")
    print(f"gas {layout} on {args[2]} ranks")
    return 0


if __name__ == "__main__":
    main()
