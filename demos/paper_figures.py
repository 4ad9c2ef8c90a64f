"""Main job: run cracklip's demos and write figures, results.json and results.md.

Today this runs what exists (issue 2, the X-FEM core): the through-crack patch
test and the core speed benchmark at 2e4 and 2e5 dofs. The paper's sections
5.1 and 5.2 join as their issues land.

    /usr/bin/python3 demos/paper_figures.py --out results
"""
from __future__ import annotations

import argparse
import json
import pathlib
import sys
import time

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent / "python"))

import bench_core  # noqa: E402
import patch_test  # noqa: E402


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", type=pathlib.Path, default=pathlib.Path("results"))
    ap.add_argument("--quick", action="store_true", help="small sizes only (smoke test)")
    args = ap.parse_args(argv)
    out = args.out
    out.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    summary: dict = {}

    print("[1/2] through-crack patch test", file=sys.stderr, flush=True)
    pt = patch_test.main(["--h", "0.2" if args.quick else "0.05", "--out", str(out / "patch_test")])
    summary["patch_test"] = {k: pt[k] for k in ("h", "ndofs", "enriched_dofs", "displacement_rel_error_top",
                                                 "displacement_rel_error_bottom", "opening_rel_error",
                                                 "strain_energy", "strain_energy_exact")}

    print("[2/2] core benchmark (X-FEM vs plain DOLFINx P1, MUMPS)", file=sys.stderr, flush=True)
    sizes = ["2e3"] if args.quick else ["2e4", "2e5"]
    bench_core.main(["--sizes", *sizes, "--repeats", "1" if args.quick else "3",
                     "--json", str(out / "bench_core.json"), "--quiet"])
    bench = json.loads((out / "bench_core.json").read_text())
    summary["bench_core"] = [{k: s[k] for k in ("ndofs", "t_xfem", "t_plain", "ratio")} for s in bench["sizes"]]
    summary["wall_time"] = time.perf_counter() - t0

    (out / "results.json").write_text(json.dumps(summary, indent=2))
    p = summary["patch_test"]
    lines = ["# cracklip results", "",
             "## X-FEM core: through-crack patch test (crack y = 0.013, unstructured mesh)", "",
             "| quantity | measured | required |", "|---|---|---|",
             f"| displacement error, top piece (rel.) | {p['displacement_rel_error_top']:.2e} | 1e-10 |",
             f"| displacement error, bottom piece (rel.) | {p['displacement_rel_error_bottom']:.2e} | 1e-10 |",
             f"| opening [[u]] error (rel.) | {p['opening_rel_error']:.2e} | 1e-10 |",
             f"| strain energy / exact | {p['strain_energy'] / p['strain_energy_exact']:.15f} | 1 |",
             "", f"h = {p['h']}, {p['ndofs']} dofs ({p['enriched_dofs']} enriched). Figures: "
             "`patch_test/patch_test_deformed.png`, `patch_test/patch_test_opening.png`.", "",
             "## Speed: whole X-FEM solve vs plain DOLFINx P1 solve (same mesh, same MUMPS)", "",
             "| dofs | X-FEM (s) | plain (s) | ratio |", "|---|---|---|---|"]
    lines += [f"| {s['ndofs']} | {s['t_xfem']:.3f} | {s['t_plain']:.3f} | {s['ratio']:.3f} |"
              for s in summary["bench_core"]]
    lines += ["", "Medians of 3 runs; `demos/bench_core.py` runs the 1e6-dof size too.", "",
              f"Total wall time of this job: {summary['wall_time']:.1f} s."]
    (out / "results.md").write_text("\n".join(lines) + "\n")
    print(f"wrote {out / 'results.md'} and {out / 'results.json'}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
