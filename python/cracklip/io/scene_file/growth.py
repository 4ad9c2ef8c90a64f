"""[growth], [material.fatigue] and [spectrum]: the keys of crack growth, of
the fatigue constants (and their da/dN table file) and of the load
spectrum, and what they build (``read_growth``, before the mesh:
cracklip.scene.growth.Growth with its FatigueMaterial and Spectrum and
their input files; ``check_growth``, on the built scene: its load groups;
``describe_growth``: its line in the notes)."""
from __future__ import annotations

import dataclasses
import pathlib

from ...errors import InputError
from ...scene.units import LENGTHS, STRESSES
from .schema import UNSET, Key, _number, _type_error, docstring_attributes, p_choice, p_factors, p_float, p_int, p_str


def _growth_keys() -> list[Key]:
    """The [growth] keys: every field of cracklip.scene.growth.Growth, with the
    meanings of its docstring (cycle_max / cycle_min are tables of load group
    = factor; the optional numbers have no default)."""
    from ...scene.growth import CRITERIA, Growth
    documented = docstring_attributes(Growth)
    keys = []
    for f in dataclasses.fields(Growth):
        meaning = documented.get(f.name, f.name.replace("_", " "))
        path = f"growth.{f.name}"
        if f.name == "criterion":
            keys.append(Key(path, "string", f.default, meaning, p_choice(*CRITERIA)))
        elif f.name in ("fatigue_material", "spectrum"):
            continue  # the [material.fatigue] and [spectrum] tables
        elif f.name in ("cycle_max", "cycle_min"):
            keys.append(Key(path, "table of group = factor", UNSET, meaning, p_factors))
        elif f.name == "reference_stress":
            keys.append(Key(path, "table of group = stress", UNSET, meaning, p_factors))
        elif f.name == "steps":
            keys.append(Key(path, "integer", f.default, meaning, p_int(1)))
        elif f.name == "corrections":
            keys.append(Key(path, "integer", f.default, meaning, p_int(0)))
        elif f.default is None:
            keys.append(Key(path, "float", UNSET, meaning, p_float()))
        else:
            keys.append(Key(path, "float", f.default, meaning, p_float()))
    return keys


def p_numbers_any(value, path):
    """A list of numbers (one load group) or of rows of numbers (several)."""
    if not isinstance(value, list) or not value:
        raise _type_error(path, "a list of factors, or of rows of factors (one per group)", value)
    if all(isinstance(v, list) for v in value):
        return [[_number(x, f"{path}[{i}][{j}]") for j, x in enumerate(v)] for i, v in enumerate(value)]
    return [_number(v, f"{path}[{i}]") for i, v in enumerate(value)]


def p_rows(value, path):
    """Rows of numbers (a tabular da/dN)."""
    if not isinstance(value, list) or not value or not all(isinstance(v, list) for v in value):
        raise _type_error(path, "rows of numbers [[da/dN, Delta K at R_1, ...], ...]", value)
    return [[_number(x, f"{path}[{i}][{j}]") for j, x in enumerate(v)] for i, v in enumerate(value)]


def p_list(value, path):
    if not isinstance(value, list) or not value:
        raise _type_error(path, "a list of numbers", value)
    return [_number(v, f"{path}[{i}]") for i, v in enumerate(value)]


def p_names(value, path):
    if not isinstance(value, list) or not value or not all(isinstance(v, str) and v for v in value):
        raise _type_error(path, "a list of load group names", value)
    return list(value)


