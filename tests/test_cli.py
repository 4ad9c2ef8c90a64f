"""The command line: check reports what the solver uses, exit codes and
one-line errors, progress on stderr, atomic outputs, and the README's quick
start run as written."""
import json
import os
import pathlib
import re
import shlex
import shutil
import subprocess
import sys

import cracklip as cl
import numpy as np
import pytest
from cracklip import cli
from cracklip.io.scene_file import load_scene_file, reference_markdown

ROOT = pathlib.Path(__file__).resolve().parents[1]
BLOCK = ROOT / "demos" / "scenes" / "block_uniform_pressure.toml"
ENV = {"PYTHONPATH": str(ROOT / "python"), "PATH": "/usr/bin:/bin", "MPLBACKEND": "Agg"}


# Under CRACKLIP_TEST_GMSH_SEED (tests/conftest.py) the CLI meshes with the test process's gmsh
# seed, so what `check` reports and what the test solves come from one mesh.
SEEDED_CLI = """import runpy, gmsh
generate = gmsh.model.mesh.generate
def seeded(*args, **kwargs):
    gmsh.option.setNumber("Mesh.RandomSeed", {seed})
    return generate(*args, **kwargs)
gmsh.model.mesh.generate = seeded
runpy.run_module("cracklip", run_name="__main__", alter_sys=True)"""


def run_cli(*args):
    """python3 -m cracklip as a user runs it: (exit status, stdout, stderr)."""
    seed = os.environ.get("CRACKLIP_TEST_GMSH_SEED")
    python = ["-m", "cracklip"] if not seed else ["-c", SEEDED_CLI.format(seed=int(seed))]
    p = subprocess.run([sys.executable, *python, *args], cwd=ROOT, env=ENV, capture_output=True,
                       text=True, timeout=300)
    return p.returncode, p.stdout, p.stderr


def numbers(pattern, text):
    m = re.search(pattern, text, re.MULTILINE)
    assert m, f"{pattern!r} not in:\n{text}"
    return [int(g) for g in m.groups()]


def test_check_reports_the_counts_the_solver_uses(tmp_path):
    """Acceptance 3: `check` on the paper's block scene prints the enrichment
    and multiplier counts; the solve of the same scene uses exactly these."""
    status, out, err = run_cli("check", str(BLOCK), "--set", "mesh.h=0.1")
    assert status == 0, err
    total, std, enr, enr_nodes, pseudo, enr_cells = numbers(
        r"^dofs: (\d+) = (\d+) standard \+ (\d+) enriched \((\d+) enriched nodes, (\d+) enriched "
        r"pseudo-nodes on (\d+) cells\)", out)
    heav_nodes, heav_dofs = numbers(r"^  Heaviside: (\d+) nodes, (\d+) dofs", out)
    tip_nodes, core, blending, tip_dofs = numbers(
        r"^  tip: (\d+) nodes \((\d+) core, (\d+) blending\), (\d+) dofs", out)
    mult, full, p0 = numbers(r"^contact: bilateral, stable space: (\d+) multipliers \((\d+) full, (\d+) P0", out)
    assert mult > 0 and tip_nodes > 0 and heav_nodes > 0

    sol = cl.solve(load_scene_file(BLOCK, overrides=["mesh.h=0.1"]).scene)
    m, layout, cs = sol.model, sol.model.layout, sol.contact["system"]
    kind, node = np.asarray(layout.kind), np.asarray(layout.node)
    assert (total, std, enr) == (m.num_dofs, 2 * layout.num_std_nodes, 2 * layout.num_enriched)
    assert len(sol.u) == total
    assert (enr_nodes, pseudo) == (np.unique(node).size, layout.num_enriched)
    assert enr_cells == np.asarray(layout.cells).size  # cells the enriched kernels integrate
    assert heav_nodes == np.unique(node[kind == 0]).size and heav_dofs == 2 * np.count_nonzero(kind == 0)
    assert tip_nodes == np.unique(node[kind != 0]).size and tip_dofs == 2 * np.count_nonzero(kind != 0)
    assert core + blending == tip_nodes
    assert mult == cs.num_multipliers == cs.B.shape[0] == len(sol.contact["lambda"])
    assert full == cs.space.num_full and p0 == np.count_nonzero(np.asarray(cs.space.full_node) < 0)

    # `run` records the same counts in results.json.
    assert cli.main(["run", str(BLOCK), "--set", "mesh.h=0.1", "--out", str(tmp_path), "--quiet"]) == 0
    model = json.loads((tmp_path / "results.json").read_text())["model"]
    assert model["dofs"] == {"total": total, "standard": std, "enriched": enr}
    assert model["contact"]["multipliers"] == mult
    assert model["cracks"][0]["tip_nodes"] == tip_nodes and model["cracks"][0]["heaviside_nodes"] == heav_nodes


