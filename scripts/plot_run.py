#!/usr/bin/python3
"""Quick-look plots of a burst run.

    /usr/bin/python3 scripts/plot_run.py OUTPUT_DIR [--field NAME]

Writes into OUTPUT_DIR
  particles.png  the particles of the last particles_NNNNNN.h5, coloured by a field (default: von
                 Mises stress); marker sizes follow each particle's volume so a body looks solid.
                 3-D output is drawn as an x-y projection of all particles seen from +z (particles
                 with larger z are drawn on top).
  energy.png     kinetic, internal and total minus external work against time from monitor.csv,
                 with the relative energy balance error in a small panel below. A run with gas
                 draws the terms of its energy budget (particles, gases, what left through open
                 faces, removed particles, the chemical energy released) and their sum, with the
                 energy and mass budget errors below.
  gas.png        a run with gas: pressure and mixture density of the last gas_NNNNNN.h5 (2-D: maps,
                 3-D: the mid-z slice, a tube one cell wide: profiles along x).
  burst.png      particles and gas together (2-D or the mid-z slice): the particles of the last
                 output coloured by fragment (failed ones grey), over the gas pressure of the same
                 step.
  histories.png  a run with gas and particles: the largest cell pressure and, with -grady, the mean
                 radial (expansion) velocity of the container against time (monitor.csv).

Fields (--field): vonmises (sqrt(3/2 s:s) of the Cauchy stress), pressure (-tr(sigma)/3), speed,
displacement (magnitude), temperature, material; any other dataset in /particles is accepted too
(its magnitude if it has several components).

Needs numpy, h5py and matplotlib: use Debian's /usr/bin/python3.
"""
import argparse
import glob
import json
import os
import re
import sys

try:
    import numpy as np
    import h5py
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib import colors
    from mpl_toolkits.axes_grid1 import make_axes_locatable
except ImportError as e:  # an interpreter without the Debian packages (e.g. a pyenv python3)
    sys.exit("plot_run.py: error: %s in %s; run the script with Debian's /usr/bin/python3" % (e, sys.executable))

BUILTIN_FIELDS = ("vonmises", "pressure", "speed", "displacement", "temperature", "material")
DPI = 150


def fail(message):
    sys.exit("plot_run.py: error: " + message)


def last_particle_file(outdir):
    """The particles_NNNNNN.h5 with the largest step number (the width of NNNNNN may grow)."""
    files = []
    for path in glob.glob(os.path.join(glob.escape(outdir), "particles_*.h5")):
        m = re.fullmatch(r"particles_(\d+)\.h5", os.path.basename(path))
        if m:
            files.append((int(m.group(1)), path))
    if not files:
        fail("no particles_*.h5 files in %s (a burst run writes them every -output_interval steps)" % outdir)
    return max(files)[1], len(files)


def scalar_attr(group, name, default=None):
    if name not in group.attrs:
        return default
    value = np.ravel(group.attrs[name])
    return value[0].item() if value.size else default


def read_particles(path):
    with h5py.File(path, "r") as f:
        if "particles" not in f:
            fail("%s has no /particles group" % path)
        g = f["particles"]
        data = {name: np.asarray(g[name][()]) for name in g if isinstance(g[name], h5py.Dataset)}
        time = scalar_attr(g, "time")
        step = scalar_attr(g, "step")
    if "coordinates" not in data:
        fail("%s has no /particles/coordinates" % path)
    x = data["coordinates"]
    if x.ndim == 1:  # a single particle or 1-D data
        x = x.reshape(x.shape[0], -1) if x.size else x.reshape(0, 2)
    data["coordinates"] = x
    return data, time, step


def as_rows(a, n):
    """Dataset as an [n][k] array (PETSc drops the second dimension of block size 1)."""
    a = np.asarray(a, dtype=float)
    return a.reshape(n, -1) if n else a.reshape(0, a.shape[1] if a.ndim > 1 else 1)