def _fatigue_keys() -> list[Key]:
    """[material.fatigue]: the growth law, its constants and their units,
    toughness, closure, retardation (cracklip.scene.fatigue)."""
    from ...scene.fatigue import CLOSURES, CONSTRAINTS, EXAMPLES, LAWS, RETARDATIONS
    t = "material.fatigue"
    const = [
        ("C", "rate coefficient (paris, walker, forman, nasgro)"), ("m", "exponent (paris, walker)"),
        ("n", "exponent (forman, nasgro)"), ("gamma", "Walker's exponent of (1 - R), 0..1 (walker)"),
        ("K_f", "Forman's critical K (forman)"), ("p", "threshold exponent (nasgro)"),
        ("q", "toughness exponent (nasgro)"), ("dK1", "long-crack threshold at R = 0 (nasgro)"),
        ("C_th_plus", "threshold R exponent for R >= 0 (nasgro)"),
        ("C_th_minus", "threshold R exponent for R < 0 (nasgro)"),
        ("alpha", "Newman's constraint factor 1..3 (nasgro; closure newman); default 2"),
        ("smax_over_flow", "S_max / sigma_0 of Newman's f (nasgro; closure newman); default 0.3"),
        ("a0", "intrinsic crack length of the threshold's small-crack term (nasgro); default 0: none"),
        ("D", "rate coefficient (hartman_schijve)"), ("dK_thr", "threshold (hartman_schijve)"),
        ("A", "apparent cyclic toughness (hartman_schijve)"), ("exponent", "exponent (hartman_schijve)"),
    ]
    keys = [
        Key(f"{t}.law", "string", UNSET, "growth law of the fatigue life: " + ", ".join(f"`{x}`" for x in LAWS)
            + " (docs/life.md); with [spectrum] or growth.cycle_min / R instead of growth.paris_C", p_choice(*LAWS)),
        Key(f"{t}.example", "string", UNSET, "start from a documented constant set (keys given here override): "
            + ", ".join(f"`{x}`" for x in EXAMPLES), p_choice(*EXAMPLES)),
    ] + [Key(f"{t}.{name}", "float", UNSET, meaning, p_float()) for name, meaning in const] + [
        Key(f"{t}.table_R", "[R, ...]", UNSET, "tabular law: the R of each da/dN curve (ascending)", p_list),
        Key(f"{t}.table", "[[da/dN, dK_R1, ...], ...]", UNSET, "tabular law: rows of a rate and the Delta K giving "
            "it at each R (easigrow's layout)", p_rows),
        Key(f"{t}.threshold", "float", 0.0, "Delta K below which a cycle does not grow (any law)", p_float(0.0)),
        Key(f"{t}.K_Ic", "float", UNSET, "plane-strain toughness: failure at K_max >= K_c (K_c(t) with B_k)",
            p_float(positive=True)),
        Key(f"{t}.A_k", "float", UNSET, "K_c(t) = K_Ic [1 + B_k exp(-(A_k t / t0)^2)], t0 = 2.5 (K_Ic / "
            "yield_stress)^2; default 1", p_float(0.0)),
        Key(f"{t}.B_k", "float", UNSET, "see A_k; unset: K_c = K_Ic", p_float(0.0)),
        Key(f"{t}.thickness", "float", UNSET, "thickness t of K_c(t) and of the plastic zone's constraint",
            p_float(positive=True)),
        Key(f"{t}.yield_stress", "float", UNSET, "yield stress: net-section yield (failure) and the plastic "
            "zone of retardation", p_float(positive=True)),
        Key(f"{t}.closure", "string", "contact", "`contact` (K from crack-lip contact at every load state; "
            "elastic, no plastic wake), `newman` (Newman's f on the linear K) or `none`; never both",
            p_choice(*CLOSURES)),
        Key(f"{t}.retardation", "string", "none", "load interaction: `none`, `wheeler` or `willenborg` "
            "(generalized)", p_choice(*RETARDATIONS)),
        Key(f"{t}.wheeler_exponent", "float", UNSET, "Wheeler's gamma", p_float(positive=True)),
        Key(f"{t}.shutoff_ratio", "float", UNSET, "Willenborg's shut-off overload ratio (> 1)", p_float(positive=True)),
        Key(f"{t}.constraint", "string", "auto", "plastic zone (K / yield_stress)^2 / (beta pi): `plane_stress` "
            "(beta 2), `plane_strain` (6) or `auto` (by thickness)", p_choice(*CONSTRAINTS)),
        Key(f"{t}.units.length", "string", UNSET, "length unit of the constants (da per cycle, a0, "
            "thickness); with units.stress they are converted into the scene's [units]", p_choice(*LENGTHS)),
        Key(f"{t}.units.stress", "string", UNSET, "stress unit of the constants (K in stress sqrt(length))",
            p_choice(*STRESSES)),
    ]
    return keys


