"""The command line: ``python3 -m cracklip {run,check,reference}``.

    python3 -m cracklip run SCENE.toml --out DIR      solve, write results into DIR
    python3 -m cracklip grow SCENE.toml --out DIR     grow the cracks ([growth] table), write the path
                                                      (--beta-table: K / (S sqrt(pi a)) along it)
    python3 -m cracklip life SCENE.toml --out DIR     a fatigue life without a mesh ([life] table)
    python3 -m cracklip check SCENE.toml             validate, print what will be modelled
    python3 -m cracklip reference [--update PAGE]    the scene-file reference (Markdown)

``--set KEY=VALUE`` (repeatable) overrides a scene key, e.g. ``--set
mesh.h=0.1``. Progress with phase timings and active-set iterations goes to
stderr (``--quiet`` silences it). Exit status: 0 on success, 2 with one line
``cracklip: error: ...`` on bad input, a solver failure or a file that
cannot be read or written.
"""
from __future__ import annotations

import argparse
import json
import logging
import math
import pathlib
import sys
import time
import typing

from ..errors import CracklipError


PROG = "python3 -m cracklip"


class _Parser(argparse.ArgumentParser):
    """argparse with one-line errors and exit status 2."""

    def error(self, message: str) -> typing.NoReturn:
        self.exit(2, f"cracklip: error: {message} (see {PROG} --help)\n")

    def _print_message(self, message: str, file=None) -> None:
        # Under mpirun every process parses the same command line (before
        # MPI starts): its usage error or --help is printed by rank 0 only.
        from ..scene.processes import launched_on_several, launcher_rank
        if launched_on_several() and launcher_rank() != 0:
            return
        super()._print_message(message, file)


class _Progress(logging.Handler):
    """Log records of the cracklip loggers as 'cracklip [  1.23 s] message' on stderr."""

    def __init__(self, start: float):
        super().__init__(logging.INFO)
        self.start = start

    def emit(self, record: logging.LogRecord) -> None:
        if record.levelno >= logging.WARNING:
            return  # warnings are printed once, as "cracklip: warning: ..." (print_warnings)
        try:
            sys.stderr.write(f"cracklip [{time.perf_counter() - self.start:7.2f} s] {record.getMessage()}\n")
            sys.stderr.flush()
        except Exception:  # pragma: no cover - never let progress break a run
            self.handleError(record)


logger = logging.getLogger("cracklip.cli")