def field_values(data, name, n):
    """Values to colour by, colour-bar label and whether the field is categorical."""
    def need(dataset):
        if dataset not in data:
            fail("field %s needs /particles/%s, which this file does not have" % (name, dataset))
        return as_rows(data[dataset], n)

    if name == "vonmises":
        sigma = need("stress")
        if sigma.shape[1] != 9:
            fail("/particles/stress has %d components per particle, expected 9" % sigma.shape[1])
        sigma = sigma.reshape(n, 3, 3)
        dev = sigma - np.trace(sigma, axis1=1, axis2=2)[:, None, None] / 3.0 * np.eye(3)
        return np.sqrt(1.5 * np.einsum("pij,pij->p", dev, dev)), "von Mises stress [Pa]", False
    if name == "pressure":
        sigma = need("stress")
        return -(sigma[:, 0] + sigma[:, 4] + sigma[:, 8]) / 3.0, "pressure -tr(σ)/3 [Pa]", False
    if name == "speed":
        return np.linalg.norm(need("velocity"), axis=1), "speed [m/s]", False
    if name == "displacement":
        return np.linalg.norm(need("displacement"), axis=1), "displacement magnitude [m]", False
    if name == "temperature":
        return need("temperature")[:, 0], "temperature [K]", False
    if name == "material":
        return need("material")[:, 0], "material index", True
    if name in data:
        values = as_rows(data[name], n)
        if values.shape[1] == 1:
            return values[:, 0], name, False
        return np.linalg.norm(values, axis=1), "|%s|" % name, False
    fail("unknown field %s: choose one of %s, or a dataset in /particles (%s)"
         % (name, ", ".join(BUILTIN_FIELDS), ", ".join(sorted(data))))


def load_summary(outdir):
    path = os.path.join(outdir, "summary.json")
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return {}


def plot_particles(outdir, field, summary, out_name="particles.png"):
    path, nfiles = last_particle_file(outdir)
    data, time, step = read_particles(path)
    x = data["coordinates"]
    n, dim = x.shape
    values, label, categorical = field_values(data, field, n)

    # Edge length of each particle's share of the body: the volume is an area in 2-D.
    if "volume" in data and n:
        vol = as_rows(data["volume"], n)[:, 0]
    else:
        vol = np.full(n, np.nan)
    edge = np.abs(vol) ** (1.0 / max(dim, 1))
    good_edge = np.isfinite(edge) & (edge > 0)
    if n and not good_edge.all():  # fall back on the typical spacing
        fallback = np.median(edge[good_edge]) if good_edge.any() else 0.0
        edge = np.where(good_edge, edge, fallback)

    xy = x[:, :2] if dim >= 2 else np.column_stack([x[:, 0], np.zeros(n)])
    if dim == 3:  # painter's order: particles with larger z on top (view from +z)
        order = np.argsort(x[:, 2], kind="stable")
        xy, values, edge = xy[order], values[order], edge[order]

    fig, ax = plt.subplots(figsize=(7.5, 6.5), dpi=DPI)
    finite_xy = np.isfinite(xy).all(axis=1)
    if n and finite_xy.any():
        lo, hi = xy[finite_xy].min(axis=0), xy[finite_xy].max(axis=0)
        pad = 0.04 * max(hi - lo) + (np.max(edge[finite_xy]) if n else 0)
        pad = pad if pad > 0 else 1.0
        ax.set_xlim(lo[0] - pad, hi[0] + pad)
        ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal", adjustable="box")

    finite_v = values[np.isfinite(values)]
    cmap = plt.get_cmap("viridis")
    norm = None
    ticks = None
    fragments = field == "fragment"
    if fragments:
        # failed and unassigned particles (id -1) as small grey dots; fragments in a cycling
        # qualitative colormap (neighbouring ids get different colours)
        debris = values < 0
        ax.scatter(xy[debris, 0], xy[debris, 1], s=0.5, c="0.7", marker="o", linewidths=0)
        xy, values, edge = xy[~debris], values[~debris], edge[~debris]
        base = plt.get_cmap("tab20")
        palette = [base(i) for i in range(20) if i not in (14, 15)]  # no greys: grey marks failed particles
        cmap = colors.ListedColormap(palette)
        norm = colors.Normalize(-0.5, len(palette) - 0.5)
        values = np.mod(values, len(palette))
    elif categorical and finite_v.size:
        levels = np.unique(finite_v)
        base = plt.get_cmap("tab10")
        cmap = colors.ListedColormap([base(i % 10) for i in range(len(levels))])
        bounds = np.concatenate([[levels[0] - 0.5], (levels[:-1] + levels[1:]) / 2, [levels[-1] + 0.5]])
        norm = colors.BoundaryNorm(bounds, cmap.N)
        ticks = levels
    elif field == "pressure" and finite_v.size:
        vmax = np.max(np.abs(finite_v)) or 1.0
        cmap = plt.get_cmap("coolwarm")
        norm = colors.Normalize(-vmax, vmax)
    elif finite_v.size:
        vmin, vmax = finite_v.min(), finite_v.max()
        if vmax <= vmin:  # constant field: give the colour bar some range
            delta = abs(vmin) * 1e-3 or 1.0
            vmin, vmax = vmin - delta, vmax + delta
        norm = colors.Normalize(vmin, vmax)

    sc = ax.scatter(xy[:, 0], xy[:, 1], c=values, s=1.0, marker="o", linewidths=0, cmap=cmap, norm=norm)
    if not fragments:
        cax = make_axes_locatable(ax).append_axes("right", size="4%", pad=0.12)
        cb = fig.colorbar(sc, cax=cax, ticks=ticks)
        cb.set_label(label)
        if ticks is not None:
            cb.ax.set_yticklabels(["%d" % t for t in ticks])
    if n == 0:
        ax.text(0.5, 0.5, "no particles", transform=ax.transAxes, ha="center", va="center")

    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    scene = summary.get("scene") or os.path.basename(os.path.normpath(outdir))
    when = "t = %.6g s" % time if time is not None else "t = ?"
    if step is not None:
        when += ", step %d" % step
    view = ", x-y projection seen from +z" if dim == 3 else ""
    what = label.split(" [")[0]
    if fragments and "fragment_count" in summary:
        what = "%d fragments (failed particles grey)" % summary["fragment_count"]
        if isinstance(summary.get("grady_tension"), dict):
            what += "; Grady %.1f-%.1f" % (summary["grady_shear"]["sector"], summary["grady_tension"]["sector"])
    ax.set_title("%s: %s\n%s, %d particles%s" % (scene, what, when, n, view), fontsize=11)

    # Marker diameter = 1.5 x particle edge, so that the circles of neighbours on a square lattice
    # (which need sqrt(2) x edge) leave no gaps and the body looks solid; in points, which needs the
    # final axes size, so lay the figure out first.
    fig.canvas.draw()
    (x0, _), (x1, _) = ax.transData.transform([(0.0, 0.0), (1.0, 0.0)])
    points_per_metre = abs(x1 - x0) * 72.0 / fig.dpi
    sc.set_sizes((1.5 * edge * points_per_metre) ** 2)

    out = os.path.join(outdir, out_name)
    fig.savefig(out, dpi=DPI, bbox_inches="tight")
    plt.close(fig)
    return out, path, nfiles