def _spectrum_keys() -> list[Key]:
    from ...scene.spectrum import COUNTING, RESIDUE
    return [
        Key("spectrum.groups", "[group, ...]", ["default"], "the load groups whose factors the spectrum's "
            "points give (columns); other groups stay at their steady factor", p_names),
        Key("spectrum.counting", "string", "rainflow", "cycle counting: " + ", ".join(f"`{c}`" for c in COUNTING),
            p_choice(*COUNTING)),
        Key("spectrum.residue", "string", "close", "`close` (the pass repeats: full cycles only, E1049's "
            "repeated history) or `half` (each pass counted alone, residue as half cycles)", p_choice(*RESIDUE)),
        Key("spectrum.steady", "table of group = factor", UNSET, "factors of the groups not in the spectrum "
            "(unset ones: 1, e.g. a residual stress)", p_factors),
        Key("spectrum.block_name", "string", "flight", "what a block is called in outputs", p_str),
        Key("spectrum.contact_levels", "integer", 2, "contact solves per growth step at the load states "
            "where the lips touch (K interpolated between them and the closure level)", p_int(1)),
        Key("spectrum.max_passes", "float", 1e9, "stop after this many passes (the life ends where the passes "
            "reach it; grow: inside the step that reaches it, the sizes there in the stop's message)",
            p_float(positive=True)),
        Key("spectrum.blocks[].points", "[factor, ...] or [[factors], ...]", UNSET, "turning points of the "
            "block: one factor per point (one group) or one row per point (one factor per group); one of "
            "points, file", p_numbers_any),
        Key("spectrum.blocks[].file", "string", UNSET, "a file of turning points, relative to the scene file: one "
            "value per line, or a header naming the group of each column, or a block-load table (header max, min, "
            "cycles); docs/life.md", p_str),
        Key("spectrum.blocks[].repeat", "integer", 1, "times the block comes in a pass", p_int(1)),
        Key("spectrum.blocks[].name", "string", "", "label of the block (e.g. a flight type)", p_str),
    ]


def _fatigue_file_keys() -> list[Key]:
    """The input-file keys of [material.fatigue]: a da/dN table file and its
    layout (cracklip.scene.input_files; listed in the reference after the
    [life] keys)."""
    from ...scene.input_files import RATE_LAYOUTS, UNSUPPORTED_RATE_LAYOUTS
    return [
        Key("material.fatigue.table_file", "string", UNSET, "tabular law: a da/dN table file instead of table_R / "
            "table, relative to the scene file (layouts: table_layout)", p_str),
        Key("material.fatigue.table_layout", "string", "auto", "layout of table_file: " + ", ".join(
            f"`{x}`" for x in RATE_LAYOUTS) + f" (not supported, undocumented publicly: "
            f"{', '.join(UNSUPPORTED_RATE_LAYOUTS)}; docs/life.md)", p_str),
    ]