def test_check_json(capsys):
    assert cli.main(["check", str(BLOCK), "--set", "mesh.h=0.2", "--json", "--quiet"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["model"]["contact"]["multipliers"] > 0
    assert {q["cells"] for q in out["model"]["quadrature"]} >= {"tip cells", "plain cells (standard block only)"}
    assert any("pressure 0.01" in n for n in out["notes"])


def test_check_nodes_lists_every_enriched_node_also_when_quiet(capsys):
    """`check --nodes` lists the enriched nodes as many as the counts say;
    with --quiet the list alone (it printed nothing: the list asked for went
    with the summary)."""
    assert cli.main(["check", str(BLOCK), "--set", "mesh.h=0.2", "--nodes"]) == 0
    out = capsys.readouterr().out
    n = int(re.search(r"^enriched nodes \((\d+)\):", out, re.M).group(1))
    listed = [line for line in out.splitlines() if line.startswith("  node ")]
    assert n == len(listed) > 0 and "valid" in out
    assert cli.main(["check", str(BLOCK), "--set", "mesh.h=0.2", "--nodes", "--quiet"]) == 0
    quiet = capsys.readouterr().out.splitlines()
    assert quiet[0] == f"enriched nodes ({n}):" and quiet[1:] == listed


def one_error_line(capsys, argv):
    status = cli.main(argv)
    captured = capsys.readouterr()
    lines = captured.err.splitlines()
    assert status == 2
    assert len(lines) == 1 and lines[0].startswith("cracklip: error: "), captured.err
    return lines[0]


def test_bad_input_exits_2_with_one_line(tmp_path, capsys):
    bad_key = tmp_path / "bad_key.toml"
    bad_key.write_text(BLOCK.read_text().replace("radius = 0.2", "raduis = 0.2"))
    line = one_error_line(capsys, ["check", str(bad_key), "--quiet"])
    assert "unknown key options.raduis; did you mean options.radius?" in line

    bad_toml = tmp_path / "bad.toml"
    bad_toml.write_text("[mesh\n")
    assert "not valid TOML" in one_error_line(capsys, ["run", str(bad_toml), "--out", str(tmp_path / "o")])
    assert not (tmp_path / "o").exists()  # nothing created for a bad scene

    line = one_error_line(capsys, ["check", str(tmp_path / "missing.toml")])
    assert "missing.toml: No such file or directory" in line

    line = one_error_line(capsys, ["check", str(BLOCK), "--set", "mesh.h=-1", "--quiet"])
    assert "mesh.h must be a positive number" in line

    line = one_error_line(capsys, ["check", str(BLOCK), "--set", "oops"])
    assert "KEY=VALUE" in line

    line = one_error_line(capsys, ["check", str(BLOCK), "--set", "dirichlet[1].point=[3.0, 3.0]", "--quiet"])
    assert "dirichlet[1].point [3.0, 3.0]" in line


def test_usage_errors_exit_2_with_one_line(capsys):
    with pytest.raises(SystemExit) as e:
        cli.main(["run", str(BLOCK)])
    assert e.value.code == 2
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1 and "the following arguments are required: --out" in err[0]
    with pytest.raises(SystemExit) as e:
        cli.main(["solve", str(BLOCK)])
    assert e.value.code == 2
    assert cli.main([]) == 2


def test_unwritable_output_folder(tmp_path, capsys):
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    out = blocker / "results"
    line = one_error_line(capsys, ["run", str(BLOCK), "--set", "mesh.h=0.2", "--out", str(out), "--quiet"])
    assert f"cannot write to the output folder {out}" in line
    with pytest.raises(cl.OutputError, match="output folder"):
        from cracklip.io.outputs import ensure_output_dir
        ensure_output_dir(out)


def test_solver_failure_exits_2_with_one_line(tmp_path, capsys):
    """A crack across the whole part leaves a piece free: reported by run and
    by check (issue 14, reproduction 6: check used to call it valid), naming
    the piece, not solved silently."""
    split = tmp_path / "split.toml"
    split.write_text('[mesh]\nh = 0.25\n[material]\nE = 1.0\nnu = 0.3\n'
                     '[[cracks]]\npoints = [[-2.0, 0.0], [2.0, 0.0]]\n'
                     '[[dirichlet]]\ntag = "bottom"\n[[loads.tractions]]\ntag = "top"\nvalue = [0.0, 0.01]\n')
    expected = ("cut the part into 2 pieces; the piece of 53 nodes in [-1, 1] x [0, 1] has no Dirichlet condition "
                "fixing its translation in x, translation in y")
    line = one_error_line(capsys, ["run", str(split), "--out", str(tmp_path / "o"), "--quiet"])
    assert expected in line, line
    assert not (tmp_path / "o" / "results.json").exists()
    assert expected in one_error_line(capsys, ["check", str(split), "--quiet"])


def test_progress_on_stderr_and_quiet(tmp_path, capsys):
    scene = ROOT / "demos" / "scenes" / "partly_open_crack.toml"
    # This coarse mesh is warned about (tip_region; the error estimate, skipped here, would too): warnings
    # are their own lines, "cracklip: warning: ...", printed with --quiet as well.
    args = ["run", str(scene), "--set", "mesh.h=0.125", "--set", "mesh.tip_h=0.05", "--set", "outputs.png=false",
            "--no-estimate"]
    assert cli.main(args + ["--out", str(tmp_path / "a")]) == 0
    captured = capsys.readouterr()
    for text in ("mesh: ", "active set iteration 1", "solve phases: ", "contact: ", "writing outputs",
                 "outputs written"):
        assert text in captured.err
    lines = captured.err.splitlines()
    warnings = [line for line in lines if line.startswith("cracklip: warning: ")]
    assert all(re.match(r"cracklip \[ *\d+\.\d\d s\] ", line) for line in lines if line not in warnings)
    assert "K_I" in captured.out and "results in" in captured.out
    assert cli.main(args + ["--out", str(tmp_path / "b"), "--quiet"]) == 0
    captured = capsys.readouterr()
    assert captured.err.splitlines() == warnings and captured.out == ""
    names = {p.name for p in (tmp_path / "b").iterdir()}
    assert names == {"results.json", "crack.csv", "sif.csv", "solution.vtu", "crack_lips.vtu"}


def test_condition_number_and_vtu_off(tmp_path):
    assert cli.main(["run", str(BLOCK), "--set", "mesh.h=0.2", "--set", "outputs.vtu=false",
                     "--set", "outputs.png=false", "--condition-number", "--out", str(tmp_path), "-q"]) == 0
    res = json.loads((tmp_path / "results.json").read_text())
    assert res["condition_number"]["cond_1norm"] > 1.0
    assert "solve.condition_number" in res["timings"]
    assert {p.name for p in tmp_path.iterdir()} == {"results.json", "crack.csv", "sif.csv"}


def test_outputs_are_never_half_written(tmp_path, monkeypatch):
    """A writer that fails leaves neither its file nor a temporary one, and no
    results.json (written last)."""
    from cracklip.io import paraview as cio
    from cracklip.io.outputs import write_outputs
    sf = load_scene_file(BLOCK, overrides=["mesh.h=0.2", "outputs.png=false"])
    sol = cl.solve(sf.scene)

    def broken(path, *args, **kwargs):
        pathlib.Path(path).write_bytes(b"partial")
        raise OSError(28, "No space left on device")
    monkeypatch.setattr(cio, "_write_vtu_file", broken)
    with pytest.raises(OSError, match="No space left"):
        write_outputs(sf, sol, tmp_path)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["crack.csv", "sif.csv"]


def test_reference_command(capsys):
    assert cli.main(["reference"]) == 0
    assert capsys.readouterr().out == reference_markdown()


def test_help_texts_say_what_each_command_does():
    """What a newcomer reads first: the error estimate `--no-estimate`
    skips is, in 2D, a solve on a finer mesh (sizes halved near each tip;
    its help said 'a coarser mesh'); `life`, which has no mesh, gives a
    [life] key as its --set example (it gave mesh.h=0.1); `grow` names the
    files it writes (it said 'dadN, life_K'), and `reference` says what it
    prints."""
    from cracklip.cli import build_parser
    sub = next(a for a in build_parser()._actions if a.dest == "command").choices
    run = " ".join(sub["run"].format_help().split())
    assert "coarser mesh" not in run and "halved within 20 element sizes of each tip" in run
    life = " ".join(sub["life"].format_help().split())
    assert "mesh." not in life and "--set life.a_final=20" in life
    grow = " ".join(sub["grow"].format_help().split())
    assert "dadN.png" in grow and "life_K.png" in grow and "residual_strength.png" in grow
    assert "scene_reference.md" in " ".join(sub["reference"].format_help().split())


def test_entry_point_exit_status():
    status, out, err = run_cli("check", "nowhere.toml")
    assert status == 2 and err == "cracklip: error: nowhere.toml: No such file or directory\n"


def quick_start():
    """The shell commands and the quoted check output of the README's quick start."""
    text = (ROOT / "README.md").read_text()
    section = text.split("## Quick start", 1)[1].split("\n## ", 1)[0]
    block = section.split("```sh\n", 1)[1].split("```", 1)[0]
    commands = [line for line in block.splitlines() if line.strip() and not line.startswith("#")]
    # `dofs: ...`, `tip: ...` and the per-tip line `tip (-0.6, 0): element size ...` (quoted whole: an
    # elided or rounded quote, as `element size 0.048, ...` for the printed 0.04762 was, fails)
    quoted = re.findall(r"`((?:dofs|Heaviside|tip|contact)(?: \([^)]*\))?: [^`]+)`", section.replace("\n", " "))
    return commands, quoted


def ignore_rules(root: pathlib.Path) -> list[tuple[str, bool, bool]]:
    """The patterns of root/.gitignore as (pattern, anchored, directory only).

    Only the forms the project's .gitignore uses are understood (a name or
    glob, a leading / anchoring it to the root, a trailing / for
    directories); anything else (negation, **) fails loudly so the copy never
    silently differs from a clone."""
    rules = []
    for line in (root / ".gitignore").read_text().splitlines():
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        if line.startswith("!") or "**" in line:
            raise ValueError(f".gitignore pattern {line!r} is not understood by fresh_checkout")
        directory = line.endswith("/")
        anchored = line.startswith("/")
        rules.append((line.strip("/"), anchored, directory))
    return rules


def fresh_checkout(dest: pathlib.Path) -> None:
    """The repository's files, as a clone or a release archive holds them,
    copied to dest, plus the C++ module that `bash scripts/setup.sh` builds.

    The tree is walked and .gitignore's rules applied (no git needed: the
    repository may arrive as an archive on a machine without git); .git
    itself is skipped (a directory in a clone, a file in a git worktree)."""
    import fnmatch
    rules = ignore_rules(ROOT)

    def ignored(rel: pathlib.PurePosixPath, is_dir: bool) -> bool:
        for pattern, anchored, directory in rules:
            if directory and not is_dir:
                continue
            target = str(rel) if anchored else rel.name
            if fnmatch.fnmatchcase(target, pattern):
                return True
        return False

    for here, dirs, files in os.walk(ROOT):
        rel_here = pathlib.PurePosixPath(pathlib.Path(here).relative_to(ROOT).as_posix())
        dirs[:] = sorted(d for d in dirs if d != ".git" and not ignored(rel_here / d, True))
        for name in files:
            rel = rel_here / name
            if name == ".git" or ignored(rel, False):  # a file in a git worktree
                continue
            (dest / rel).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(ROOT / rel, dest / rel)
    for so in (ROOT / "python" / "cracklip").glob("_cracklip*.so"):
        shutil.copy2(so, dest / "python" / "cracklip" / so.name)


def test_fresh_checkout_copies_what_a_clone_holds(tmp_path):
    """fresh_checkout needs no git; where git is present, the files it copies
    are exactly git's tracked and untracked-not-ignored files (plus the built
    module), so the quick-start test runs on what a clone would hold."""
    fresh_checkout(tmp_path)
    copied = {p.relative_to(tmp_path).as_posix() for p in tmp_path.rglob("*") if p.is_file()}
    assert "README.md" in copied and "scripts/setup.sh" in copied
    assert not any(c.startswith(("build/", ".git/")) or "__pycache__" in c for c in copied)
    if shutil.which("git") is None or not (ROOT / ".git").exists():
        pytest.skip("no git here: the comparison with git ls-files needs it")
    listing = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard", "-z"],
                             cwd=ROOT, capture_output=True, check=True).stdout.decode()
    expected = {n for n in listing.split("\0") if n and (ROOT / n).is_file()}
    modules = {p.relative_to(ROOT).as_posix() for p in (ROOT / "python" / "cracklip").glob("_cracklip*.so")}
    assert copied == expected | modules


def test_readme_quick_start_works_as_written(tmp_path):
    """Acceptance 4: the quick start's commands, run as written in a fresh
    copy of the repository, succeed and give what the README quotes. The
    set-up line (apt + CMake build) is stood in for by copying the module it
    builds; everything else runs verbatim."""
    commands, quoted = quick_start()
    assert commands[0] == "bash scripts/setup.sh" and len(commands) == 3
    assert len(quoted) == 5
    fresh_checkout(tmp_path)
    assert not (tmp_path / "out").exists()
    outputs = []
    for command in commands[1:]:
        words = shlex.split(command)
        env = {"PATH": "/usr/bin:/bin", "HOME": os.environ.get("HOME", "/tmp"), "MPLBACKEND": "Agg"}
        while "=" in words[0]:
            key, value = words.pop(0).split("=", 1)
            env[key] = value
        p = subprocess.run(words, cwd=tmp_path, env=env, capture_output=True, text=True, timeout=300)
        assert p.returncode == 0, f"{command}\n{p.stderr}"
        outputs.append(p.stdout)
    for q in quoted:  # what the README says check prints
        assert q in outputs[0], q
    out = tmp_path / "out" / "block"
    res = json.loads((out / "results.json").read_text())
    assert abs(res["cracks"][0]["pressure"]["max"] - 0.01) < 1e-8
    assert abs(res["sifs"][0]["K_I"]) < 1e-8
    for name in ("crack.csv", "sif.csv", "solution.vtu", "crack_lips.vtu", "deformed.png",
                 "crack_pressure.png", "stress.png"):
        assert (out / name).stat().st_size > 0


def test_large_mesh_pngs_are_rasterised_exactly():
    """The image path of the PNGs (above outputs.RASTER_MIN_TRIANGLES): on an
    unstructured mesh, every pixel carries the value of a triangle that
    contains its centre, and pixels outside the part are NaN."""
    from cracklip.scene.mesh import create_rectangle
    from cracklip.io.raster import image_shape, rasterize
    md = create_rectangle(-1.0, -0.5, 1.0, 0.5, 0.05)
    x = md.mesh.geometry.x[:, :2]
    cells = md.mesh.geometry.dofmap.array.reshape(-1, 3)
    tris = x[cells]
    values = np.arange(len(cells), dtype=float)
    extent = (-1.2, 1.2, -0.6, 0.6)  # a margin outside the part
    shape = image_shape(extent, 300)
    assert shape == (150, 300)
    img = rasterize(tris, values, extent, shape)
    ny, nx = shape
    yc = extent[2] + (np.arange(ny) + 0.5) * (extent[3] - extent[2]) / ny
    xc = extent[0] + (np.arange(nx) + 0.5) * (extent[1] - extent[0]) / nx
    X, Y = np.meshgrid(xc, yc)
    inside = (np.abs(X) < 1.0 - 1e-9) & (np.abs(Y) < 0.5 - 1e-9)
    outside = (np.abs(X) > 1.0 + 1e-9) | (np.abs(Y) > 0.5 + 1e-9)
    assert np.all(np.isnan(img[outside])) and not np.any(np.isnan(img[inside]))
    # Barycentric coordinates of every inside pixel centre in its triangle.
    t = tris[img[inside].astype(int)]
    p = np.stack([X[inside], Y[inside]], axis=1)
    d = np.stack([t[:, 1] - t[:, 0], t[:, 2] - t[:, 0]], axis=2)
    lam = np.linalg.solve(d, (p - t[:, 0])[:, :, None])[:, :, 0]
    assert lam.min() >= -1e-9 and (1.0 - lam.sum(axis=1)).min() >= -1e-9


def test_png_crop_matches_savefig_tight(tmp_path):
    """outputs.save_png draws once and cuts the ink (pixels not of the face
    colour) plus PNG_PAD_INCHES out of the canvas: the same content as
    savefig(bbox_inches="tight") (the ink spans the same box, as many ink
    pixels to 1 %), the pad exact on every side, and a picture the size of
    savefig's but for the artists' few pixels of slack and rounding. A title longer than
    the figure is wide (ink on the canvas's border, clipped) goes to savefig,
    which widens the picture to hold it."""
    from PIL import Image
    from cracklip.io import pictures as outputs
    pad = int(round(outputs.PNG_PAD_INCHES * outputs.PNG_DPI))

    def figure(overflow: bool):
        fig = outputs.new_figure((5.0, 3.0))
        fig.subplots_adjust(top=0.75, bottom=0.2)
        ax = fig.add_subplot()
        ax.plot([0.0, 1.0, 2.0], [1.0, 0.0, 2.0], "b.-")
        ax.set_title(("a title far too long for the width of this figure " * 3) if overflow else
                     "a title\nover two lines")
        ax.set_xlabel("x")
        return fig

    def ink_box(img):
        ink = np.argwhere(img.sum(axis=2) < 765)
        return ink.min(axis=0), ink.max(axis=0), len(np.argwhere(img.sum(axis=2) < 600))

    for overflow in (False, True):
        ours, ref = tmp_path / f"ours{overflow}.png", tmp_path / f"ref{overflow}.png"
        outputs.save_png(figure(overflow), ours)
        figure(overflow).savefig(ref, dpi=outputs.PNG_DPI, bbox_inches="tight", pad_inches=outputs.PNG_PAD_INCHES)
        a = np.asarray(Image.open(ours).convert("RGB")).astype(int)
        b = np.asarray(Image.open(ref).convert("RGB")).astype(int)
        (lo_a, hi_a, n_a), (lo_b, hi_b, n_b) = ink_box(a), ink_box(b)
        assert np.abs((hi_a - lo_a) - (hi_b - lo_b)).max() <= 1
        assert abs(n_a - n_b) <= 0.01 * n_b
        if overflow:  # savefig's picture, wider than the figure: the whole title is in it
            assert a.shape == b.shape and a.shape[1] > 5.0 * outputs.PNG_DPI
        else:
            assert list(lo_a) == [pad, pad] and list(np.array(a.shape[:2]) - 1 - hi_a) == [pad, pad]
            # savefig's box: the artists' (a few pixels of slack), rounded (+-2 px).
            assert -2 <= b.shape[0] - a.shape[0] <= 12 and -2 <= b.shape[1] - a.shape[1] <= 12, (a.shape, b.shape)


def test_force_is_offered_where_a_part_is_meshed_only(capsys):
    """--force (mesh beyond the memory estimate) is an option of the
    commands that mesh a part; `life` meshes nothing and does not list it."""
    parser = cli.build_parser()
    sub = next(a for a in parser._actions if a.dest == "command").choices
    for name in ("run", "grow", "check"):
        assert "--force" in sub[name].format_help(), name
    assert "--force" not in sub["life"].format_help()
    with pytest.raises(SystemExit):
        parser.parse_args(["life", str(BLOCK), "--out", "x", "--force"])
