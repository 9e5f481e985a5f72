#!/usr/bin/env bash
# The main job: builds burst if needed, runs the default scene on 2 MPI ranks, prints its summary and
# draws the pictures. Usage: scripts/run-main.sh [extra burst options]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
scene=options/scenes/cylinder2d_4340.opts
out=output/cylinder2d_4340
mpiexec --allow-run-as-root --oversubscribe -x OMP_NUM_THREADS=1 -n 2 build/burst -options_file "$scene" -output_dir "$out" "$@"
/usr/bin/python3 scripts/plot_run.py "$out"
echo "main: summary in $out/summary.json; pictures $out/fragments.png, $out/fragment_masses.png, $out/particles.png, $out/energy.png; ParaView: $out/particles.xmf"
