#!/usr/bin/python3
"""The budgets of a run with gas (src/io/monitor.cxx ComputeBudget; monitor.csv and summary.json
"budget"): mass, momentum and total energy of particles + gases + what crossed the open faces +
removed particles, with the face impulses and the chemical energy released. Each subcommand runs
burst, prints the measured figures with a verdict (`name: value (tol X) OK|FAIL`) and exits non-zero
on failure. ctest calls them (tests/CMakeLists.txt, block 4e).

  gas_open   gas only, open faces: Sod with an outflow face at x = 1 run until the shock and the
             contact have left (t = 0.6), the quarter blast (blast2d, outflow at x and y max, 50^2
             cells to t = 0.6) and the JWL tube (a cold energy) with an outflow face to 4 times its
             final time; 14-30 % of the gas mass leaves, so the open-face terms are large,
             and the budgets must close to round-off: the open faces count the advection's own face
             fluxes and the face work of the conservative energy form; the diagnostics of the gas
             step's own non-conservation (advection, -p dV fallbacks, traces, one-sided face work)
             must read round-off too
  burn       the PBX block burning slowly in a closed box (tests/decks/burning_block.opts, Simple Burn
             A = 1 kg/(m^2 s)): the mass budget closes to round-off (what burns leaves the particles
             and enters the gas), the chemical energy is Q times the burnt mass, momentum stays at
             round-off of p0 L t (symmetric); the heat that the cells give the solids arrives at the
             particles (1e-6: the mass that burns between the projection and the particle update); the
             energy budget's residual within --energy-tol (1e-3) of the chemical energy released
  burnout    the burning block's deck as written (tests/decks/burning_block.opts, Simple Burn's
             default rate: the charge burns out by about 0.18 ms) to its final time on --ranks, and
             with half its time step: every particle burns out (none left, the whole charge counted
             as burnt), the mass budget closes to round-off, and the gas holds the closed box's end
             state: all mass gas, with the energy E = E_gas(0) + M_charge (c_v,s T_0 + Q). Its
             internal + kinetic energy must converge to E at first order in the time step and be
             within --end-tol (1 %, the issue's bound) at half the step; from there on the closed box's gas
             conserves its total energy to round-off (verify_ice.py conservation), so it comes to
             rest at T = E / (M c_v) and p = (gamma - 1) E / V, which are printed with the kinetic
             energy still in it; the energy budget's residual is printed
  exploding  the main job's short form (exploding_cylinder2d at 40^2 cells, to its final time 180 us:
             about 10 s a run) on 1 and 2 ranks: every budget term and error the same on both (to
             --tol of the budget's largest term), the mass budget closed on each, the momentum the
             cells give the solids received by the nodes (1e-8), the energy budget's residual
             within --energy-tol (1 %, the issue's bound) of the chemical energy released; the energy and
             momentum residuals are printed with their parts: what the gas step does not conserve
             (-p dV fallbacks, traces, the pressure source's work on the solids' cells, the exchange
             with the drag's dropped heat, the equilibration, the advection) and the coupling's
             transfers as the cells and as the particles see them (heat, kinetic energy, momentum)
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from verify_coupling import run, monitor, scratch, options  # noqa: E402
from verify import check, finish  # noqa: E402

BURN = "tests/decks/burning_block.opts"
EXPLODING = "options/scenes/exploding_cylinder2d.opts"


def budget_lines(s):
    """Prints the energy budget of summary.json's "budget"."""
    e, m, p = s["budget"]["energy"], s["budget"]["mass"], s["budget"]["momentum"]
    print(f"  mass: particles {m['particles']:.6g} kg, gas {m['gas']:.6g}, out through open faces {m['open_faces']:.6g}, removed particles {m['removed_particles']:.6g};"
          f" residual {m['residual']:.3e} kg, error {m['error']:.3e}")
    print(f"  momentum: particles {p['particles']}, gas {p['gas']}, open faces {p['open_faces']}, face pressure impulse {p['face_pressure_impulse']},"
          f" grid faces on the particles {p['grid_face_impulse']}, removed {p['removed_particles']}; residual {p['residual']}, error {p['error']:.3e}")
    print(f"  energy [J]: particles kinetic {e['particles_kinetic']:.6g}, stress work {e['particles_internal']:.6g}, heat from the gas {e['heat_to_particles']:.6g},"
          f" reactant's thermal energy to the gas {e['reactant_thermal']:.6g}; gas kinetic {e['gas_kinetic']:.6g}, internal {e['gas_internal']:.6g};"
          f" out through open faces {e['open_faces']:.6g} + work {e['open_face_work']:.6g}; removed particles {e['removed_particles']:.6g};"
          f" external work {e['external_work']:.6g}; chemical {e['chemical']:.6g}")
    print(f"  energy: residual {e['residual']:.6g} J, error {e['error']:.3e} of the largest term ({e['largest_term']:.6g} J)"
          + (f", {e['error_of_chemical']:+.4f} of the chemical energy released" if e["chemical"] > 0 else ""))


