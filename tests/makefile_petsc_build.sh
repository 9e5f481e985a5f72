#!/bin/sh
# Builds burst with Makefile.petsc (PETSc's makefile rules) into a scratch folder and checks that the
# executable starts: `burst -help` must print the program's description (a line naming burst that is
# not part of a PETSc error message).
#
#   tests/makefile_petsc_build.sh [BUILD_DIR]
#
# BUILD_DIR defaults to a new mktemp folder, removed afterwards; a folder given as $1 is kept.
# Exit status 0 on success, non-zero with a message on stderr otherwise.
set -u

root=$(cd "$(dirname "$0")/.." && pwd)
fail() {
  echo "makefile_petsc_build: FAIL: $*" >&2
  exit 1
}

if [ $# -ge 1 ] && [ -n "$1" ]; then
  build=$1
  mkdir -p "$build" || fail "cannot create build folder $build"
  build=$(cd "$build" && pwd)
  cleanup=""
else
  build=$(mktemp -d "${TMPDIR:-/tmp}/burst-makefile-petsc.XXXXXX") || fail "mktemp failed"
  cleanup=$build
fi
log=$(mktemp "${TMPDIR:-/tmp}/makefile_petsc_build.log.XXXXXX") || fail "mktemp failed"
trap 'rm -f "$log"; [ -n "$cleanup" ] && rm -rf "$cleanup"' EXIT

echo "makefile_petsc_build: make -j2 -f Makefile.petsc BUILD=$build"
if ! make -C "$root" -f Makefile.petsc -j2 BUILD="$build" >"$log" 2>&1; then
  tail -n 40 "$log" >&2
  fail "make -f Makefile.petsc failed (last lines of the log above)"
fi
if grep -q "warning:" "$log"; then
  echo "makefile_petsc_build: note: the build printed compiler warnings:" >&2
  grep "warning:" "$log" >&2
fi

exe=$build/burst
[ -x "$exe" ] || fail "make succeeded but $exe is missing or not executable"

# -help prints the description and PETSc's help, then the run stops early (without a scene it
# ends in a PETSc error), so the exit status of the binary is reported but not required to be 0.
# The binary starts as a singleton MPI process; OMPI_ALLOW_RUN_AS_ROOT* only matter under root.
status=0
OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1 \
  timeout 120 "$exe" -help >"$log" 2>&1 || status=$?
[ "$status" -eq 124 ] && fail "$exe -help did not finish within 120 s"
if ! grep -v "PETSC ERROR" "$log" | grep -qi "burst"; then
  head -n 40 "$log" >&2
  fail "$exe -help (exit status $status) did not print the burst description (output above)"
fi
echo "makefile_petsc_build: OK: $exe -help printed the burst description (exit status $status)"
grep -v "PETSC ERROR" "$log" | grep -i -m 1 "burst"
exit 0
