#!/usr/bin/python3
"""Where methods fail: the largest stable Courant number of each interpolator x transfer x step order,
the energy histories of FLIP, PIC, APIC and XPIC, Jaumann against Green-Naghdi, cell-crossing noise,
numerical fracture with too few particles per cell, and the mesh dependence of strain softening.

  scripts/study_stability.py --burst build/burst [--out doc/figures] [--quick] [--study NAME]

--study cfl (default): the stability map below.
--study shear: simple shear to gamma = 10 through the material-point driver (-mode point) of the
  Green-Naghdi (elastic_plastic, unreachable yield), Jaumann (linear_elastic) and neo-Hookean solids
  against their closed forms (models.md 7.5); stability_shear.csv/png.
--study noise: cell-crossing noise. The 2-D manufactured solution (tests/decks/mms_axis_aligned.opts,
  16 x 16 cells, 2 x 2 particles per cell, USL, FLIP, one period) at growing amplitude A: the largest
  displacement A/h runs from 0.05 to 1.6 cells (particles first cross a cell face at A/h = 0.25). The
  noise is the RMS over particles of |sigma_p - sigma_exact(X_p, t)| (Frobenius) over the RMS of
  |sigma_exact|, averaged over 20 instants of the period; stability_noise.csv/png.
--study fracture: numerical fracture. The elastic ring of tests/decks/tension_ring.opts (no failure
  model) at 1-4 particles per cell per direction for each interpolator. At every output: the hoop
  stretch lambda (mean radius / 0.11 m), the grid fragments (groups of particles that share no node
  with a non-zero weight of both, i.e. between which the grid carries no force; computed from the
  supports: linear |x - x_I| < h, GIMP < h + lp, cpGIMP lp = lp0 |F_dd| clamped to h/2, B-spline < 1.5 h)
  and the stored elastic energy over that of the intact ring at the particles' hoop stretches.
  stability_fracture.csv (per run: lambda at the first split and where the stored energy falls below
  half the intact value), stability_fracture_history.csv, stability_fracture.png.
--study softening: the fragment study's counts (doc/figures/fragments_study.csv, written by
  scripts/study_fragments.py; not rerun here) against resolution; stability_softening.png.
--study overview: the four panels above from their CSVs in one figure (stability_overview.png).
--study all: cfl, shear, noise, fracture, softening, overview.

Problem: the colliding elastic disks (options/scenes/colliding_disks.opts, 20 x 20 cells, t = 3 s).
A run counts as stable when it reaches the final time without burst stopping it: the energy check
-mpm_energy_growth_limit 0.01 (the total energy may not grow by more than 1 % of the largest energy
seen), the NaN check and the J <= 0 check all stop an unstable run with its step, particle and cause.
For each method the CFL numbers are tried in increasing order up to the first failure.
Writes OUT/stability_cfl.csv, OUT/stability_cfl.png (the map: largest stable CFL per method) and
OUT/energy_histories.png (total energy against time at CFL 0.1, MUSL, linear and cpGIMP).
--quick: a reduced form of the chosen study (cfl: two methods, two CFL numbers, no histories; noise:
two interpolators, three amplitudes; fracture: linear and cpGIMP at 1 and 4 per cell), the suite's
smoke tests.
Exits non-zero when a cfl run stops for a reason other than the three instability stops (a crash or
a refused option is not a stability limit), and when --quick's cfl map differs from the recorded map
doc/figures/stability_cfl.csv (the README's chart) on the methods it covers."""
import argparse
import csv
import glob
import importlib.util
import json
import os
import subprocess
import sys
import tempfile

import h5py

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DECK = os.path.join(ROOT, "options/scenes/colliding_disks.opts")
TRANSFERS = {"FLIP": [], "PIC": ["-mpm_flip_fraction", "0"], "APIC": ["-mpm_transfer", "apic"], "XPIC(2)": ["-mpm_transfer", "xpic", "-mpm_xpic_order", "2"]}