def transfers(s):
    """The energy residual's parts (summary.json "budget" "energy", monitor.cxx): what the gas step
    itself does not conserve (cells' view, solids' cell materials included), and the coupling's
    transfers as the cells and as the particles (nodes) see them. Returns the parts."""
    e, p = s["budget"]["energy"], s["budget"]["momentum"]
    parts = {
        "sources: -p dV fallbacks": e["fallback_energy_change"],
        "sources: traces accelerated without work": e["trace_energy_change"],
        "sources: pressure work on the solids' cells (-theta_s grad p)": e["solid_pressure_work"],
        "particles: work of the (p - p_ref) I in their stress": e["ambient_stress_work"],
        "the gases paid for the two (pressure_work.cxx)": -e["pressure_work_charged"],
        "gas face work booked on one side only": e["gas_interface_work"],
        "equilibration": e["equilibration_energy_change"],
        "exchange": e["exchange_energy_change"],
        "advection (dual-energy fallbacks, trace resets)": e["advection_energy_change"],
        "heat: particles received - cells gave": e["heat_to_particles"] - e["heat_to_solid_cells"],
        "reactant energy: products received - particles lost": e["reactant_energy_cells"] - e["reactant_thermal"] - e["burnt_particles"],
        "solids' kinetic energy from the gas: nodes - cells": e["kinetic_to_nodes"] - e["kinetic_to_solid_cells"],
    }
    parts["the rest"] = e["residual"] - sum(parts.values())
    scale = e["chemical"] if e["chemical"] > 0 else e["largest_term"]
    print(f"  energy residual {e['residual']:+.6g} J, its parts (J, and of the {'chemical energy released' if e['chemical'] > 0 else 'largest term'}):")
    for name, value in parts.items():
        print(f"    {name:62s} {value:+13.6g} {value / scale:+.4f}")
    print(f"    (of the exchange: the drag's kinetic energy not given back as heat {e['drag_energy_change']:+.6g}, its temperature-form fallbacks"
          f" {e['exchange_fallback_energy']:+.6g})")
    if e.get("solid_cell_energy_transfer"):
        print(f"    (-ice_solid_cell_energy: the gases of solids' cells handed their solids {e['solid_cell_energy_transfer']:+.6g} as heat, a transfer in no part)")
    own = e["particles_kinetic"] + e["particles_internal"] + e["burnt_particles"] + e["removed_particles"] - e["kinetic_to_nodes"] - e["external_work"] - e["ambient_stress_work"]
    print(f"    (of the pressure work: no gas in its cell could pay {e['pressure_work_held']:+.6g})")
    print(f"    (the rest: the particles' kinetic energy + stress work beyond the gas's increments at the nodes and the (p - p_ref) I work {own:+.6g},"
          f" MPM's own remainder; of it burning took {e['burnt_particles']:.6g} to the products)")
    print(f"  heat to the solids: cells gave {e['heat_to_solid_cells']:.6g} J, particles received {e['heat_to_particles']:.6g} J;"
          f" kinetic energy: cells {e['kinetic_to_solid_cells']:.6g} J, nodes {e['kinetic_to_nodes']:.6g} J;"
          f" momentum: cells gave {p['to_solid_cells']}, nodes received {p['to_nodes']}")
    return parts