def read_monitor(outdir):
    path = os.path.join(outdir, "monitor.csv")
    if not os.path.exists(path):
        return None, "no monitor.csv in %s" % outdir
    try:
        table = np.genfromtxt(path, delimiter=",", names=True, invalid_raise=False)
    except ValueError as e:
        return None, "could not read %s: %s" % (path, e)
    if table.dtype.names is None or table.size == 0:
        return None, "%s has no data rows" % path
    table = np.atleast_1d(table)
    missing = [c for c in ("time", "kinetic", "internal", "total", "external_work", "balance_error")
               if c not in table.dtype.names]
    if missing:
        return None, "%s lacks the column(s) %s" % (path, ", ".join(missing))
    return table, None


def has_budget(table):
    return table is not None and "budget_energy" in table.dtype.names


def plot_budget(outdir, summary, table):
    """A run with gas: the terms of the energy budget (monitor.cxx ComputeBudget) and their sum, which a
    conservative run keeps at its initial value; below, the energy and mass budget errors."""
    t = table["time"]
    names = table.dtype.names
    zero = np.zeros_like(t)
    col = lambda name: table[name] if name in names else zero
    fig, (ax, axe) = plt.subplots(2, 1, sharex=True, figsize=(7.5, 6.0), dpi=DPI,
                                  gridspec_kw={"height_ratios": [3, 1], "hspace": 0.08})
    style = {"marker": "." if t.size < 60 else None, "lw": 1.5}
    particles = summary.get("particles", 0) > 0 or np.any(col("kinetic") != 0)
    if particles:
        ax.plot(t, col("kinetic"), label="particles: kinetic", color="tab:blue", **style)
        ax.plot(t, col("internal") + col("heat_to_particles") - col("reactant_thermal_energy"),
                label="particles: stress work + heat from gas − reactant's heat to gas", color="tab:orange", **style)
    ax.plot(t, col("gas_kinetic_energy"), label="gas: kinetic", color="tab:cyan", **style)
    ax.plot(t, col("gas_internal_energy"), label="gas: internal", color="tab:red", **style)
    if np.any(col("open_face_energy") != 0) or np.any(col("open_face_work") != 0):
        ax.plot(t, col("open_face_energy") + col("open_face_work"), label="out through open faces (energy + p u A dt)", color="tab:green", **style)
    if np.any(col("removed_particle_energy") != 0):
        ax.plot(t, col("removed_particle_energy"), label="removed particles", color="tab:brown", **style)
    if np.any(col("chemical_energy") != 0):
        ax.plot(t, col("chemical_energy"), label="chemical energy released", color="tab:purple", ls="--", lw=1.5)
    if np.any(col("external_work") != 0):
        ax.plot(t, col("external_work"), label="external work", color="tab:gray", ls="--", lw=1.5)
    ax.plot(t, table["budget_energy"], label="sum − chemical − external work", color="black", **style)
    ax.set_ylabel("energy [J] (per metre in 2-D)" if summary.get("dim") == 2 else "energy [J]")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    scene = summary.get("scene") or os.path.basename(os.path.normpath(outdir))
    ax.set_title("%s: energy budget" % scene, fontsize=11)
    # scaled by hand, as plot_energy: matplotlib's offset text would sit on the panel above
    errors = np.concatenate([np.abs(table["balance_error"]), np.abs(col("mass_budget_error"))])
    errors = errors[np.isfinite(errors)]
    exponent = int(np.floor(np.log10(errors.max()))) if errors.size and errors.max() > 0 else 0
    exponent = exponent if exponent < -1 or exponent > 2 else 0
    axe.plot(t, table["balance_error"] / 10.0 ** exponent, color="tab:red", label="energy", **style)
    axe.plot(t, col("mass_budget_error") / 10.0 ** exponent, color="tab:green", label="mass", **style)
    axe.axhline(0.0, color="gray", lw=0.8)
    axe.set_ylabel("budget error\n/ largest term" + ("\n[×1e%d]" % exponent if exponent else ""), fontsize=9)
    axe.set_xlabel("time [s]")
    axe.legend(fontsize=8)
    axe.grid(True, alpha=0.3)
    out = os.path.join(outdir, "energy.png")
    fig.savefig(out, dpi=DPI, bbox_inches="tight")
    plt.close(fig)
    return out