def run(burst, extra, history=False):
    with tempfile.TemporaryDirectory() as out:
        cmd = [burst, "-options_file", DECK, "-output_dir", out, "-progress", "false", "-output_interval", "0", "-output_grid", "false",
               "-monitor_interval", "10", "-mpm_energy_growth_limit", "0.01", *extra]
        proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
        reason = ""
        if proc.returncode:
            text = proc.stdout + proc.stderr
            reason = "energy growth" if "unstable: the total energy grew" in text else ("NaN" if "not finite" in text else ("J <= 0" if "det F <= 0" in text else "other"))
        hist = None
        if history and not proc.returncode:
            data = np.genfromtxt(os.path.join(out, "monitor.csv"), delimiter=",", names=True)
            hist = (data["time"], data["total"] - data["external_work"])
        return proc.returncode == 0, reason, hist


def study_cfl(a):
    cfls = [0.1, 0.2] if a.quick else [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.8, 1.0]
    shapes = ["linear"] if a.quick else ["linear", "ugimp", "cpgimp", "bspline2"]
    transfers = ["FLIP", "APIC"] if a.quick else list(TRANSFERS)
    schemes = ["musl"] if a.quick else ["usl", "musl", "usf"]
    rows, failures = [], []
    for scheme in schemes:
        for shape in shapes:
            for tr in transfers:
                best, why = 0.0, "stable to the largest CFL tried"
                for cfl in cfls:
                    ok, reason, _ = run(a.burst, ["-mpm_shape_type", shape, "-mpm_scheme", scheme, "-mpm_cfl", str(cfl), *TRANSFERS[tr]])
                    if not ok:
                        why = f"{reason} at CFL {cfl}"
                        if reason == "other":
                            failures.append(f"{scheme} {shape} {tr} at CFL {cfl}: burst stopped, not on an instability")
                        break
                    best = cfl
                rows.append(dict(scheme=scheme, shape=shape, transfer=tr, largest_stable_cfl=best, failure=why))
                print(f"{scheme} {shape} {tr}: largest stable CFL {best} ({why})", flush=True)
    path = os.path.join(a.out, "stability_cfl.csv")
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print(f"wrote {path}")
    cols = [(sc, tr) for sc in schemes for tr in transfers]
    grid = np.array([[next(r["largest_stable_cfl"] for r in rows if r["shape"] == sh and r["scheme"] == sc and r["transfer"] == tr) for sc, tr in cols] for sh in shapes])
    fig, ax = plt.subplots(figsize=(1.0 + 0.6 * len(cols), 1.2 + 0.5 * len(shapes)))
    im = ax.imshow(grid, cmap="viridis", vmin=0, vmax=max(cfls), aspect="auto")
    for i in range(len(shapes)):
        for j in range(len(cols)):
            ax.text(j, i, f"{grid[i, j]:g}", ha="center", va="center", color="w" if grid[i, j] < 0.5 * max(cfls) else "k", fontsize=7)
    ax.set_xticks(range(len(cols)), [f"{sc}\n{tr}" for sc, tr in cols], fontsize=6)
    ax.set_yticks(range(len(shapes)), shapes, fontsize=7)
    fig.colorbar(im, ax=ax, label="largest stable CFL")
    ax.set_title("colliding disks: largest stable Courant number (energy growth < 1 %, no NaN, J > 0)", fontsize=8)
    fig.tight_layout()
    png = os.path.join(a.out, "stability_cfl.png")
    fig.savefig(png, dpi=110)
    print(f"wrote {png}")
    if a.quick:
        # The quick search is the full one's first steps (the same CFL numbers in the same order), so it
        # must find what the recorded map found, clipped to the CFL numbers it tries.
        recorded = {(r["scheme"], r["shape"], r["transfer"]): float(r["largest_stable_cfl"]) for r in read_csv(os.path.join(ROOT, "doc/figures/stability_cfl.csv"))}
        for r in rows:
            key = (r["scheme"], r["shape"], r["transfer"])
            if key not in recorded:
                failures.append(f"{' '.join(key)} not in doc/figures/stability_cfl.csv")
                continue
            expect = max([c for c in cfls if c <= recorded[key] + 1e-12], default=0.0)
            ok = r["largest_stable_cfl"] == expect
            print(f"  {' '.join(key)}: largest stable CFL {r['largest_stable_cfl']} (recorded map {recorded[key]}, within the CFL numbers tried {expect}) {'OK' if ok else 'FAIL'}")
            if not ok:
                failures.append(f"{' '.join(key)} largest stable CFL {r['largest_stable_cfl']}, recorded {expect}")
        return failures
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.5), sharey=True)
    for ax, shape in zip(axes, ["linear", "cpgimp"]):
        for tr in TRANSFERS:
            ok, reason, hist = run(a.burst, ["-mpm_shape_type", shape, "-mpm_scheme", "musl", "-mpm_cfl", "0.1", *TRANSFERS[tr]], history=True)
            if hist is not None:
                ax.plot(hist[0], hist[1] / hist[1][0], label=tr)
        ax.set_title(f"{shape}, MUSL, CFL 0.1", fontsize=9)
        ax.set_xlabel("time (s)")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("total energy / initial")
    axes[0].legend(fontsize=7)
    fig.tight_layout()
    png = os.path.join(a.out, "energy_histories.png")
    fig.savefig(png, dpi=110)
    print(f"wrote {png}")
    return failures



