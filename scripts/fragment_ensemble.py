"""Ensembles of fragmenting runs over the random porosity and damage seeds (scripts/study_fragments.py --seeds).

aggregate(rows)           per (regularisation, cells, particles per cell): the number of seeds, the mean and
                          sample standard deviation of the count, of the first-failure velocity and time, and
                          the Mott and Grady-Kipp fits of the pooled masses
fit_cumulative(masses, kind, runs)
                          least squares of ln N(>= m) on f(m), N(>= m_k) = k / runs for the pooled masses sorted
                          largest first (the mean number per run); Mott: f = m^(1/2), N0 exp(-(m/mu)^(1/2));
                          Grady-Kipp: f = m, N0 exp(-m/mu). burst fits each run's own masses the same way
                          (summary.json fragment_mass_fit, src/mpm/fragments.cxx)
plot_ensemble(rows, png)  the count's mean and deviation per case, and N(>= m) per run of each case's pooled
                          masses with both fits and Grady's mean fragment mass (the fragmenting mass over the
                          Grady-Hightower count at the first failure, shear and tension) marked
"""
import math
import statistics

ENSEMBLE_FIELDS = ["regularization", "cells", "particles_per_cell", "seeds", "fragments_mean", "fragments_std", "fragments_min", "fragments_max",
                   "fracture_velocity_mean", "fracture_velocity_std", "grady_shear_mean", "grady_tension_mean", "mott_N0", "mott_mu_kg",
                   "grady_kipp_N0", "grady_kipp_mu_kg", "wall_time_s_mean"]


def masses_of(row):
    return [float(m) for m in row["fragment_masses_kg"].split(";") if m]


def fit_cumulative(masses, kind, runs=1):
    """(N0, mu) of the cumulative distribution N(>= m) per run, or None with fewer than three masses."""
    if len(masses) < 3:
        return None
    f = math.sqrt if kind == "mott" else (lambda m: m)
    xs = [f(m) for m in sorted(masses, reverse=True)]
    ys = [math.log((k + 1) / runs) for k in range(len(xs))]
    n = len(xs)
    sx, sy = sum(xs), sum(ys)
    sxx, sxy = sum(x * x for x in xs), sum(x * y for x, y in zip(xs, ys))
    det = n * sxx - sx * sx
    if det <= 0:
        return None
    slope = (n * sxy - sx * sy) / det
    if slope >= 0:
        return None
    N0 = math.exp((sy - slope * sx) / n)
    return N0, (1 / slope ** 2 if kind == "mott" else -1 / slope)


def groups(rows):
    keys = []
    for r in rows:
        k = (r["regularization"], int(r["cells"]), int(r["particles_per_cell"]))
        if k not in keys:
            keys.append(k)
    return [(k, [r for r in rows if (r["regularization"], int(r["cells"]), int(r["particles_per_cell"])) == k]) for k in keys]


def aggregate(rows):
    out = []
    for (reg, cells, ppc), sel in groups(rows):
        counts = [int(r["fragments"]) for r in sel]
        velocities = [float(r["fracture_velocity"]) for r in sel]
        pooled = [m for r in sel for m in masses_of(r)]
        mott, gk = fit_cumulative(pooled, "mott", len(sel)), fit_cumulative(pooled, "grady_kipp", len(sel))
        sd = lambda v: statistics.stdev(v) if len(v) > 1 else float("nan")  # noqa: E731
        out.append(dict(regularization=reg, cells=cells, particles_per_cell=ppc, seeds=len(sel), fragments_mean=statistics.mean(counts),
                        fragments_std=sd(counts), fragments_min=min(counts), fragments_max=max(counts),
                        fracture_velocity_mean=statistics.mean(velocities), fracture_velocity_std=sd(velocities),
                        grady_shear_mean=statistics.mean(float(r["grady_shear"]) for r in sel),
                        grady_tension_mean=statistics.mean(float(r["grady_tension"]) for r in sel),
                        mott_N0=mott[0] if mott else float("nan"), mott_mu_kg=mott[1] if mott else float("nan"),
                        grady_kipp_N0=gk[0] if gk else float("nan"), grady_kipp_mu_kg=gk[1] if gk else float("nan"),
                        wall_time_s_mean=statistics.mean(float(r["wall_time_s"]) for r in sel)))
    return out


