#!/usr/bin/env python3
"""ParaView opens burst's output without complaint.

Runs a short 2-D scene (colliding disks) and a short 3-D scene (spheres), then opens particles.xmf
and grid.xmf (and gas.xmf of a 2-D and a 3-D gas blast) with ParaView's XDMF readers (XDMFReader, i.e. Xdmf2, and Xdmf3ReaderS) in a pvpython
subprocess, updates every time step and checks:
  - nothing on stdout/stderr of pvpython matches HDF5|Error|ERROR|error (HDF5 error traces, VTK errors);
  - the number of time steps, particles (points and polyvertex cells) and grid points/cells;
  - the arrays exist with the expected names and components; grid bounds match -grid_lower/-grid_upper;
  - particle mass sum equals the HDF5 files' sum; grid mass >= 0, and from step 1 on, grid mass sum and
    first moment equal the particles' (P2G reproduces linear functions) to 1e-10 relative, which also
    checks the axis order (the scenes are made non-square and off-diagonal for that).

Usage: check_paraview.py --burst build/burst [--ranks 1,2] [--pvpython /usr/bin/pvpython] [--out DIR]
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

SCENES = [
    # name, deck, extra options (non-square grid, asymmetric bodies: axis mix-ups change the answer)
    ("disks2d", "options/scenes/colliding_disks.opts",
     ["-max_steps", "3", "-grid_upper", "1,1.25", "-grid_cells", "20,25", "-lower_center", "0.25,0.35"]),
    ("spheres3d", "options/scenes/spheres3d.opts",
     ["-max_steps", "2", "-grid_upper", "1,1.25,1.5", "-grid_cells", "16,20,24", "-a_center", "0.3,0.35,0.4"]),
    # gas cells (gas.xmf): the blast off-centre on a non-square grid, 2-D and 3-D
    ("gas2d", "options/scenes/blast2d.opts",
     ["-max_steps", "2", "-output_interval", "1", "-grid_upper", "1,1.25", "-grid_cells", "20,25", "-ice_riemann_center", "0.2,0.5,0"]),
    ("gas3d", "options/scenes/blast2d.opts",
     ["-dim", "3", "-max_steps", "2", "-output_interval", "1", "-grid_lower", "0,0,0", "-grid_upper", "1,1.25,1.5", "-grid_cells", "8,10,12",
      "-ice_riemann_shape", "sphere", "-ice_riemann_center", "0.2,0.5,0.7", "-ice_bc_zmin", "symmetry", "-ice_bc_zmax", "outflow"]),
]

# Runs inside pvpython: prints one JSON line with what ParaView read.
PV_SCRIPT = r'''
import json, sys
from paraview.simple import *
from vtkmodules.util.numpy_support import vtk_to_numpy
import numpy as np

def leaves(obj):
    if obj.IsA("vtkCompositeDataSet"):
        it = obj.NewIterator()
        it.InitTraversal()
        while not it.IsDoneWithTraversal():
            yield it.GetCurrentDataObject()
            it.GoToNextItem()
    else:
        yield obj

def read(kind, path):
    if kind == "xdmf2":
        r = XDMFReader(FileNames=[path])
        r.UpdatePipelineInformation()
        r.PointArrayStatus = r.GetProperty("PointArrayInfo")[::2]
        r.CellArrayStatus = r.GetProperty("CellArrayInfo")[::2]
    else:
        r = Xdmf3ReaderS(FileName=[path])
        r.UpdatePipelineInformation()
    times = list(r.TimestepValues) if r.TimestepValues else [0.0]
    steps = []
    for t in times:
        r.UpdatePipeline(time=t)
        out = r.GetClientSideObject().GetOutputDataObject(0)
        step = {"time": t, "points": 0, "cells": 0, "arrays": {}, "bounds": None}
        for ds in leaves(out):
            if ds is None or not ds.IsA("vtkDataSet"):
                continue
            step["points"] += ds.GetNumberOfPoints()
            step["cells"] += ds.GetNumberOfCells()
            b = ds.GetBounds()
            step["bounds"] = list(b)
            pts = vtk_to_numpy(ds.GetPoints().GetData()) if ds.IsA("vtkPointSet") else \
                np.array([ds.GetPoint(i) for i in range(ds.GetNumberOfPoints())])
            for where, fd in (("point", ds.GetPointData()), ("cell", ds.GetCellData())):
                for i in range(fd.GetNumberOfArrays()):
                    a = fd.GetArray(i)
                    if a is None:
                        continue
                    v = vtk_to_numpy(a).astype(float)
                    info = {"where": where, "components": a.GetNumberOfComponents(), "tuples": a.GetNumberOfTuples(), "min": float(v.min()) if v.size else 0.0,
                            "max": float(v.max()) if v.size else 0.0, "sum": float(v.sum())}
                    if a.GetName() == "mass" and where == "point" and v.ndim == 1 and v.size == len(pts):
                        info["moment"] = [float((v * pts[:, d]).sum()) for d in range(3)]
                    step["arrays"][a.GetName()] = info
        steps.append(step)
    Delete(r)
    return steps

result = {}
for kind in ("xdmf2", "xdmf3"):
    for path in sys.argv[1:]:
        result[kind + ":" + path] = read(kind, path)
print("PVRESULT " + json.dumps(result))
'''

NOISE = re.compile(r"HDF5|Error|ERROR|error")


def find_pvpython(arg):
    """A headless pvpython command: pvpython --force-offscreen-rendering, else python3 with paraview."""
    candidates = []
    if arg:
        candidates.append([arg, "--force-offscreen-rendering"])
    if shutil.which("pvpython"):
        candidates.append([shutil.which("pvpython"), "--force-offscreen-rendering"])
    candidates.append([sys.executable])
    for c in candidates:
        try:
            p = subprocess.run(c + ["-c", "from paraview.simple import *; print('PVOK')"], capture_output=True, text=True, timeout=120)
        except (OSError, subprocess.TimeoutExpired):
            continue
        if "PVOK" in p.stdout:
            return c
    return None


def grid_option(deck, extra, name, dim):
    value = None
    for line in open(os.path.join(ROOT, deck)):
        tok = line.split()
        if len(tok) >= 2 and tok[0] == name:
            value = tok[1]
    if name in extra:
        value = extra[extra.index(name) + 1]
    return [float(x) for x in value.split(",")][:dim]


def run_scene(args, ranks, name, deck, extra, out):
    cmd = [args.burst, "-options_file", deck, "-output_interval", "1", "-output_grid", "true", "-output_dir", out] + extra
    if ranks > 1:
        cmd = ["mpiexec", "--allow-run-as-root", "--oversubscribe", "-x", "OMP_NUM_THREADS=1", "-n", str(ranks)] + cmd
    p = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    if p.returncode:
        print(p.stdout[-3000:], p.stderr[-3000:])
        raise SystemExit(f"{name}: burst failed ({p.returncode})")


def particle_reference(out):
    ref = []
    for f in sorted(x for x in os.listdir(out) if re.fullmatch(r"particles_\d+\.h5", x)):
        with h5py.File(os.path.join(out, f), "r") as h:
            m = np.asarray(h["/particles/mass"]).reshape(-1)
            x = np.asarray(h["/particles/coordinates"])
            x = x.reshape(m.size, -1)
            moment = [float((m * x[:, d]).sum()) if d < x.shape[1] else 0.0 for d in range(3)]
            ref.append({"file": f, "n": m.size, "mass": float(m.sum()), "moment": moment})
    return ref


def gas_reference(out):
    """Per gas output file (in step order): the sum of each scalar cell dataset."""
    ref = []
    files = sorted(f for f in os.listdir(out) if f.startswith("gas_") and f.endswith(".h5"))
    for f in files:
        with h5py.File(os.path.join(out, f), "r") as h:
            ref.append({k: float(np.asarray(h["cells"][k]).sum()) for k in h["cells"]})
    return ref


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--burst", required=True)
    ap.add_argument("--ranks", default="1", help="MPI ranks, or a comma list run in turn (1,2)")
    ap.add_argument("--pvpython", default=None, help="pvpython executable (default: pvpython on PATH, else this python)")
    ap.add_argument("--out", default=None, help="output directory (default: a temporary one, removed)")
    args = ap.parse_args()
    args.burst = os.path.abspath(args.burst)

    pv = find_pvpython(args.pvpython)
    if pv is None:
        raise SystemExit("ParaView's Python (python3-paraview) not found: install it (scripts/install-deps.sh)")
    print("pvpython command:", " ".join(pv))

    base = args.out or tempfile.mkdtemp(prefix="check_paraview_")
    os.makedirs(base, exist_ok=True)
    failures = []

    def check(cond, msg):
        if not cond:
            failures.append(msg)
        return cond

    for ranks, (name, deck, extra) in [(int(r), sc) for r in args.ranks.split(",") for sc in SCENES]:
        out = os.path.join(base, f"{name}_np{ranks}")
        shutil.rmtree(out, ignore_errors=True)
        run_scene(args, ranks, name, deck, extra, out)
        name = f"{name} np{ranks}"
        dim = 3 if "3d" in name else 2
        lower = grid_option(deck, extra, "-grid_lower", dim)
        upper = grid_option(deck, extra, "-grid_upper", dim)
        cells = [int(c) for c in grid_option(deck, extra, "-grid_cells", dim)]
        gas = name.startswith("gas")
        ref = gas_reference(out) if gas else particle_reference(out)
        files = [os.path.join(out, "gas.xmf")] if gas else [os.path.join(out, "particles.xmf"), os.path.join(out, "grid.xmf")]
        p = subprocess.run(pv + ["-c", PV_SCRIPT] + files, capture_output=True, text=True, timeout=600)
        lines = [l for l in (p.stdout + p.stderr).splitlines() if not l.startswith("PVRESULT ")]
        noise = [l for l in lines if NOISE.search(l)]
        check(not noise, f"{name}: ParaView printed {len(noise)} error line(s), first: {noise[:5]}")
        if noise:
            print(f"--- {name}: pvpython output ({len(lines)} lines), first 40:\n" + "\n".join(lines[:40]))
        res = [l for l in p.stdout.splitlines() if l.startswith("PVRESULT ")]
        if not check(p.returncode == 0 and res, f"{name}: pvpython failed ({p.returncode})"):
            print(p.stdout[-3000:], p.stderr[-3000:])
            continue
        result = json.loads(res[0][len("PVRESULT "):])
        npoints = int(np.prod([c + 1 for c in cells]))
        ncells = int(np.prod(cells))
        for key, steps in result.items():
            kind, path = key.split(":", 1)
            tag = f"{name} {kind} {os.path.basename(path)}"
            if not check(len(steps) == len(ref), f"{tag}: {len(steps)} time steps, expected {len(ref)}"):
                continue
            for i, (s, r) in enumerate(zip(steps, ref)):
                st = f"{tag} t={s['time']:.6g}"
                a = s["arrays"]
                for k, info in a.items():
                    expect = s["points"] if info["where"] == "point" else s["cells"]
                    check(info["tuples"] == expect, f"{st}: array {k} has {info['tuples']} tuples, expected {expect}")
                if path.endswith("gas.xmf"):
                    check(s["cells"] == ncells, f"{st}: {s['cells']} cells, expected {ncells}")
                    for field, comps in (("pressure", 1), ("gas_density", 1), ("gas_velocity", 3), ("gas_temperature", 1), ("gas_volume_fraction", 1)):
                        ok = check(field in a and a[field]["components"] == comps and a[field]["where"] == "cell",
                                   f"{st}: gas cell array {field} ({comps} components) missing: { {k: v['components'] for k, v in a.items()} }")
                        if ok and comps == 1:
                            check(abs(a[field]["sum"] - r[field]) <= 1e-12 * abs(r[field]), f"{st}: {field} sum {a[field]['sum']!r} != HDF5 {r[field]!r}")
                    if s["bounds"]:
                        b = s["bounds"]
                        check(all(abs(b[2 * d] - lower[d]) < 1e-12 and abs(b[2 * d + 1] - upper[d]) < 1e-12 for d in range(dim)), f"{st}: gas bounds {b}")
                elif path.endswith("particles.xmf"):
                    # Xdmf3 makes no cells of a Polyvertex topology without a connectivity DataItem
                    # (points and arrays load; shown with the Points representation).
                    cells_ok = s["cells"] == r["n"] or (kind == "xdmf3" and s["cells"] == 0)
                    check(s["points"] == r["n"] and cells_ok, f"{st}: {s['points']} points / {s['cells']} cells, expected {r['n']}")
                    for field, comps in (("mass", 1), ("velocity", 3), ("displacement", 3), ("stress", 9), ("material", 1), ("id", 1)):
                        check(field in a and a[field]["components"] == comps, f"{st}: particle array {field} ({comps} components) missing: {sorted(a)}")
                    if "mass" in a:
                        check(a["mass"]["min"] > 0, f"{st}: particle mass min {a['mass']['min']}")
                        check(abs(a["mass"]["sum"] - r["mass"]) <= 1e-12 * r["mass"], f"{st}: particle mass {a['mass']['sum']} != {r['mass']}")
                else:
                    check(s["points"] == npoints and s["cells"] == ncells, f"{st}: {s['points']} points / {s['cells']} cells, expected {npoints} / {ncells}")
                    for field, comps in (("mass", 1), ("velocity", 3), ("force", 3)):
                        check(field in a and a[field]["components"] == comps and a[field]["where"] == "point",
                              f"{st}: grid point array {field} ({comps} components) missing: { {k: v['components'] for k, v in a.items()} }")
                    if s["bounds"]:
                        b = s["bounds"]
                        expect = [v for d in range(3) for v in ((lower[d], upper[d]) if d < dim else (0.0, 0.0))]
                        check(np.allclose(b, expect, atol=1e-12), f"{st}: grid bounds {b}, expected {expect}")
                    if "mass" in a:
                        m = a["mass"]
                        check(m["min"] >= 0, f"{st}: grid mass min {m['min']} < 0")
                        if i > 0:  # step 0 is written before the first P2G
                            check(abs(m["sum"] - r["mass"]) <= 1e-10 * r["mass"], f"{st}: grid mass sum {m['sum']!r} != particle mass {r['mass']!r}")
                            # The grid holds the P2G of the positions before this step's move, i.e. the
                            # previous output's (every step is written).
                            mom, prev = m.get("moment"), ref[i - 1]["moment"]
                            check(mom is not None and np.allclose(mom, prev, rtol=1e-10, atol=1e-12 * r["mass"]),
                                  f"{st}: grid mass moment {mom} != particle moment {prev} (axis order?)")
        print(f"{name}: {len(ref)} outputs, ParaView read {len(result)} file/reader pairs, {len(noise)} error lines")

    if not args.out:
        shutil.rmtree(base, ignore_errors=True)
    if failures:
        print(f"FAILED: {len(failures)} check(s)")
        for f in failures[:40]:
            print("  " + f)
        return 1
    print("PASSED: ParaView reads particles.xmf, grid.xmf and gas.xmf (XDMF2 and XDMF3 readers) cleanly")
    return 0


if __name__ == "__main__":
    sys.exit(main())