def write_csv(path, rows):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print(f"wrote {path}")


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


# --- Jaumann against Green-Naghdi (the closed forms and runs of tests/verify_point.py) ---------------
def verify_point_module():
    spec = importlib.util.spec_from_file_location("verify_point", os.path.join(ROOT, "tests/verify_point.py"))
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def study_shear(a):
    vp = verify_point_module()
    G = 1e6
    steps = 400 if a.quick else 2000
    with tempfile.TemporaryDirectory() as tmp:
        gn, ja, nh = vp.shear_runs(a.burst, steps, tmp, G=G)
    g = gn["strain"]
    s11, s12 = vp.green_naghdi(g)
    e_gn, e_ja, e_nh = vp.shear_errors(gn, ja, nh, G)
    rows = [dict(gamma=f"{g[i]:.6g}", gn_s12=f"{gn['stress_xy'][i] / G:.8g}", gn_s11=f"{gn['stress_xx'][i] / G:.8g}", dienes_s12=f"{s12[i]:.8g}",
                 dienes_s11=f"{s11[i]:.8g}", jaumann_s12=f"{ja['stress_xy'][i] / G:.8g}", jaumann_s11=f"{ja['stress_xx'][i] / G:.8g}",
                 exact_jaumann_s12=f"{np.sin(g[i]):.8g}", exact_jaumann_s11=f"{1 - np.cos(g[i]):.8g}", neo_hookean_s12=f"{nh['stress_xy'][i] / G:.8g}",
                 neo_hookean_s11=f"{nh['stress_xx'][i] / G:.8g}") for i in range(0, len(g), max(1, len(g) // 200))]
    write_csv(os.path.join(a.out, "stability_shear.csv"), rows)
    print(f"simple shear, {steps} steps to gamma 10: max |sigma/G - closed form| Green-Naghdi {e_gn:.2e}, Jaumann {e_ja:.2e}, neo-Hookean {e_nh:.2e}; "
          f"at gamma 10 sigma12/G: GN {gn['stress_xy'][-1] / G:.4f}, Jaumann {ja['stress_xy'][-1] / G:.4f}, neo-Hookean {nh['stress_xy'][-1] / G:.4f}; "
          f"Jaumann max {np.max(ja['stress_xy']) / G:.4f} at gamma {g[np.argmax(ja['stress_xy'])]:.3f}, min {np.min(ja['stress_xy']) / G:.4f} at gamma {g[np.argmin(ja['stress_xy'])]:.3f}")
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.6))
    plot_shear(axes[0], axes[1], read_csv(os.path.join(a.out, "stability_shear.csv")))
    fig.tight_layout()
    png = os.path.join(a.out, "stability_shear.png")
    fig.savefig(png, dpi=110)
    print(f"wrote {png}")


def plot_shear(ax12, ax11, rows):
    col = lambda k: np.array([float(r[k]) for r in rows])  # noqa: E731
    g = col("gamma")
    for ax, comp in ((ax12, "s12"), (ax11, "s11")) if ax11 is not None else ((ax12, "s12"),):
        ax.plot(g, col(f"neo_hookean_{comp}"), color="0.6", lw=1, label="neo-Hookean (hyperelastic)")
        ax.plot(g, col(f"dienes_{comp}"), "k-", lw=2.5, alpha=0.35, label="Green-Naghdi closed form (Dienes)")
        ax.plot(g, col(f"gn_{comp}"), "C0--", label="elastic_plastic (polar R)")
        ax.plot(g, col(f"exact_jaumann_{comp}"), "k:", lw=2.5, alpha=0.35, label="Jaumann closed form")
        ax.plot(g, col(f"jaumann_{comp}"), "C3--", label="linear_elastic (Jaumann)")
        ax.set_xlabel("shear strain gamma")
        ax.grid(alpha=0.3)
        ax.set_ylim(-1.5, 8)
    ax12.set_ylabel("sigma_12 / G")
    if ax11 is not None:
        ax11.set_ylabel("sigma_11 / G")
    ax12.set_title("simple shear: Jaumann oscillates, Green-Naghdi grows", fontsize=8)
    ax12.legend(fontsize=6)


# --- cell-crossing noise ---------------------------------------------------------------------------
MMS = os.path.join(ROOT, "tests/decks/mms_axis_aligned.opts")


def mms_stress_noise(burst, shape, amplitude, cells=16):
    """Relative RMS stress error of the manufactured solution (E = 1e4 Pa, nu = 0.3, c = 100 m/s):
    time mean and max over the outputs of one period, and the run's summary."""
    E, nu, c = 1e4, 0.3, 100.0
    mu = E / (2 * (1 + nu))
    lam = E / (3 * (1 - 2 * nu)) - 2 * mu / 3
    with tempfile.TemporaryDirectory() as out:
        cmd = [burst, "-options_file", MMS, "-output_dir", out, "-progress", "false", "-output_interval", "100", "-grid_cells", f"{cells},{cells}",
               "-analytic_amplitude", repr(amplitude), "-mpm_shape_type", shape]
        proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
        if proc.returncode:
            text = proc.stdout + proc.stderr
            return None, None, None, next((line for line in text.splitlines() if "step" in line.lower() and ("not finite" in line or "det F" in line or "unstable" in line)), "failed")
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
        errs = []
        for name in sorted(glob.glob(os.path.join(out, "particles_*.h5"))):
            step = int(name[-9:-3])
            if step == 0:
                continue
            t = step * 1e-5  # the deck's fixed -mpm_dt
            with h5py.File(name, "r") as h:
                x = h["particles/coordinates"][:]
                X = x - h["particles/displacement"][:, :2]
                s = h["particles/stress"][:].reshape(-1, 3, 3)
            F = np.zeros((len(X), 3, 3))
            F[:, 2, 2] = 1
            for d in range(2):
                F[:, d, d] = 1 + amplitude * np.pi * np.cos(np.pi * X[:, d]) * np.sin(c * np.pi * t + d * 2 * np.pi / 3)
            J = np.linalg.det(F)
            B = F @ np.transpose(F, (0, 2, 1))
            exact = (lam * np.log(J) / J)[:, None, None] * np.eye(3) + (mu / J)[:, None, None] * (B - np.eye(3))
            errs.append(np.sqrt(((s - exact) ** 2).sum(axis=(1, 2)).mean() / (exact ** 2).sum(axis=(1, 2)).mean()))
    return float(np.mean(errs)), float(np.max(errs)), summary, ""


def study_noise(a):
    shapes = ["linear", "cpgimp"] if a.quick else ["linear", "ugimp", "cpgimp", "bspline2"]
    ratios = [0.05, 0.4, 1.6] if a.quick else [0.05, 0.1, 0.2, 0.4, 0.8, 1.6]
    cells = 16
    rows = []
    for shape in shapes:
        for r in ratios:
            mean, peak, summary, why = mms_stress_noise(a.burst, shape, r / cells, cells)
            rows.append(dict(shape=shape, cells=cells, amplitude_m=r / cells, amplitude_cells=r, max_strain=np.pi * r / cells,
                             stress_error_mean=mean if mean is not None else "", stress_error_max=peak if peak is not None else "",
                             displacement_error_rms=summary["displacement_error_rms"] if summary else "",
                             energy_balance_error=summary["energy_balance_error"] if summary else "", stopped=why))
            print(f"noise {shape} A/h {r}: relative stress error mean {mean if mean is None else f'{mean:.3e}'}, max {peak if peak is None else f'{peak:.3e}'}"
                  + (f", energy balance {summary['energy_balance_error']:.2e}" if summary else f", stopped: {why}"), flush=True)
    write_csv(os.path.join(a.out, "stability_noise.csv"), rows)
    fig, ax = plt.subplots(figsize=(5, 3.6))
    plot_noise(ax, rows)
    fig.tight_layout()
    png = os.path.join(a.out, "stability_noise.png")
    fig.savefig(png, dpi=110)
    print(f"wrote {png}")


def plot_noise(ax, rows):
    for k, shape in enumerate(dict.fromkeys(r["shape"] for r in rows)):
        pts = [(float(r["amplitude_cells"]), float(r["stress_error_mean"]), float(r["stress_error_max"])) for r in rows if r["shape"] == shape and r["stress_error_mean"] != ""]
        x, m, p = (np.array(v) for v in zip(*pts))
        ax.plot(x, m, "o-", color=f"C{k}", label=f"{shape} (time mean)")
        ax.plot(x, p, ":", color=f"C{k}", alpha=0.7)
    ax.axvline(0.25, color="0.5", lw=0.8)
    ax.text(0.26, 0.9, "first cell\ncrossing", fontsize=6, color="0.4", transform=ax.get_xaxis_transform())
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("largest displacement A/h (cells)")
    ax.set_ylabel("RMS stress error / RMS stress")
    ax.set_title("cell-crossing noise: manufactured solution, 16 cells, 2x2/cell (dotted: max over time)", fontsize=7)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=6)


