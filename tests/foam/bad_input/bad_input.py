#!/usr/bin/env python3
"""Bad input to meltdemFoam stops with an OpenFOAM FatalIOError whose text names the entry.

A tiny 1D conduction case (5 cells, physics { flow off; energy on; }) that runs cleanly is
broken one entry at a time in constant/meltdemProperties (the metal/gas data, the switches,
darcy, and the laser and evaporation sub-dictionaries). Each variant must end with a non-zero
exit code that is not a signal (no segfault, no floating-point trap), print 'FOAM FATAL IO ERROR'
and name the offending entry; the clean case must run to the end (so a variant cannot pass by
breaking something else).
usage: bad_input.py [--keep]
"""
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

from meltdem import paths
from meltdem.case import foam as fc
from meltdem.testing.report import report

src = paths.source_dir()

TEST = "foam.bad_input"
METAL = "metal { Tsolidus 1700; Tliquidus 1710; L 2.7e5; cp 965; k 35.95; }\n"
GAS = "gas { cp 10; k 0.026; }\n"
PHYSICS = {"flow": "off", "energy": "on", "surfaceTension": "off"}

# name -> (what is wrong, physics overrides, metal text, gas text, extra text, words the message must hold)
VARIANTS = {
    "solidus_above_liquidus": ("Tsolidus 1800 > Tliquidus 1710", {},
                               METAL.replace("Tsolidus 1700", "Tsolidus 1800"), GAS, "",
                               ["Tsolidus", "Tliquidus"]),
    "negative_conductivity": ("metal k = -35.95", {}, METAL.replace("k 35.95", "k -35.95"), GAS, "",
                              ["'k'"]),
    "negative_gas_conductivity": ("gas k = -0.026", {}, METAL, GAS.replace("k 0.026", "k -0.026"), "",
                                  ["'k'", "gas"]),
    "missing_cp": ("metal cp missing", {}, METAL.replace("cp 965; ", ""), GAS, "", ["'cp'"]),
    "missing_latent_heat": ("metal L missing", {}, METAL.replace("L 2.7e5; ", ""), GAS, "", ["'L'"]),
    "negative_latent_heat": ("metal L = -2.7e5", {}, METAL.replace("L 2.7e5", "L -2.7e5"), GAS, "",
                             ["'L'"]),
    "missing_gas_dict": ("no gas sub-dictionary", {}, METAL, "", "", ["'gas'"]),
    "unknown_switch": ("physics { flw on; }", {"flw": "on"}, METAL, GAS, "", ["'flw'"]),
    "laser_outside_domain": ("laser position (5e-3 0.3e-3 1e-4) outside the 1 mm x 0.2 mm slab", {"laser": "on"},
                             METAL, GAS, "laser { power 10; absorptivity 0.5; radius 5e-5; direction (0 -1 0); "
                             "position (5e-3 0.3e-3 1e-4); velocity (0 0 0); }\n", ["position", "outside"]),
    "unknown_absorptivity_model": ("laser { absorptivityModel drude; }", {"laser": "on"}, METAL, GAS,
                                   "laser { power 10; absorptivity 0.5; radius 5e-5; direction (0 -1 0); "
                                   "position (0.5e-3 0.2e-3 1e-4); absorptivityModel drude; }\n",
                                   ["absorptivityModel", "drude"]),
    "missing_absorptivity_slope": ("laser { absorptivityModel linear; } without dAbsorptivitydT", {"laser": "on"},
                                   METAL, GAS, "laser { power 10; absorptivity 0.5; radius 5e-5; direction (0 -1 0); "
                                   "position (0.5e-3 0.2e-3 1e-4); absorptivityModel linear; Tabsorptivity 1700; }\n",
                                   ["dAbsorptivitydT"]),
    "laser_misspelt_velocity": ("laser { velocty (0.5 0 0); } (misspelt: the beam would stand)", {"laser": "on"},
                                METAL, GAS, "laser { power 10; absorptivity 0.5; radius 5e-5; direction (0 -1 0); "
                                "position (0.5e-3 0.2e-3 1e-4); velocty (0.5 0 0); tStop 1e-4; }\n",
                                ["velocty", "position mode"]),
    "laser_slope_without_linear": ("laser { dAbsorptivitydT 2e-4; } with the constant model", {"laser": "on"},
                                   METAL, GAS, "laser { power 10; absorptivity 0.5; radius 5e-5; direction (0 -1 0); "
                                   "position (0.5e-3 0.2e-3 1e-4); dAbsorptivitydT 2e-4; Tabsorptivity 1700; }\n",
                                   ["dAbsorptivitydT", "constant"]),
    "surface_tension_misspelt_entry": ("surfaceTension nsmooth 2 (misspelt; merged into the written block)",
                                       {"flow": "on", "surfaceTension": "on"}, METAL, GAS,
                                       "surfaceTension { nsmooth 2; }\n", ["nsmooth", "surfaceTension"]),
    "evaporation_misspelt_mass_loss": ("evaporation massloss on (misspelt)", {"evaporation": "on"}, METAL, GAS,
                                       "evaporation { pAmbient 1e5; CT 5e4; Tboil 3000; hv 6.583e6; cp 965; "
                                       "Th0 663.731; CM 1.1095e-3; massloss on; }\n", ["massloss", "evaporation"]),
    "negative_boiling_point": ("evaporation Tboil = -3000", {"evaporation": "on"}, METAL, GAS,
                               "evaporation { pAmbient 1e5; CT 5e4; Tboil -3000; hv 6.583e6; cp 965; "
                               "Th0 663.731; CM 1.1095e-3; }\n", ["Tboil"]),
    "vapour_jet_without_mass_loss": ("evaporation vapourJet on without massLoss", {"evaporation": "on"}, METAL, GAS,
                                     "evaporation { pAmbient 1e5; CT 5e4; Tboil 3000; hv 6.583e6; cp 965; "
                                     "Th0 663.731; CM 1.1095e-3; vapourJet on; }\n", ["vapourJet", "massLoss"]),
    "negative_vapour_spread": ("evaporation vapourSpread = -1e-5", {"evaporation": "on"}, METAL, GAS,
                               "evaporation { pAmbient 1e5; CT 5e4; Tboil 3000; hv 6.583e6; cp 965; "
                               "Th0 663.731; CM 1.1095e-3; massLoss on; vapourJet on; vapourSpread -1e-5; }\n",
                               ["vapourSpread"]),
    "missing_darcy_C": ("darcy on, darcy { b 1e-3; } (no C)", {"flow": "on", "darcy": "on"}, METAL, GAS,
                        "darcy { b 1e-3; }\n", ["'C'"]),
    "negative_thermal_courant": ("energyControls { maxThermalCo -1; }", {}, METAL, GAS,
                                 "energyControls { maxThermalCo -1; }\n", ["maxThermalCo"]),
    "top_level_unknown_entry": ("refinment { ... } (a misspelt block)", {}, METAL, GAS,
                                "refinment { maxLevel 1; criteria { interface { level 1; } } }\n",
                                ["refinment", "meltdemProperties"]),
    "energy_controls_unknown_entry": ("energyControls { nCorrector 50; } (misspelt)", {}, METAL, GAS,
                                      "energyControls { nCorrector 50; }\n", ["nCorrector", "energyControls"]),
    "isothermal_temperature_zero": ("isothermalTemperature 0 with energy off", {"energy": "off"}, METAL, GAS,
                                    "isothermalTemperature 0;\n", ["isothermalTemperature"]),
}