# ---------------------------------------------------------------------------------------------

def gas_open(args):
    failures = []
    cases = [("sod, outflow at x = 1", "options/scenes/sod.opts", ["-ice_bc_xmax", "outflow", "-final_time", "0.6"]),
             ("blast2d, 50^2 cells", "options/scenes/blast2d.opts", ["-grid_cells", "50,50", "-final_time", "0.6", "-output_interval", "0"]),
             # a cold energy (JWL products): the advection carries c_v T + e_cold + |u|^2/2
             ("jwl_tube, outflow at x = 1", "tests/decks/jwl_tube.opts", ["-ice_bc_xmax", "outflow", "-final_time", "6.4e-4"])]
    for name, deck, extra in cases:
        out = scratch()
        s = run(args.burst, deck, out, extra + args.extra.split(), ranks=args.ranks)
        m = monitor(out)
        left = m["open_face_mass"][-1] / m["gas_mass"][0]
        print(f"{name}: {s['steps']} steps to t = {s['final_time']:.4g} s on {args.ranks} rank(s); {left:.1%} of the gas mass and"
              f" {(m['open_face_energy'][-1] + m['open_face_work'][-1]) / m['gas_total_energy'][0]:.1%} of its energy left through the open faces")
        budget_lines(s)
        # the open-face terms matter: without them the budgets would be off by what left
        ok = left > 0.1
        print(f"  more than a tenth of the gas left (the open faces are tested): {'OK' if ok else 'FAIL'}")
        if not ok:
            failures.append(f"{name}: nothing left")
        check(f"{name}: max |mass budget error| over the run", float(np.abs(m["mass_budget_error"]).max()), args.tol, failures)
        check(f"{name}: max |energy budget error| over the run", float(np.abs(m["balance_error"]).max()), args.tol, failures)
        check(f"{name}: max momentum budget error over the run", float(np.abs(m["momentum_budget_error"]).max()), args.tol, failures)
        check(f"{name}: summary energy_balance_error = the budget's", abs(s["energy_balance_error"] - s["budget"]["energy"]["error"]), 0.0, failures)
        e = s["budget"]["energy"]  # the diagnostics of the residual's parts: nothing to find here
        for key in ("advection_energy_change", "fallback_energy_change", "trace_energy_change", "equilibration_energy_change", "exchange_energy_change", "gas_interface_work"):
            check(f"{name}: |{key}| / largest term", abs(e[key]) / e["largest_term"], args.tol, failures)
    finish(f"gas_open[{args.ranks} rank(s)]", failures)


def reactant_energy_closes(e, failures, name=""):
    """The products take the burnt reactant's whole energy (burn.cxx): c_v T less the heat of its
    stress updates, its stress work and its kinetic energy, projected per unit mass with the weights
    that take the burnt mass from the particles, so what the cells gave is what the particles lost."""
    lost = e["reactant_thermal"] + e["burnt_particles"]
    check(f"{name}|reactant energy the products received - what the burnt particles lost| / what they lost",
          abs(e["reactant_energy_cells"] - lost) / lost, 1e-9, failures)


