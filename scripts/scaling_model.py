#!/usr/bin/python3
"""A model of burst's parallel cost from the decomposition alone, checked against PETSc's own counts.

What it counts, per time step and rank, for the coupled MPM + ICE step of the exploding cylinders
(src/step.cxx CoupledStep, MUSL, explicit gas pressure):
  exchanges: every ghost exchange of a DMDA (node grid: P2G ghost sums, grid-velocity ghosts, the
          coupling's node fields; cell grid: the ICE state ghosts, the burn sources, the pressure-work
          increments), each with its grid, dof and stencil width (EXCHANGES below, from the code).
          For a BOX stencil of width w the ghost box of a rank is its owned box grown by w and clipped
          to the domain (DM_BOUNDARY_NONE and GHOSTED alike: points outside are not communicated);
          rank r receives |ghost(r) & owned(q)| points from each q and sends |ghost(q) & owned(r)|.
          PETSc logs one message per send and per receive and both lengths, so per exchange
          messages(r) = #senders + #receivers and bytes(r) = 8 dof (points received + points sent).
  reductions: the MPM and gas time steps, the migration count, the burnt-out particle count and
          the checkpoint/signal check: 5 per step on more than one rank (PETSc counts none on one).
  semi-implicit pressure (--semi-implicit, CG + Jacobi): the MatMult halo (STAR, width 1) and the
          CG reductions, from the outer and CG iteration counts, which are inputs taken from the log.
  migration: DMSwarmMigrate runs only on steps where a particle changes rank (swarm.cxx); in the
          checked steps no particle crosses (they start at rest), so its messages are 0 exactly.
          Over a longer run (command migration): 12 reductions per migrating step (exact), 6
          messages per exchanging neighbour (within bounds); the prediction charges one every step.
  compute: particles per rank (the scene's seeding rule replayed on the DMDA's cell ownership) and
          owned cells per rank.
Not modelled: -mpm_stress_share (a crowded rank's stress updates done by others; src/mpm/
stress_share.cxx), whose messages follow the measured cost of sending a point; every run here has
-mpm_stress_share 0.
The DMDA decomposition is PETSc 3.18's (DMSetUp_DA_2D/3D: process grid and M/m + (M%m > i) ranges);
the cell DMDA copies the node ranges less the last node (src/ice/setup.cxx).

Commands:
  check   runs burst (--burst) on --ranks (oversubscribed) for 1 and 2 steps with
          -log_view :file:ascii_info_detail and compares, per rank and per event of the Stepping stage,
          the difference (one step) of messages, message bytes and reductions with the model. PETSc
          prints these with 6 significant digits: a value under 1e6 is compared exactly, a larger one
          to its printed rounding (half a unit of the 6th digit of each of the two runs). Exits 1 on any
          mismatch. Writes --out/check_<scene>_<grid>[_semi_implicit].csv.
  migration  runs --ranks ranks to --final-time (particles cross rank boundaries) and checks the
          migration's reductions exactly given the number of migrating steps, and its messages within
          bounds (which ranks exchange how many particles is the motion's, not the model's).
  times   calibrates the compute cost per particle-step and per cell-step (1 rank, --calibrate-grid;
          each point the fastest of --repeats runs),
          the latency and bandwidth of this machine's shared-memory MPI (a ping-pong, scripts/
          mpi_pingpong.c, built with mpicc), and compares predicted and measured stepping time per step
          on 1 and 2 ranks at --grid (a different grid from the calibration). Times are run
          differences (steps + 2 less 2: the first step's scatter set-up left out). Writes
          --out/times_<scene>.csv. Prints the error; never fails on time.
  predict strong and weak scaling of the 3-D exploding cylinder from 1 to 1,024 ranks on a cluster
          (--latency, --bandwidth, --cores-per-node; the on-node figures from times.csv), with the
          particle imbalance of the box decomposition; writes --out/prediction.csv and
          --out/scaling_model.png (with the measured 1-2 rank points of times.csv).
Example:
  scripts/scaling_model.py check --burst build/burst --scene 2d --ranks 1,2,4,8 --grid 40,40
  scripts/scaling_model.py times --burst build/burst --scene 3d
  scripts/scaling_model.py predict --times build/scaling_model/times_3d.csv --measured build/scaling_model/times_*.csv
Units: bytes, seconds, metres. Run from anywhere; burst runs in the repository root."""
import argparse
import csv
import datetime
import json
import math
import os
import platform
import re
import shlex
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LAUNCHER = "mpiexec --allow-run-as-root --oversubscribe -x OMP_NUM_THREADS=1 -n {n}"
BYTES_PER_SCALAR = 8  # PetscScalar: real double

# The scenes: the option file, the small grid of the check, the paper-like grid of the prediction,
# and the counts that set the dof (options/scenes/exploding_cylinder*.opts): two solids (steel, pbx),
# pbx in a velocity field of its own (-mpm_contact_material: two velocity fields), two gases (air,
# products) besides the two solids in the ICE material list, cpGIMP (ghost width 2, shape.hpp).
SCENES = {
    "2d": dict(opts="options/scenes/exploding_cylinder2d.opts", dim=2, grid=(40, 40), lower=(0, 0, 0), upper=(0.12, 0.12, 0),
               ppc=2, solids=2, gases=2, velocity_fields=2, node_width=2),
    "3d": dict(opts="options/scenes/exploding_cylinder3d.opts", dim=3, grid=(10, 10, 15), lower=(0, 0, 0), upper=(0.09, 0.09, 0.135),
               ppc=2, solids=2, gases=2, velocity_fields=2, node_width=2),
}
# The seeded solid of both scenes: everything within the wall's outer radius in the quarter (the wall
# annulus and the charge disk/cylinder meet at 50.8 mm), for z in [0, 0.1] m in 3-D, plus the cap
# (r <= 57.15 mm, z in [0.1, 0.10635] m).
OUTER_RADIUS = 0.05715
Z_BODY, Z_CAP = 0.1, 0.10635