def print_warnings(warnings) -> None:
    """Each model or SIF warning as one 'cracklip: warning: ...' line on
    stderr (under mpirun by rank 0)."""
    comm = _processes()
    if comm is not None and comm.rank != 0:
        return
    for w in warnings:
        sys.stderr.write(f"cracklip: warning: {' '.join(str(w).split())}\n")
    sys.stderr.flush()


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog=PROG, description="cracklip: X-FEM cracks in planar parts (with crack-lip contact, "
                     "growth and fatigue life) and in solids (K along the crack fronts), from a TOML scene file.",
                     epilog="Scene keys: `python3 -m cracklip reference` or docs/scene_reference.md.")
    sub = parser.add_subparsers(dest="command", metavar="{run,grow,life,check,reference}", parser_class=_Parser)

    def common(p: argparse.ArgumentParser, meshes: bool = True) -> None:
        """The arguments of every command; meshes: the command meshes a
        part (--force; not `life`, which needs no mesh, so its --set example
        is a key of the [life] table)."""
        p.add_argument("scene", type=pathlib.Path, help="scene file (TOML)")
        example = "mesh.h=0.1" if meshes else "life.a_final=20"
        p.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE",
                       help=f"override a scene key, e.g. --set {example} (repeatable; VALUE in TOML "
                            "syntax, a bare word is a string; the keys: docs/scene_reference.md)")
        p.add_argument("--quiet", "-q", action="store_true",
                       help="no progress on stderr, no summary on stdout (warnings are still printed on stderr)")
        if meshes:
            p.add_argument("--force", action="store_true",
                           help="mesh a solid even when its run is estimated to need more memory than the "
                                "machine has available (refused otherwise, before meshing)")

    run = sub.add_parser("run", help="solve a scene and write its results into a folder",
                         description="Solve a scene and write results.json, the crack's tables (crack.csv and "
                                     "sif.csv; 3D: crack_opening.csv and front.csv), ParaView files and PNGs into "
                                     "--out.")
    common(run)
    run.add_argument("--out", type=pathlib.Path, required=True, metavar="DIR",
                     help="output folder (created if missing)")
    run.add_argument("--condition-number", action="store_true",
                     help="also estimate the 1-norm condition number (as outputs.condition_number = true)")
    run.add_argument("--accuracy", type=float, metavar="TARGET",
                     help="refine the mesh until the estimated error of every K is below TARGET times the K "
                          "scale, e.g. 0.01 (as options.accuracy): 2D, every element size halved within 20 element "
                          "sizes of each tip per level; 3D, every size divided by sqrt(2) per level")
    run.add_argument("--no-estimate", action="store_true",
                     help="skip the error estimate of K: one solve fewer (2D: the one with the element sizes "
                          "halved within 20 element sizes of each tip; 3D: every size times sqrt(2)) (as "
                          "outputs.error_estimate = false)")
    run.set_defaults(func=cmd_run)

    grow = sub.add_parser("grow", help="grow a scene's cracks (its [growth] table) and write the path",
                          description="Grow the cracks of a scene with a [growth] table through the fixed mesh: "
                                      "results.json and the ParaView series growth.pvd into --out, with (2D) "
                                      "path.csv, path.png, sif_history.png or (3D) front_path.csv, shape.csv, "
                                      "shape.png; with fatigue a_N.png, dadN.png/.csv (da/dN against Delta K), "
                                      "life_K.png/.csv (K of each step's largest cycle) and residual_strength.png; "
                                      "a progress line per step.")
    common(grow)
    grow.add_argument("--out", type=pathlib.Path, required=True, metavar="DIR",
                      help="output folder (created if missing)")
    grow.add_argument("--beta-table", action="store_true",
                      help="also write beta = K / (S sqrt(pi a)) of every load group along the grown path (and a "
                           "residual-stress K, and with contact beta per load level): beta.csv and beta_afgrow.txt "
                           "(S: growth.reference_stress, default 1)")
    grow.add_argument("--accuracy", type=float, metavar="TARGET",
                      help="at every step, refine around the crack tips until the estimated error of every K is "
                           "below TARGET times the K scale (as options.accuracy; several solves per step)")
    grow.set_defaults(func=cmd_grow)
    from .life import add_life_parser
    add_life_parser(sub, common)

    check = sub.add_parser("check", help="validate a scene and print what will be modelled",
                           description="Validate a scene, mesh it and build its model without "
                                       "solving: print which nodes get which enrichment, the dofs, "
                                       "the multipliers and the quadrature in each kind of cell.")
    common(check)
    check.add_argument("--json", action="store_true", help="print the model summary as JSON")
    check.add_argument("--nodes", action="store_true",
                       help="also list every enriched node with its enrichments")
    check.set_defaults(func=cmd_check)

    ref = sub.add_parser("reference", help="print the scene-file reference (Markdown table)",
                         description="Print every scene-file key with its type, default and meaning as a "
                                     "Markdown table (the page docs/scene_reference.md).")
    ref.add_argument("--update", metavar="PAGE", type=pathlib.Path,
                     help="replace the reference table in PAGE (a Markdown file, e.g. docs/scene_reference.md) "
                          "instead of printing it")
    ref.set_defaults(func=cmd_reference)
    return parser


def replicated(fn: typing.Callable[[], typing.Any]) -> typing.Any:
    """fn() (no collective call inside: e.g. reading the scene file, which
    every process does alike); under mpirun an error of any process is
    raised on all (scene.processes.replicated) instead of on one alone."""
    comm = _processes()
    if comm is None:
        return fn()
    from ..scene.processes import replicated as on_every_process
    return on_every_process(fn, comm)


def _load(args):
    """Read and validate the scene document (nothing built yet)."""
    return replicated(lambda: _read_and_check(args))


def _read_and_check(args):
    from ..io.scene_file import apply_override, parse_settings, read_document
    doc = read_document(args.scene)
    if "life" in doc and "mesh" not in doc and getattr(args, "command", None) in ("run", "grow"):
        from ..errors import InputError
        raise InputError(f"{args.scene} describes a life without a mesh ([life], no [mesh]): run "
                         f"`python3 -m cracklip life {args.scene}`; `{args.command}` solves a part (a [mesh])")
    for o in args.overrides:
        apply_override(doc, o)
    if getattr(args, "accuracy", None) is not None:
        apply_override(doc, f"options.accuracy={args.accuracy!r}")
    if getattr(args, "no_estimate", False):
        apply_override(doc, "outputs.error_estimate=false")
    if getattr(args, "condition_number", False):
        apply_override(doc, "outputs.condition_number=true")
    parse_settings(doc)
    return doc