def plot_energy(outdir, summary):
    table, problem = read_monitor(outdir)
    if table is None:
        return None, problem
    if has_budget(table):
        return plot_budget(outdir, summary, table), None
    t = table["time"]
    fig, (ax, axe) = plt.subplots(2, 1, sharex=True, figsize=(7.5, 6.0), dpi=DPI,
                                  gridspec_kw={"height_ratios": [3, 1], "hspace": 0.08})
    style = {"marker": "." if t.size < 60 else None, "lw": 1.5}
    ax.plot(t, table["kinetic"], label="kinetic", color="tab:blue", **style)
    ax.plot(t, table["internal"], label="internal (stress work)", color="tab:orange", **style)
    ax.plot(t, table["total"] - table["external_work"], label="total − external work", color="black", **style)
    ax.set_ylabel("energy [J] (per metre in 2-D)" if summary.get("dim") == 2 else "energy [J]")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize=9)
    scene = summary.get("scene") or os.path.basename(os.path.normpath(outdir))
    ax.set_title("%s: energy balance%s" % (scene, " (%s)" % summary["scheme"] if "scheme" in summary else ""), fontsize=11)

    # Scale the error by hand: matplotlib's offset text ("1e-3") would sit on the panel above.
    err = table["balance_error"]
    finite = np.abs(err[np.isfinite(err)])
    exponent = int(np.floor(np.log10(finite.max()))) if finite.size and finite.max() > 0 else 0
    exponent = exponent if exponent < -1 or exponent > 2 else 0
    axe.plot(t, err / 10.0 ** exponent, color="tab:red", **style)
    axe.axhline(0.0, color="gray", lw=0.8)
    axe.set_ylabel("relative\nbalance error" + ("\n[×1e%d]" % exponent if exponent else ""), fontsize=9)
    axe.set_xlabel("time [s]")
    axe.grid(True, alpha=0.3)
    if t.size == 1:  # a single row: give the time axis some width
        ax.set_xlim(t[0] - 0.5, t[0] + 0.5) if t[0] == 0 else ax.set_xlim(0, 1.05 * t[0])

    out = os.path.join(outdir, "energy.png")
    fig.savefig(out, dpi=DPI, bbox_inches="tight")
    plt.close(fig)
    return out, None


