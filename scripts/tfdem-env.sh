# Source this file to run TFDEM's programs and the OpenFOAM/LIGGGHTS tools by hand:
#   . scripts/tfdem-env.sh
# It puts build/ and scripts/bin/ on PATH and sets what Debian's OpenFOAM needs (WM_PROJECT_DIR).
TFDEM_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
export TFDEM_ROOT
export TFDEM_BUILD="${TFDEM_BUILD:-$TFDEM_ROOT/build}"
export WM_PROJECT_DIR=/usr/share/openfoam
export PATH="$TFDEM_ROOT/scripts/bin:$TFDEM_BUILD/openfoam_solver:$TFDEM_BUILD/engines:$TFDEM_BUILD/engines/liggghts:$TFDEM_BUILD/coupling:$PATH"
# Python scripts use Debian's python3 (matplotlib, numpy, yaml from apt) and the tfdem
# package in python/.
export TFDEM_PYTHON=/usr/bin/python3
export PYTHONPATH="$TFDEM_ROOT/python${PYTHONPATH:+:$PYTHONPATH}"
if [ "$(id -u)" -eq 0 ]; then
    # Open MPI refuses to start as root without these (containers and CI run as root).
    export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi
# Two cores: let mpirun place as many ranks as asked.
export OMPI_MCA_rmaps_base_oversubscribe=1