def _build(args, doc):
    from ..io.scene_file import build_scene
    from ..scene.mesh_estimate import available_memory
    sf = build_scene(doc, base_dir=args.scene.parent, path=args.scene,
                     memory_limit=None if args.force else available_memory())
    msh = sf.scene.mesh.mesh
    logger.info("mesh: %d nodes, %d %s (%.2f s)", msh.topology.index_map(0).size_global,
                msh.topology.index_map(msh.topology.dim).size_global,
                "tetrahedra" if msh.topology.dim == 3 else "cells", sf.timings["mesh"])
    return sf


def cmd_run(args) -> int:
    from . import prefetch
    loading = prefetch.start()  # DOLFINx, PETSc and the solver load in a thread while the scene is read and meshed
    t_start = time.perf_counter()
    try:
        doc = _load(args)
        if doc.get("outputs", {}).get("png", True):
            loading.add("matplotlib.figure", "matplotlib.backends.backend_agg")  # (0.3 s)
    finally:
        loading.close()  # (also when the scene is rejected: no thread left waiting)
    comm = _processes()
    if comm is not None and doc.get("outputs", {}).get("condition_number", False):
        from ..scene.processes import not_parallel
        not_parallel("the condition number", comm)  # (before meshing, as every refusal the scene alone decides)
    from ..io.outputs import ensure_output_dir, write_outputs
    out = _on_rank0(lambda: ensure_output_dir(args.out))  # before meshing (under mpirun rank 0 writes)
    t0 = time.perf_counter()
    logger.info("scene %s: meshing", args.scene)
    sf = _build(args, doc)
    t_build = time.perf_counter() - t0
    from ..analysis.solve import solve
    cond = bool(sf.outputs["condition_number"])  # (--condition-number is the scene key, set in _read_and_check)
    logger.info("solving (%s enrichment, contact %s)", sf.scene.options.enrichment, sf.scene.options.contact)
    sol = solve(sf.scene, condition_number=cond)
    no_estimate = "outputs.error_estimate = false"  # why a K has no error estimate, as the summary says
    if sf.outputs["error_estimate"] and sf.scene.options.accuracy == 0.0:
        from ..analysis.accuracy import EstimateUnavailable, estimate_error
        try:
            estimate_error(sf.scene, sol, solve)
        except EstimateUnavailable as e:
            logger.info("%s", e)
            no_estimate = "not available for this mesh (see the log line above)"
    phases = ", ".join(f"{k} {v:.3f} s" for k, v in sol.timings.items())
    logger.info("solve phases: %s", phases)
    if sol.contact:
        c = sol.contact
        logger.info("contact: %d active-set iteration(s), active multipliers per iteration %s of %d",
                    c["iterations"], c["history"], c["system"].num_multipliers)
    t0 = time.perf_counter()
    rows = sol.stress_intensity_factors(None)  # computed once (with their warnings), written with the outputs
    t_sif = time.perf_counter() - t0
    logger.info("stress intensity factors: %d %s (%.2f s)", len(rows),
                "tip(s)" if sol.model.crack_type.END == "tip" else "front point(s)", t_sif)
    logger.info("writing outputs into %s", out)
    t0 = time.perf_counter()
    results = write_outputs(sf, sol, out, timings={"mesh": sf.timings["mesh"], "build_scene": t_build, "sif": t_sif})
    print_warnings(w["message"] for w in results["warnings"])
    logger.info("outputs written (%.2f s); total %.2f s", time.perf_counter() - t0,
                time.perf_counter() - t_start)
    comm = _processes()
    if args.quiet or (comm is not None and comm.rank != 0):  # (under mpirun rank 0 prints the summary)
        return 0
    units = sf.scene.units
    solid = sol.model.crack_type.END == "front"
    energy = ("" if units is None else f" {units.name('force')} {units.name('length')}"
              + ("" if solid else f" per {units.name('length')} of thickness"))
    print(f"{sf.title}: {results['solution']['dofs']} dofs, strain energy "
          f"{results['solution']['strain_energy']:.6g}{energy}")
    if solid:
        for line in front_summary(results["sifs"], results.get("error_estimate"), units):
            print(line)
        unit = "" if units is None else f" {units.name('length')}"
        area, volume = ("", "") if units is None else (f" {units.name('length')}^2", f" {units.name('length')}^3")
        for c in results["cracks"]:
            fr = c["front"]
            shape = ", ".join("a closed loop" if p["closed"] else
                              f"a line with {p['ends_on_boundary']} of 2 ends on the boundary" for p in fr["pieces"])
            overlap = (f", the lips overlapping by up to {c['interpenetration_max']:.4g}{unit} (see the warning)"
                       if any(w["code"] == "interpenetration" for w in results["warnings"]) else "")
            print(f"  {c['name']}: area {c['area_in_part']:.4g}{area} in the part, opening up to "
                  f"{c['gap_max']:.4g}{unit} (mean {c['gap_mean']:.4g}{unit}){overlap}, opened volume "
                  f"{c['opening_volume']:.4g}{volume}; front {fr['points']} points, length {fr['length']:.4g}{unit}: "
                  f"{shape}")
    else:
        for line in sif_summary(results["sifs"], results.get("error_estimate"), sf.scene.units, no_estimate):
            print(line)
        for c in results["cracks"]:
            line = f"  {c['name']}: closed {c['closed_fraction'] * 100:.0f} % of {c['length_in_part']:.4g}"
            if results["contact"] and "pressure" in c:
                line += f", pressure {c['pressure']['min']:.4g} .. {c['pressure']['max']:.4g}"
            print(line)
    print(f"results in {out}: {', '.join(results['files'])}")
    return 0