def last_gas_file(outdir):
    files = []
    for path in glob.glob(os.path.join(glob.escape(outdir), "gas_*.h5")):
        m = re.fullmatch(r"gas_(\d+)\.h5", os.path.basename(path))
        if m:
            files.append((int(m.group(1)), path))
    return max(files)[1] if files else None


def plot_gas(outdir, summary):
    """Pressure and mixture density (sum of the bulk densities) of the last gas output."""
    path = last_gas_file(outdir)
    if path is None:
        return None
    with h5py.File(path, "r") as h:
        cells = h["cells"]
        time = scalar_attr(cells, "time", 0.0)
        p = np.asarray(cells["pressure"])
        rho = sum(np.asarray(cells[k]) for k in cells if k.endswith("_density"))
    if p.shape[0] > 1:  # 3-D: the mid-z slice
        p, rho = p[p.shape[0] // 2], rho[rho.shape[0] // 2]
    else:
        p, rho = p[0], rho[0]
    lower = summary.get("grid_lower", [0, 0, 0])
    upper = summary.get("grid_upper", [p.shape[1], p.shape[0], 1])
    scene = summary.get("scene") or os.path.basename(os.path.normpath(outdir))
    if p.shape[0] == 1:  # a tube along x
        x = lower[0] + (np.arange(p.shape[1]) + 0.5) * (upper[0] - lower[0]) / p.shape[1]
        fig, axes = plt.subplots(2, 1, sharex=True, figsize=(7.5, 6), dpi=DPI)
        axes[0].plot(x, p[0], color="tab:red")
        axes[0].set_ylabel("pressure [Pa]")
        axes[1].plot(x, rho[0], color="tab:blue")
        axes[1].set_ylabel("density [kg/m³]")
        axes[1].set_xlabel("x [m]")
        for a in axes:
            a.grid(True, alpha=0.3)
    else:
        fig, axes = plt.subplots(1, 2, figsize=(12, 4.8), dpi=DPI, gridspec_kw={"wspace": 0.45})
        extent = [lower[0], upper[0], lower[1], upper[1]]
        for a, data, label, cmap in ((axes[0], p, "pressure [Pa]", "inferno"), (axes[1], rho, "density [kg/m³]", "viridis")):
            im = a.imshow(data, origin="lower", extent=extent, cmap=cmap, interpolation="nearest")
            a.set_xlabel("x [m]")
            a.set_ylabel("y [m]")
            a.set_aspect("equal")
            cax = make_axes_locatable(a).append_axes("right", size="4%", pad=0.05)
            fig.colorbar(im, cax=cax, label=label)
    fig.suptitle("%s: gas at t = %.4g s" % (scene, time), fontsize=11)
    out = os.path.join(outdir, "gas.png")
    fig.savefig(out, dpi=DPI, bbox_inches="tight")
    plt.close(fig)
    return out


def plot_gas_energy(outdir, summary):
    """A gas-only run: gas kinetic, internal and total energy, and the relative mass change."""
    path = os.path.join(outdir, "monitor.csv")
    table = np.atleast_1d(np.genfromtxt(path, delimiter=",", names=True))
    if has_budget(table):
        return plot_budget(outdir, summary, table)
    t = table["time"]
    fig, (ax, axe) = plt.subplots(2, 1, sharex=True, figsize=(7.5, 6.0), dpi=DPI, gridspec_kw={"height_ratios": [3, 1], "hspace": 0.08})
    ax.plot(t, table["gas_kinetic_energy"], label="kinetic", color="tab:blue")
    ax.plot(t, table["gas_internal_energy"], label="internal", color="tab:orange")
    ax.plot(t, table["gas_total_energy"], label="total", color="black")
    ax.set_ylabel("energy [J] (per metre in 2-D)")
    ax.legend(fontsize=9)
    ax.grid(True, alpha=0.3)
    ax.set_title("%s: gas energy" % (summary.get("scene") or ""), fontsize=11)
    e0 = table["gas_total_energy"][0]
    axe.plot(t, (table["gas_total_energy"] - e0) / e0, color="tab:red", label="total energy")
    axe.plot(t, (table["gas_mass"] - table["gas_mass"][0]) / table["gas_mass"][0], color="tab:green", label="mass")
    axe.set_ylabel("relative\nchange", fontsize=9)
    axe.set_xlabel("time [s]")
    axe.legend(fontsize=8)
    axe.grid(True, alpha=0.3)
    out = os.path.join(outdir, "energy.png")
    fig.savefig(out, dpi=DPI, bbox_inches="tight")
    plt.close(fig)
    return out


def last_particles_and_pressure(outdir):
    """The last particle output and the gas pressure of the same step, or None without one."""
    ppath, _ = last_particle_file(outdir)
    step = int(re.fullmatch(r"particles_(\d+)\.h5", os.path.basename(ppath)).group(1))
    gpath = os.path.join(outdir, "gas_%06d.h5" % step)
    if not os.path.exists(gpath):
        return None
    data, time, _ = read_particles(ppath)
    with h5py.File(gpath, "r") as h:
        p = np.asarray(h["cells"]["pressure"])
    return data, time, data["coordinates"], p


def plot_burst(outdir, summary):
    """The last particle output over the gas pressure of the same step."""
    last = last_particles_and_pressure(outdir)
    if last is None:
        return None
    data, time, x, p = last
    n, dim = x.shape
    p = p[p.shape[0] // 2] if p.shape[0] > 1 else p[0]
    lower = summary.get("grid_lower", [0, 0, 0])
    upper = summary.get("grid_upper", [p.shape[1], p.shape[0], 1])
    fig, ax = plt.subplots(figsize=(7.5, 6.5), dpi=DPI)
    im = ax.imshow(p, origin="lower", extent=[lower[0], upper[0], lower[1], upper[1]], cmap="Blues",
                   norm=colors.LogNorm(vmin=max(p.min(), 1e3), vmax=max(p.max(), 1e4)), interpolation="nearest")
    cax = make_axes_locatable(ax).append_axes("right", size="4%", pad=0.05)
    fig.colorbar(im, cax=cax, label="gas pressure [Pa]")
    frag = as_rows(data["fragment"], n)[:, 0] if "fragment" in data else np.full(n, -1)
    if dim == 3:  # the slab around mid-z
        z = x[:, 2]
        keep = np.abs(z - 0.5 * (lower[2] + upper[2])) <= 0.5 * (upper[2] - lower[2]) / max(p.shape[0], 1) * 2
        x, frag = x[keep], frag[keep]
    size = 4.0 * (72.0 / DPI) ** 2 * 30
    broken = frag < 0
    ax.scatter(x[broken, 0], x[broken, 1], s=size * 0.5, c="0.6", linewidths=0, label="failed or not counted")
    labels = frag[~broken]
    if labels.size:
        ax.scatter(x[~broken, 0], x[~broken, 1], s=size, c=labels % 20, cmap="tab20", vmin=0, vmax=19, linewidths=0)
    ax.set_xlim(lower[0], upper[0])
    ax.set_ylim(lower[1], upper[1])
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    count = summary.get("fragment_count")
    ax.set_title("%s: t = %.4g s%s" % (summary.get("scene") or "", time, "" if count is None else ", %d fragments" % count), fontsize=11)
    out = os.path.join(outdir, "burst.png")
    fig.savefig(out, dpi=DPI, bbox_inches="tight")
    plt.close(fig)
    return out


def plot_burst3d(outdir, summary):
    """3-D runs: the fragments seen in perspective, and the gas in the planes z = 0 (across the
    charge) and y = 0 (along the axis, through the wall and the cap), products volume fraction over
    the pressure, which shows where the gas escapes."""
    last = last_particles_and_pressure(outdir)
    if last is None or last[2].shape[1] != 3:
        return None
    data, time, x, p = last  # p: [z][y][x]
    n = x.shape[0]
    frag = as_rows(data["fragment"], n)[:, 0] if "fragment" in data else np.full(n, -1)
    material = as_rows(data["material"], n)[:, 0] if "material" in data else np.zeros(n)
    lower = summary.get("grid_lower", [0, 0, 0])
    upper = summary.get("grid_upper", [1, 1, 1])
    fig = plt.figure(figsize=(17, 5.2), dpi=DPI)
    fig.subplots_adjust(wspace=0.35)
    ax = fig.add_subplot(1, 3, 1, projection="3d")
    solid = material == 0  # the container (the first material)
    counted = solid & (frag >= 0)
    loose = solid & (frag < 0)
    ax.scatter(x[loose, 0], x[loose, 1], x[loose, 2], s=0.3, c="0.65", linewidths=0, depthshade=False)
    if counted.any():
        ax.scatter(x[counted, 0], x[counted, 1], x[counted, 2], s=0.8, c=frag[counted] % 10, cmap="tab10", vmin=0, vmax=9, linewidths=0, depthshade=True)
    ax.set_xlim(lower[0], upper[0])
    ax.set_ylim(lower[1], upper[1])
    ax.set_zlim(lower[2], upper[2])
    ax.set_box_aspect((upper[0] - lower[0], upper[1] - lower[1], upper[2] - lower[2]))
    ax.view_init(elev=22, azim=-130)
    ax.set_xlabel("x [m]", fontsize=8)
    ax.set_ylabel("y [m]", fontsize=8)
    ax.set_zlabel("z [m]", fontsize=8)
    ax.tick_params(labelsize=7)
    count = summary.get("fragment_count")
    ax.set_title("container%s (grey: failed or debris)" % ("" if count is None else ", %d fragments" % count), fontsize=10)
    norm = colors.LogNorm(vmin=max(p.min(), 1e4), vmax=max(p.max(), 1e5))
    for panel, (cut, title) in enumerate(((p[0], "gas pressure at z = 0 (mid-length)"), (p[:, 0, :], "gas pressure at y = 0 (along the axis)"))):
        a = fig.add_subplot(1, 3, panel + 2)
        extent = [lower[0], upper[0], lower[1], upper[1]] if panel == 0 else [lower[0], upper[0], lower[2], upper[2]]
        im = a.imshow(cut, origin="lower", extent=extent, cmap="Greys", norm=norm, interpolation="nearest")
        # particles within a cell of the plane
        h = (upper[2] - lower[2]) / p.shape[0] if panel == 0 else (upper[1] - lower[1]) / p.shape[1]
        near = solid & (np.abs(x[:, 2 if panel == 0 else 1] - (lower[2] if panel == 0 else lower[1])) < h)
        kept = near & (frag >= 0)
        a.scatter(x[near & (frag < 0), 0], x[near & (frag < 0), 1 if panel == 0 else 2], s=1.2, c="tab:red", linewidths=0)
        a.scatter(x[kept, 0], x[kept, 1 if panel == 0 else 2], s=2.0, c=frag[kept] % 10, cmap="tab10", vmin=0, vmax=9, linewidths=0)
        a.set_xlim(extent[0], extent[1])
        a.set_ylim(extent[2], extent[3])
        a.set_aspect("equal")
        a.set_xlabel("x [m]")
        a.set_ylabel("y [m]" if panel == 0 else "z [m]")
        a.set_title(title, fontsize=10)
        cax = make_axes_locatable(a).append_axes("right", size="4%", pad=0.05)
        fig.colorbar(im, cax=cax, label="pressure [Pa]")
    fig.suptitle("%s: t = %.4g s" % (summary.get("scene") or "", time), fontsize=11)
    out = os.path.join(outdir, "burst3d.png")
    fig.savefig(out, dpi=DPI, bbox_inches="tight")
    plt.close(fig)
    return out


def plot_histories(outdir, summary):
    """Largest gas pressure and the container's expansion velocity against time."""
    table = np.atleast_1d(np.genfromtxt(os.path.join(outdir, "monitor.csv"), delimiter=",", names=True))
    if "gas_max_pressure" not in table.dtype.names:
        return None
    t = table["time"] * 1e6
    has_v = "expansion_velocity" in table.dtype.names
    fig, axes = plt.subplots(2 if has_v else 1, 1, sharex=True, figsize=(7.5, 6.0 if has_v else 3.5), dpi=DPI, squeeze=False)
    axes = axes[:, 0]
    axes[0].semilogy(t, np.maximum(table["gas_max_pressure"], 1.0), color="tab:red")
    axes[0].set_ylabel("largest cell pressure [Pa]")
    if has_v:
        axes[1].plot(t, table["expansion_velocity"], color="tab:blue")
        axes[1].set_ylabel("mean radial velocity [m/s]")
        ft = summary.get("fracture_time")
        if ft is not None and ft >= 0:
            for a in axes:
                a.axvline(ft * 1e6, color="0.4", ls="--", lw=0.8)
            axes[1].text(ft * 1e6, axes[1].get_ylim()[1] * 0.9, " first failure", fontsize=8, color="0.3")
    axes[-1].set_xlabel("time [µs]")
    for a in axes:
        a.grid(True, alpha=0.3)
    axes[0].set_title("%s: gas pressure and wall velocity" % (summary.get("scene") or ""), fontsize=11)
    out = os.path.join(outdir, "histories.png")
    fig.savefig(out, dpi=DPI, bbox_inches="tight")
    plt.close(fig)
    return out


def plot_fragment_masses(outdir, summary):
    """Mass distribution of the fragments (fragments.csv): mass of each fragment, largest first."""
    path = os.path.join(outdir, "fragments.csv")
    if not os.path.exists(path):
        return None
    data = np.genfromtxt(path, delimiter=",", names=True, ndmin=1)
    if data.size == 0:
        return None
    mass = np.sort(np.atleast_1d(data["mass"]))[::-1]
    count = np.atleast_1d(data["particles"])[np.argsort(np.atleast_1d(data["mass"]))[::-1]]
    minimum = summary.get("fragment_min_particles", 1)
    fig, ax = plt.subplots(figsize=(6.5, 4), dpi=DPI)
    ranks = np.arange(1, mass.size + 1)
    counted = count >= minimum
    ax.bar(ranks[counted], mass[counted], color="C0", label="fragments (>= %d particles)" % minimum)
    ax.bar(ranks[~counted], mass[~counted], color="0.7", label="debris")
    ax.set_yscale("log")
    ax.set_xlabel("fragment, largest first")
    ax.set_ylabel("mass [kg] (per metre in 2-D)")
    ax.set_title("%s: fragment masses" % (summary.get("scene") or ""), fontsize=11)
    ax.legend(fontsize=8)
    out = os.path.join(outdir, "fragment_masses.png")
    fig.savefig(out, dpi=DPI, bbox_inches="tight")
    plt.close(fig)
    return out


def main(argv=None):
    parser = argparse.ArgumentParser(description="Plot the particles and the energy balance of a burst run.")
    parser.add_argument("output_dir", help="the -output_dir of a burst run")
    parser.add_argument("--field", default="vonmises",
                        help="colour particles by: %s (default vonmises), or any /particles dataset"
                        % ", ".join(BUILTIN_FIELDS))
    args = parser.parse_args(argv)

    outdir = args.output_dir
    if not os.path.isdir(outdir):
        fail("%s is not a folder" % outdir)
    summary = load_summary(outdir)

    has_particles = bool(glob.glob(os.path.join(glob.escape(outdir), "particles_*.h5")))
    gas_png = plot_gas(outdir, summary)
    if gas_png:
        print("wrote %s" % gas_png)
    if not has_particles:
        if gas_png is None:
            fail("no particles_*.h5 or gas_*.h5 files in %s" % outdir)
        print("wrote %s" % plot_gas_energy(outdir, summary))
        return 0
    png, source, nfiles = plot_particles(outdir, args.field, summary)
    print("wrote %s (%s, last of %d particle file%s)" % (png, os.path.basename(source), nfiles, "" if nfiles == 1 else "s"))
    if os.path.exists(os.path.join(outdir, "fragments.csv")):
        png, _, _ = plot_particles(outdir, "fragment", summary, "fragments.png")
        print("wrote %s" % png)
        png = plot_fragment_masses(outdir, summary)
        if png:
            print("wrote %s" % png)
    if gas_png:
        for png in (plot_burst(outdir, summary), plot_burst3d(outdir, summary), plot_histories(outdir, summary)):
            if png:
                print("wrote %s" % png)
    png, problem = plot_energy(outdir, summary)
    if png is None:
        print("plot_run.py: warning: energy.png not written: %s" % problem, file=sys.stderr)
    else:
        print("wrote %s" % png)
    return 0


if __name__ == "__main__":
    sys.exit(main())