# the meltdemBalance function object of system/controlDict: name -> (what is wrong, its entries, words)
DOC_BALANCE = ("alpha alpha.metal; T T; U U; phi phi; p p; liquidFraction liquidFraction; "
               "laserHeatSource laserHeatSource; evaporationHeatLoss evaporationHeatLoss;")
BALANCE_VARIANTS = {
    "balance_misspelt_alpha": ("meltdemBalance alpha alpha.metl (misspelt: every cell would count as metal)",
                               "alpha alpha.metl;", ["alpha.metl", "alpha", "balance"]),
    "balance_misspelt_temperature": ("meltdemBalance T Temp (misspelt: the enthalpy columns would go)",
                                     "T Temp;", ["Temp", "balance"]),
}


def build(case, physics, metal, gas, extra, balance=""):
    nx = 5
    g = fc.Grid2D(1e-3, 2e-4, nx, 1, dz=2e-4)
    g.block_mesh(case, patches={"left": ("hot", "patch"), "right": ("cold", "patch"),
                                "bottom": ("sides", "empty"), "top": ("sides", "empty")})
    zg = "type zeroGradient;"
    b = {"hot": zg, "cold": zg, "sides": "type empty;"}
    fc.field(case, "alpha.metal", "[0 0 0 0 0 0 0]", np.ones(nx), b)
    fc.field(case, "T", "[0 0 0 1 0 0 0]", np.full(nx, 1700.0),
             dict(b, hot="type fixedValue; value uniform 1800;"))
    fc.field(case, "U", "[0 1 -1 0 0 0 0]", np.zeros((nx, 3)),
             dict(b, hot="type noSlip;", cold="type noSlip;"), vector=True)
    fc.field(case, "p_rgh", "[1 -1 -2 0 0 0 0]", np.zeros(nx), b)
    fc.transport(case, 7430.0, 6e-3 / 7430.0, 7.43, 6e-4 / 7.43, 1.8)
    fc.gravity(case)
    ph = dict(PHYSICS)
    ph.update(physics)
    fc.meltdem_properties(case, physics=ph, extra=metal + gas + extra)
    fc.control_dict(case, "meltdemFoam", 1e-3, 1e-4, 1e-3, adjustable=False,
                    extra=f"functions\n{{\n    balance {{ type meltdemBalance; {balance} }}\n}}\n")
    fc.fv_schemes(case, extra_div="    div(rhoCpPhi,T) Gauss upwind;\n")
    fc.fv_solution(case, p_ref_cell=0, extra_solvers='    "T.*" { solver PBiCGStab; preconditioner DILU; '
                                                     'tolerance 1e-12; relTol 0; }\n')
    fc.run(["blockMesh"], case, "log.blockMesh")


