#!/usr/bin/env bash
# The main job: builds burst if needed, runs the default scene on 2 MPI ranks, prints its summary and
# draws the pictures. The default scene is the cylinder burst by its own gases
# (options/scenes/exploding_cylinder2d.opts) at the paper's resolution, 160 x 160 cells over the
# quarter (-grid_cells 80,80 runs the short form). Usage: scripts/run-main.sh [extra burst options]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
scene=options/scenes/exploding_cylinder2d.opts
out=output/exploding_cylinder2d
mpiexec --allow-run-as-root --oversubscribe -x OMP_NUM_THREADS=1 -n 2 build/burst -options_file "$scene" -output_dir "$out" "$@"
/usr/bin/python3 scripts/plot_run.py "$out"
echo "main: summary in $out/summary.json; pictures $out/burst.png (fragments over the gas pressure), $out/histories.png (pressure, wall velocity), $out/fragments.png, $out/gas.png, $out/energy.png; ParaView: $out/particles.xmf, $out/gas.xmf"