# --- numerical fracture ----------------------------------------------------------------------------
RING = os.path.join(ROOT, "tests/decks/tension_ring.opts")
RING_H, RING_RMID, RING_MU = 0.01, 0.11, 5e5  # the deck's cell size, mid radius, shear modulus E/2 (nu = 0)


def grid_fragments(x, F, shape, lp0, h):
    """Groups of particles connected through shared grid nodes (a node in the support of both)."""
    n = len(x)
    dim = x.shape[1]
    lo = np.zeros((n, dim), int)
    hi = np.zeros((n, dim), int)
    for d in range(dim):
        if shape == "linear":
            r = np.full(n, h)
        elif shape == "bspline2":
            r = np.full(n, 1.5 * h)
        elif shape == "ugimp":
            r = np.full(n, h + lp0)
        else:
            r = h + np.clip(lp0 * np.abs(F[:, 4 * d]), 1e-3 * h, 0.5 * h)
        lo[:, d] = np.floor((x[:, d] - r) / h).astype(int) + 1
        hi[:, d] = np.ceil((x[:, d] + r) / h).astype(int) - 1
    share = np.ones((n, n), bool)
    for d in range(dim):
        share &= np.maximum(lo[:, None, d], lo[None, :, d]) <= np.minimum(hi[:, None, d], hi[None, :, d])
    parent = np.arange(n)

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for i, j in zip(*np.nonzero(np.triu(share, 1))):
        ri, rj = find(i), find(j)
        if ri != rj:
            parent[max(ri, rj)] = min(ri, rj)
    return len({find(i) for i in range(n)})