def dofs(scene):
    """dof per node or cell of each DMDA that exchanges ghosts (the code's own formulas)."""
    d, nvf, ns = scene["dim"], scene["velocity_fields"], scene["solids"]
    nmat = scene["gases"] + ns
    nfield = nvf  # coupling fields (coupling.cxx: 2 with the charge in its own field)
    return {
        "node": nvf * (1 + 2 * d + (d if nvf > 1 else 0)),  # Grid::NodeStride x fields (simulation.hpp)
        "velocity": nvf * 2 * d,  # da_velocity (grid.cxx)
        "mass": ns * (3 + d),  # da_mass (coupling.cxx; the charge burns: one more value per solid, burn.cxx)
        "inc": 1 + nfield * (d + 1),  # Coupling::IncDof
        "phi": ns,  # da_phi (burn.cxx)
        "impulse": nfield * d,  # da_impulse (coupling.cxx)
        "work": 1,  # da_work
        "spread": 2,  # da_spread (coupling.cxx)
        "state": nmat * 15 + 4,  # ICE stride: kMatFields per material + kCellFields (ice.hpp)
        "source": 5 * nmat + ns,  # da_source (burn.cxx)
        "dv": ns * 3,  # da_dv (coupling.cxx)
    }


# Every ghost exchange of one coupled step: (name, grid, dof key, the events whose inclusive counts
# hold it). "node" grids have the interpolator's ghost width, "cell" grids width 2 (ice/setup.cxx).
# Cpl_PressureWork is logged inside Cpl_PressureToPart (the ambient impulse) and on its own;
# MPM_GhostSums inside MPM_P2G and MPM_Remap; ICE_Ghosts inside the ICE and coupling phases.
SPREAD_SWEEPS = 4  # -coupling_pressure_work_spread's default (coupling_impl.hpp)
EXCHANGES = [
    ("P2G ghost sums (mass, momentum)", "node", "node", ["MPM_P2G", "MPM_GhostSums"]),
    ("coupling mass L2G add", "node", "mass", ["Cpl_Project"]),
    ("coupling mass G2L", "node", "mass", ["Cpl_Project"]),
    ("ICE ghosts after projection", "cell", "state", ["Cpl_Project", "ICE_Ghosts"]),
    ("burn sources L2G add", "cell", "source", ["Cpl_Burn"]),
    ("burn sources G2L", "cell", "source", ["Cpl_Burn"]),
    ("burnt fraction G2L", "node", "phi", ["Cpl_BurnParticles"]),
    ("ICE ghosts after pressure", "cell", "state", ["ICE_Pressure", "ICE_Ghosts"]),
    ("nodal pressure G2L", "node", "inc", ["Cpl_PressureToPart"]),
    ("ambient impulse L2G add", "node", "impulse", ["Cpl_PressureToPart", "Cpl_PressureWork"]),
    ("P2G ghost sums (force)", "node", "node", ["MPM_P2G", "MPM_GhostSums"]),
    ("grid velocity ghosts (update)", "node", "velocity", ["MPM_GridUpdate"]),
    ("ICE ghosts after solid velocity", "cell", "state", ["Cpl_SolidVelocity", "ICE_Ghosts"]),
    ("ICE ghosts in exchange", "cell", "state", ["ICE_Exchange", "ICE_Ghosts"]),
    ("grid velocity G2L", "node", "velocity", ["Cpl_IncrementsToNode"]),
    ("increments G2L", "node", "inc", ["Cpl_IncrementsToNode"]),
    ("pressure work spread: open fraction and gas energy G2L", "node", "spread", ["Cpl_PressureWork"]),
    ("pressure work spread: reach G2L", "node", "work", ["Cpl_PressureWork"]),
    *[(f"pressure work spread: sweep {k + 1} G2L", "node", "work", ["Cpl_PressureWork"]) for k in range(SPREAD_SWEEPS)],
    ("pressure work G2L", "node", "work", ["Cpl_PressureWork"]),
    ("solid increments L2L", "cell", "dv", ["Cpl_PressureWork"]),
    ("ICE ghosts after pressure work", "cell", "state", ["Cpl_PressureWork", "ICE_Ghosts"]),
    ("remap ghost sums", "node", "node", ["MPM_Remap", "MPM_GhostSums"]),
    ("grid velocity ghosts (momentum)", "node", "velocity", ["MPM_GridUpdate"]),
    ("ICE ghosts in advection", "cell", "state", ["ICE_Advect", "ICE_Ghosts"]),
]
# Global reductions per step (on more than one rank): event (None: outside any event) and count.
REDUCTIONS = [("MPM_TimeStep", 1), ("ICE_TimeStep", 1), ("MPM_Migrate", 1), ("Cpl_BurnParticles", 1), (None, 1)]
SEMI_IMPLICIT = "-ice_pressure_solver semi_implicit -ice_pressure_pc_type jacobi"
CHECKED_EVENTS = sorted({e for x in EXCHANGES for e in x[3]} | {e for e, _ in REDUCTIONS if e})