def _fatigue_material(f: dict):
    """The FatigueMaterial of the [material.fatigue] settings."""
    from ...scene.fatigue import FatigueMaterial, from_example
    f = dict(f)
    units = f.pop("units", None)
    if units is not None:
        if set(units) != {"length", "stress"}:
            raise InputError("material.fatigue.units needs both length and stress (e.g. length = \"in\", "
                             "stress = \"ksi\")")
        units = (units["length"], units["stress"])
    example = f.pop("example", None)
    fields = {fl.name for fl in dataclasses.fields(FatigueMaterial)}
    top = {k: v for k, v in f.items() if k in fields}
    constants = {k: v for k, v in f.items() if k not in fields}
    if units is not None:
        top["units"] = units
    if example is not None:
        return from_example(example, constants=constants, **top)
    if "law" not in top:
        raise InputError("material.fatigue needs law (paris, walker, forman, nasgro, hartman_schijve, tabular) or "
                         "example (a documented constant set)")
    return FatigueMaterial(constants=constants, **top)


def _spectrum(sp: dict, base_dir: pathlib.Path):
    """The Spectrum of the [spectrum] settings (blocks inline or from CSV files)."""
    from ...scene.spectrum import Spectrum, SpectrumBlock, read_spectrum_csv
    groups = list(sp["groups"])
    blocks = []
    for i, b in enumerate(sp["blocks"]):
        where = f"spectrum.blocks[{i}]"
        if "file" in b:
            f = pathlib.Path(b["file"])
            cols, pts = read_spectrum_csv(f if f.is_absolute() else base_dir / f, f"{where}.file", groups)
            missing = [g for g in groups if g not in cols]
            if missing:
                raise InputError(f"{where}.file {b['file']}: no column for load group(s) {missing} of spectrum.groups "
                                 f"(its columns: {cols})")
            pts = pts[:, [cols.index(g) for g in groups]]
        else:
            pts = b["points"]
        blocks.append(SpectrumBlock(pts, b["repeat"], b["name"], f"file {b['file']}" if "file" in b else ""))
    return Spectrum(blocks, tuple(groups), sp["counting"], sp["residue"], dict(sp.get("steady", {})),
                    sp["block_name"], sp["contact_levels"], sp["max_passes"])


def describe_growth(g, dim: int = 2) -> str:
    """One line of the growth settings (check and the progress); dim 3: a
    front's wording and stops."""
    if dim == 3:
        return _describe_front_growth(g)
    if g.life:
        load = _describe_load(g)
        how = f"fatigue life: {g.fatigue_material.describe()}; {load}; fastest tip da = " + \
            (f"{g.da:g}" if g.da else "3 tip elements")
    elif g.fatigue:
        cycle = (f"cycle max {g.cycle_max or 'every group at 1'}, min "
                 f"{g.cycle_min if g.cycle_min is not None else f'R = {g.R:g} x max'}")
        how = (f"fatigue: Paris C = {g.paris_C:g}, m = {g.paris_m:g}"
               + (f", Walker gamma = {g.walker_gamma:g}" if g.walker_gamma != 1.0 else "")
               + (f", threshold {g.threshold:g}" if g.threshold else "") + f"; {cycle}; fastest tip da = "
               + (f"{g.da:g}" if g.da else "3 tip elements"))
    else:
        how = "fixed increments da = " + (f"{g.da:g}" if g.da else "3 tip elements") + \
            (f", K_eq threshold {g.threshold:g}" if g.threshold else "")
    stops = [f"{g.steps} steps"] + ([f"K_Ic = {g.K_Ic:g}"] if g.K_Ic is not None else []) + \
        ([f"length {g.max_length:g}"] if g.max_length is not None else []) + [f"kink change > {g.max_kink_change:g} deg"]
    return f"{g.criterion.replace('_', ' ')} criterion, {how}; stops: {', '.join(stops)}"


def _describe_load(g) -> str:
    """The cycles of a fatigue life, in words (2D and 3D)."""
    sp = g.spectrum
    if sp is not None:
        return (f"spectrum of {sp.blocks_per_pass} {sp.block_name}(s) per pass, groups {list(sp.groups)}, "
                f"{sp.counting} counting, residue {sp.residue}")
    return (f"cycle max {g.cycle_max or 'every group at 1'}, min "
            f"{g.cycle_min if g.cycle_min is not None else f'R = {g.R:g} x max'}")