def ring_run(burst, shape, ppc, history):
    with tempfile.TemporaryDirectory() as out:
        cmd = [burst, "-options_file", RING, "-output_dir", out, "-mpm_shape_type", shape, "-hoop_particles_per_cell", str(ppc)]
        proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
        stopped = ""
        if proc.returncode:
            text = proc.stdout + proc.stderr
            stopped = next((line for line in text.splitlines() if "left the domain" in line or "not finite" in line or "det F" in line), "failed")
        with open(os.path.join(out, "monitor.csv")) as f:
            internal = {int(r["step"]): float(r["internal"]) for r in csv.DictReader(f)}
        split = half = None
        for name in sorted(glob.glob(os.path.join(out, "particles_*.h5"))):
            step = int(name[-9:-3])
            with h5py.File(name, "r") as h:
                x = h["particles/coordinates"][:]
                X = x - h["particles/displacement"][:, :2]
                F = h["particles/deformation_gradient"][:]
                V = h["particles/volume"][:]
            lam_p = np.hypot(x[:, 0], x[:, 1]) / np.hypot(X[:, 0], X[:, 1])
            V0 = V / np.abs(F[:, 0] * F[:, 4] - F[:, 1] * F[:, 3])
            intact = float(np.sum(RING_MU * (lam_p ** 2 / 2 - np.log(lam_p) - 0.5) * V0))
            lam = float(np.hypot(x[:, 0], x[:, 1]).mean() / RING_RMID)
            frags = grid_fragments(x, F, shape, RING_H / (2 * ppc), RING_H)
            ratio = internal[step] / intact if step in internal and intact > 0 else float("nan")
            history.append(dict(shape=shape, particles_per_cell=ppc, step=step, hoop_stretch=lam, grid_fragments=frags, stored_over_intact=ratio))
            if split is None and frags > 1:
                split = (lam, frags)
            if half is None and step > 0 and ratio < 0.5:
                half = lam
    return split, half, lam, frags, stopped


