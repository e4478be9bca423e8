"""The evaporation{} entries of the steel melt-pool scenes (Fuchs2022 table 1) and the option that
makes the metal evaporate with its vapour jet (doc/foam_laser_evaporation.rst)."""

VAPOUR_JET_HELP = ("the metal evaporates and its vapour streams off as gas (evaporation massLoss, vapourJet: "
                   "doc/foam_laser_evaporation.rst)")


def steel_dict(cp=965.0, vapour_jet=False):
    """evaporation{} with Fuchs2022's steel data (cp: the metal's, for h(T) = cp (T - Th0));
    vapour_jet: massLoss and vapourJet on."""
    jet = "    massLoss on;\n    vapourJet on;\n" if vapour_jet else ""
    return f"""evaporation
{{
    pAmbient 1e5;
    CT 5e4;
    Tboil 3000;
    hv 6.583e6;
    cp {cp!r};
    Th0 663.731;
    CM 1.1095e-3;
{jet}}}
"""