# ---------------------------------------------------------------- decomposition (PETSc 3.18 DMDA)
def process_grid(size, M, N, P=None):
    """PETSc's default process grid for a DMDA of M x N (x P) points (DMSetUp_DA_2D/3D)."""
    if P is None:
        m = max(1, int(0.5 + math.sqrt(M * size / N)))
        while m > 0:
            n = size // m
            if m * n == size:
                break
            m -= 1
        if M > N and m < n:
            m, n = n, m
        return [m, n, 1]
    n = max(1, int(0.5 + ((N * N) * size / (P * M)) ** (1.0 / 3.0)))
    while n > 0:
        pm = size // n
        if n * pm == size:
            break
        n -= 1
    n = max(n, 1)
    m = max(1, int(0.5 + math.sqrt(M * size / (P * n))))
    while m > 0:
        p = size // (m * n)
        if m * n * p == size:
            break
        m -= 1
    if M > P and m < p:
        m, p = p, m
    return [m, n, p]


def split(M, m):
    return [M // m + (1 if M % m > i else 0) for i in range(m)]


class Decomposition:
    """Node and cell ownership boxes of every rank (rank = i + m (j + n k))."""

    def __init__(self, dim, cells, size):
        nodes = [c + 1 for c in cells[:dim]]
        self.dim, self.size, self.cells = dim, size, list(cells[:dim])
        self.procs = process_grid(size, *nodes) if dim == 3 else process_grid(size, nodes[0], nodes[1])
        self.node_ranges = [split(nodes[d], self.procs[d]) for d in range(dim)]
        self.cell_ranges = [r[:-1] + [r[-1] - 1] for r in self.node_ranges]
        self.node_boxes = self._boxes(self.node_ranges)
        self.cell_boxes = self._boxes(self.cell_ranges)

    def _boxes(self, ranges):
        starts = [np.concatenate([[0], np.cumsum(r)]) for r in ranges]
        boxes = []
        for r in range(self.size):
            idx = [r % self.procs[0], (r // self.procs[0]) % self.procs[1], r // (self.procs[0] * self.procs[1])]
            boxes.append([(int(starts[d][idx[d]]), int(starts[d][idx[d] + 1])) for d in range(self.dim)])
        return boxes

    def exchange(self, grid, width, star=False):
        """Per rank: (messages, points received, points sent) of one ghost exchange: a BOX stencil
        (the owned box grown by width in every direction at once), or a STAR one (grown along one
        direction at a time: the face neighbours of the pressure matrix's MatMult)."""
        boxes = self.node_boxes if grid == "node" else self.cell_boxes
        extent = [c + 1 for c in self.cells] if grid == "node" else self.cells

        def grown(box, dirs):
            return [(max(0, a - width), min(extent[d], b + width)) if d in dirs else (a, b) for d, (a, b) in enumerate(box)]

        shapes = [[d] for d in range(self.dim)] if star else [list(range(self.dim))]
        ghost = [[grown(box, dirs) for dirs in shapes] for box in boxes]

        def overlap(gs, o):  # the star's arms are disjoint outside the owned box, which o does not meet
            total = 0
            for g in gs:
                v = 1
                for (a, b), (c, e) in zip(g, o):
                    v *= max(0, min(b, e) - max(a, c))
                total += v
            return total

        out = []
        for r in range(self.size):
            recv = [overlap(ghost[r], boxes[q]) for q in range(self.size) if q != r]
            send = [overlap(ghost[q], boxes[r]) for q in range(self.size) if q != r]
            out.append((sum(1 for x in recv if x) + sum(1 for x in send if x), sum(recv), sum(send)))
        return out

    def pairs(self, grid, width, reach=2):
        """Per rank, {q: (points r receives from q, points r sends to q)} of a BOX exchange, over the
        ranks within `reach` process-grid slots (enough while each rank owns 2 or more cells per
        direction: the prediction's many ranks; the check counts all pairs)."""
        boxes = self.node_boxes if grid == "node" else self.cell_boxes
        extent = [c + 1 for c in self.cells] if grid == "node" else self.cells
        ghost = [[(max(0, a - width), min(extent[d], b + width)) for d, (a, b) in enumerate(box)] for box in boxes]

        def overlap(g, o):
            v = 1
            for (a, b), (c, e) in zip(g, o):
                v *= max(0, min(b, e) - max(a, c))
            return v

        m, n = self.procs[0], self.procs[1]
        out = []
        for r in range(self.size):
            i, j, k = r % m, (r // m) % n, r // (m * n)
            near = {}
            for dk in range(-reach, reach + 1) if self.dim == 3 else [0]:
                for dj in range(-reach, reach + 1):
                    for di in range(-reach, reach + 1):
                        a, b, c = i + di, j + dj, k + dk
                        if (di or dj or dk) and 0 <= a < m and 0 <= b < n and 0 <= c < self.procs[2]:
                            q = a + m * (b + n * c)
                            rv, sd = overlap(ghost[r], boxes[q]), overlap(ghost[q], boxes[r])
                            if rv or sd:
                                near[q] = (rv, sd)
            out.append(near)
        return out

    def owned_cells(self):
        return [int(np.prod([b - a for a, b in box])) for box in self.cell_boxes]


def semi_implicit_terms(solves, iterations):
    """The semi-implicit pressure's extra exchanges and reductions in one step (pressure_implicit.cxx,
    PETSc's CG with Jacobi, whose every message PETSc logs; hypre's own, with the default BoomerAMG
    or PFMG, it does not): `solves` outer iterations, each one KSPSolve, `iterations` CG iterations
    in all. CG: one MatMult per iteration and one per solve (the initial residual), two VecTDot per
    iteration and per solve, one VecNorm per iteration and two per solve. Outside the KSP: one ICE
    ghost exchange per outer iteration, the residual's reduction per outer iteration and one for the
    final residual, and one for the matrix's diagonal dominance."""
    matmults = iterations + solves
    ksp_reductions = 2 * (iterations + solves) + (iterations + 2 * solves)
    exchanges = [("ICE ghosts per outer iteration", "cell", "state", ["ICE_Pressure", "ICE_Ghosts"], False, solves),
                 ("pressure MatMult", "cellp", "one", ["ICE_Pressure", "ICE_PSolve", "KSPSolve", "MatMult"], True, matmults)]
    reductions = [("ICE_Pressure", ksp_reductions + (solves + 1) + 1), ("ICE_PSolve", ksp_reductions), ("KSPSolve", ksp_reductions),
                  ("VecTDot", 2 * (iterations + solves)), ("VecNorm", iterations + 2 * solves)]
    return exchanges, reductions


def predict_counts(scene, cells, size, perturb=False, solves=0, iterations=0):
    """{event: [(messages, bytes, reductions) per rank]} for one step, plus "summary" (the stage).
    perturb: the self-test's wrong model, one dof too many in the pressure-work exchange. solves,
    iterations: the semi-implicit pressure's outer iterations and CG iterations in the step (0: explicit)."""
    dec = Decomposition(scene["dim"], cells, size)
    dof = dict(dofs(scene), one=1)
    if perturb:
        dof["work"] += 1
    exchanges = [(*x, False, 1) for x in EXCHANGES]
    reductions = list(REDUCTIONS)
    if solves:
        extra_x, extra_r = semi_implicit_terms(solves, iterations)
        exchanges += extra_x
        reductions += extra_r
    events = sorted({e for x in exchanges for e in x[3]} | {e for e, _ in reductions if e})
    per = {e: [[0, 0, 0] for _ in range(size)] for e in events + ["summary"]}
    cache = {}
    for _, grid, key, evs, star, times in exchanges:
        width = 1 if grid == "cellp" else scene["node_width"] if grid == "node" else 2  # the pressure DMDA: STAR, width 1
        tag = (grid, width, star)
        if tag not in cache:
            cache[tag] = dec.exchange("cell" if grid == "cellp" else grid, width, star)
        for r, (msgs, recv, send) in enumerate(cache[tag]):
            nbytes = BYTES_PER_SCALAR * dof[key] * (recv + send)
            for e in evs + ["summary"]:
                per[e][r][0] += times * msgs
                per[e][r][1] += times * nbytes
    if size > 1:
        for e, n in reductions:
            for r in range(size):
                if e:
                    per[e][r][2] += n
                if e in (None, "MPM_TimeStep", "ICE_TimeStep", "MPM_Migrate", "Cpl_BurnParticles", "ICE_Pressure"):  # not nested in another counted one
                    per["summary"][r][2] += n
    return per, dec


# ---------------------------------------------------------------- particles per rank (seeding replayed)
def seeded_points(scene, cells):
    """Particles per owned cell: an array of particle counts over the cells (i, j[, k]), from the
    seeding rule (seed.cxx: ppc^dim sub-cell centres, kept if a geometry contains them)."""
    dim, ppc = scene["dim"], scene["ppc"]
    lo, hi = scene["lower"], scene["upper"]
    h = [(hi[d] - lo[d]) / cells[d] for d in range(dim)]
    # in-plane sub-cell centres, the same arithmetic as seed.cxx
    x = lo[0] + (np.arange(cells[0])[:, None] + (np.arange(ppc)[None, :] + 0.5) / ppc) * h[0]
    y = lo[1] + (np.arange(cells[1])[:, None] + (np.arange(ppc)[None, :] + 0.5) / ppc) * h[1]
    r = np.sqrt(x[:, None, :, None] ** 2 + y[None, :, None, :] ** 2)  # [i, j, si, sj]
    inplane = (r <= OUTER_RADIUS).sum(axis=(2, 3))  # per (i, j) cell
    if dim == 2:
        return inplane
    z = lo[2] + (np.arange(cells[2])[:, None] + (np.arange(ppc)[None, :] + 0.5) / ppc) * h[2]
    layers = ((z >= 0) & (z <= Z_CAP)).sum(axis=1)  # body (<= 0.1) and cap (0.1, 0.10635] share the outer radius
    return inplane[:, :, None] * layers[None, None, :]


def particles_per_rank(scene, cells, dec):
    counts = seeded_points(scene, cells)
    out = []
    for box in dec.node_boxes:  # a cell belongs to the rank of its lower node
        sl = tuple(slice(a, min(b, cells[d])) for d, (a, b) in enumerate(box))
        out.append(int(counts[sl].sum()))
    return out


# ---------------------------------------------------------------- running burst
def burst_run(args, n, options, steps, log=True):
    """One run; returns (summary.json, {rank: {event: (count, time, messages, bytes, reductions)}})."""
    with tempfile.TemporaryDirectory() as out:
        launch = shlex.split(LAUNCHER.format(n=n)) if n > 1 else []
        logfile = os.path.join(out, "log.txt")
        cmd = ["nice", "-n", "19", *launch, args.burst, *options, "-max_steps", str(steps), "-output_dir", out, "-output_interval", "0",
               "-output_grid", "false", "-progress", "false", "-fragments", "false", "-monitor_interval", "100000"]
        if log:
            cmd += ["-log_view", f":{logfile}:ascii_info_detail"]
        proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
        if proc.returncode:
            print(proc.stdout[-3000:], proc.stderr[-3000:])
            raise SystemExit(f"run failed: {' '.join(cmd)}")
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
        events = {}
        if log:
            pat = re.compile(r'^Stages\["Stepping"\]\["([^"]+)"\]\[(\d+)\] = (\{.*\})$')
            with open(logfile) as f:
                for line in f:
                    mt = pat.match(line.strip())
                    if mt:
                        # (PETSc writes numbers such as "212.": not JSON)
                        d = {k: float(v) for k, v in re.findall(r'"(\w+)"\s*:\s*([-+0-9.eE]+)', mt.group(3))}
                        events.setdefault(int(mt.group(2)), {})[mt.group(1)] = (d.get("count", 1), d["time"], d["numMessages"], d["messageLength"], d["numReductions"])
        return summary, events


def printed_half_unit(v):
    """Half a unit of the 6th significant digit of a value PETSc printed with %g (0 below 1e6)."""
    return 0.0 if abs(v) < 1e6 else 0.5 * 10 ** (math.floor(math.log10(abs(v))) - 5)


def scene_options(scene, cells, extra=""):
    # the model is of the run without -mpm_stress_share: the points a crowded rank sends depend on
    # its measured cost of sending them, so those messages are not a function of the decomposition
    return ["-options_file", scene["opts"], "-grid_cells", ",".join(str(c) for c in cells), "-mpm_stress_share", "0", *shlex.split(extra)]


def cmd_check(args):
    scene = SCENES[args.scene]
    cells = tuple(int(c) for c in args.grid.split(",")) if args.grid else scene["grid"]
    rows, bad = [], 0
    for n in [int(x) for x in args.ranks.split(",")]:
        extra = args.extra + (" " + SEMI_IMPLICIT if args.semi_implicit else "")
        s1, m1 = burst_run(args, n, scene_options(scene, cells, extra), 1)
        s2, m2 = burst_run(args, n, scene_options(scene, cells, extra), 2)
        solves = iterations = 0
        if args.semi_implicit:  # the solver's iteration counts are inputs (rank 0's log; every rank takes part)
            solves = int(m2[0]["KSPSolve"][0] - m1[0]["KSPSolve"][0])
            iterations = int(m2[0]["MatMult"][0] - m1[0]["MatMult"][0]) - solves
            print(f"semi-implicit pressure in the second step: {solves} outer iterations, {iterations} CG iterations")
        pred, dec = predict_counts(scene, cells, n, perturb=args.perturb, solves=solves, iterations=iterations)
        parts = particles_per_rank(scene, cells, dec)
        if sum(parts) != s1["particles"]:
            print(f"particles: model {sum(parts)}, burst {s1['particles']}")
            bad += 1
        for r in range(n):
            for e in pred:
                a, b = m1[r].get(e, (0, 0, 0, 0, 0)), m2[r].get(e, (0, 0, 0, 0, 0))
                for q, name in ((0, "messages"), (1, "bytes"), (2, "reductions")):
                    measured = b[2 + q] - a[2 + q]
                    tol = printed_half_unit(a[2 + q]) + printed_half_unit(b[2 + q])
                    model = pred[e][r][q]
                    ok = abs(model - measured) <= tol
                    bad += not ok
                    rows.append(dict(scene=args.scene, grid="x".join(map(str, cells)), ranks=n, procs="x".join(map(str, dec.procs[:scene["dim"]])),
                                     rank=r, event=e, quantity=name, model=model, measured=measured, tolerance=tol, ok=int(ok)))
                    if not ok:
                        print(f"MISMATCH {args.scene} n={n} rank {r} {e} {name}: model {model}, measured {measured} (tolerance {tol})")
        tot = pred["summary"]
        print(f"{args.scene} {cells} on {n} rank(s), process grid {dec.procs[:scene['dim']]}: per step and rank messages "
              f"{[t[0] for t in tot]}, bytes {[t[1] for t in tot]}, reductions {[t[2] for t in tot]}; particles per rank {parts}")
    os.makedirs(args.out, exist_ok=True)
    path = os.path.join(args.out, f"check_{args.scene}_{'x'.join(map(str, cells))}{'_semi_implicit' if args.semi_implicit else ''}.csv")
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    print(f"{len(rows) - bad} of {len(rows)} counts agree; wrote {path}")
    return 1 if bad else 0


# ---------------------------------------------------------------- migration
MIGRATION_REDUCTIONS = 12  # per migrating step: DMSwarmMigrate's 11 (its topology set-up) and the count check (swarm.cxx)
MIGRATION_MESSAGES_PER_NEIGHBOUR = 6  # topology, send counts and particles, each one way and back
MIGRATION_BYTES_PER_NEIGHBOUR = 28  # topology (20) and the two counts (8), besides the particles' own bytes


def box_neighbours(dec):
    """Per rank, the ranks whose cell boxes touch its own (faces, edges, corners)."""
    out = []
    for r, br in enumerate(dec.cell_boxes):
        out.append(sum(1 for q, bq in enumerate(dec.cell_boxes) if q != r and all(max(a, c) <= min(b, e) for (a, b), (c, e) in zip(br, bq))))
    return out


def cmd_migration(args):
    """The migration's counts over a run long enough for the particles to cross rank boundaries.
    Which steps migrate, between which ranks and how many particles is the motion's, not the
    decomposition's: the reductions are checked exactly given the number of migrating steps M (the
    DMSwarmMigrate count in the log), the messages as 6 per neighbour and migrating step, between
    6 M_r (one neighbour, on the steps where rank r sends or receives) and 6 M n_r (all n_r box
    neighbours every time)."""
    scene = SCENES[args.scene]
    cells = tuple(int(c) for c in args.grid.split(","))
    summary, ev = burst_run(args, args.ranks, scene_options(scene, cells, f"-final_time {args.final_time} -max_steps 100000"), 100000)
    steps = int(ev[0]["MPM_Migrate"][0])
    migrations = int(ev[0].get("DMSwarmMigrate", (0,) * 5)[0])
    dec = Decomposition(scene["dim"], cells, args.ranks)
    nb = box_neighbours(dec)
    bad = 0
    print(f"{args.scene} {cells} on {args.ranks} ranks to {args.final_time} s: {steps} steps, {migrations} with a migration")
    for r in range(args.ranks):
        mig = ev[r]["MPM_Migrate"]
        red_model = steps + MIGRATION_REDUCTIONS * migrations
        exchanged = mig[2] / MIGRATION_MESSAGES_PER_NEIGHBOUR
        ok_red = mig[4] == red_model
        ok_msg = mig[2] % MIGRATION_MESSAGES_PER_NEIGHBOUR == 0 and exchanged <= migrations * nb[r]
        particle_bytes = mig[3] - MIGRATION_BYTES_PER_NEIGHBOUR * exchanged
        bad += not (ok_red and ok_msg)
        print(f"  rank {r}: reductions {mig[4]:.0f} (model {red_model}, {'exact' if ok_red else 'MISMATCH'}), messages {mig[2]:.0f} = 6 x {exchanged:.0f} "
              f"neighbour-steps (bound {migrations * nb[r]}: {'ok' if ok_msg else 'MISMATCH'}), bytes {mig[3]:.0f} of which particles {particle_bytes:.0f}")
    return 1 if bad else 0


# ---------------------------------------------------------------- times
PARTICLE_EVENTS = ["MPM_P2G", "MPM_GridUpdate", "MPM_G2P", "MPM_Remap", "MPM_Stress", "MPM_Migrate", "MPM_TimeStep",
                   "Cpl_BurnParticles", "Cpl_PressureToPart", "Cpl_IncrementsToNode", "Cpl_HeatToParticles"]
# (MPM_GhostSums and ICE_Ghosts are nested in these; Cpl_PressureWork partly in Cpl_PressureToPart)


def pingpong(args):
    """Latency (s) and bandwidth (B/s) of this machine's MPI between two ranks, from the half
    round-trip times of scripts/mpi_pingpong.c (t(n) = alpha + n / beta)."""
    exe = os.path.join(args.out, "mpi_pingpong")
    os.makedirs(args.out, exist_ok=True)
    subprocess.run(["mpicc", "-O2", "-o", exe, os.path.join(ROOT, "scripts", "mpi_pingpong.c")], check=True)
    out = subprocess.run(["nice", "-n", "19", *shlex.split(LAUNCHER.format(n=2)), exe], capture_output=True, text=True, check=True).stdout
    data = np.array([[float(x) for x in line.split()] for line in out.splitlines() if line.strip() and not line.startswith("#")])
    # latency: the smallest message; bandwidth: the slope between the two largest (where the
    # latency is lost in the transfer)
    alpha = data[0, 1]
    beta = (data[-1, 0] - data[-2, 0]) / (data[-1, 1] - data[-2, 1])
    return alpha, beta, data


def step_costs(events, steps, particles, cells):
    """Seconds per particle-step and per cell-step of one 1-rank run (the particle phases against
    the rest of the stepping stage)."""
    ev = events[0]
    total = ev["summary"][1]
    t_part = sum(ev[e][1] for e in PARTICLE_EVENTS if e in ev)
    return t_part / (particles * steps), (total - t_part) / (cells * steps)


def predict_step_time(scene, cells, size, cost_particle, cost_cell, net, part=None, migrate=False):
    """Predicted seconds per step: the slowest rank's compute, then each exchange in turn (the
    busiest rank's latencies, alpha per message pair, and its on-node bytes at beta_on each way, then
    the busiest node's off-node bytes through its one network port at beta_off), then the reductions
    (a tree: 2 levels per halving, those within a node at alpha_on, the others at alpha_off).
    Ranks fill nodes in order (rank // cores_per_node). net: dict(alpha_on, beta_on, alpha_off,
    beta_off, cores_per_node). migrate: add a migration on every step (the burst's late phase on many
    ranks: 12 reductions and 6 messages per box neighbour; the particles' bytes left out)."""
    dec = Decomposition(scene["dim"], cells, size)
    if part is None:
        part = particles_per_rank(scene, cells, dec)
    owned = dec.owned_cells()
    compute = [cost_particle * p + cost_cell * c for p, c in zip(part, owned)]
    t_compute = max(compute)
    t_mean = sum(compute) / size
    dof = dofs(scene)
    cpn = net["cores_per_node"]
    node_of = [r // cpn for r in range(size)]
    nodes = node_of[-1] + 1
    t_comm = 0.0
    cache = {}
    for _, grid, key, _ in EXCHANGES if size > 1 else []:
        width = scene["node_width"] if grid == "node" else 2
        if (grid, width) not in cache:
            cache[(grid, width)] = dec.pairs(grid, width)
        scalar = BYTES_PER_SCALAR * dof[key]
        busiest_rank, node_bytes = 0.0, [0.0] * nodes
        for r, near in enumerate(cache[(grid, width)]):
            t = 0.0
            for q, (rv, sd) in near.items():
                msgs = (rv > 0) + (sd > 0)
                if node_of[q] == node_of[r]:
                    t += msgs / 2 * net["alpha_on"] + scalar * max(rv, sd) / net["beta_on"]
                else:
                    t += msgs / 2 * net["alpha_off"]
                    node_bytes[node_of[r]] += scalar * sd
            busiest_rank = max(busiest_rank, t)
        t_comm += busiest_rank + max(node_bytes) / net["beta_off"]
    reductions = sum(n for _, n in REDUCTIONS) if size > 1 else 0
    if size > 1 and migrate:
        reductions += MIGRATION_REDUCTIONS
        t_comm += max(box_neighbours(dec)) * MIGRATION_MESSAGES_PER_NEIGHBOUR / 2 * (net["alpha_off"] if nodes > 1 else net["alpha_on"])
    levels = math.ceil(math.log2(size)) if size > 1 else 0
    levels_on = min(levels, math.ceil(math.log2(min(size, cpn)))) if size > 1 else 0
    t_red = reductions * 2 * (levels_on * net["alpha_on"] + (levels - levels_on) * net["alpha_off"])
    return dict(total=t_compute + t_comm + t_red, compute=t_compute, compute_mean=t_mean, comm=t_comm, reductions=t_red,
                imbalance=t_compute / t_mean if t_mean > 0 else 1.0, particles_max=max(part), particles=sum(part),
                procs="x".join(map(str, dec.procs[:scene["dim"]])))


def stepping_difference(args, n, options, steps):
    """The event times of `steps` steps without the first two (lazy set-up of the scatters in the
    first step): a run of steps + 2 less a run of 2, per rank and event."""
    _, a = burst_run(args, n, options, 2)
    s, b = burst_run(args, n, options, steps + 2)
    diff = {r: {e: (v[0], v[1] - a[r].get(e, (0, 0))[1], *v[2:]) for e, v in b[r].items()} for r in b}
    return s, diff


def cmd_times(args):
    scene = SCENES[args.scene]
    calib = tuple(int(c) for c in args.calibrate_grid.split(","))
    cells = tuple(int(c) for c in args.grid.split(","))
    steps = args.steps
    alpha, beta, _ = pingpong(args)
    print(f"ping-pong (2 ranks, shared memory): latency {alpha * 1e6:.2f} us, bandwidth {beta / 1e9:.2f} GB/s")
    ncell = int(np.prod(calib[:scene["dim"]]))
    costs = []
    for _ in range(args.repeats):  # the fastest of the repeats: a loaded machine only slows a run
        s, ev = stepping_difference(args, 1, scene_options(scene, calib), steps)
        costs.append(step_costs(ev, steps, s["particles"], ncell))
    cp, cc = min(costs, key=lambda c: c[0] * s["particles"] + c[1] * ncell)
    print(f"calibration {calib} on 1 rank: {cp * 1e6:.3f} us per particle-step, {cc * 1e6:.3f} us per cell-step")
    net = dict(alpha_on=alpha, beta_on=beta, alpha_off=alpha, beta_off=beta, cores_per_node=2)
    rows = []
    for n in (1, 2):
        measured = math.inf
        for _ in range(args.repeats):
            s, ev = stepping_difference(args, n, scene_options(scene, cells), steps)
            measured = min(measured, max(ev[r]["summary"][1] for r in ev) / steps)
        p = predict_step_time(scene, cells, n, cp, cc, net)
        err = p["total"] / measured - 1
        rows.append(dict(scene=args.scene, grid="x".join(map(str, cells)), ranks=n, steps=steps, load_average=os.getloadavg()[0], measured_s_per_step=measured, predicted_s_per_step=p["total"],
                         error=err, compute=p["compute"], comm=p["comm"], reductions=p["reductions"], imbalance=p["imbalance"],
                         cost_particle=cp, cost_cell=cc, alpha=alpha, beta=beta))
        print(f"{args.scene} {cells} on {n} rank(s): measured {measured * 1e3:.3f} ms per step, predicted {p['total'] * 1e3:.3f} ms "
              f"(compute {p['compute'] * 1e3:.3f}, exchanges {p['comm'] * 1e3:.3f}, reductions {p['reductions'] * 1e3:.4f}); error {err * 100:+.1f} %")
    os.makedirs(args.out, exist_ok=True)
    path = os.path.join(args.out, f"times_{args.scene}.csv")
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    print(f"wrote {path}")
    return 0


# ---------------------------------------------------------------- prediction
def cmd_predict(args):
    scene = SCENES["3d"]
    with open(args.times) as f:
        t = list(csv.DictReader(f))
    cp, cc = float(t[0]["cost_particle"]), float(t[0]["cost_cell"])
    net = dict(alpha_on=float(t[0]["alpha"]), beta_on=float(t[0]["beta"]), alpha_off=args.latency, beta_off=args.bandwidth,
               cores_per_node=args.cores_per_node)
    paper = tuple(int(c) for c in args.paper_grid.split(","))
    ranks = [2 ** k for k in range(11)]
    rows = []
    base = predict_step_time(scene, paper, 1, cp, cc, net)
    for n in ranks:
        p = predict_step_time(scene, paper, n, cp, cc, net, migrate=True)
        rows.append(dict(kind="strong", ranks=n, grid="x".join(map(str, paper)), efficiency=base["total"] / (n * p["total"]), **p))
    coarse = tuple(int(c) for c in args.weak_base.split(","))
    wbase = predict_step_time(scene, coarse, 1, cp, cc, net)
    for n in ranks:
        f = n ** (1.0 / 3.0)
        g = tuple(int(round(c * f)) for c in coarse)
        p = predict_step_time(scene, g, n, cp, cc, net, migrate=True)
        # the work grows as the cells: efficiency is time per unit of work, 1 rank against n
        work = (p["particles"] * cp + np.prod(g) * cc) / (wbase["particles"] * cp + np.prod(coarse) * cc)
        rows.append(dict(kind="weak", ranks=n, grid="x".join(map(str, g)), efficiency=wbase["total"] * work / (n * p["total"]), **p))
    os.makedirs(args.out, exist_ok=True)
    path = os.path.join(args.out, "prediction.csv")
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    for r in rows:
        print(f"{r['kind']:6s} {r['ranks']:5d} {r['grid']:>12s} procs {r['procs']:>8s} eff {r['efficiency']:.3f} step {r['total'] * 1e3:9.3f} ms "
              f"compute {r['compute'] * 1e3:9.3f} (imbalance {r['imbalance']:.2f}) exchanges {r['comm'] * 1e3:7.3f} reductions {r['reductions'] * 1e3:.4f} ms")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7.5, 4.6))
    for kind, style in (("strong", "o-"), ("weak", "s-")):
        sel = [r for r in rows if r["kind"] == kind]
        ax.semilogx([r["ranks"] for r in sel], [r["efficiency"] for r in sel], style, base=2, label=f"predicted, {kind}")
    bal = [r for r in rows if r["kind"] == "strong"]
    ax.semilogx([r["ranks"] for r in bal], [1 / r["imbalance"] for r in bal], ":", base=2, color="gray", label="strong, the compute imbalance alone (mean/max over ranks)")
    for f, colour in zip(args.measured, ("black", "tab:red", "tab:green")):
        with open(f) as fh:
            m = list(csv.DictReader(fh))
        if len(m) >= 2:
            t1, t2 = float(m[0]["measured_s_per_step"]), float(m[1]["measured_s_per_step"])
            p1, p2 = float(m[0]["predicted_s_per_step"]), float(m[1]["predicted_s_per_step"])
            ax.plot([2], [t1 / (2 * t2)], "^", color=colour, label=f"measured on this machine ({args.machine}), {m[0]['scene']} {m[0]['grid']}, 2 ranks")
            ax.plot([2], [p1 / (2 * p2)], "x", color=colour, ms=9, label=f"model of the same, on this machine's figures")
    ax.set_xticks(ranks)
    ax.set_xticklabels([str(r) for r in ranks])
    ax.set_xlabel("ranks")
    ax.set_ylabel("parallel efficiency (time per step)")
    ax.set_ylim(0, 1.45)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="upper right")
    ax.set_title(f"3-D exploding cylinder {args.paper_grid.replace(',', ' x ')} (strong); weak from {args.weak_base.replace(',', ' x ')} per rank\n"
                 f"{args.cores_per_node} cores/node, {args.latency * 1e6:.1f} us, {args.bandwidth / 1e9:.1f} GB/s between nodes", fontsize=8)
    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    fig.text(0.01, 0.005, f"{args.machine}, {datetime.date.today()}, commit {commit}", fontsize=7)
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    png = os.path.join(args.out, "scaling_model.png")
    fig.savefig(png, dpi=120)
    print(f"wrote {path}, {png}")
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    c = sub.add_parser("check")
    c.add_argument("--burst", required=True)
    c.add_argument("--scene", choices=SCENES, default="2d")
    c.add_argument("--ranks", default="1,2,4,8")
    c.add_argument("--grid", default="", help="cells per direction (default: the scene's small grid)")
    c.add_argument("--extra", default="", help="further burst options")
    c.add_argument("--semi-implicit", action="store_true", help=f"the semi-implicit gas pressure with CG + Jacobi ({SEMI_IMPLICIT})")
    c.add_argument("--perturb", action="store_true", help="self-test: one dof too many in the pressure-work exchange; the check must fail")
    c.add_argument("--out", default=os.path.join(ROOT, "build", "scaling_model"))
    g = sub.add_parser("migration")
    g.add_argument("--burst", required=True)
    g.add_argument("--scene", choices=SCENES, default="2d")
    g.add_argument("--grid", default="40,40")
    g.add_argument("--ranks", type=int, default=8)
    g.add_argument("--final-time", type=float, default=1e-4)
    t = sub.add_parser("times")
    t.add_argument("--burst", required=True)
    t.add_argument("--scene", choices=SCENES, default="2d")
    t.add_argument("--calibrate-grid", default="40,40")
    t.add_argument("--grid", default="60,60")
    t.add_argument("--steps", type=int, default=20)
    t.add_argument("--repeats", type=int, default=3, help="runs per point; the fastest counts")
    t.add_argument("--out", default=os.path.join(ROOT, "build", "scaling_model"))
    p = sub.add_parser("predict")
    p.add_argument("--times", default=os.path.join(ROOT, "build", "scaling_model", "times_3d.csv"), help="the 3-D calibration (times)")
    p.add_argument("--measured", nargs="*", default=[], help="times_*.csv whose 1-2 rank points go on the chart")
    p.add_argument("--paper-grid", default="120,120,180", help="the 2-D paper's 0.75 mm cells on the 3-D scene's box")
    p.add_argument("--weak-base", default="30,30,45", help="the grid of one rank in the weak study (cells x ranks^(1/3))")
    p.add_argument("--latency", type=float, default=1.5e-6, help="between nodes (s)")
    p.add_argument("--bandwidth", type=float, default=12.0e9, help="between nodes (B/s)")
    p.add_argument("--cores-per-node", type=int, default=64)
    p.add_argument("--machine", default=platform.node())
    p.add_argument("--out", default=os.path.join(ROOT, "build", "scaling_model"))
    args = ap.parse_args()
    return {"check": cmd_check, "migration": cmd_migration, "times": cmd_times, "predict": cmd_predict}[args.cmd](args)


if __name__ == "__main__":
    sys.exit(main())
