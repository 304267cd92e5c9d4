"""Running TFDEM's programs and OpenFOAM's tools: environment, MPI, decomposition."""
import os
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


def write_decompose_dict(case_path, split):
    """system/decomposeParDict: simple decomposition into split = (nx, ny, nz)."""
    nx, ny, nz = split
    with open(os.path.join(case_path, "system", "decomposeParDict"), "w") as out:
        out.write("FoamFile { version 2.0; format ascii; class dictionary; object decomposeParDict; }\n"
                  f"numberOfSubdomains {nx * ny * nz};\nmethod          simple;\n"
                  f"coeffs          {{ n ({nx} {ny} {nz}); }}\n")


def decompose(case_path, split):
    """Decompose the case's mesh and fields for len(split) ranks."""
    write_decompose_dict(case_path, split)
    run(["decomposePar", "-force"], case_path, "log.decomposePar")