def burn(args):
    failures = []
    out = scratch()
    s = run(args.burst, BURN, out, ["-pbx_burn_simple_A", str(args.rate), "-final_time", str(args.final_time), "-output_interval", "0"] + args.extra.split(), ranks=args.ranks)
    m = monitor(out)
    burnt = s["gas"]["burnt_mass"]
    Q = float(options(BURN).get("-pbx_burn_simple_Q", 2.0e6))  # Simple Burn's default (models/burn/simple_burn.cxx)
    print(f"burning_block: {s['steps']} steps to t = {s['final_time']:.4g} s on {args.ranks} rank(s), burnt {burnt:.6e} kg/m"
          f" ({burnt / m['mass'][0]:.3e} of the charge), Q = {Q:g} J/kg")
    budget_lines(s)
    transfers(s)
    ok = burnt > 1e-5 * m["mass"][0]
    print(f"  it burns (> 1e-5 of the charge): {'OK' if ok else 'FAIL'}")
    if not ok:
        failures.append("nothing burnt")
    check("max |mass budget error| over the run (particles + gas)", float(np.abs(m["mass_budget_error"]).max()), args.tol, failures)
    e = s["budget"]["energy"]
    check("|chemical energy - Q x burnt mass| / (Q x burnt mass)", abs(e["chemical"] - Q * burnt) / (Q * burnt), 1e-12, failures)
    # the coupling's transfers are conservative (coupling.cxx CouplingIncrementsToNodes): the heat the
    # cells give their solids arrives at the particles, up to the mass that burns between the
    # projection and the particle update (~1e-5 of the charge here; momentum is checked by exploding,
    # this problem's is zero)
    check("|heat the particles received - heat the cells gave| / heat the cells gave",
          abs(e["heat_to_particles"] - e["heat_to_solid_cells"]) / abs(e["heat_to_solid_cells"]), 1e-6, failures)
    # the products take the burnt reactant's whole energy (burn.cxx): c_v T less the heat of its
    # stress updates, its stress work and its kinetic energy, projected per unit mass with the weights
    # that take the burnt mass from the particles, so what the cells gave is what the particles lost
    reactant_energy_closes(e, failures)
    scale = 1e5 * 0.01 * s["final_time"]  # the impulse of 1 atm on the 1 cm block over the run (symmetric: momentum 0)
    residual = np.abs(np.array(s["budget"]["momentum"]["residual"], float)).max()
    check("max |momentum budget residual| / (p0 L t)", residual / scale, 1e-9, failures)
    # the gases pay the pressure's work on the block (pressure_work.cxx): without that the residual is
    # the work of the gas compressing the block; what is left is MPM's own (measured 3e-4)
    check("|energy budget residual| / chemical energy released", abs(e["error_of_chemical"]), args.energy_tol, failures)
    finish(f"budget burn[{args.ranks} rank(s)]", failures)