def study_fracture(a):
    shapes = ["linear", "cpgimp"] if a.quick else ["linear", "ugimp", "cpgimp", "bspline2"]
    ppcs = [1, 4] if a.quick else [1, 2, 3, 4]
    rows, history = [], []
    for shape in shapes:
        for ppc in ppcs:
            split, half, lam_end, frags_end, stopped = ring_run(a.burst, shape, ppc, history)
            rows.append(dict(shape=shape, particles_per_cell=ppc, stretch_first_split=split[0] if split else "", fragments_at_split=split[1] if split else "",
                             stretch_energy_half=half if half else "", stretch_end=lam_end, grid_fragments_end=frags_end, stopped=stopped))
            print(f"fracture {shape} {ppc}/cell: first grid split at hoop stretch {split[0] if split else 'none'} ({split[1] if split else 1} groups), "
                  f"stored energy below half the intact ring's at {half if half else 'none'}; end: stretch {lam_end:.2f}, {frags_end} groups {stopped}", flush=True)
    write_csv(os.path.join(a.out, "stability_fracture.csv"), rows)
    write_csv(os.path.join(a.out, "stability_fracture_history.csv"), history)
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.6))
    plot_fracture(axes[0], rows)
    for k, shape in enumerate(shapes):
        for ppc, style in zip(ppcs, ["-", "--", "-.", ":"]):
            hh = [r for r in history if r["shape"] == shape and r["particles_per_cell"] == ppc and np.isfinite(r["stored_over_intact"])]
            axes[1].plot([r["hoop_stretch"] for r in hh], [r["stored_over_intact"] for r in hh], style, color=f"C{k}", label=f"{shape} {ppc}/cell" if ppc in (ppcs[0], ppcs[-1]) else None)
    axes[1].set_xlabel("hoop stretch")
    axes[1].set_ylabel("stored energy / intact ring's")
    axes[1].set_ylim(0, 1.2)
    axes[1].grid(alpha=0.3)
    axes[1].legend(fontsize=6)
    axes[1].set_title("elastic ring: energy the grid still holds (1-4 per cell: - -- -. :)", fontsize=7)
    fig.tight_layout()
    png = os.path.join(a.out, "stability_fracture.png")
    fig.savefig(png, dpi=110)
    print(f"wrote {png}")


def plot_fracture(ax, rows):
    for k, shape in enumerate(dict.fromkeys(r["shape"] for r in rows)):
        pts = [(int(r["particles_per_cell"]), float(r["stretch_first_split"]), float(r["stretch_energy_half"]) if r["stretch_energy_half"] != "" else np.nan)
               for r in rows if r["shape"] == shape and r["stretch_first_split"] != ""]
        n, s, e = (np.array(v) for v in zip(*pts))
        ax.plot(n + 0.04 * k, s, "o-", color=f"C{k}", label=f"{shape}: grid splits")
        ax.plot(n + 0.04 * k, e, "s:", color=f"C{k}", alpha=0.7, mfc="none")
    ax.set_xticks([1, 2, 3, 4])
    ax.set_xlabel("particles per cell per direction")
    ax.set_ylabel("hoop stretch")
    ax.set_title("numerical fracture of an elastic ring (open squares: stored energy < half)", fontsize=7)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=6)