def front_summary(rows, estimate, units) -> list[str]:
    """K along each 3D front as printed: per crack and mode, the smallest and
    largest value over its front points and where (the point's index and
    position; the parametric angle on an elliptical front), the largest
    estimated error, and how many points are flagged (a free surface, a
    domain that reaches an obstacle)."""
    unit = "" if units is None else f" {units.name('K')}"
    out = estimate_lines(estimate)
    for c in sorted({r["crack"] for r in rows}):
        mine = [r for r in rows if r["crack"] == c]
        out.append(f"  {mine[0]['crack_name']}: K along its front at {len(mine)} points")
        fitted = [m for m in ("K_I", "K_II", "K_III")
                  if any(r.get(f"{m}_unsmoothed") is not None and r[m] != r[f"{m}_unsmoothed"] for r in mine)]
        if fitted:
            out.append(f"    {', '.join(fitted)} fitted along the front (options.sif_smoothing = \"fit\"; as computed: "
                       "results.json's K_I_unsmoothed ...)")

        def where(r) -> str:
            angle = ("" if r["parametric_angle"] is None else
                     f", parametric angle {math.degrees(r['parametric_angle']):.1f} deg")
            flags = "".join([", the end value at a free surface" if r["free_surface"] else "",
                             "" if r["domain_clear"] else ", NOT reliable"])
            name = (f"point {r['point']}" if r["point"] is not None else
                    f"s = {r['s']:.4g} (between front points)")
            return f"{name} ({', '.join(f'{v:.4g}' for v in r['position'])}{angle}{flags})"
        inner = [r for r in mine if not r["free_surface"]] or mine
        for mode in ("K_I", "K_II", "K_III"):
            lo = min(mine, key=lambda r: r[mode])
            hi = max(mine, key=lambda r: r[mode])
            line = f"    {mode}: min {lo[mode]:.6g}{unit} at {where(lo)}, max {hi[mode]:.6g}{unit} at {where(hi)}"
            if inner[0].get(f"{mode}_error") is not None:
                worst = max(inner, key=lambda r: (r[f"{mode}_error"], r["point"] is not None))
                line += f"; estimated error up to {worst[f'{mode}_error']:.2g}{unit} at {where(worst)}"
            out.append(line)
        free = sum(1 for r in mine if r["free_surface"])
        unclear = sum(1 for r in mine if not r["domain_clear"])
        if free or unclear:
            out.append(f"    flagged: {free} point(s) where the front meets a free surface (K is not the square-root "
                       f"singularity's there), {unclear} whose SIF domain reaches an obstacle (NOT reliable)")
    return out


