#!/usr/bin/env bash
# Idempotent set-up of a fresh Debian bookworm machine for TFDEM:
#   1. Debian packages (OpenFOAM, LIGGGHTS, Open MPI, yaml-cpp, GoogleTest, plotting);
#   2. OpenFOAM v1912 headers from Debian's own openfoam source package (Debian ships none),
#      unpacked to .cache/ with lnInclude folders for the libraries we include;
#   3. one CMake build of coupling/, engines/, openfoam_solver/ and tfm_models/ into build/.
# Each step is skipped when its result is already there; with --if-built the build too when
# one exists (the CMake build otherwise rebuilds what changed).
set -euo pipefail

TOP=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
CACHE="$TOP/.cache"
BUILD="$TOP/build"
OPENFOAM_VERSION=1912
OPENFOAM_SRC="$CACHE/openfoam-src"
APT_PACKAGES=(openfoam libopenfoam liggghts libliggghts-dev libopenmpi-dev openmpi-bin
              libyaml-cpp-dev libgtest-dev googletest cmake g++ make dpkg-dev bzip2 xz-utils
              python3 python3-matplotlib python3-yaml mkdocs)
# lnInclude folders: the libraries tfdemFoam includes, and for tfm_models/ twoPhaseEulerFoam's
# own libraries and the ones their headers include
TWO_PHASE_EULER=applications/solvers/multiphase/twoPhaseEulerFoam
OPENFOAM_LNINCLUDE_DIRS=(src/OpenFOAM src/OSspecific/POSIX src/finiteVolume src/meshTools
    src/TurbulenceModels/turbulenceModels src/TurbulenceModels/compressible src/TurbulenceModels/phaseCompressible
    src/transportModels/compressible src/transportModels/incompressible src/thermophysicalModels/basic
    src/thermophysicalModels/specie "$TWO_PHASE_EULER/twoPhaseSystem" "$TWO_PHASE_EULER/interfacialModels"
    "$TWO_PHASE_EULER/phaseCompressibleTurbulenceModels")

log() { printf '[tfdem setup] %s\n' "$*"; }
die() { printf '[tfdem setup] error: %s\n' "$*" >&2; exit 1; }

as_root() {
    if [ "$(id -u)" -eq 0 ]; then "$@"; elif command -v sudo >/dev/null; then sudo "$@";
    else die "need root to run '$*' (no sudo found)"; fi
}

missing_packages() {
    local p
    for p in "${APT_PACKAGES[@]}"; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || echo "$p"
    done
}

install_packages() {
    local missing
    missing=$(missing_packages)
    if [ -z "$missing" ]; then log "Debian packages: all present"; return; fi
    log "installing Debian packages: $(echo $missing)"
    as_root apt-get update -qq
    as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $missing >/dev/null
}

# Write a deb-src twin of every enabled deb822 .sources file and sources.list line.
enable_deb_src() {
    local f twin="/etc/apt/sources.list.d/tfdem-deb-src.sources"
    [ -f "$twin" ] && return 0
    log "adding deb-src twins of the configured apt sources ($twin)"
    {
        for f in /etc/apt/sources.list.d/*.sources; do
            [ -f "$f" ] && [ "$f" != "$twin" ] || continue
            grep -q '^Types:.*\bdeb\b' "$f" || continue
            grep -q 'debian' "$f" || continue
            sed -e 's/^Types:.*/Types: deb-src/' "$f"
            echo
        done
    } | as_root tee "$twin.tmp" >/dev/null
    if [ -f /etc/apt/sources.list ]; then
        grep -E '^deb ' /etc/apt/sources.list | sed 's/^deb /deb-src /' \
            | as_root tee /etc/apt/sources.list.d/tfdem-deb-src.list >/dev/null || true
    fi
    as_root mv "$twin.tmp" "$twin"
    as_root apt-get update -qq
}

fetch_openfoam_headers() {
    local stamp="$OPENFOAM_SRC/.lninclude-twophase-done" tarball dir
    [ -f "$stamp" ] && { log "OpenFOAM $OPENFOAM_VERSION headers: present"; return; }
    enable_deb_src
    mkdir -p "$CACHE/download"
    tarball=$(ls "$CACHE"/download/openfoam_${OPENFOAM_VERSION}*.orig.tar.* 2>/dev/null | head -n1 || true)
    if [ -z "$tarball" ]; then
        log "downloading Debian's openfoam source package (~45 MB)"
        (cd "$CACHE/download" && apt-get source --download-only -qq openfoam >/dev/null)
        tarball=$(ls "$CACHE"/download/openfoam_${OPENFOAM_VERSION}*.orig.tar.* 2>/dev/null | head -n1 || true)
        [ -n "$tarball" ] || die "apt-get source openfoam gave no openfoam_${OPENFOAM_VERSION}*.orig.tar.*"
    fi
    log "unpacking $(basename "$tarball") (src/, wmake/ and twoPhaseEulerFoam's sources only)"
    rm -rf "$OPENFOAM_SRC.partial" && mkdir -p "$OPENFOAM_SRC.partial"
    tar -xf "$tarball" -C "$OPENFOAM_SRC.partial" --strip-components=1 --wildcards '*/src/*' '*/wmake/*' "*/$TWO_PHASE_EULER/*"
    for dir in "${OPENFOAM_LNINCLUDE_DIRS[@]}"; do
        (cd "$OPENFOAM_SRC.partial" && WM_PROJECT_DIR="$OPENFOAM_SRC.partial" \
            ./wmake/wmakeLnInclude -s "$dir" >/dev/null) \
            || die "wmakeLnInclude failed for $dir"
    done
    rm -rf "$OPENFOAM_SRC" && mv "$OPENFOAM_SRC.partial" "$OPENFOAM_SRC"
    touch "$stamp"
}

build() {
    log "building into $BUILD"
    mkdir -p "$BUILD"
    cmake -S "$TOP" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DOPENFOAM_SRC="$OPENFOAM_SRC/src" \
        > "$BUILD/configure.log" 2>&1 || { tail -n 40 "$BUILD/configure.log"; die "CMake configure failed (log: $BUILD/configure.log)"; }
    cmake --build "$BUILD" -j "$(nproc)" > "$BUILD/build.log" 2>&1 \
        || { grep -E -B2 -A8 'error|Error' "$BUILD/build.log" | head -n 80; die "build failed (log: $BUILD/build.log)"; }
}

install_packages
fetch_openfoam_headers
# --if-built: the commands that only run what a build has (tfdem new, pack, stats, ...) build
# only when there is none; run, test, study, pareto and setup build what changed
if [ "${1:-}" = "--if-built" ] && [ -x "$BUILD/openfoam_solver/tfdemFoam" ]; then
    exit 0
fi
build
log "ready"