def print_ensemble(table):
    print(f"{'regularisation':14s} {'cells':>5s} {'ppc':>3s} {'seeds':>5s}  count mean +- std [min, max]   V_fail (m/s)     Grady      Mott mu (kg)  Grady-Kipp mu (kg)")
    for e in table:
        print(f"{e['regularization']:14s} {e['cells']:5d} {e['particles_per_cell']:3d} {e['seeds']:5d}  {e['fragments_mean']:6.2f} +- {e['fragments_std']:5.2f} "
              f"[{e['fragments_min']}, {e['fragments_max']}]   {e['fracture_velocity_mean']:6.1f} +- {e['fracture_velocity_std']:5.1f}  "
              f"{e['grady_shear_mean']:.2f}-{e['grady_tension_mean']:.2f}  {e['mott_mu_kg']:.4g}  {e['grady_kipp_mu_kg']:.4g}")


def plot_ensemble(rows, png, title):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    grouped = groups(rows)
    table = aggregate(rows)
    fig, axes = plt.subplots(1, 2, figsize=(13, 4.8))
    ax = axes[0]
    names = [f"{reg}\n{cells} cells, {ppc}x{ppc}" for (reg, cells, ppc), _ in grouped]
    for i, ((_, sel), e) in enumerate(zip(grouped, table)):
        ax.plot([i] * len(sel), [int(r["fragments"]) for r in sel], "o", color="C0", alpha=0.4, ms=5)
        ax.errorbar([i + 0.15], [e["fragments_mean"]], yerr=[0 if math.isnan(e["fragments_std"]) else e["fragments_std"]], fmt="s", color="C3", capsize=4)
        ax.plot([i - 0.25, i + 0.25], [e["grady_shear_mean"]] * 2, color="0.5")
        ax.plot([i - 0.25, i + 0.25], [e["grady_tension_mean"]] * 2, color="0.5")
    ax.plot([], [], "o", color="C0", alpha=0.4, label="one seed")
    ax.errorbar([], [], yerr=[], fmt="s", color="C3", label="mean +- standard deviation")
    ax.plot([], [], color="0.5", label="Grady-Hightower, shear and tension")
    ax.set_xticks(range(len(names)), names, fontsize=7)
    ax.set_ylabel("fragments")
    ax.set_title(f"{title}: count over the porosity seeds", fontsize=9)
    ax.legend(fontsize=7)
    ax = axes[1]
    for i, ((reg, cells, ppc), sel) in enumerate(grouped):
        pooled = sorted((m for r in sel for m in masses_of(r)), reverse=True)
        if not pooled:
            continue
        runs = len(sel)
        ax.step(pooled, [(k + 1) / runs for k in range(len(pooled))], where="post", color=f"C{i}", label=f"{reg}, {cells} cells, {ppc}x{ppc} ({runs} seeds)")
        lo, hi = min(pooled), max(pooled)
        ms = [lo * (hi / lo) ** (j / 60) for j in range(61)] if hi > lo else [lo]
        for kind, style in (("mott", "--"), ("grady_kipp", ":")):
            fit = fit_cumulative(pooled, kind, runs)
            if fit:
                N0, mu = fit
                f = (lambda m: math.exp(-math.sqrt(m / mu))) if kind == "mott" else (lambda m: math.exp(-m / mu))
                ax.plot(ms, [N0 * f(m) for m in ms], style, color=f"C{i}", lw=1, label=f"  {'Mott' if kind == 'mott' else 'Grady-Kipp'}: N0 {N0:.3g}, mu {mu:.3g} kg")
        mass = statistics.mean(float(r["initial_mass"]) for r in sel)
        for key in ("grady_shear", "grady_tension"):
            ax.axvline(mass / statistics.mean(float(r[key]) for r in sel), color=f"C{i}", alpha=0.3, lw=3)
    ax.plot([], [], color="0.5", alpha=0.3, lw=3, label="Grady's mean mass (fragmenting mass / count, shear and tension)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("fragment mass m (kg, per m of length in 2-D)")
    ax.set_ylabel("fragments of mass >= m, per run")
    ax.set_title("pooled cumulative mass distribution", fontsize=9)
    ax.legend(fontsize=6)
    fig.savefig(png, dpi=120, bbox_inches="tight")
    plt.close(fig)
    return table
