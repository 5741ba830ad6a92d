#!/usr/bin/env python3
"""Writes src/scene/mitsuba/conductors.rs: the RGB `eta` and `k` that Mitsuba 3 (variant
scalar_rgb) uses for each of its named conductor materials (`<string name="material"
value="Au"/>`), read back from Mitsuba itself, so that footprint's named conductors are
Mitsuba's to the last printed digit.

    python3 scripts/mitsuba_conductors.py      # needs `pip install mitsuba`
"""
import os

import mitsuba as mi

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# Mitsuba 3's data/ior presets (its conductor plugin's documented list, with the `_palik`
# measurements beside the others).
NAMES = ["a-C", "Ag", "Al", "AlAs", "AlAs_palik", "AlSb", "AlSb_palik", "Au", "Be", "Be_palik", "Cr", "CsI",
         "CsI_palik", "Cu", "Cu_palik", "Cu2O", "Cu2O_palik", "CuO", "CuO_palik", "d-C", "d-C_palik", "Hg",
         "Hg_palik", "HgTe", "HgTe_palik", "Ir", "Ir_palik", "K", "K_palik", "Li", "Li_palik", "MgO", "MgO_palik",
         "Mo", "Mo_palik", "Na_palik", "Nb", "Nb_palik", "Ni_palik", "Rh", "Rh_palik", "Se", "Se_palik", "SiC",
         "SiC_palik", "SnTe", "SnTe_palik", "Ta", "Ta_palik", "Te", "Te_palik", "ThF4", "ThF4_palik", "TiC",
         "TiC_palik", "TiN", "TiN_palik", "TiO2", "TiO2_palik", "VC", "VC_palik", "V_palik", "VN", "VN_palik", "W"]


def main():
    mi.set_variant("scalar_rgb")
    rows = []
    for n in NAMES:
        p = mi.traverse(mi.load_dict({"type": "conductor", "material": n}))
        e, k = p["eta.value"], p["k.value"]
        rows.append(f'    ("{n}", [{e[0]:.6}, {e[1]:.6}, {e[2]:.6}], [{k[0]:.6}, {k[1]:.6}, {k[2]:.6}]),')
    out = os.path.join(ROOT, "src", "scene", "mitsuba", "conductors.rs")
    with open(out, "w") as f:
        f.write(f"""//! Mitsuba 3's named conductor materials (`material="Au"` of `conductor` and
//! `roughconductor`) as the RGB `eta` and `k` its `scalar_rgb` variant renders them with,
//! written by `scripts/mitsuba_conductors.py` from Mitsuba {mi.__version__} itself (do not edit).

/// `(name, eta, k)`, both relative to vacuum.
#[rustfmt::skip]
pub(super) const NAMED_CONDUCTORS: &[(&str, [f32; 3], [f32; 3])] = &[
""")
        f.write("\n".join(rows) + "\n];\n")
    print(f"{len(rows)} materials -> {os.path.relpath(out, ROOT)}")


if __name__ == "__main__":
    main()