def burnout(args):
    failures = []
    o = options(BURN)
    final_time = float(o["-final_time"])
    rho_s, cv_s, T0 = float(o["-pbx_density"]), float(o["-pbx_heat_capacity"]), float(o["-charge_temperature"])
    lower, upper = [np.array([float(v) for v in o[k].split(",")]) for k in ("-charge_lower", "-charge_upper")]
    box_lower, box_upper = [np.array([float(v) for v in o[k].split(",")]) for k in ("-grid_lower", "-grid_upper")]
    charge = rho_s * np.prod(upper - lower)  # kg/m (2-D)
    Q = float(o.get("-pbx_burn_simple_Q", 2.0e6))
    gamma, cv = float(o["-products_gamma"]), float(o["-products_cv"])
    volume = np.prod(box_upper - box_lower)
    # the deck as written, then with the time step halved (both Courant numbers: -ice_cfl 0.25 and
    # -mpm_cfl 0.4 are the defaults)
    errors = []
    for name, extra in (("as written", []), ("half the time step", ["-ice_cfl", "0.125", "-mpm_cfl", "0.2"])):
        out = scratch()
        s = run(args.burst, BURN, out, ["-output_interval", "0"] + extra + args.extra.split(), ranks=args.ranks)
        e = s["budget"]["energy"]
        print(f"burning_block, {name}: {s['steps']} steps to t = {s['final_time']:.6g} s (deck: {final_time:g}) on {args.ranks} rank(s);"
              f" {s['particles']} particles left, {s['gas']['burnt_out_particles']} burnt out, burnt {s['gas']['burnt_mass']:.10g} of {charge:.10g} kg/m")
        budget_lines(s)
        transfers(s)
        check(f"{name}: |t_end - final time| / final time", abs(s["final_time"] - final_time) / final_time, 1e-12, failures)
        check(f"{name}: particles left", float(s["particles"]), 0.0, failures)
        check(f"{name}: |burnt mass - charge| / charge", abs(s["gas"]["burnt_mass"] - charge) / charge, args.tol, failures)
        check(f"{name}: mass budget error (particles + gas)", abs(s["budget"]["mass"]["error"]), args.tol, failures)
        energy_end = e["initial"] + charge * (cv_s * T0 + Q)
        gas_energy = e["gas_internal"] + e["gas_kinetic"]
        mass = s["budget"]["mass"]["gas"]
        print(f"  end state: E = E_gas(0) {e['initial']:.6g} J + M_charge (c_v,s T_0 + Q) {charge * (cv_s * T0 + Q):.6g} J = {energy_end:.6g} J;"
              f" the gas holds {gas_energy:.6g} J ({e['gas_kinetic'] / energy_end:.2%} still kinetic)")
        print(f"  at rest: T = {gas_energy / (mass * cv):.6g} K (exact {energy_end / (mass * cv):.6g}), p = {(gamma - 1) * gas_energy / volume:.6g} Pa"
              f" (exact {(gamma - 1) * energy_end / volume:.6g}); now: mean T {e['gas_internal'] / (mass * cv):.6g} K, mean p {(gamma - 1) * e['gas_internal'] / volume:.6g} Pa")
        reactant_energy_closes(e, failures, f"{name}: ")
        ok = e["burnt_particles"] > 1e-3 * e["reactant_thermal"]
        print(f"  {name}: the burnt particles' kinetic energy and stress work ({e['burnt_particles']:.4g} J) reach the products, over 1e-3 of"
              f" their thermal energy ({e['reactant_thermal']:.4g} J): {'OK' if ok else 'FAIL'}")
        if not ok:
            failures.append(f"{name}: no kinetic energy or stress work burnt")
        errors.append(abs(gas_energy - energy_end) / energy_end)
        print(f"  |gas energy - end state's| / end state's: {errors[-1]:.3e}; energy budget residual {e['error_of_chemical']:+.3e} of the chemical energy released")
    # The gas's end energy is off by the coupled step's error in time (the particles' own transfer
    # remainder, about +7-9 % of the chemical energy as written, and the solids' kinetic energy the
    # nodes lose to the gas beyond what the cells see, about -5 %, largely cancel): measured 1.38 %,
    # 0.59 %, 0.13 % at the deck's, half and a quarter of its Courant numbers. It must fall at first
    # order at least, and be within --end-tol (1 %) at half the step.
    print(f"  observed order in the time step: {np.log2(errors[0] / errors[1]):.2f}")
    check("half the time step: |gas energy - end state's| / end state's", errors[1], args.end_tol, failures)
    check("the same over the deck's (first order: 0.5)", errors[1] / errors[0], 0.6, failures)
    finish(f"budget burnout[{args.ranks} rank(s)]", failures)