def _describe_front_growth(g) -> str:
    if g.life:
        load = _describe_load(g)
        law = f"fatigue life: {g.fatigue_material.describe()}; {load}"
    else:
        law = (f"fatigue: Paris C = {g.paris_C:g}, m = {g.paris_m:g}"
               + (f", Walker gamma = {g.walker_gamma:g}" if g.walker_gamma != 1.0 else "")
               + (f", threshold {g.threshold:g}" if g.threshold else "") + f"; cycle max "
               f"{g.cycle_max or 'every group at 1'}, min {g.cycle_min if g.cycle_min is not None else f'R = {g.R:g} x max'}")
    step = (f"{g.da_fraction:g} of the fastest point's crack size" if g.da_fraction else
            f"{g.da:g}" if g.da else "2 front elements")
    stops = [f"{g.steps} steps"] + ([f"K_Ic = {g.K_Ic:g}"] if g.K_Ic is not None else []) + \
        ([f"size {g.max_length:g}"] if g.max_length is not None else []) + \
        ["breakthrough"] + (["K_c, net-section yield"] if g.life else [])
    return (f"3D fronts, maximum hoop stress with K_III (SITT_MAX_DEVER), {law}; largest advance per step {step}; "
            f"stops: {', '.join(stops)}")


def read_growth(s: dict, life: bool, units, base_dir: pathlib.Path):
    """The Growth of the [growth] settings with its [material.fatigue] and
    [spectrum] and their files (None without [growth]), read before the
    mesh so a bad input file stops the run before any meshing. life: the
    document has a [life] table (`cracklip life` reads the fatigue inputs)."""
    if "growth" not in s:
        if not life and ("spectrum" in s or "fatigue" in s["material"]):
            raise InputError(f"[{'spectrum' if 'spectrum' in s else 'material.fatigue'}] is read by `cracklip grow` "
                             "(add a [growth] table: growth.da, growth.steps) or `cracklip life` (a [life] table)")
        return None
    from ...scene.growth import Growth
    from ...scene.input_files import resolve_rate_table
    fatigue = (_fatigue_material(resolve_rate_table(s["material"]["fatigue"], base_dir))
               if "fatigue" in s["material"] else None)
    spectrum = _spectrum(s["spectrum"], base_dir) if "spectrum" in s else None
    if fatigue is not None:
        fatigue.converted(units)  # units given without the scene's [units]: an error now, not at the solve
    try:
        return Growth(**s["growth"], fatigue_material=fatigue, spectrum=spectrum)
    except InputError as e:
        raise InputError(f"growth: {e}") from None


def check_growth(growth, scene, notes: list[str]) -> None:
    """Check a Growth (read_growth) against the built scene: no load path,
    every load group it names belongs to a load; its line goes into the
    notes."""
    if growth is None:
        return
    if scene.load_path is not None:
        raise InputError("a scene with [growth] solves its loads (or its load cycle) at every step: give "
                         "growth.cycle_max / cycle_min instead of [[load_path]]")
    from ...scene.scene import load_groups
    groups = load_groups(scene) | {"default"}
    for name in ("cycle_max", "cycle_min"):
        unknown = sorted(set(getattr(growth, name) or {}) - groups)
        if unknown:
            raise InputError(f"growth.{name} names load group(s) {unknown} that no load belongs to; the "
                             f"scene's groups: {sorted(groups)}")
    checks = [("growth.reference_stress", set(growth.reference_stress or {}))]
    if growth.spectrum is not None:
        checks += [("spectrum.groups", set(growth.spectrum.groups)), ("spectrum.steady", set(growth.spectrum.steady))]
    for name, named in checks:
        unknown = sorted(named - groups)
        if unknown:
            raise InputError(f"{name} names load group(s) {unknown} that no load belongs to; the scene's "
                             f"groups: {sorted(groups)}")
    notes.append("growth: " + describe_growth(growth, scene.mesh.gdim))