# --- mesh dependence of strain softening (the fragment study's CSV) ---------------------------------
def plot_softening(ax, rows, ppc_ax=None):
    """Fragments against cells (2 per cell) per regularisation, the Grady band of the same runs; on
    ppc_ax the fragments against particles per cell at 160 cells."""
    regs = list(dict.fromkeys(r["regularization"] for r in rows))
    two = [r for r in rows if r["particles_per_cell"] == "2"]
    cells = sorted({int(r["cells"]) for r in two})
    band = [(min(float(r["grady_shear"]) for r in two if int(r["cells"]) == c), max(float(r["grady_tension"]) for r in two if int(r["cells"]) == c)) for c in cells]
    ax.fill_between(cells, [b[0] for b in band], [b[1] for b in band], color="0.85", label="Grady band (eqs. 25-26)")
    for k, reg in enumerate(regs):
        pts = sorted((int(r["cells"]), int(r["fragments"])) for r in two if r["regularization"] == reg)
        if pts:
            ax.plot(*zip(*pts), "o-", color=f"C{k}", label=reg)
        if ppc_ax is not None:
            pts = sorted((int(r["particles_per_cell"]), int(r["fragments"])) for r in rows if r["regularization"] == reg and r["cells"] == "160")
            if pts:
                ppc_ax.plot(*zip(*pts), "o-", color=f"C{k}", label=reg)
    ax.set_xscale("log", base=2)
    ax.set_xticks(cells, [str(c) for c in cells])
    ax.set_xlabel("cells across the quarter (2 per cell)")
    ax.set_ylabel("fragments")
    ax.set_title("strain softening: cylinder fragments vs resolution\n(doc/figures/fragments_study.csv)", fontsize=7)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=6)


def study_softening(a):
    path = os.path.join(ROOT, "doc/figures/fragments_study.csv")
    rows = read_csv(path)
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.6))
    plot_softening(axes[0], rows, axes[1])
    axes[1].set_xticks([2, 3, 4])
    axes[1].set_xlabel("particles per cell per direction (160 cells)")
    axes[1].set_ylabel("fragments")
    axes[1].grid(alpha=0.3)
    axes[1].legend(fontsize=6)
    for reg in dict.fromkeys(r["regularization"] for r in rows):
        pts = sorted((int(r["cells"]), int(r["particles_per_cell"]), int(r["fragments"])) for r in rows if r["regularization"] == reg)
        print(f"softening {reg}: " + ", ".join(f"{c} cells x {p}/cell: {f}" for c, p, f in pts))
    fig.tight_layout()
    png = os.path.join(a.out, "stability_softening.png")
    fig.savefig(png, dpi=110)
    print(f"wrote {png}")


def study_overview(a):
    fig, axes = plt.subplots(2, 2, figsize=(10, 7.5))
    plot_shear(axes[0, 0], None, read_csv(os.path.join(a.out, "stability_shear.csv")))
    plot_noise(axes[0, 1], read_csv(os.path.join(a.out, "stability_noise.csv")))
    plot_fracture(axes[1, 0], read_csv(os.path.join(a.out, "stability_fracture.csv")))
    plot_softening(axes[1, 1], read_csv(os.path.join(ROOT, "doc/figures/fragments_study.csv")))
    fig.tight_layout()
    png = os.path.join(a.out, "stability_overview.png")
    fig.savefig(png, dpi=110)
    print(f"wrote {png}")


STUDIES = {"cfl": study_cfl, "shear": study_shear, "noise": study_noise, "fracture": study_fracture, "softening": study_softening, "overview": study_overview}


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--burst", default=os.path.join(ROOT, "build/burst"))
    p.add_argument("--out", default=os.path.join(ROOT, "doc/figures"))
    p.add_argument("--quick", action="store_true")
    p.add_argument("--study", default="cfl", choices=[*STUDIES, "all"])
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    failures = []
    for name in (STUDIES if a.study == "all" else [a.study]):
        failures += STUDIES[name](a) or []
    if failures:
        print(f"study_stability: FAIL ({'; '.join(failures)})")
        sys.exit(1)
    print("study_stability: OK")


if __name__ == "__main__":
    main()