def run(case):
    env = dict(os.environ)
    env.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")
    r = subprocess.run([fc.solver()], cwd=case, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       env=env, timeout=120)
    out = r.stdout.decode(errors="replace")
    with open(os.path.join(case, "log.solver"), "w") as f:
        f.write(out)
    return r.returncode, out


def fatal_text(out):
    """The FatalIOError block: from the banner to 'FOAM exiting'."""
    i = out.find("FOAM FATAL IO ERROR")
    return out[i:] if i >= 0 else ""


def judge(name, rc, out, text, words):
    """(whether a bad-input run stopped as it should: non-zero exit, no signal, the error text
    holding every word; the measured outcome in words), printing the error's first lines."""
    signal = rc < 0 or rc >= 128 or re.search(r"Foam::sigSegv|Foam::sigFpe|printStack|Segmentation fault", out)
    named = bool(text) and all(w in text for w in words)
    first = " ".join(text.split("\n")[1:3]).strip()[:160] if text else out.strip()[-160:]
    print(f"{name}: rc {rc}; {first!r}")
    measured = (f"rc {rc}, {'fatal error' if text else 'no fatal error'}, "
                f"{'names it' if named else 'does not name it'}")
    return rc != 0 and not signal and named, measured


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="bad_input.")
    ok = True

    clean = os.path.join(work, "clean")
    build(clean, {}, METAL, GAS, "")
    rc, out = run(clean)
    clean_ok = rc == 0 and "End" in out
    ok &= report(TEST, "clean tiny case runs to the end (exit code)", rc, 0, "exact", clean_ok)

    for name, (what, physics, metal, gas, extra, words) in VARIANTS.items():
        case = os.path.join(work, name)
        build(case, physics, metal, gas, extra)
        rc, out = run(case)
        good, measured = judge(name, rc, out, fatal_text(out), words)
        ok &= report(TEST, f"{what}: FatalIOError naming {' '.join(words)}", measured,
                     "FatalIOError naming the entry", "exact", good)

    # the balance block of doc/foam_meltdem_balance.rst, every name at its default (no laser or
    # evaporation field in this case), runs; a renamed field that does not exist stops
    case = os.path.join(work, "balance_doc_block")
    build(case, {}, METAL, GAS, "", DOC_BALANCE)
    rc, out = run(case)
    ok &= report(TEST, "meltdemBalance with the doc's block (default names) runs to the end (exit code)", rc, 0,
                 "exact", rc == 0 and "End" in out)
    for name, (what, balance, words) in BALANCE_VARIANTS.items():
        case = os.path.join(work, name)
        build(case, {}, METAL, GAS, "", balance)
        rc, out = run(case)
        good, measured = judge(name, rc, out, fatal_text(out), words)
        ok &= report(TEST, f"{what}: FatalIOError naming {' '.join(words)}", measured,
                     "FatalIOError naming the entry", "exact", good)
    return fc.finish(ok, work, keep)


if __name__ == "__main__":
    sys.exit(main())