def estimate_lines(estimate) -> list[str]:
    """What the run's error estimate is, as printed (none without one)."""
    if not estimate:
        return []
    floor = estimate.get("K_floor", 0.0)
    zero = estimate["K_scale"] <= floor
    largest = (f"every K below {floor:.3g}, 1e-3 of a K the loads could make (K is zero to that), the largest "
               f"error {estimate['largest_error']:.2g}" if zero else
               f"largest {100 * estimate['largest_relative_error']:.2g} % of the K scale")
    if estimate["target"] is None:
        return [f"  K +- its estimated discretisation error (from one more solve, {estimate['meshes']}; the error is "
                f"at most that if K converges at least like h): {largest}"]
    return [f"  accuracy target {100 * estimate['target']:.3g} %: refinement levels 0..{estimate['refinement_levels']} "
            f"({estimate['meshes']}; {estimate['dofs'][0]} -> {estimate['dofs'][-1]} dofs), "
            + ("reached" if estimate["reached"] else "NOT reached")
            + (f": {largest}" if zero else f", largest estimated error {100 * estimate['largest_relative_error']:.2g} %")]


def sif_summary(rows, estimate, units, no_estimate: str = "outputs.error_estimate = false") -> list[str]:
    """The run's K per tip as printed: K with its unit, the estimated
    discretisation error (what the "+-" is), the SIF domain spread named as
    such (it is not an error bar); `no_estimate` says why a K has none."""
    unit = "" if units is None else f" {units.name('K')}"
    out = estimate_lines(estimate)
    for r in rows:
        mix = "n/a (K negligible)" if r["mode_mix_deg"] is None else f"{r['mode_mix_deg']:.1f} deg"
        parts = []
        for mode in ("K_I", "K_II"):
            text = f"{mode} = {r[mode]:.6g}"
            if r.get(f"{mode}_error") is not None:
                text += f" +- {r[f'{mode}_error']:.2g}"
            if r.get(f"{mode}_extrapolated") is not None:
                text += f" (extrapolated {r[f'{mode}_extrapolated']:.6g})"
            parts.append(text)
        out.append(f"  {r['crack_name']} tip ({r['x']:.6g}, {r['y']:.6g}): {', '.join(parts)}{unit}, mode mix {mix}")
        if r.get("inner_radius") is not None:
            out.append(f"    SIF ring [{r['inner_radius']:.4g}, {r['radius']:.4g}] (options.sif_ring: one domain, "
                       "no spread)" + ("" if r["domain_clear"] else f"; it reaches {r['limited_by']}: NOT reliable"))
            continue
        out.append(f"    SIF domain spread (K over 3 domains; not an error bar): K_I {r['K_I_spread']:.2g}, "
                   f"K_II {r['K_II_spread']:.2g}" + ("" if r.get("K_I_error") is not None else
                                                     f"; no error estimate ({no_estimate})"))
    return out


def cmd_grow(args) -> int:
    from ..errors import InputError
    from ..analysis.growth import grow
    from ..io.growth_outputs import SeriesWriter, write_growth_outputs
    from ..io.outputs import ensure_output_dir
    t_start = time.perf_counter()
    doc = _load(args)

    def has_growth():
        if "growth" not in doc:
            raise InputError(f"{args.scene} has no [growth] table: give growth.da (fixed increments) or "
                             "growth.paris_C and growth.paris_m (fatigue) and growth.steps")
    replicated(has_growth)  # (every process finds it alike: one message under mpirun)
    out = _on_rank0(lambda: ensure_output_dir(args.out))  # (under mpirun rank 0 writes)
    sf = _build(args, doc)
    series = SeriesWriter(out) if sf.outputs["vtu"] else None
    comm = _processes()
    quiet = args.quiet or (comm is not None and comm.rank != 0)  # (under mpirun rank 0 prints)

    def progress(k, records, solution):
        if series is not None:
            series.add(k, solution)
        if not quiet:
            life = ""
            if sf.growth.life and records:
                r0 = records[0]
                name = sf.growth.spectrum.block_name if sf.growth.spectrum is not None else "cycle"
                life = f" | {r0.blocks:.6g} {name}s done ({r0.passes:.6g} passes), N = {r0.N:.6g} cycles"
            sys.stderr.write(f"cracklip grow: step {k}: " + "; ".join(
                f"{sf.scene.cracks[r.crack].name} end {r.end}: "
                + (f"a = {r.a:.5g} (length in the part {r.length:.5g})" if r.a is not None else
                   f"length in the part {r.length:.5g}") + f", K_I = {r.K_I:.5g}, "
                f"K_II = {r.K_II:.5g}, kink {r.kink_deg:+.2f} deg"
                + (f", N = {r.N:.5g}" if sf.growth.fatigue and not sf.growth.life else "")
                + ("" if r.status == "growing" else f" ({r.status})")
                for r in records) + life + "\n")
            sys.stderr.flush()
    if sf.scene.mesh.gdim == 3:
        return _grow_3d(args, sf, out, series, t_start, quiet)
    result = grow(sf.scene, sf.growth, on_step=progress, beta_table=args.beta_table)
    results = _on_rank0(lambda: write_growth_outputs(sf, result, out, sf.growth,
                                                     {"total": time.perf_counter() - t_start}, series))
    print_warnings(result.warnings)
    if not quiet:
        print(_growth_headline(sf.title, results["steps"], result.stop_reason))
        from ..analysis.life import PAST_STOP
        past = any(t["status"] in PAST_STOP for t in results["final"]["tips"])
        for c in results["final"]["cracks"]:
            a = c["length_in_part"]
            print(f"  {c['name']}: " + (f"length {a:.6g} in the part" if a is not None else
                                        f"through the part (polyline length {c['polyline_length']:.6g})")
                  + (" (the last geometry, past the stop inside its increment)" if past else ""))
        if sf.growth.fatigue:
            print(f"  cycles: {result.cycles:.6g}")
        _print_life_and_files(result.life, results, out)
    return 0


