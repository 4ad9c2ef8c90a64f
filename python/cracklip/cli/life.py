"""`cracklip life SCENE --out DIR`: a fatigue life without a mesh (the
[life] table; docs/life.md), and `cracklip check` on such a scene.

    python3 -m cracklip life SCENE.toml --out DIR    the life: results.json, a_N.csv/png, beta.csv/png

Progress (a line a second on a long cycle-by-cycle life) goes to stderr,
the summary to stdout.
"""
from __future__ import annotations

import json
import logging
import pathlib
import sys
import time

logger = logging.getLogger("cracklip.cli")


def add_life_parser(sub, common) -> None:
    life = sub.add_parser("life", help="the fatigue life of a crack from a beta table or a handbook solution "
                                       "(the [life] table), without a mesh",
                          description="Integrate the fatigue life of the [life] table's crack (K from a beta "
                                      "table file or a handbook solution) under [spectrum] with "
                                      "[material.fatigue]'s law, closure and retardation: results.json, a_N.csv, "
                                      "a_N.png, beta.csv, beta.png into --out.")
    common(life, meshes=False)
    life.add_argument("--out", type=pathlib.Path, required=True, metavar="DIR",
                      help="output folder (created if missing)")
    life.add_argument("--no-png", action="store_true", help="write no pictures (the CSVs and results.json only)")
    life.set_defaults(func=cmd_life)


def read_doc(args) -> dict:
    from ..io.scene_file import apply_override, read_document
    doc = read_document(args.scene)
    for o in args.overrides:
        apply_override(doc, o)
    return doc


def cmd_life(args) -> int:
    from ..analysis.table_life import life_of
    from ..io.life_file import build_life
    from ..io.life_outputs import write_life_outputs
    from ..io.outputs import ensure_output_dir
    t_start = time.perf_counter()
    lf = build_life(read_doc(args), args.scene.parent, args.scene)
    out = ensure_output_dir(args.out)
    setup, result, s = life_of(lf, progress=lambda text: logger.info("life: %s", text))
    results = write_life_outputs(lf, setup, result, s, out, {"total": time.perf_counter() - t_start},
                                 png=not args.no_png)
    from . import print_warnings
    print_warnings(result.warnings)
    if not args.quiet:
        for line in life_summary(lf.title, s):
            print(line)
        print(f"results in {out}: {', '.join(results['files'])}")
    return 0


cmd_life.rank0_only = True  # needs no mesh: under mpirun rank 0 runs it, its files written once (cli.main)


def life_counts(life: dict) -> str:
    """A life as printed: "N cycles = B <block>s", and "= P passes" where a
    pass of the spectrum is not one block."""
    text = f"{life['cycles']:.6g} cycles = {life['blocks']:.6g} {life['block_name']}s"
    if abs(life["passes"] - life["blocks"]) > 1e-9 * max(1.0, abs(life["blocks"])):
        text += f" = {life['passes']:.6g} passes"
    return text


#: How the life was integrated (life results' "integration"), as printed.
INTEGRATION = {"cycles": "integrated cycle by cycle", "blocks": "integrated block by block"}


def life_summary(title: str, s: dict) -> list[str]:
    """The printed summary of a life (cmd_life)."""
    block = s["block_name"]
    lines = [f"{title}: life {life_counts(s)} ({INTEGRATION.get(s['integration'], s['integration'])}); "
             f"{s['stop_reason']}"]
    crit = s["critical"]
    if crit is not None and crit.get("at_initial_size"):
        lines.append(f"  critical crack size: a0 = {crit['a']:.6g} or below ({crit['criterion']})")
    elif crit is not None:
        lines.append(f"  critical crack size: a = {crit['a']:.6g}" + (f", c = {crit['c']:.6g}" if "c" in crit else "")
                     + f" ({crit['criterion']})")
    else:
        lines.append(f"  critical crack size: not reached within the life (it ended by {s['stop']})")
    ins = s["inspection"]
    if ins is not None:
        text = f"  inspections: threshold {ins['threshold_cycles']:.6g} cycles ({ins['threshold_blocks']:.6g} {block}s)"
        if ins.get("interval_cycles") is not None:
            text += (f", interval {ins['interval_cycles']:.6g} cycles ({ins['interval_blocks']:.6g} {block}s) from "
                     f"the detectable size {ins['detectable_size']:g}")
        lines.append(text + (f"; {ins['note']}" if ins.get("note") else ""))
    lines.append(f"  K: {s['K_source']}; {s['law']}; closure {s['closure']}; retardation {s['retardation']}")
    return lines


def check_life(args, doc: dict, quiet: bool = False) -> int:
    """Check a life scene's tables and files without meshing; print what
    the life will be."""
    from ..analysis.table_life import create_table_life, critical_size, tabulation_error
    from ..io.life_file import build_life
    lf = build_life(doc, args.scene.parent, args.scene)
    setup = create_table_life(lf.life, lf.material, lf.spectrum, lf.units, lf.table)
    if quiet or args.quiet:
        return 0
    info = setup.table_info
    a_crit, criterion = critical_size(setup) if setup.table.sizes == 1 else (None, None)
    err = tabulation_error(info, a_crit if a_crit is not None else setup.table.a[-1])
    if getattr(args, "json", False):
        print(json.dumps({"title": lf.title, "notes": lf.notes, "life": {
            "K_source": setup.source, "K_table_points": info["points"], "tabulation_error": err,
            "critical": None if a_crit is None else {"a": a_crit, "criterion": criterion},
            "cycles_per_pass": setup.cycles_per_pass, "blocks_per_pass": setup.blocks_per_pass,
            "load_states": int(len(setup.load.states)), "load_cases": list(setup.load.cases),
            "integration": setup.method, "law": setup.law.law.describe(), "closure": setup.law.closure,
            "K_crit": setup.K_crit}}, indent=2))
        return 0
    lines = [f"scene {args.scene} ({lf.title!r}): valid (a life without a mesh: `cracklip life`)"] + lf.notes + [
        f"K: {setup.source}; table of {info['points']} sizes"
        + (f", tabulation error {err:.1e} up to a = {a_crit if a_crit is not None else setup.table.a[-1]:.6g}"
           if err is not None else ""),
        "critical crack size: " + (f"a = {a_crit:.6g} ({criterion})" if a_crit is not None else
                                   "not within the table (two sizes: found along the path)"),
        f"cycles: {setup.cycles_per_pass:.6g} per pass ({setup.blocks_per_pass} {setup.spectrum.block_name}s), "
        f"{len(setup.load.states)} load states, load cases {list(setup.load.cases)}; integration {setup.method}",
        f"law: {setup.law.law.describe()}; closure {setup.law.closure}; K_c = "
        + (f"{setup.K_crit:.6g}" if setup.K_crit is not None else "none"),
        "life writes: results.json, a_N.csv, beta.csv, a_N.png, beta.png"]
    print("\n".join(lines))
    sys.stdout.flush()
    return 0


__all__ = ["add_life_parser", "cmd_life", "life_summary", "check_life", "read_doc"]
