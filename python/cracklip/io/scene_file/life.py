"""[life]: the keys of a fatigue life without a mesh (`cracklip life`): the
crack's geometry factor (a handbook solution or a beta table file), its
sizes, the reference stresses, the integration and the a-N table's rows.
What they build is cracklip.scene.life (``life_settings``), read with the
fatigue inputs by cracklip.io.life_file; docs/life.md explains them."""
from __future__ import annotations

from .schema import REQUIRED, UNSET, Key, p_choice, p_factors, p_float, p_int, p_numbers, p_str


def _life_keys() -> list[Key]:
    from ...scene.life import CENTRE_FORMS, GEOMETRIES, INTEGRATIONS
    t = "life"
    return [
        Key(f"{t}.geometry", "string", REQUIRED, "the crack's geometry factor for `cracklip life` (a life without a "
            "mesh): " + ", ".join(f"`{g}`" for g in GEOMETRIES) + " (docs/life.md)", p_choice(*GEOMETRIES)),
        Key(f"{t}.a0", "float", REQUIRED, "initial crack size a (half length of a centre crack; length from the edge "
            "or the hole's edge; depth of a surface or corner crack)", p_float(positive=True)),
        Key(f"{t}.c0", "float", UNSET, "initial second size c of a surface crack (half length) or corner crack "
            "(length), or of a two-size beta table", p_float(positive=True)),
        Key(f"{t}.a_final", "float", UNSET, "stop when a reaches this (unset: at failure or the end of the table "
            "or handbook range)", p_float(positive=True)),
        Key(f"{t}.detectable_size", "float", UNSET, "crack size a an inspection finds: the inspection interval is "
            "half the life from it to failure (the threshold half the life from a0)", p_float(positive=True)),
        Key(f"{t}.width", "float", UNSET, "plate width W (centre and edge crack; surface crack 2b, corner crack b; "
            "hole crack: net-section yield only)", p_float(positive=True)),
        Key(f"{t}.thickness", "float", UNSET, "plate thickness t (surface and corner cracks)", p_float(positive=True)),
        Key(f"{t}.hole_radius", "float", UNSET, "radius R of the hole (hole_crack)", p_float(positive=True)),
        Key(f"{t}.cracks", "integer", 1, "cracks at the hole: 1 or 2 symmetric ones (hole_crack)", p_int(1)),
        Key(f"{t}.form", "string", "feddersen", "centre crack: `feddersen` (sqrt(sec(pi a / W))) or `tada` "
            "(0.1 %)", p_choice(*CENTRE_FORMS)),
        Key(f"{t}.table", "string", UNSET, "beta_table: a file of K or beta against crack size (a, beta[_group] / "
            "K[_group]; a, c, beta_a, beta_c; a beta; or the beta.csv of `cracklip grow --beta-table`), relative "
            "to the scene file", p_str),
        Key(f"{t}.table_scale", "float", 1.0, "factor on the table's crack sizes (an a/d table: d)",
            p_float(positive=True)),
        Key(f"{t}.tip", "[crack, end]", UNSET, "the tip of a beta.csv or beta_afgrow.txt `cracklip grow` wrote for "
            "several tips",
            p_numbers(2, "a tip [crack, end]")),
        Key(f"{t}.reference_stress", "table of group = stress", UNSET, "remote stress S of factor 1 of each load "
            "group: K = factor x S x beta x sqrt(pi a) (handbook solutions and beta columns; default 1; a group the "
            "life has no load for, or a table of K columns, is an error; a beta table `cracklip grow` wrote says "
            "its S on a '# reference_stress' line: the same S is required)", p_factors),
        Key(f"{t}.integration", "string", "auto", "`cycles` (cycle by cycle, sequence effects), `blocks` (growth "
            "per pass summed) or `auto` (cycles with retardation, else blocks)", p_choice(*INTEGRATIONS)),
        Key(f"{t}.points", "integer", 200, "rows of the a-N table", p_int(2)),
    ]


KEYS: list[Key] = _life_keys()