def _growth_headline(title: str, steps: int, reason: str) -> str:
    """The first line of grow's summary (2D and 3D)."""
    return f"{title}: {steps} growth step{'' if steps == 1 else 's'}; {reason}"


def _print_life_and_files(lf: dict | None, results: dict, out) -> None:
    """The last lines of grow's summary (2D and 3D): the life, where the files are."""
    from .life import life_counts
    if lf is not None:
        print(f"  life: {life_counts(lf)}; closure {lf['closure']}; {lf['level_solves']} level solves"
              + (f"; failure ({lf['failure']['criterion']}) at a = {lf['failure']['a']:.6g}" if lf["failure"] else ""))
    print(f"results in {out}: {', '.join(results['files'][:6])}" + (" ..." if len(results["files"]) > 6 else ""))


def _on_rank0(write: typing.Callable[[], typing.Any]) -> typing.Any:
    """write() (the output folder's check, the files of a growth run, from
    the results every process holds alike) by rank 0 under mpirun, its
    return value on all, its error raised on all."""
    comm = _processes()
    if comm is None:
        return write()
    from ..scene.processes import on_rank0
    return on_rank0(write, comm)


def _grow_3d(args, sf, out, series, t_start: float, quiet: bool) -> int:
    """cracklip grow on a solid part: per step a progress line per crack
    (front points, K_I range, the largest advance, a and c of surface and
    corner cracks, flights done), then the 3D outputs."""
    from ..analysis.front_growth import SurfaceGrowth
    from ..analysis.life import PAST_STOP
    from ..io.front_growth_outputs import write_front_growth_outputs
    run = SurfaceGrowth(sf.scene, sf.growth, False, None, args.beta_table)
    block = sf.growth.spectrum.block_name if sf.growth.spectrum is not None else "cycle"

    def progress(k, records, solution):
        if series is not None:
            series.add(k, solution)
        if quiet:
            return
        shape = run.shape[-1] if run.shape else {}
        parts = []
        for ci in sorted({r.crack for r in records}):
            rs = [r for r in records if r.crack == ci]
            sh = shape.get(ci, {})
            size = (f"a = {sh['a']:.5g}, c = {sh['c']:.5g} (a/c {sh['a_over_c']:.3f}, a/t {sh['a_over_t']:.3f})"
                    if sh.get("a") is not None else f"mean radius {sh.get('radius_mean', float('nan')):.5g}, "
                    f"roundness {100 * sh.get('roundness', 0.0):.2f} %")
            parts.append(f"{sf.scene.cracks[ci].name}: {len(rs)} front points, {size}, K_I {min(r.K_I for r in rs):.5g}"
                         f" .. {max(r.K_I for r in rs):.5g}")
        r0 = records[0] if records else None
        life = f" | {r0.blocks:.6g} {block}s done, N = {r0.N:.6g} cycles" if r0 is not None else ""
        sys.stderr.write(f"cracklip grow: step {k}: " + "; ".join(parts) + life + "\n")
        sys.stderr.flush()
    run.on_step = progress
    result = run.run()
    results = _on_rank0(lambda: write_front_growth_outputs(sf, result, out, run.growth,
                                                           {"total": time.perf_counter() - t_start}, series))
    print_warnings(result.warnings)
    if not quiet:
        print(_growth_headline(sf.title, results["steps"], result.stop_reason))
        past = bool(result.records and result.records[-1]
                    and result.records[-1][0].status in PAST_STOP)
        for c in results["final"]["cracks"]:
            sh = c["shape"] or {}
            print(f"  {c['name']}: {sh.get('kind', '')} crack"
                  + (f", a = {sh['a']:.6g}, c = {sh['c']:.6g}, a/c = {sh['a_over_c']:.4g}, a/t = {sh['a_over_t']:.4g}"
                     if sh.get("a") is not None else f", mean radius {sh.get('radius_mean', float('nan')):.6g}")
                  + (" (the last geometry, past the stop inside its increment)" if past else ""))
        _print_life_and_files(result.life, results, out)
    return 0


