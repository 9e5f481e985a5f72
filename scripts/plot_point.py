#!/usr/bin/python3
"""Flow-stress charts from the material-point driver (burst -mode point).

  scripts/plot_point.py --burst build/burst [--out DIR]

writes DIR/flow_stress_materials.png (uniaxial stress at 1000 /s, 298 K, adiabatic, for every
shipped elastic-plastic material file) and DIR/flow_stress_4340_data.png (the 4340 Johnson-Cook set
against the Johnson & Cook (1985) data of verification.md 5, at each test's rate and temperature).
Any CSV written with -point_output can also be plotted: scripts/plot_point.py --csv FILE.csv
"""
import argparse
import glob
import os
import subprocess
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# Johnson & Cook (1985), 4340 Rc 30: (label, rate 1/s, T0 K, [(eps_p, sigma MPa)]) (verification.md 5)
DATA_4340 = [("tension 0.002/s 298 K", 0.002, 298, [(0, 808.7), (0.05, 968.9), (0.10, 1042.8), (0.20, 1135.1)]),
             ("torsion 0.009/s 298 K", 0.009, 298, [(0, 798.2), (0.05, 933.4), (0.10, 988.4), (0.20, 1027.1)]),
             ("torsion 1.1/s 298 K", 1.1, 298, [(0, 865.6), (0.05, 1003.3), (0.10, 1067.1), (0.20, 1114.7)]),
             ("tension 570/s 298 K", 570, 298, [(0, 818.6), (0.05, 1058.9), (0.10, 1162.3)]),
             ("tension 604/s 500 K", 604, 500, [(0, 753.6), (0.05, 918.2), (0.10, 985.5)]),
             ("tension 650/s 735 K", 650, 735, [(0, 677.8), (0.05, 827.8), (0.10, 862.3)])]


def run_point(burst, deck, rate, temperature, strain, out, extra=()):
    cmd = [burst, "-mode", "point", "-options_file", deck, "-point_path", "uniaxial_stress", "-point_rate", str(rate), "-point_temperature", str(temperature),
           "-point_final_strain", str(strain), "-point_steps", "300", "-point_adiabatic", "true" if rate > 10 else "false", "-point_output", out, *extra]
    subprocess.run(cmd, cwd=ROOT, check=True, capture_output=True)
    return np.genfromtxt(out, delimiter=",", names=True)


def is_elastic_plastic(deck):
    with open(deck) as f:
        return "elastic_plastic" in f.read()


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--burst", default=os.path.join(ROOT, "build/burst"))
    p.add_argument("--out", default=os.path.join(ROOT, "output"))
    p.add_argument("--csv", help="plot one driver CSV instead")
    args = p.parse_args()
    os.makedirs(args.out, exist_ok=True)
    if args.csv:
        d = np.genfromtxt(args.csv, delimiter=",", names=True)
        fig, ax = plt.subplots(figsize=(6, 4))
        ax.plot(d["strain"], d["von_mises"] / 1e6, label="von Mises stress")
        ax.plot(d["strain"], d["flow_stress"] / 1e6, "--", label="flow stress")
        ax.set_xlabel("strain of the path")
        ax.set_ylabel("stress (MPa)")
        ax.legend()
        name = os.path.join(args.out, os.path.splitext(os.path.basename(args.csv))[0] + ".png")
        fig.savefig(name, dpi=130, bbox_inches="tight")
        print("wrote", name)
        return

    with tempfile.TemporaryDirectory() as tmp:
        fig, ax = plt.subplots(figsize=(7, 4.5))
        for deck in sorted(glob.glob(os.path.join(ROOT, "options/materials/*.opts"))):
            if not is_elastic_plastic(deck):
                continue
            d = run_point(args.burst, deck, 1000, 298, 0.3, os.path.join(tmp, "m.csv"))
            ax.plot(d["plastic_strain"], d["von_mises"] / 1e6, label=os.path.basename(deck).replace(".opts", ""))
        ax.set_xlabel("equivalent plastic strain")
        ax.set_ylabel("von Mises stress (MPa)")
        ax.set_title("uniaxial stress, 1000 /s, 298 K, adiabatic")
        ax.legend(fontsize=8)
        name = os.path.join(args.out, "flow_stress_materials.png")
        fig.savefig(name, dpi=130, bbox_inches="tight")
        print("wrote", name)

        fig, ax = plt.subplots(figsize=(7, 4.5))
        deck = os.path.join(ROOT, "options/materials/steel_4340_jc.opts")
        for k, (label, rate, T0, points) in enumerate(DATA_4340):
            color = f"C{k}"
            d = run_point(args.burst, deck, rate, T0, 0.25, os.path.join(tmp, "s.csv"), ["-steel_eos_type", "hypoelastic", "-steel_flow_stress_min_rate", "1e-4"])
            plastic = d["plastic_strain"] > 0
            ax.plot(d["plastic_strain"][plastic], d["von_mises"][plastic] / 1e6, color=color, label=f"JC, {label}")
            ax.plot([e for e, _ in points], [s for _, s in points], "o", color=color)
        ax.set_xlabel("equivalent plastic strain")
        ax.set_ylabel("equivalent stress (MPa)")
        ax.set_title("4340 steel: Johnson-Cook (lines) against Johnson & Cook 1985 (dots)")
        ax.legend(fontsize=7)
        name = os.path.join(args.out, "flow_stress_4340_data.png")
        fig.savefig(name, dpi=130, bbox_inches="tight")
        print("wrote", name)


if __name__ == "__main__":
    main()