def exploding(args):
    failures = []
    extra = ["-grid_cells", f"{args.cells},{args.cells}", "-final_time", str(args.final_time), "-output_interval", "0"] + args.extra.split()
    runs = []
    for ranks in (1, 2):
        out = scratch()
        s = run(args.burst, EXPLODING, out, extra, ranks=ranks)
        print(f"exploding cylinder, {args.cells}^2 cells to t = {s['final_time']:.4g} s on {ranks} rank(s): {s['steps']} steps, burnt {s['gas']['burnt_mass']:.6g} kg/m")
        budget_lines(s)
        transfers(s)
        runs.append((s, monitor(out)))
        check(f"{ranks} rank(s): max |mass budget error| over the run", float(np.abs(runs[-1][1]["mass_budget_error"]).max()), args.mass_tol, failures)
        check(f"{ranks} rank(s): summary energy_balance_error = the energy budget's", abs(s["energy_balance_error"] - s["budget"]["energy"]["error"]), 0.0, failures)
        # issue 23's bound for the exploding scenes: the whole system's energy within 1 % of the
        # chemical energy released (measured +0.47 % at 40 x 40; +15.6 % if the gases do not pay the
        # pressure's work on the solids, -coupling_charge_pressure_work 0)
        check(f"{ranks} rank(s): |energy budget residual| / chemical energy released", abs(s["budget"]["energy"]["error_of_chemical"]), args.energy_tol, failures)
        p = s["budget"]["momentum"]
        given, received = np.array(p["to_solid_cells"], float), np.array(p["to_nodes"], float)
        check(f"{ranks} rank(s): max |momentum the nodes received - momentum the cells gave| / max |given| (conservative transfer)",
              float(np.abs(received - given).max() / np.abs(given).max()), 1e-8, failures)
    (s1, m1), (s2, m2) = runs
    ok = len(m1["step"]) == len(m2["step"]) and np.array_equal(m1["step"], m2["step"])
    print(f"  the same monitor steps on 1 and 2 ranks: {'OK' if ok else 'FAIL'}")
    if not ok:
        finish("budget exploding", ["monitor steps differ"])
    # every budget column of monitor.csv, relative to its budget's largest term at that row
    groups = {
        "mass": (["mass", "gas_mass", "open_face_mass", "removed_particle_mass"], None),
        "momentum": ([f"{k}_{d}" for k in ("momentum", "gas_momentum", "open_face_momentum", "face_pressure_impulse", "grid_face_impulse",
                                          "removed_particle_momentum", "momentum_budget_residual") for d in "xy"], None),
        "energy": (["kinetic", "internal", "heat_to_particles", "reactant_thermal_energy", "gas_kinetic_energy", "gas_internal_energy",
                    "open_face_energy", "open_face_work", "removed_particle_energy", "chemical_energy", "budget_energy", "energy_budget_residual"], "energy_budget_scale"),
    }
    for group, (columns, scale_column) in groups.items():
        scale = m1[scale_column] if scale_column else np.max([np.abs(m1[c]) for c in columns], axis=0)
        scale = np.maximum(scale, 1e-300)
        worst, where = 0.0, ""
        for c in columns:
            d = float(np.max(np.abs(m1[c] - m2[c]) / scale))
            if d > worst:
                worst, where = d, c
        check(f"{group} budget: max |1 rank - 2 ranks| / largest term, over every term and row (worst: {where or '-'})", worst, args.tol, failures)
    for c in ("mass_budget_error", "momentum_budget_error", "balance_error"):
        check(f"|{c} on 1 rank - on 2 ranks|, max over the rows", float(np.abs(m1[c] - m2[c]).max()), args.tol, failures)
    finish(f"budget exploding[{args.cells} cells, 1 and 2 ranks]", failures)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--burst", required=True)
    sub = p.add_subparsers(dest="cmd", required=True)
    g = sub.add_parser("gas_open")
    g.add_argument("--tol", type=float, default=1e-12)
    g.add_argument("--ranks", type=int, default=1)
    g.add_argument("--extra", default="")
    b = sub.add_parser("burn")
    b.add_argument("--rate", type=float, default=1.0, help="Simple Burn A (kg/(m^2 s)), the slow burn of verify_coupling.py burn")
    b.add_argument("--final-time", type=float, default=1e-4)
    b.add_argument("--tol", type=float, default=1e-12)
    b.add_argument("--energy-tol", type=float, default=1e-3)
    b.add_argument("--ranks", type=int, default=1)
    b.add_argument("--extra", default="")
    bo = sub.add_parser("burnout")
    bo.add_argument("--tol", type=float, default=1e-12)
    bo.add_argument("--end-tol", type=float, default=1e-2)
    bo.add_argument("--ranks", type=int, default=1)
    bo.add_argument("--extra", default="")
    e = sub.add_parser("exploding")
    e.add_argument("--cells", type=int, default=40)
    e.add_argument("--final-time", type=float, default=1.8e-4)
    e.add_argument("--tol", type=float, default=1e-11)
    e.add_argument("--mass-tol", type=float, default=1e-12)
    e.add_argument("--energy-tol", type=float, default=1e-2)
    e.add_argument("--extra", default="")
    args = p.parse_args()
    {"gas_open": gas_open, "burn": burn, "burnout": burnout, "exploding": exploding}[args.cmd](args)


if __name__ == "__main__":
    main()