def cmd_check(args) -> int:
    from ..contact.frictionless import create_contact_system
    from ..model.model import create_model
    from ..io.life_file import is_life_scene
    from ..io.model_summary import describe_model, enriched_nodes, format_model
    from ..io.outputs import output_files
    from .life import check_life, read_doc
    if is_life_scene(replicated(lambda: read_doc(args))):  # a life without a mesh: nothing to mesh
        from ..scene.processes import on_rank0  # (under mpirun rank 0 checks it)
        return on_rank0(lambda: check_life(args, read_doc(args)))
    doc = _load(args)
    if "life" in doc:
        check_life(args, doc, quiet=True)  # its files too, before the mesh
    sf = _build(args, doc)
    scene = sf.scene
    comm = _processes()
    if comm is not None and args.nodes:
        from ..scene.processes import not_parallel
        not_parallel("`cracklip check --nodes` (the list of enriched nodes)", comm)
    model = create_model(scene)  # runs the model checks of a run (cracklip.model.checks)
    cs = create_contact_system(model) if scene.options.contact != "none" and model.cracks else None
    summary = describe_model(model, cs)
    nodes = enriched_nodes(model) if args.nodes else None
    print_warnings(model.warnings)
    if comm is not None and comm.rank != 0:  # (under mpirun rank 0 prints)
        return 0
    if args.json:
        doc = {"title": sf.title, "notes": sf.notes, "model": summary,
               "warnings": [w.as_dict() for w in model.warnings]}
        if nodes is not None:
            doc["enriched_nodes"] = nodes
        print(json.dumps(doc, indent=2))
        return 0
    if args.quiet and nodes is None:
        return 0
    mat = scene.material
    o = sf.outputs
    three_d = model.gdim == 3
    lines = []
    if not args.quiet:  # (--quiet with --nodes: the list asked for, without the summary)
        lines += [f"scene {args.scene} ({sf.title!r}): valid" + (f", {len(model.warnings)} warning(s) on stderr"
                                                                if model.warnings else ""),
                  f"material: E = {mat.E:g}, nu = {mat.nu:g} " + ("(3D elasticity)" if three_d
                                                                  else f"(plane {mat.plane})")]
        lines += sf.notes
        lines += format_model(summary)
        lines.append(f"run writes: {', '.join(output_files(model, o))}")
    if nodes is not None:
        names = [c.crack.name for c in model.cracks]
        lines.append(f"enriched nodes ({len(nodes)}):")
        lines += [f"  node {n['node']} ({n['x']:.6g}, {n['y']:.6g}" + (f", {n['z']:.6g}" if "z" in n else "") + "): "
                  + ", ".join(f"{what} ({names[c]})" for c, what in n["enrichment"]) for n in nodes]
    print("\n".join(lines))
    return 0


def rank0_only(cmd):
    """Mark a command that needs no mesh: under mpirun rank 0 runs it (its
    output and files once), the other processes wait for its status."""
    cmd.rank0_only = True
    return cmd


@rank0_only
def cmd_reference(args) -> int:
    from ..io.scene_file import reference_markdown
    table = reference_markdown()
    if args.update is None:
        sys.stdout.write(table)
        return 0
    from ..errors import InputError
    try:
        lines = args.update.read_text().splitlines(keepends=True)
    except OSError as e:
        raise InputError(f"reference --update: cannot read {args.update}: {e.strerror}") from None
    start = next((i for i, line in enumerate(lines) if line.startswith("| key | type | default | meaning |")), None)
    if start is None:
        raise InputError(f"reference --update: {args.update} has no reference table (a line starting "
                         "'| key | type | default | meaning |') to replace")
    end = start
    while end < len(lines) and lines[end].startswith("|"):
        end += 1
    args.update.write_text("".join(lines[:start]) + table + "".join(lines[end:]))
    print(f"{args.update}: reference table updated ({len(table.splitlines()) - 2} keys)")
    return 0


def _one_line(e: BaseException) -> str:
    if isinstance(e, OSError) and not isinstance(e, CracklipError) and e.strerror:
        text = f"{e.filename}: {e.strerror}" if e.filename else e.strerror
    else:
        text = str(e) or type(e).__name__
    return " ".join(text.split())


def _processes():
    """MPI.COMM_WORLD if this run has several processes (mpirun), else None."""
    mpi = sys.modules.get("mpi4py.MPI")
    if mpi is None or not mpi.Is_initialized() or mpi.Is_finalized() or mpi.COMM_WORLD.size == 1:
        return None
    return mpi.COMM_WORLD


def _report_error(e: BaseException) -> None:
    """'cracklip: error: ...' once. Under mpirun an error every process
    raised alike (scene.processes marks it collective) is printed by rank 0
    and every process exits 2; an error of one process alone would leave the
    others waiting in their next collective call, so it aborts the job."""
    comm = _processes()
    if comm is None:
        sys.stderr.write(f"cracklip: error: {_one_line(e)}\n")
        return
    from ..scene.processes import is_collective
    if is_collective(e):
        if comm.rank == 0:
            sys.stderr.write(f"cracklip: error: {_one_line(e)}\n")
        return
    sys.stderr.write(f"cracklip: error: (process {comm.rank} of {comm.size} alone; aborting the job) "
                     f"{_one_line(e)}\n")
    sys.stderr.flush()
    comm.Abort(2)


def finish_processes() -> None:
    """Under mpirun (also `mpirun -n 1`): MPI_Finalize, so that a process
    leaving by os._exit is a normal end for mpirun (no-op in a serial run
    without a launcher)."""
    import os
    from ..scene.processes import LAUNCHER_SIZE
    comm = _processes()
    if comm is not None:
        comm.Barrier()
    mpi = sys.modules.get("mpi4py.MPI")
    if (mpi is not None and mpi.Is_initialized() and not mpi.Is_finalized()
            and (comm is not None or any(name in os.environ for name in LAUNCHER_SIZE))):
        mpi.Finalize()


def main(argv: typing.Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status."""
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.command is None:
        parser.print_help(sys.stderr)
        return 2
    from ..scene.processes import launched_on_several, on_rank0
    if launched_on_several():
        from mpi4py import MPI  # noqa: F401 (MPI_Init now: errors and progress are then printed by rank 0 only)
    comm = _processes()
    root = logging.getLogger("cracklip")
    old_level, old_propagate = root.level, root.propagate
    # Progress on stderr unless --quiet (under mpirun from rank 0); warnings
    # are printed by the commands themselves (print_warnings), not again
    # through logging.
    quiet = getattr(args, "quiet", False) or (comm is not None and comm.rank != 0)
    handler = logging.NullHandler() if quiet else _Progress(time.perf_counter())
    root.addHandler(handler)
    root.setLevel(logging.INFO)
    root.propagate = False
    try:
        if comm is not None and getattr(args.func, "rank0_only", False):
            return on_rank0(lambda: args.func(args), comm)
        return args.func(args)
    except (CracklipError, OSError) as e:
        _report_error(e)
        return 2
    except KeyboardInterrupt:
        sys.stderr.write("cracklip: error: interrupted\n")
        return 130
    except Exception:
        comm = _processes()
        if comm is not None:  # a bug on one process: abort the job rather than leave the others waiting
            import traceback
            traceback.print_exc()
            sys.stderr.flush()
            comm.Abort(1)
        raise
    finally:
        root.removeHandler(handler)
        root.setLevel(old_level)
        root.propagate = old_propagate
