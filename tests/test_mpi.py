"""Every command under ``mpirun -n 2`` (issue 40): no crash, no hang, no
traceback, one clear message.

What runs on several processes today: the mesh (gmsh meshes on rank 0,
its cells and facet tags go into DOLFINx, which partitions them with vertex
patches), its checks, a plain P1 solve (equal to serial), `run` and `check`
of open 2D and 3D cracks on the direct path (results.json, crack.csv,
sif.csv, solution.vtu, crack_lips.vtu, the PNGs written once, equal to
serial), also with symmetry planes, a body force, an initial stress, a load
path without contact and the nodal rescaling, and on the iterative path
(equal to the serial iterative K to the Krylov tolerance; also along a
load path and at a life's load levels); `run` with frictionless crack-lip
contact in 2D and 3D (bilateral and unilateral: the same multipliers,
active sets, pressures and K as serial), also along a load path, nodally
rescaled and on the iterative path, and Coulomb friction in 2D and 3D
(the four shipped friction scenes, `run` and `check`: the same states,
slips and iterations); `grow` of open 2D and 3D cracks (fixed
increments, fatigue cycles, spectrum lives: the path, K per step and the
cycles equal to serial, the files written once) and of a fatigue crack
closed by contact at the cycle's minimum; and the commands that need no
mesh (`life`, `check` of a life scene, `reference`), run by rank 0 with
their files written once. What the distributed model does not do yet (a
crack without a tip inside the part, `check --nodes`, the condition
number) is refused with one ``cracklip: error: ... is not available under
MPI yet`` naming it (rank 0) and exit status 2 on every process. Each
case runs `mpirun --allow-run-as-root
--oversubscribe -n 2 /usr/bin/python3 -m cracklip ...` with a timeout: a
hang fails the test instead of stalling the suite.

A fatigue life closed by crack-lip contact runs too: its load levels
(analysis.load_path.LevelSolver) with frictionless contact on the
distributed saddle point, each level from the last one's active set (the
levels of tests/mpi/levels.py; `grow` of the spectrum life at a hole and
the ground-air-ground corner crack), equal to serial.
"""
from __future__ import annotations

import csv
import json
import shutil
import subprocess

import numpy as np
import pytest
from conftest import ROOT

pytestmark = pytest.mark.mpi

ENV = {"PYTHONPATH": str(ROOT / "python"), "PATH": "/usr/bin:/bin", "MPLBACKEND": "Agg", "HOME": "/tmp",
       "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}
SCENES = ROOT / "demos" / "scenes"
#: Small meshes of the shipped scenes (a few seconds per process).
SMALL_2D = ["--set", "mesh.tip_h=0.1"]
SMALL_3D = ["--set", "mesh.h=2.0", "--set", "mesh.tip_h=0.5", "--set", "mesh.crack_h=0.5"]
REFUSED = "is not available under MPI yet (2 processes): run it without mpirun"


def mpirun(*args: str, timeout: float = 600, n: int = 2) -> subprocess.CompletedProcess:
    """`python3 -m cracklip ARGS` on n processes."""
    return python_on(n, "-m", "cracklip", *args, timeout=timeout)


def python_on(n: int, *args: str, timeout: float = 600) -> subprocess.CompletedProcess:
    """`/usr/bin/python3 ARGS` on n processes (mpirun)."""
    cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-n", str(n), "/usr/bin/python3", *args]
    return subprocess.run(cmd, cwd=ROOT, env=ENV, capture_output=True, text=True, timeout=timeout)


def script_on_one_and_two(script: str, *args: str) -> tuple[dict, dict]:
    """The JSON line a tests/mpi script prints (rank 0) run alone and on 2
    processes, each run clean: (serial, 2 processes)."""
    runs = {}
    for n in (1, 2):
        p = python_on(n, str(ROOT / "tests" / "mpi" / script), *args)
        assert_clean(p, 0)
        runs[n] = json.loads(p.stdout.strip().splitlines()[-1])
    return runs[1], runs[2]


def assert_clean(p: subprocess.CompletedProcess, status: int) -> None:
    """Exit status `status`, no Python traceback, no signal, no MPI abort."""
    report = f"exit {p.returncode}\nstdout:\n{p.stdout[-3000:]}\nstderr:\n{p.stderr[-3000:]}"
    assert p.returncode == status, report
    for bad in ("Traceback", "signal", "SEGV", "MPI_ABORT", "malloc", "exiting improperly"):
        assert bad not in p.stdout + p.stderr, report


def assert_refused(p: subprocess.CompletedProcess) -> None:
    """Exit 2 with exactly one 'cracklip: error: ...' line, the not-yet-parallel message."""
    assert_clean(p, 2)
    errors = [line for line in p.stderr.splitlines() if line.startswith("cracklip: error:")]
    assert len(errors) == 1, p.stderr
    assert REFUSED in errors[0], errors[0]


def test_mpirun_is_installed():
    """Open MPI's mpirun comes with DOLFINx's packages (scripts/setup.sh names openmpi-bin)."""
    assert shutil.which("mpirun", path=ENV["PATH"]) is not None


#: A crack across the whole part (no tip inside it): the pieces it may cut
#: off are checked on one process only, not distributed yet.
REFUSED_THROUGH = "a crack without a tip inside the part"


@pytest.mark.parametrize("command", ["run", "check"])
def test_2d_model_refused_not_crashed(command, tmp_path):
    """The issue's reproducer crashed both processes with SEGV (every process
    passed the whole mesh to DOLFINx); now it runs (test_run_contact_same_on_one_and_two_processes),
    and what is not distributed yet is refused collectively, by name (here
    the block's crack carried across the whole block)."""
    extra = ["--out", str(tmp_path / "out")] if command != "check" else []
    p = mpirun(command, str(SCENES / "block_uniform_pressure.toml"),
               "--set", "cracks[0].points=[[-1.5,0.0],[1.5,0.0]]", *extra)
    assert_refused(p)
    assert f"cracklip: error: {REFUSED_THROUGH}" in p.stderr, p.stderr


@pytest.mark.parametrize("command", ["run", "check"])
def test_3d_refused_not_crashed(command, tmp_path):
    """What a 3D part does not do under mpirun yet (here a penny larger
    than the box: a crack surface without a front inside the part) is
    refused collectively, by name."""
    extra = ["--out", str(tmp_path / "out")] if command == "run" else []
    p = mpirun(command, str(SCENES / "penny_crack.toml"), *SMALL_3D, "--set", "cracks[0].ellipse.a=20.0", *extra)
    assert_refused(p)
    assert f"cracklip: error: {REFUSED_THROUGH}" in p.stderr, p.stderr


def test_3d_grow_without_growth_table_printed_once(tmp_path):
    """No shipped 3D scene grows; `grow` on one stops before meshing with
    the scene's own error, once."""
    p = mpirun("grow", str(SCENES / "penny_crack.toml"), *SMALL_3D, "--out", str(tmp_path / "out"))
    assert_clean(p, 2)
    errors = [line for line in p.stderr.splitlines() if line.startswith("cracklip: error:")]
    assert len(errors) == 1 and "has no [growth] table" in errors[0], p.stderr


def test_input_error_printed_once(tmp_path):
    """An error every process finds alike (here a bad scene key, before any
    mesh) is printed once, exit 2 on all."""
    p = mpirun("run", str(SCENES / "pressurised_crack.toml"), *SMALL_2D, "--set", "mesh.h=-1",
               "--out", str(tmp_path / "out"))
    assert_clean(p, 2)
    assert len([line for line in p.stderr.splitlines() if line.startswith("cracklip: error:")]) == 1, p.stderr


@pytest.mark.parametrize("args, message", [
    (["run", "pressurised_crack.toml", "--accuracy", "abc"], "argument --accuracy: invalid float value: 'abc'"),
    (["run", "pressurised_crack.toml", "--out", "/dev/null/out"], "cannot write to the output folder /dev/null/out"),
    (["grow", "fatigue_edge_crack.toml", "--out", "/dev/null/out"], "cannot write to the output folder /dev/null/out"),
    (["check", "pressurised_crack.toml", "--set", "material.nu=0.6"], "Poisson's ratio nu must lie in"),
    (["check", "ct_specimen.toml", "--set", "mesh.path=nofile.geo"], "mesh.path 'nofile.geo': no such file"),
    (["check", "hole_crack_spectrum.toml", "--set", "spectrum.blocks[0].file=nofile.csv"],
     "spectrum.blocks[0].file: cannot read"),
    (["check", "hole_crack.toml", "--set", "mesh.h=0.3", "--set", "dirichlet[0].tag=nowhere"],
     "dirichlet[0]: unknown boundary tag 'nowhere'"),
    (["check", "pressurised_crack.toml", *SMALL_2D, "--set", "dirichlet[0].point=[50.0,0.0]"],
     "put the point on the part"),
    (["check", "pressurised_crack.toml", *SMALL_2D, "--set", "cracks[0].points=[[30.0,0.0],[40.0,0.0]]"],
     "does not cross any cell of the mesh")])
def test_user_mistake_printed_once(args, message, tmp_path):
    """A user's mistake that every process finds alike (an option argparse
    refuses, a material out of range, a missing mesh or spectrum file, an
    unknown tag, a point support or a crack off the part, an output folder
    that cannot be written, found before meshing) stops every process with
    one message and exit 2. They were printed once per process (argparse),
    or each process aborted the job alone (MPI_ABORT, one message per
    process): the errors were not marked collective."""
    command, scene, *rest = args
    extra = ["--out", str(tmp_path / "out")] if command == "run" and "--out" not in rest else []
    p = mpirun(command, str(SCENES / scene), *rest, *extra)
    assert_clean(p, 2)
    errors = [line for line in p.stderr.splitlines() if line.startswith("cracklip: error:")]
    assert len(errors) == 1 and message in errors[0], p.stderr
    if "--out" in rest:
        assert "meshing" not in p.stderr, p.stderr  # (the folder is checked first)


@pytest.mark.parametrize("option", [["--condition-number"], ["--set", "outputs.condition_number=true"]])
def test_condition_number_refused_before_meshing(option, tmp_path):
    """The condition number (not distributed yet) is refused by name before
    any meshing work, as docs/speed.md says of every refusal the scene
    alone decides; it was refused after meshing and building the model."""
    p = mpirun("run", str(SCENES / "pressurised_crack.toml"), *SMALL_2D, *option, "--out", str(tmp_path / "out"))
    assert_refused(p)
    assert "the condition number" in p.stderr and "meshing" not in p.stderr, p.stderr


def test_one_process_under_mpirun_ends_cleanly():
    """`mpirun -n 1 python3 -m cracklip ...` (a one-task cluster job): the
    process finalises MPI before leaving by os._exit; it did not (only
    several processes did), so mpirun reported it as exiting improperly
    and returned 1 after a successful run."""
    p = python_on(1, "-m", "cracklip", "check", str(SCENES / "pressurised_crack.toml"), *SMALL_2D)
    assert_clean(p, 0)


def test_progress_counts_are_the_whole_models(tmp_path):
    """The progress lines of `run` count the whole model under mpirun, as
    serial: they printed rank 0's part of it (ghosts included: 38 enriched
    pseudo-nodes on 81 cells of the crack from a hole's 45 on 110), and the
    'solved N dofs' line was missing."""
    import re
    lines = {}
    for n in (1, 2):
        p = python_on(n, "-m", "cracklip", "run", str(SCENES / "pressurised_crack.toml"), *SMALL_2D, "--no-estimate",
                      "--out", str(tmp_path / f"n{n}"))
        assert_clean(p, 0)
        lines[n] = [re.sub(r"^cracklip \[ *[0-9.]+ s\] | in [0-9.]+ s$", "", line) for line in p.stderr.splitlines()
                    if "enriched pseudo-nodes on" in line or " dofs (" in line]
    assert len(lines[1]) == 2 and lines[2] == lines[1], lines


def test_box_support_same_on_one_and_two_processes(tmp_path):
    """A Dirichlet box holds the nodes of every process inside it, the same
    list on each: under mpirun a process without a node in the box refused
    the scene alone (MPI_ABORT), and processes with different lists would
    have made different collective calls."""
    text = (SCENES / "pressurised_crack.toml").read_text()
    scene = tmp_path / "box.toml"
    scene.write_text(text.replace("point = [-10.0, -10.0]", "box = [-10.0, -10.0, -9.0, -9.0]", 1))
    runs = {}
    for n in (1, 2):
        p = python_on(n, "-m", "cracklip", "run", str(scene), *SMALL_2D, "--no-estimate", "-q",
                      "--out", str(tmp_path / f"n{n}"))
        assert_clean(p, 0)
        runs[n] = json.loads((tmp_path / f"n{n}" / "results.json").read_text())
    scale = max(abs(r["K_I"]) for r in runs[1]["sifs"])
    for a, b in zip(runs[1]["sifs"], runs[2]["sifs"]):
        assert abs(a["K_I"] - b["K_I"]) <= 1e-10 * scale and abs(a["K_II"] - b["K_II"]) <= 1e-10 * scale


def test_error_estimate_of_kirsch_traction_same_on_one_and_two_processes(tmp_path):
    """The crack from a hole (a Kirsch traction on the outer arc, closed by
    contact) with its error estimate: the estimate's finer mesh is loaded
    by the normals of its own facets, and the K scale is the whole crack's
    (fracture.sif.natural_k summed its length over one process's part). The
    finer level's K_I came out 0.006 for an exact 0 (no multiplier active)
    in 4 of 5 runs on 2 processes, and the K scale 16 % off (the default
    mesh); the serial test of the cause: test_loads.py::test_field_traction_on_another_mesh."""
    runs = {}
    for n in (1, 2):
        p = python_on(n, "-m", "cracklip", "run", str(SCENES / "hole_crack.toml"), "--set", "mesh.h=0.15", "-q",
                      "--out", str(tmp_path / f"n{n}"))
        assert_clean(p, 0)
        runs[n] = json.loads((tmp_path / f"n{n}" / "results.json").read_text())
    one, two = runs[1]["error_estimate"], runs[2]["error_estimate"]
    scale = one["K_scale"]
    assert abs(two["K_scale"] - scale) <= 1e-12 * scale
    for key, a in one["points"].items():
        b = two["points"][key]
        for mode in ("K_I", "K_II"):
            for u, v in zip(a[f"{mode}_levels"], b[f"{mode}_levels"]):
                assert abs(u - v) <= 1e-10 * scale, (key, mode, a[f"{mode}_levels"], b[f"{mode}_levels"])


@pytest.mark.parametrize("scene, message", [("pressurised_crack.toml", "mesh size h = 1000.0 must be positive and "
                                                                    "at most the domain size"),
                                            ("penny_crack.toml", "mesh size h = 1000.0 must be positive and at "
                                                                 "most the box size")])
def test_rank0_mesh_error_printed_once(scene, message):
    """gmsh meshes on rank 0 only; its refusal (here h larger than the part)
    reaches every process: one message, exit 2 on all."""
    p = mpirun("check", str(SCENES / scene), "--set", "mesh.h=1000")
    assert_clean(p, 2)
    errors = [line for line in p.stderr.splitlines() if line.startswith("cracklip: error:")]
    assert errors == [f"cracklip: error: {message}"], p.stderr


@pytest.mark.parametrize("scene", ["life_hole_crack.toml", "life_surface_crack.toml"])
def test_life_runs_once(scene, tmp_path):
    """`life` needs no mesh: rank 0 runs it, the summary and the files once;
    the same results as a serial run."""
    out, serial = tmp_path / "mpi", tmp_path / "serial"
    p = mpirun("life", str(SCENES / scene), "--no-png", "--out", str(out))
    assert_clean(p, 0)
    assert p.stdout.count("results in ") == 1, p.stdout
    s = subprocess.run(["/usr/bin/python3", "-m", "cracklip", "life", str(SCENES / scene), "--no-png", "--out",
                        str(serial), "-q"], cwd=ROOT, env=ENV, capture_output=True, text=True, timeout=600)
    assert s.returncode == 0, s.stderr
    a, b = json.loads((out / "results.json").read_text()), json.loads((serial / "results.json").read_text())
    for r in (a, b):  # wall-clock times
        r.pop("timings", None), r["life"].pop("seconds", None), r["life"].pop("cycles_per_second", None)
    assert a == b


def test_check_life_scene_and_reference_print_once():
    p = mpirun("check", str(SCENES / "life_hole_crack.toml"))
    assert_clean(p, 0)
    assert p.stdout.count(": valid") == 1, p.stdout
    p = mpirun("reference")
    assert_clean(p, 0)
    assert p.stdout.count("| key | type | default | meaning |") == 1


@pytest.mark.parametrize("dim", [2, 3])
def test_plain_solve_same_on_one_and_two_processes(dim):
    """A plain P1 solve on the distributed mesh (vertex-patch ghosts, parallel
    MUMPS) gives the serial strain energy and largest displacement to 1e-10;
    every owned node's patch is whole on its process; extract_node_mesh
    gives the owned and ghost nodes at V's dof coordinates."""
    one, two = script_on_one_and_two("plain_solve.py", str(dim))
    assert two["processes"] == 2 and one["dofs"] == two["dofs"]
    assert two["gmsh_processes"] == 1  # gmsh meshes on rank 0 only
    assert two["incomplete"] == 0 and one["incomplete"] == 0
    # V's dof coordinates are pushed forward through the cell map: round-off only
    assert two["node_mesh_ok"] and two["node_mesh_distance"] <= 1e-12
    # measured: 2D 0.01217993719720318 / ...203287 (9e-15), 3D 0.013463497732888517 / ...512 (4e-16)
    assert abs(two["energy"] - one["energy"]) <= 1e-10 * abs(one["energy"]), (one, two)
    assert abs(two["u_max"] - one["u_max"]) <= 1e-10 * abs(one["u_max"]), (one, two)
    if dim == 3:  # what the vertex patches change: ghosts across facets only leave patches incomplete (24 measured)
        p = python_on(2, str(ROOT / "tests" / "mpi" / "plain_solve.py"), str(dim), "facet")
        assert_clean(p, 0)
        assert json.loads(p.stdout.strip().splitlines()[-1])["incomplete"] > 0


@pytest.mark.parametrize("scene, settings", [
    ("penny_crack.toml", ["mesh.h=2.0", "mesh.tip_h=0.2", "mesh.crack_h=0.4"]),   # a closed loop
    # an open front ending on the free surface (its boundary faces counted over the processes)
    ("surface_crack_plate.toml", ["mesh.h=8.0", "mesh.tip_h=0.6", "mesh.crack_h=0.0"])])
def test_3d_front_same_on_one_and_two_processes(scene, settings):
    """A 3D crack's front (model/cracks/shared_front.py) is the same on
    every process of a 2-process run and equal to the serial front: the
    same points in the same order from the same start, arc lengths,
    frames (to round-off of the segments' end points: 1e-12 of the part),
    pieces, closed loops and boundary ends, while each process holds the
    cells of only part of it."""
    one, two = script_on_one_and_two("front_3d.py", str(SCENES / scene), *settings)
    assert two["processes"] == 2 and two["same"]
    a, b = one["front"], two["front"]
    assert len(a["s"]) == len(b["s"]) > 10
    for k in ("on_boundary", "piece_offsets", "closed"):
        assert a[k] == b[k], k
    size = float(np.ptp(np.asarray(a["x"]), axis=0).max())
    assert np.abs(np.asarray(a["x"]) - np.asarray(b["x"])).max() <= 1e-12 * size
    assert np.abs(np.asarray(a["s"]) - np.asarray(b["s"])).max() <= 1e-12 * size
    assert np.abs(np.asarray(a["frame"]) - np.asarray(b["frame"])).max() <= 1e-12
    # the front is split: both processes own front cells, neither holds every segment's cell
    assert min(two["owned_front"]) > 0 and max(two["local"]) < two["segments"]
    assert one["local"] == [one["segments"]]
    if scene.startswith("penny"):
        assert a["closed"] == [1] and not any(a["on_boundary"])
    else:
        assert a["closed"] == [0] and a["on_boundary"][0] == a["on_boundary"][-1] == 1


@pytest.mark.parametrize("scene, settings, exact", [
    # Griffith K_I = p sqrt(pi a), 1.0062 for the width (Tada)
    ("pressurised_crack.toml", ["mesh.tip_h=0.05", "options.radius=0.3"], 1.7835),
    # Williams K_I = 1 prescribed on the whole boundary (non-zero Dirichlet values, lifted)
    ("westergaard.toml", [], 1.0)])
def test_open_crack_same_on_one_and_two_processes(scene, settings, exact):
    """The Python API path of an open 2D crack on 2 processes: the global
    numbering of standard and enriched dofs (pseudo-nodes owned with their
    base node), the distributed matrix assembled on owned cells, parallel
    MUMPS, K by the interaction integral summed over processes. The same
    dofs as serial, K and the work of the loads to 1e-10 relative (the
    direct path's target). Measured: pressurised crack 3082 dofs (610
    enriched), K_I 1.782554724946618 / 1.7839816078402078 serial, equal to
    6e-15 on 2 processes (4e-15 on 3); Westergaard 4122 dofs (252
    enriched), K_I 1.0007752004528616 serial, ...558 on 2."""
    args = (str(SCENES / scene), *settings, "options.solver=direct")
    one, two = script_on_one_and_two("open_crack.py", *args)
    # The case under test is a crack whose dofs lie on both processes. DOLFINx's
    # partition varies from run to run and, rarely, leaves the crack on one
    # process (1 run in about 10 of the pressurised crack): run again then.
    for _ in range(3):
        if two["split"][0] == 2 and two["split"][1] > 0:
            break
        p = python_on(2, str(ROOT / "tests" / "mpi" / "open_crack.py"), *args)
        assert_clean(p, 0)
        two = json.loads(p.stdout.strip().splitlines()[-1])
    assert two["processes"] == 2
    assert two["split"][0] == 2 and two["split"][1] > 0, two  # the crack's dofs lie on both processes
    assert (two["dofs"], two["enriched"]) == (one["dofs"], one["enriched"]), (one, two)
    assert len(one["sifs"]) == len(two["sifs"]) > 0
    scale = max(abs(k) for ks in one["sifs"] for k in ks)
    for a, b in zip(one["sifs"], two["sifs"]):
        assert max(abs(x - y) for x, y in zip(a, b)) <= 1e-10 * scale, (one, two)
    assert abs(two["work"] - one["work"]) <= 1e-10 * abs(one["work"]), (one, two)
    # the method, not just agreement: K against the closed form within 1 %
    for k_i, k_ii in one["sifs"]:
        assert abs(k_i / exact - 1.0) < 0.01 and abs(k_ii) < 0.01 * k_i, one
    assert two["residual"] < 1e-10


#: The partition (tests/mpi/split.py) on which the block under pressure
#: (mesh.h = 0.1) once came out wrong on 2 processes: rank 1 owns a node at
#: (-1, -0.1) whose enriched neighbours by the crack's mouth it holds as
#: ghosts without their cut cells, so its own crack band missed that node
#: and the phantom transform left its row as it was (T^T A T unsymmetric by
#: 1.16; K_II -1.6e-3 = 14 % of the K scale, pressure 0.0085-0.023 against
#: 0.01, the residual check passed on the wrong matrix). SCOTCH chose such a
#: partition in 0.5-15 % of the runs.
BLOCK_SPLIT = "--cells-below=-0.12"


def script_args(scene: str, settings: list[str]) -> list[str]:
    """A tests/mpi script's arguments: its options (tests/mpi/split.py's
    --cells-below) first, then the shipped scene and its KEY=VALUE settings."""
    options = [a for a in settings if a.startswith("--")]
    return [*options, str(SCENES / scene), *(a for a in settings if not a.startswith("--"))]


@pytest.mark.parametrize("scene, settings, n", [
    ("westergaard.toml", [], 2), ("penny_crack.toml", ["mesh.h=2.0", "mesh.tip_h=0.3", "mesh.crack_h=0.3"], 2),
    ("penny_crack.toml", ["mesh.h=2.0", "mesh.tip_h=0.3", "mesh.crack_h=0.3"], 3),
    ("block_uniform_pressure.toml", [BLOCK_SPLIT, "mesh.h=0.1"], 2)])
def test_phantom_transform_in_place_equals_ptap(scene, settings, n):
    """The distributed phantom transform in A's storage (each process its
    owned rows coupled to any process's Heaviside dofs, read from A's
    pattern, the T rows of ghost columns scattered from their owners)
    equals PETSc's parallel PtAP T^T A T to round-off, also on the pinned
    partition of the block under pressure (BLOCK_SPLIT). Measured (of
    ||A||): Westergaard 6.9e-18, penny 2.7e-18 on 2 processes and 2.8e-18
    on 3, block 5.2e-18; the change itself 0.16, 0.055 and 0.095."""
    p = python_on(n, str(ROOT / "tests" / "mpi" / "phantom_transform.py"), *script_args(scene, settings))
    assert_clean(p, 0)
    out = json.loads(p.stdout.strip().splitlines()[-1])
    assert out["processes"] == n and out["in_place"], out
    assert out["changed"] > 1e-3, out
    assert out["difference"] <= 1e-14, out


@pytest.mark.parametrize("scene, settings, exact", [
    ("westergaard.toml", [], 1.0),  # 2D: the band with its ring of neighbours (BAND_RINGS)
    # 3D: front enrichment, the tip dofs left out of GAMG (TIP_DOFS_OUT_OF_GAMG)
    ("penny_crack.toml", ["mesh.h=2.0", "mesh.tip_h=0.3", "mesh.crack_h=0.3"], None),
    # bilateral contact on the pinned partition (BLOCK_SPLIT): K = 0 exactly
    ("block_uniform_pressure.toml", [BLOCK_SPLIT, "mesh.h=0.1"], 0.0)])
def test_iterative_path_same_on_one_and_two_processes(scene, settings, exact):
    """options.solver = "iterative" on 2 processes (solvers/
    distributed_iterative.py: the serial CG + Schwarz {MUMPS band | GAMG |
    band} on the global numbering, the phantom transform in A's storage,
    the band marked on every process's cells and summed): K equal to the
    serial iterative K to 1e-6 relative (issue 40's bar for the iterative
    path; both solves stop at a Krylov residual of 1e-10). Measured:
    Westergaard K_I 1.0007752004575963 serial, ...403845 on 2 processes
    (5e-11), 21 iterations on both; penny (6 front points) 3e-11,
    23 / 21 iterations; the block under pressure on BLOCK_SPLIT (closed,
    bilateral contact, the exact K 0): K_I -2.4246e-9 on both, K_II 3e-14 /
    2e-14 of the K scale p sqrt(pi a) = 0.0112, 19 / 21 CG iterations
    (before the transform read its rows from A's pattern: K_II -1.6e-3,
    GMRES after CG broke down)."""
    one, two = script_on_one_and_two("iterative.py", *script_args(scene, settings))
    assert two["processes"] == 2
    for run in (one, two):
        assert run["solver"] == "iterative" and "GAMG" in run["method"], run
        assert run["residual"] <= 1e-10 and 0 < run["iterations"] < 60, run
    assert len(one["sifs"]) == len(two["sifs"]) > 0
    scale = max(abs(k) for ks in one["sifs"] for k in ks)
    if exact == 0.0:  # (K vanishes: the K scale p sqrt(pi a) of the block's pressure p = 0.01 and crack a = 0.4)
        scale = 0.01 * np.sqrt(np.pi * 0.4)
    for a, b in zip(one["sifs"], two["sifs"]):
        assert max(abs(x - y) for x, y in zip(a, b)) <= 1e-6 * scale, (one, two)
    if exact == 0.0:  # closed: K = 0
        for run in (one, two):
            assert "CG" in run["method"], run  # (CG broke down on the unsymmetric wrong matrix)
            assert max(abs(k) for ks in run["sifs"] for k in ks) <= 1e-6 * scale, run
    elif exact is not None:  # the method, not just agreement
        assert abs(one["sifs"][0][0] / exact - 1.0) < 0.01, one


def test_open_crack_refusals_by_scene_key(tmp_path):
    """What the distributed model does not do yet stops with one message
    naming it (here a crack across the whole plate), on every process
    through the Python API, no hang."""
    p = python_on(2, str(ROOT / "tests" / "mpi" / "open_crack.py"), str(SCENES / "pressurised_crack.toml"),
                  "mesh.tip_h=0.1", "cracks[0].points=[[-11.0,0.0],[11.0,0.0]]")
    assert p.returncode != 0
    assert f"{REFUSED_THROUGH} (the pieces it may cut off are checked on one process only) is not available " \
        "under MPI yet (2 processes)" in p.stderr, p.stderr[-3000:]
    assert "MPI_ABORT" not in p.stderr and "signal" not in p.stderr


def _run_serial(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run(["/usr/bin/python3", "-m", "cracklip", *args], cwd=ROOT, env=ENV, capture_output=True,
                          text=True, timeout=600)


def _same(a, b, tol: float) -> bool:
    """a == b, numbers to tol relative."""
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k], tol) for k in a)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(_same(x, y, tol) for x, y in zip(a, b))
    if isinstance(a, float) or isinstance(b, float):
        return abs(a - b) <= tol * max(abs(a), abs(b))
    return a == b


def _relative(a: float, b: float, scale: float) -> float:
    return abs(a - b) / scale


def _run_both(scene: str, settings: list[str], tmp_path) -> tuple:
    """`cracklip run` of a shipped scene under mpirun -n 2 (one summary
    printed) and serially: (the two output directories, serial and mpi
    results.json)."""
    out, serial = tmp_path / "mpi", tmp_path / "serial"
    p = mpirun("run", str(SCENES / scene), *settings, "--out", str(out))
    assert_clean(p, 0)
    assert p.stdout.count("results in ") == 1, p.stdout
    s = _run_serial("run", str(SCENES / scene), *settings, "--out", str(serial), "-q")
    assert s.returncode == 0, s.stderr
    a, b = (json.loads((d / "results.json").read_text()) for d in (serial, out))
    assert b["parallel"]["processes"] == 2
    return out, serial, a, b


@pytest.mark.parametrize("scene, settings", [
    # with the error estimate: its second mesh (the recipe, gmsh on rank 0 again) solved on 2 processes too
    ("pressurised_crack.toml", ["--set", "mesh.tip_h=0.1"]),
    # options.accuracy: the tips' regions refined level by level (two levels, 2236 -> 31972 dofs)
    ("pressurised_crack.toml", ["--set", "mesh.tip_h=0.1", "--accuracy", "0.005"]),
    ("westergaard.toml", ["--no-estimate"]),  # non-zero Dirichlet values on every side
    ("edge_notch_bending.toml", ["--set", "mesh.h=0.1", "--set", "mesh.tip_h=0.03", "--no-estimate"]),
    # point forces (each on the nearest owned node of all processes, added by its owner)
    ("three_point_bending.toml", ["--set", "mesh.h=0.1", "--set", "mesh.tip_h=0.03", "--no-estimate"])])
def test_run_open_crack_same_on_one_and_two_processes(scene, settings, tmp_path):
    """`cracklip run` of a shipped open 2D crack scene under mpirun -n 2: one
    summary printed (rank 0), results.json, crack.csv, sif.csv, solution.vtu,
    crack_lips.vtu and the PNGs written once, equal to the serial run's: K to 1e-10
    of the K scale (the direct path's target), the dofs and model counts
    exactly, the energy, the crack's opening and the error estimate to
    1e-10, the reactions and load resultants to 1e-10 of the loads' size,
    solution.vtu (gathered on rank 0) with the same sub-cells and stresses.
    Measured: K equal to 3e-15 (pressurised crack), 1.5e-14 (the same to
    an accuracy of 0.5 %), 5e-15 (Westergaard), 3e-12 (edge notch), 1.4e-14
    (three-point bending)."""
    out, serial, a, b = _run_both(scene, settings, tmp_path)
    assert b["files"] == a["files"] == ["crack.csv", "sif.csv", "solution.vtu", "crack_lips.vtu", "deformed.png",
                                        "crack_pressure.png", "stress.png", "results.json"]
    assert all((out / f).is_file() for f in b["files"])
    # the sub-cell field gathered on rank 0: the same sub-triangles and stresses
    import meshio
    va, vb = (meshio.read(d / "solution.vtu") for d in (serial, out))
    assert len(va.cells[0].data) == len(vb.cells[0].data) and len(va.points) == len(vb.points)
    for name in ("stress_von_mises", "stress_xx", "stress_xy"):
        x, y = np.sort(va.cell_data[name][0]), np.sort(vb.cell_data[name][0])
        assert np.abs(x - y).max() <= 1e-10 * np.abs(x).max(), name
    assert a["solution"]["dofs"] == b["solution"]["dofs"] and a["model"]["dofs"] == b["model"]["dofs"]
    assert a["model"]["quadrature"] == b["model"]["quadrature"]
    for key in ("enriched_pseudo_nodes", "enriched_cells", "nodes", "cells"):
        assert a["model"][key] == b["model"][key], key
    assert a["boundary_conditions_and_loads"] == b["boundary_conditions_and_loads"]
    assert [w["message"] for w in a["warnings"]] == [w["message"] for w in b["warnings"]]
    assert len(a["sifs"]) == len(b["sifs"]) > 0
    scale = max(abs(r[k]) for r in a["sifs"] for k in ("K_I", "K_II"))
    for ra, rb in zip(a["sifs"], b["sifs"]):
        assert (ra["crack"], ra["tip"]) == (rb["crack"], rb["tip"])
        for k in ("K_I", "K_II", "G"):
            assert _relative(ra[k], rb[k], scale if k != "G" else abs(ra["G"])) <= 1e-10, (k, ra, rb)
        assert (ra["limited_by"], ra["domain_clear"]) == (rb["limited_by"], rb["domain_clear"])
        assert _relative(ra["radius"], rb["radius"], ra["radius"]) <= 1e-12  # (element sizes: summation order)
    for key in ("strain_energy", "max_displacement"):
        assert _relative(a["solution"][key], b["solution"][key], abs(a["solution"][key])) <= 1e-10, key
    for ca, cb in zip(a["cracks"], b["cracks"]):
        assert ca["points"] == cb["points"]
        for key in ("length_in_part", "gap_max"):
            assert _relative(ca[key], cb[key], abs(ca[key])) <= 1e-10, key
    if a["error_estimate"] is not None:
        assert a["error_estimate"]["dofs"] == b["error_estimate"]["dofs"]
        assert _relative(a["error_estimate"]["largest_error"], b["error_estimate"]["largest_error"],
                         a["error_estimate"]["largest_error"]) <= 1e-8
    # the reactions: each process's rows and loads of its owned cells and facets, summed
    ra, rb = a["reactions"], b["reactions"]
    # (the size of the forces: the loads', or 2 W / |u|max where lip pressures or prescribed displacements load)
    load = max(ra["load_magnitude"], 2 * a["solution"]["strain_energy"] / a["solution"]["max_displacement"])
    assert load > 0 and _relative(ra["load_magnitude"], rb["load_magnitude"], load) <= 1e-10
    for key in ("gross_load",):
        assert _relative(ra[key], rb[key], load) <= 1e-10, key
    for key in ("sum", "applied_load", "load_components"):
        va = ra[key] if key != "load_components" else ra[key]["positive"] + ra[key]["negative"]
        vb = rb[key] if key != "load_components" else rb[key]["positive"] + rb[key]["negative"]
        assert max(_relative(x, y, load) for x, y in zip(va, vb)) <= 1e-10, key
    assert [(c["condition"], c["kind"], c["nodes"]) for c in ra["conditions"]] == \
        [(c["condition"], c["kind"], c["nodes"]) for c in rb["conditions"]]
    for ca, cb in zip(ra["conditions"], rb["conditions"]):
        assert max(_relative(x, y, load) for x, y in zip(ca["force"], cb["force"])) <= 1e-10, (ca, cb)
    for ia, ib in zip(ra["load_items"], rb["load_items"]):
        assert max(_relative(x, y, load) for x, y in zip(ia["resultant"], ib["resultant"])) <= 1e-10, (ia, ib)
    rows = [(d / "sif.csv").read_text().splitlines() for d in (serial, out)]
    assert rows[0][0] == rows[1][0] and len(rows[0]) == len(rows[1])


@pytest.mark.parametrize("scene, settings", [
    ("penny_crack.toml", SMALL_3D),  # a closed front
    # an open front ending on the free surface (its ends' K from their own domains)
    ("surface_crack_plate.toml", ["--set", "mesh.h=8.0", "--set", "mesh.tip_h=0.6", "--set", "mesh.crack_h=0.0",
                                  "--set", "options.radius=1.2"])])
def test_run_3d_open_crack_same_on_one_and_two_processes(scene, settings, tmp_path):
    """`cracklip run` of a shipped open 3D crack (small mesh, with the error
    estimate's second mesh) under mpirun -n 2: K along the front equal to
    the serial K to 1e-10 of the K scale (the direct path's target), with
    the same front points; the model's counts, the energy, the crack's
    statistics, front.csv and crack_opening.csv's rows equal; every file
    of the serial run written once (rank 0), solution.vtu with the same
    sub-tetrahedra and stresses (each cell with its own vertices). Measured: K
    to 9e-15 (penny, tip_h 0.5), 2.3e-14 (penny, tip_h 0.2, 8 front
    points), 5e-14 (surface crack, 7 front points)."""
    out, serial, a, b = _run_both(scene, settings, tmp_path)
    assert b["files"] == a["files"] and "solution.vtu" in a["files"]
    assert all((out / f).is_file() for f in b["files"])
    import meshio
    va, vb = (meshio.read(d / "solution.vtu") for d in (serial, out))
    assert len(va.cells[0].data) == len(vb.cells[0].data)
    for name in ("stress_von_mises", "stress_zz", "stress_yz", "side", "crack"):
        x, y = np.sort(va.cell_data[name][0]), np.sort(vb.cell_data[name][0])
        assert np.abs(x - y).max() <= 1e-10 * max(np.abs(x).max(), 1.0), name
    assert len(a["sifs"]) == len(b["sifs"]) > 0
    scale = max(abs(r[k]) for r in a["sifs"] for k in ("K_I", "K_II", "K_III"))
    for ra, rb in zip(a["sifs"], b["sifs"]):
        assert (ra["crack"], ra["point"]) == (rb["crack"], rb["point"])
        assert max(abs(ra[c] - rb[c]) for c in ("x", "y", "z", "s")) <= 1e-12
        for k in ("K_I", "K_II", "K_III"):
            assert _relative(ra[k], rb[k], scale) <= 1e-10, (k, ra, rb)
            assert _relative(ra[k + "_error"], rb[k + "_error"], scale) <= 1e-10, (k, ra, rb)
        assert _relative(ra["radius"], rb["radius"], ra["radius"]) <= 1e-12
    assert a["solution"]["dofs"] == b["solution"]["dofs"]
    for key in ("strain_energy", "max_displacement"):
        assert _relative(a["solution"][key], b["solution"][key], abs(a["solution"][key])) <= 1e-10, key
    ca, cb = a["model"]["cracks"][0], b["model"]["cracks"][0]
    for key in ("front", "front_element_size", "enriched_pseudo_nodes", "enriched_cells"):
        assert _same(ca.get(key), cb.get(key), 1e-12), key
    assert _relative(ca["area_in_part"], cb["area_in_part"], ca["area_in_part"]) <= 1e-12
    assert a["model"]["quadrature"] == b["model"]["quadrature"]
    assert [w["message"] for w in a["warnings"]] == [w["message"] for w in b["warnings"]]
    for key in ("area_in_part", "facets", "points", "opening_volume", "gap_mean", "gap_max"):
        assert _same(a["cracks"][0][key], b["cracks"][0][key], 1e-10), key
    for f in ("front.csv", "crack_opening.csv"):
        rows = [(d / f).read_text().splitlines() for d in (serial, out)]
        assert rows[0][0] == rows[1][0] and len(rows[0]) == len(rows[1]), f


#: Half of the pressurised Griffith crack (Tada: K_I = 1.7835 for the plate's width) on x >= 0, the line x = 0
#: of symmetry ([[symmetry]] by --set) meeting the crack at right angles.
HALF_GRIFFITH = ["--set", "mesh.domain=[0.0,-10.0,10.0,10.0]", "--set", "mesh.tip_h=0.05",
                 "--set", "cracks[0].points=[[0.0,0.0],[1.0,0.0]]", "--set", 'symmetry=[{tag="left"}]',
                 "--set", 'dirichlet=[{point=[10.0,-10.0],component="y"}]', "--set", "options.radius=0.3"]


@pytest.mark.parametrize("scene, settings, exact", [
    # 3D, two symmetry planes: the front's ends on them (K from the domain and its mirror image); Irwin's
    # K_I = 0.7318 at x = a, 1.0349 at y = b (the least and largest K_I; this coarse front: +4.3 %, -1.5 %)
    ("quarter_ellipse.toml", ["--set", "mesh.h=2.0", "--set", "mesh.tip_h=0.2", "--set", "mesh.crack_h=0.3"],
     ((0.7318, 1.0349), 0.05)),
    ("pressurised_crack.toml", HALF_GRIFFITH, ((1.7835,), 0.01)),  # 2D, a line of symmetry (measured -0.07 %)
    # an initial (residual) stress, 2D; without its contact (the lips overlap: a K_I < 0, equal all the same)
    ("residual_stress.toml", ["--set", "mesh.h=0.1", "--set", "mesh.tip_h=0.02", "--set", "options.contact=none"],
     None),
    # a body force, 2D and 3D
    ("pressurised_crack.toml", ["--set", "mesh.tip_h=0.1", "--set", "loads.body_force=[0.3,-0.5]"], None),
    ("penny_crack.toml", [*SMALL_3D, "--set", "loads.body_force=[0.05,0.02,-0.1]"], None),
    # an initial stress, 3D: linear, its divergence (0, 0, 0.2) the interaction integral's body force per point
    ("penny_crack.toml", [*SMALL_3D, "--set", "loads.initial_stress={value=[0.0,0.0,1.0,0.0,0.0,0.1],gradient=["
                                               "[0.0,0.0,0.5,0.0,0.0,0.0],[0.0,0.0,0.0,0.0,0.0,0.0],"
                                               "[0.0,0.0,0.2,0.0,0.0,0.0]]}"], None),
    # a load path without contact: three steps of two load groups on one matrix
    ("frictional_crack.toml", ["--set", "mesh.h=0.2", "--set", "mesh.tip_h=0.05", "--set", "options.contact=none",
                               "--set", "options.friction=0"], None),
    ("penny_crack.toml", [*SMALL_3D, "--set", 'load_path=[{name="half",factors={default=0.5}},'
                                              '{name="full",factors={default=1.0}}]'], None),  # 3D
    # the nodal rescaling (each enriched node's group transformed by the process owning it), 2D and 3D
    ("pressurised_crack.toml", ["--set", "mesh.tip_h=0.1", "--set", "options.radius=0.3",
                                "--set", 'options.rescale="nodal"'], ((1.7835,), 0.01)),
    ("quarter_ellipse.toml", ["--set", "mesh.h=2.0", "--set", "mesh.tip_h=0.2", "--set", "mesh.crack_h=0.3",
                              "--set", 'options.rescale="nodal"'], None)])
def test_run_symmetry_cell_loads_load_path_rescale_same_on_one_and_two_processes(scene, settings, exact, tmp_path):
    """`cracklip run` under mpirun -n 2 of what the distributed model took
    on after open cracks: symmetry planes (the normal component and the
    enriched dofs that would move the plane's nodes out of it fixed on the
    owners' rows; the plane found from every process's tag nodes), a body
    force and an initial stress (integrated on the owned cells, enriched
    ones included, each once), a load path (each group's right-hand side
    assembled once on the distributed matrix, every step solved by parallel
    MUMPS), the nodal rescaling (T^T A T with T built per enriched node by
    its owner). K per point (per step) to 1e-10 of the K scale, the energy
    to 1e-10, the dofs and front points exactly, each condition's reaction
    to 1e-10 of the loads. Measured: quarter ellipse 8e-15, half Griffith
    5e-15, residual stress 1.5e-12 (3D, linear with a divergence: 2.9e-14), body force 2D 1.8e-13, 3D 2.8e-13, load
    path 1.6e-14 (2D, its worst step), 2.3e-14 (3D), nodal rescaling 7e-16 (2D), 1.3e-14
    (quarter ellipse)."""
    out, serial, a, b = _run_both(scene, [*settings, "--no-estimate"], tmp_path)
    assert a["solution"]["dofs"] == b["solution"]["dofs"]
    assert ("solve.rescale" in b["timings"]) == ('options.rescale="nodal"' in settings), b["timings"]
    for key in ("strain_energy", "max_displacement"):
        assert _relative(a["solution"][key], b["solution"][key], abs(a["solution"][key])) <= 1e-10, key
    modes = [k for k in ("K_I", "K_II", "K_III") if a["sifs"][0].get(k) is not None]
    states = [(a["sifs"], b["sifs"])] + [(sa["sifs"], sb["sifs"]) for sa, sb in zip(a["steps"] or [], b["steps"] or [])]
    assert len(a["steps"] or []) == len(b["steps"] or []) == (3 if scene == "frictional_crack.toml" else 2
                                                              if "load_path" in str(settings) else 0)
    for sa, sb in states:
        assert len(sa) == len(sb) > 0
        scale = max(abs(r[k]) for r in sa for k in modes)
        for ra, rb in zip(sa, sb):
            for k in modes:
                assert _relative(ra[k], rb[k], scale) <= 1e-10, (k, ra, rb)
    if exact is not None:  # the method, not just agreement: the least and largest K_I against the closed form
        k_i = sorted(r["K_I"] for r in a["sifs"])
        for got, want in zip((k_i[0], k_i[-1]) if len(exact[0]) > 1 else (k_i[0],), exact[0]):
            assert abs(got / want - 1.0) < exact[1], (got, want)
    if (out / "front.csv").exists():  # 3D: a row per front point per step, the same rows as the serial run's
        rows = [(d / "front.csv").read_text().splitlines() for d in (serial, out)]
        assert rows[0][0] == rows[1][0] and len(rows[0]) == len(rows[1]) == 1 + len(a["sifs"]) * max(
            len(a["steps"] or []), 1)
    if scene == "quarter_ellipse.toml":  # both ends on the planes: their K from the mirrored domains
        ends = [r for r in b["sifs"] if r.get("K_source") == "mirrored_domain"]
        assert len(ends) == 2 and all(abs(r["K_III"]) <= 1e-12 for r in ends), b["sifs"]
    ra, rb = a["reactions"], b["reactions"]
    load = max(ra["load_magnitude"], 2 * a["solution"]["strain_energy"] / a["solution"]["max_displacement"])
    assert [(c["condition"], c["nodes"]) for c in ra["conditions"]] == [(c["condition"], c["nodes"])
                                                                       for c in rb["conditions"]]
    for ca, cb in zip(ra["conditions"], rb["conditions"]):
        assert max(_relative(x, y, load) for x, y in zip(ca["force"], cb["force"])) <= 1e-10, (ca, cb)


def test_symmetry_refusal_and_check_as_serial(tmp_path):
    """A crack meeting a line of symmetry at 73 degrees is refused with the
    serial message, once (each process checks the cells it holds; all raise
    the first finding), exit 2; `cracklip check` of the quarter ellipse (two
    symmetry planes) prints the serial summary."""
    bad = [*HALF_GRIFFITH, "--set", "cracks[0].points=[[0.0,0.0],[1.0,0.3]]"]
    p = mpirun("run", str(SCENES / "pressurised_crack.toml"), *bad, "--out", str(tmp_path / "bad"))
    assert_clean(p, 2)
    errors = [line for line in p.stderr.splitlines() if line.startswith("cracklip: error:")]
    assert len(errors) == 1 and "meets it at 73.3 degrees instead of 90" in errors[0], p.stderr
    args = ["check", str(SCENES / "quarter_ellipse.toml"), "--set", "mesh.h=2.0", "--set", "mesh.tip_h=0.2",
            "--set", "mesh.crack_h=0.3", "--json"]
    p = mpirun(*args)
    assert_clean(p, 0)
    s = _run_serial(*args)
    assert s.returncode == 0, s.stderr
    a, b = json.loads(s.stdout), json.loads(p.stdout)
    assert [c.pop("snapped_nodes") for c in b["model"]["cracks"]] == [None]
    a["model"]["cracks"][0].pop("snapped_nodes")
    assert _same(a, b, 1e-12), (a, b)
def test_run_inclined_penny_iterative_same_on_one_and_two_processes(tmp_path):
    """`cracklip run` of the shipped inclined penny (options.solver =
    "iterative", mixed mode I/II/III) under mpirun -n 2, with the error
    estimate's second mesh solved on both: K and its estimate equal to the
    serial run's to 1e-6 of the K scale (the iterative path's bar; the
    Krylov solves stop at a residual of 1e-10), the solver the iterative one.
    Measured (h 2, tip_h 0.5): K to 8e-11, the estimate to 4e-10."""
    out, serial, a, b = _run_both("inclined_penny.toml", SMALL_3D, tmp_path)
    for r in (a, b):
        assert {s["solver"] for s in r["solution"]["solves"]} == {"iterative"}, r["solution"]
    assert len(a["sifs"]) == len(b["sifs"]) > 0
    scale = max(abs(r[k]) for r in a["sifs"] for k in ("K_I", "K_II", "K_III"))
    for ra, rb in zip(a["sifs"], b["sifs"]):
        assert max(abs(ra[c] - rb[c]) for c in ("x", "y", "z")) <= 1e-12
        for k in ("K_I", "K_II", "K_III"):
            assert _relative(ra[k], rb[k], scale) <= 1e-6, (k, ra, rb)
            assert _relative(ra[k + "_error"], rb[k + "_error"], scale) <= 1e-6, (k, ra, rb)
#: Two load steps of the scene's loads (half, then all of them).
HALF_FULL = ["--set", 'load_path=[{name="half",factors={default=0.5}},{name="full",factors={default=1.0}}]']


@pytest.mark.parametrize("scene, settings", [
    # 2D: the shipped clamp-shear-unload path without its contact (three steps of two load groups)
    ("frictional_crack.toml", ["--set", "mesh.h=0.2", "--set", "mesh.tip_h=0.05", "--set", "options.contact=none",
                               "--set", "options.friction=0"]),
    # 3D: front enrichment, the tip dofs left out of GAMG
    ("penny_crack.toml", ["--set", "mesh.h=2.0", "--set", "mesh.tip_h=0.3", "--set", "mesh.crack_h=0.3",
                          *HALF_FULL])], ids=["frictional-crack-2d", "penny-3d"])
def test_run_iterative_load_path_same_on_one_and_two_processes(scene, settings, tmp_path):
    """`cracklip run` of a load path with options.solver = "iterative"
    under mpirun -n 2 (analysis/load_path.py: the distributed matrix put in
    the phantom-node basis once, the GAMG hierarchy set up on the first
    increment's solve and reused by every later one, as serially): every
    solve (one per increment) iterative, the later ones reusing the set-up,
    K of every step equal to the serial iterative run's to 1e-6 of the K
    scale (the iterative path's bar; the Krylov solves stop at 1e-10), the
    energy to 1e-8. Measured: frictional crack (3 steps, 6 increments)
    1.2e-11 .. 2.2e-11, penny (2 steps) 3.2e-11 .. 5.6e-11."""
    out, serial, a, b = _run_both(scene, [*settings, "--set", 'options.solver="iterative"', "--no-estimate"],
                                  tmp_path)
    for r in (a, b):
        solves = r["solution"]["solves"]
        assert len(solves) >= len(r["steps"]) > 1 and {s["solver"] for s in solves} == {"iterative"}, solves
        assert [s["setup_reused"] for s in solves] == [False] + [True] * (len(solves) - 1), solves
        assert all(s["relative_residual"] <= 1e-10 and 0 < s["iterations"] < 60 for s in solves), solves
    modes = [k for k in ("K_I", "K_II", "K_III") if a["sifs"][0].get(k) is not None]
    states = [(sa["sifs"], sb["sifs"]) for sa, sb in zip(a["steps"], b["steps"])]
    scale = max(abs(r[k]) for sa, _ in states for r in sa for k in modes)
    worst = 0.0
    for sa, sb in states:
        assert len(sa) == len(sb) > 0
        for ra, rb in zip(sa, sb):
            worst = max([worst] + [_relative(ra[k], rb[k], scale) for k in modes])
    assert worst <= 1e-6, worst
    print(scene, "K", worst)
    assert _relative(a["solution"]["strain_energy"], b["solution"]["strain_energy"],
                     a["solution"]["strain_energy"]) <= 1e-8


#: A 2D cantilever under an end shear, its vertical crack across the neutral
#: axis partly closed: the active set changes (7, 6, 5, 4, 4 of 12).
CANTILEVER_2D = """title = "cracked cantilever under an end shear"
[mesh]
kind = "rectangle"
domain = [0.0, 0.0, 4.0, 1.0]
h = 0.1
tip_h = 0.04
tip_radius = 0.2
[material]
E = 1.0
nu = 0.3
[[cracks]]
points = [[1.0, 0.2], [1.0, 0.8]]
[[dirichlet]]
tag = "left"
[[loads.tractions]]
tag = "right"
value = [0.0, -1.0e-5]
[options]
enrichment = "vector"
radius = 0.1
contact = "unilateral"
multipliers = "stable"
sif_radius = 0.1
"""

#: A penny across a bent beam (clamped at x = -4, end shear at x = 4): its
#: lower half pressed shut, the active set changes (2, 1, 1 of 5).
PENNY_BENT_3D = """title = "penny across a bent beam"
[mesh]
kind = "box"
box = [-4.0, -2.0, -2.0, 4.0, 2.0, 2.0]
h = 1.0
tip_h = 0.3
crack_h = 0.3
[material]
E = 1.0
nu = 0.3
[[cracks]]
ellipse = { center = [0.0, 0.0, 0.0], normal = [1.0, 0.0, 0.0], a = 1.0, a_direction = [0.0, 0.0, 1.0] }
[[dirichlet]]
tag = "xmin"
[[loads.tractions]]
tag = "xmax"
value = [0.0, 0.0, -0.01]
[options]
radius = 0.3
contact = "unilateral"
"""


@pytest.mark.parametrize("scene, settings, k_tol", [
    ("block_uniform_pressure.toml", ["--set", "mesh.h=0.1"], 1e-10),   # bilateral, K = 0, p = 0.01 exactly
    ("hole_crack.toml", ["--set", "mesh.h=0.15"], 1e-10),               # unilateral, closed (7 of 7)
    (CANTILEVER_2D, [], 1e-10),                                          # unilateral, partly open
    # a penny under compression and shear: unilateral, closed (19 of 19 multipliers)
    ("penny_crack.toml", ["--set", "mesh.h=2.0", "--set", "mesh.tip_h=0.25", "--set", "mesh.crack_h=0.25",
                          "--set", "options.contact=unilateral", "--set", "loads.tractions[0].value=[0.0,0.3,-1.0]",
                          "--set", "loads.tractions[1].value=[0.0,-0.3,1.0]"], 5e-10),
    (PENNY_BENT_3D, [], 1e-10),                                          # unilateral, partly open
    # a corner crack at a hole (a geometry file), lip pressure and remote compression, without its friction:
    # unilateral, partly closed (2, 1, 1 of 4)
    ("corner_crack_closure.toml", ["--set", "options.friction=0.0", "--set", "mesh.tip_h=0.5", "--set",
                                   "mesh.crack_h=0.5", "--set", "mesh.refine[0].h=0.5", "--set", "options.radius=1.0"],
     1e-10),
], ids=["block-bilateral", "hole-unilateral", "cantilever-partly-open", "penny-closed-3d", "penny-bent-3d",
        "corner-crack-3d"])
def test_run_contact_same_on_one_and_two_processes(scene, settings, k_tol, tmp_path):
    """Crack-lip contact (frictionless, the direct path) under mpirun -n 2
    equals the serial run: the same multipliers, active-set history and
    active count, the contact pressure at every lip sample (2D crack.csv
    with the gap; 3D the crack's pressure statistics) to 1e-8 of its
    largest value, K to k_tol of the K scale (the larger of max |K| and
    p_max sqrt(pi a)), the energy to 1e-10. The P1- groups come from the
    crack band gathered onto every process in input order (contact/band.py),
    the serial run's too. Measured (several runs: the partition varies): K
    to 3e-15 (block), 1e-15 (hole), 3e-13 (cantilever), 3e-14 (penny bent),
    1e-14 (corner crack); pressure to 2e-14, 1e-14, 1e-12, 3e-14, 2e-13.
    The closed penny: K to 2e-11 ..
    6e-11, pressure and the multipliers to 5e-11 .. 3e-10 (at tip_h 0.3,
    5 multipliers: K to 1.2e-10, the multipliers to 4e-10) while the
    energy agrees to 1e-13: the multipliers of a closed 3D front are
    ill-conditioned (a small inf-sup constant), so two MUMPS pivot orders
    give them to ~1e-10 (serial with and without MUMPS iterative refinement
    agree to 6e-14, 2 processes with it differ as much): the 1e-10 target of
    the direct path is not met there; its bound is 5e-10."""
    if scene.startswith("title"):
        path = tmp_path / "scene.toml"
        path.write_text(scene)
        scene = str(path)
    out, serial, a, b = _run_both(scene, [*settings, "--no-estimate"], tmp_path)
    _assert_contact_as_serial(serial, out, a, b, k_tol, p_tol=1e-8)


def _assert_contact_as_serial(serial, out, a: dict, b: dict, k_tol: float, p_tol: float) -> dict:
    """A contact run on 2 processes (out, b its results.json) equals the
    serial one (serial, a): the same multipliers, states, active sets and
    iteration counts (the last state's and every load step's), the files;
    the contact pressure (statistics, and at every lip sample: 2D crack.csv
    with the gap, the shear and the slip of every step, 3D crack_surface.vtu)
    to p_tol of the largest pressure, the gap and slip to p_tol of the
    largest displacement; K of every state (the last, each step's) to k_tol
    of the K scale (the larger of max |K| over the path and p_max sqrt(pi
    a)); the energy to 1e-10. Returns the largest differences found
    (relative to those scales)."""
    assert a["contact"] == b["contact"] and a["contact"]["multipliers"] > 0, (a["contact"], b["contact"])
    assert b["files"] == a["files"]
    steps = list(zip(a["steps"] or [], b["steps"] or []))
    assert len(a["steps"] or []) == len(b["steps"] or [])
    for sa, sb in steps:  # states, active sets and iterations of every load step
        assert sa["contact"] == sb["contact"], (sa["name"], sa["contact"], sb["contact"])
    found = {}
    pa, pb = a["cracks"][0]["pressure"], b["cracks"][0]["pressure"]
    p_max = pa["max"]  # (the last state's; in 2D the largest of every step's samples)
    u_scale = a["cracks"][0]["gap_tolerance"] / 1e-6   # (the largest displacement: io/outputs.py)
    three_d = a["dimension"] == 3
    if three_d:  # at every lip facet vertex (crack_surface.vtu; facets in rank order: sorted)
        import meshio
        va, vb = (meshio.read(d / "crack_surface.vtu").point_data for d in (serial, out))
        for name, scale in (("pressure", p_max), ("shear", p_max), ("gap", u_scale), ("slip", u_scale)):
            if name in va:
                x, y = (np.sort(np.linalg.norm(v[name].reshape(len(v[name]), -1), axis=1)) for v in (va, vb))
                assert x.shape == y.shape
                found[name] = float(np.abs(x - y).max() / scale)
        if "state" in va:
            assert np.array_equal(np.sort(va["state"]), np.sort(vb["state"]))
    else:  # every lip sample of every step (rows sorted by step, crack and s)
        cols = {"pressure": 5, "shear": 6, "gap": 7, "slip": 8}
        csv_files = [d / "crack.csv" for d in (serial, out)]
        rows = [np.loadtxt(f, delimiter=",", skiprows=1, usecols=(0, 1, 2, 5, 6, 7, 8)) for f in csv_files]
        states = [np.loadtxt(f, delimiter=",", skiprows=1, usecols=(9,), dtype=str) for f in csv_files]
        order = [np.lexsort((r[:, 2], r[:, 1], r[:, 0])) for r in rows]
        rows = [r[o] for r, o in zip(rows, order)]
        assert rows[0].shape == rows[1].shape and np.array_equal(rows[0][:, :2], rows[1][:, :2])
        assert np.array_equal(states[0][order[0]], states[1][order[1]])  # open / stick / slip at every sample
        p_max = max(p_max, float(np.abs(rows[0][:, 3]).max()))
        for name, col in cols.items():
            j = col - 2
            scale = p_max if name in ("pressure", "shear") else max(np.abs(rows[0][:, j]).max(), u_scale)
            found[name] = float(np.abs(rows[0][:, j] - rows[1][:, j]).max() / scale)
    assert p_max > 0.0
    found["pressure_statistics"] = max(_relative(pa[key], pb[key], p_max) for key in pa)
    for name, diff in found.items():
        assert diff <= p_tol, (name, found)
    size = np.sqrt(a["cracks"][0]["area_in_part"]) if three_d else a["cracks"][0]["length_in_part"]
    comps = ("K_I", "K_II", "K_III") if three_d else ("K_I", "K_II")
    sifs = [(a["sifs"], b["sifs"])] + [(sa["sifs"], sb["sifs"]) for sa, sb in steps]
    scale = max(max(abs(r[k]) for sa, _ in sifs for r in sa for k in comps), p_max * np.sqrt(np.pi * size))
    found["K"] = 0.0
    for sa, sb in sifs:
        assert len(sa) == len(sb) > 0
        for ra, rb in zip(sa, sb):
            for k in comps:
                found["K"] = max(found["K"], _relative(ra[k], rb[k], scale))
                assert _relative(ra[k], rb[k], scale) <= k_tol, (k, ra, rb)
    assert _relative(a["solution"]["strain_energy"], b["solution"]["strain_energy"],
                     a["solution"]["strain_energy"]) <= 1e-10
    return found


#: The four shipped friction scenes on small meshes (a few seconds per process).
FRICTION_SCENES = {
    "frictional_crack.toml": ["--set", "mesh.h=0.2", "--set", "mesh.tip_h=0.05"],
    "brazilian_disc.toml": ["--set", "mesh.h=8", "--set", "mesh.tip_h=1.0"],
    "wing_crack.toml": ["--set", "mesh.h=0.3", "--set", "mesh.refine[0].h=0.04", "--set", "mesh.refine[0].radius=0.6",
                        "--set", "options.radius=0.15"],
    "corner_crack_closure.toml": ["--set", "mesh.tip_h=0.5", "--set", "mesh.crack_h=0.5", "--set",
                                  "mesh.refine[0].h=0.5", "--set", "options.radius=1.0"]}
#: Two load steps of the same loads (half, then all of them), each in two increments.
TWO_STEPS = ["--set", 'load_path=[{name="half",factors={default=0.5}},{name="full",factors={default=1.0}}]',
             "--set", "options.load_steps=2"]


def _states(open_: int, stick: int, slip: int) -> dict:
    return {"open": open_, "stick": stick, "slip": slip}


@pytest.mark.parametrize("scene, settings, states", [
    *[(scene, settings, None) for scene, settings in FRICTION_SCENES.items()],
    # 2D, unilateral: open, stick and slip at once (5 iterations)
    (CANTILEVER_2D, ["--set", "options.friction=0.5"], [_states(8, 2, 2)]),
    # the shipped clamp-shear-unload path with a smaller coefficient: every multiplier slips at "shear up"
    # (its shear / pressure is 0.7 everywhere: mu = 0.7 would put every one on the Coulomb cone to round-off,
    # stick or slip by the last bit, which differed between runs; |tau| / (mu p) = 1.077 here)
    ("frictional_crack.toml", [*FRICTION_SCENES["frictional_crack.toml"], "--set", "options.friction=0.65"],
     [_states(0, 16, 0), _states(0, 0, 16), _states(0, 16, 0)]),
    # 3D: the penny across the bent beam, one multiplier slipping (its direction by the Newton rows)
    (PENNY_BENT_3D, ["--set", "options.friction=0.5"], [_states(3, 0, 1)]),
    # frictionless contact along a load path: the active set carried from increment to increment
    (CANTILEVER_2D, TWO_STEPS, None)],
    ids=["frictional-crack", "brazilian-disc", "wing-crack", "corner-crack-3d", "cantilever-stick-slip",
         "frictional-crack-mu-0.65", "penny-bent-3d", "cantilever-load-path"])
def test_run_friction_and_contact_path_same_on_one_and_two_processes(scene, settings, states, tmp_path):
    """Coulomb friction (2D and 3D) and frictionless contact along a load
    path under mpirun -n 2 (analysis/load_path.py: the friction system's
    normal, tangential and slip rows bordering the distributed stiffness,
    solvers/saddle.py bordered_matrix, solved by parallel MUMPS; the
    multipliers broadcast from the process holding them, B u and B_t u
    summed over the processes' owned dofs, so every process takes the same
    states, slip directions and active sets; the slips and states carried
    from increment to increment) equal the serial run: states, active sets
    and iteration counts of every step exactly, pressures, shears, gaps and
    slips at every lip sample and K of every step to 1e-10 (the direct
    path's target). Measured (the larger of two runs: the partition
    varies), K / the lip samples' pressure, shear and slip: frictional crack
    (its 3 steps) 2e-14 / 1e-11, Brazilian disc 9e-14 / 8e-12, wing crack
    2e-14 / 2e-12, corner crack 5e-13 / 4e-13, cantilever with stick and
    slip 2e-12 / 2e-12, the frictional crack at mu 0.65 2e-14 / 1e-12, bent
    penny 2.4e-12 / 4e-12, the cantilever's load path 9e-13 / 3e-12."""
    if scene.startswith("title"):
        path = tmp_path / "scene.toml"
        path.write_text(scene)
        scene = str(path)
    out, serial, a, b = _run_both(scene, [*settings, "--no-estimate"], tmp_path)
    found = _assert_contact_as_serial(serial, out, a, b, k_tol=1e-10, p_tol=1e-10)
    print(scene, found)
    path_case = "load_path" in str(settings)
    assert ("states" in a["contact"]) != path_case, a["contact"]
    if states is not None:  # the states the case is chosen for (each step's)
        assert [s["contact"]["states"] for s in a["steps"] or [a]] == states, a["contact"]
    if path_case:  # the active set carried: the later increments start settled
        incs = [s["contact"]["increment_iterations"] for s in a["steps"]]
        assert len(incs) == 2 and incs[0][0] > 1 and incs[1] == [1, 1], incs


@pytest.mark.parametrize("scene", list(FRICTION_SCENES))
def test_check_friction_scene_same_on_one_and_two_processes(scene):
    """`cracklip check --json` of each shipped friction scene under mpirun
    -n 2: the model's and the contact summary equal to serial (the
    friction coefficient, multipliers and groups from the gathered band)."""
    args = ["check", str(SCENES / scene), *FRICTION_SCENES[scene], "--json"]
    p = mpirun(*args)
    assert_clean(p, 0)
    s = _run_serial(*args)
    assert s.returncode == 0, s.stderr
    a, b = json.loads(s.stdout), json.loads(p.stdout)
    for c in a["model"]["cracks"] + b["model"]["cracks"]:  # (a per-process count: null under mpirun)
        c.pop("snapped_nodes")
    assert a["model"]["contact"]["multipliers"] > 0
    assert _same(a, b, 1e-12), (a, b)


#: options.rescale = "nodal" by --set.
NODAL = ["--set", 'options.rescale="nodal"']
#: The iterative solver by --set.
ITERATIVE = ["--set", 'options.solver="iterative"']


@pytest.mark.parametrize("basis, k_tol", [(NODAL, 1e-10), (ITERATIVE, 1e-6)], ids=["nodal", "iterative"])
@pytest.mark.parametrize("scene, settings", [
    ("block_uniform_pressure.toml", ["--set", "mesh.h=0.1"]),          # bilateral
    ("hole_crack.toml", ["--set", "mesh.h=0.15"]),                      # unilateral, closed
    (CANTILEVER_2D, []),                                                 # unilateral, partly open
    (PENNY_BENT_3D, []),                                                 # 3D, partly open
    ("frictional_crack.toml", FRICTION_SCENES["frictional_crack.toml"]),  # friction along its 3-step load path
    (PENNY_BENT_3D, ["--set", "options.friction=0.5"]),                 # 3D friction, one multiplier slipping
    (CANTILEVER_2D, TWO_STEPS)],                                         # frictionless along a load path
    ids=["block-bilateral", "hole-unilateral", "cantilever-partly-open", "penny-bent-3d", "frictional-crack",
         "penny-bent-friction-3d", "cantilever-load-path"])
def test_run_contact_in_a_solver_basis_same_on_one_and_two_processes(scene, settings, basis, k_tol, tmp_path):
    """Crack-lip contact in a solver path's basis under mpirun -n 2: the
    constraints act on u = T y, so the contact system is taken in that
    basis, B T and B_t T (solvers/rescaling.py times_basis: each process's
    columns of B times its rows of the distributed T, summed; whole on
    every process, as B is), the distributed saddle point bordering T^T K T
    (one AIJ, the multiplier rows on the last process). Nodal rescaling
    (options.rescale = "nodal", parallel MUMPS) and the iterative path
    (options.solver = "iterative", the phantom-node basis: the serial
    path's Krylov + Schwarz {MUMPS band | GAMG | band} with every
    multiplier in the band, CG, GMRES(30) for friction's unsymmetric rows,
    warm-started from the last active set's solution). Frictionless
    (single solve and along a load path) and with Coulomb friction, 2D and
    3D: the same multipliers, active sets, states and iteration counts as
    serial (in the same basis), the pressure at every lip sample and K of
    every step to k_tol (1e-10, the direct path's target; 1e-6 the
    iterative one's) of their largest / the K scale. Measured (K / the
    largest difference at the lip samples and in the pressure
    statistics), nodal: block 2e-15 / 2e-14, hole 9e-16 / 4e-15,
    cantilever 5e-13 / 1e-12, bent penny 4e-14 / 5e-13, frictional crack
    (3 steps) 2e-14 / 1e-12, bent penny with friction 3e-13 / 3e-12, the
    cantilever's load path 4e-13 / 1e-12; iterative: block 2.4e-12 /
    2.2e-12, hole 5e-13 / 3e-12, cantilever 2.5e-13 / 1e-12, bent penny
    3.5e-13 / 3.2e-12, frictional crack 1.1e-11 / 5.4e-11, bent penny with
    friction 1.3e-12 / 1.3e-11, the cantilever's load path 7.6e-13 /
    2e-12, CG or GMRES iterations per solve within 3 of serial."""
    if scene.startswith("title"):
        path = tmp_path / "scene.toml"
        path.write_text(scene)
        scene = str(path)
    out, serial, a, b = _run_both(scene, [*settings, *basis, "--no-estimate"], tmp_path)
    for r in (a, b):
        solvers = {s["solver"] for s in r["solution"]["solves"]}
        if basis is NODAL:
            assert "solve.rescale" in r["timings"] and solvers == {"direct"}, r["solution"]["solves"]
        else:
            assert solvers == {"iterative"}, r["solution"]["solves"]
    found = _assert_contact_as_serial(serial, out, a, b, k_tol=k_tol, p_tol=k_tol)
    its = [[s.get("iterations") for s in r["solution"]["solves"]] for r in (a, b)]
    print(scene[-30:], found, "iterations serial / 2 processes", its)


def _two_groups(scene: str, tag: str, shear: str, axial: str) -> str:
    """The scene with its one traction on `tag` as load group "shear" and an
    axial traction on the same face as group "axial"."""
    old = f'value = {shear}\n'
    assert scene.count(old) == 1
    return scene.replace(old, f'{old}group = "shear"\n[[loads.tractions]]\ntag = "{tag}"\nvalue = {axial}\n'
                                   'group = "axial"\n')


#: Load levels of the cantilever (end shear, axial pull) and their contact
#: states measured serially: partly closed (4 of 12 active), open, closed
#: (12), a linear level between, partly closed from the closed set, the
#: other half closed (3 of 12), then the same from there (1 iteration).
LEVELS_2D = [[True, {"shear": 1.0}], [True, {"axial": 1.0}], [True, {"axial": -1.0}],
             [False, {"shear": 1.0, "axial": -0.5}], [True, {"shear": 1.0, "axial": -0.5}],
             [True, {"shear": -1.0, "axial": 0.3}], [True, {"shear": -1.0}]]
#: The penny across the beam: its lower half closed (1 of 5), closed (5),
#: linear, open, the upper half closed (3).
LEVELS_3D = [[True, {"shear": 1.0}], [True, {"axial": -1.0}], [False, {"shear": 1.0}], [True, {"axial": 1.0}],
             [True, {"shear": -1.0, "axial": 0.1}]]


LEVEL_SCENES = [_two_groups(CANTILEVER_2D, "right", "[0.0, -1.0e-5]", "[1.0e-5, 0.0]"),
                _two_groups(PENNY_BENT_3D, "xmax", "[0.0, 0.0, -0.01]", "[0.01, 0.0, 0.0]")]


@pytest.mark.parametrize("scene, levels, settings, k_tol", [
    (LEVEL_SCENES[0], LEVELS_2D, [], 1e-10),
    (LEVEL_SCENES[1], LEVELS_3D, [], 1e-10),
    # nodally rescaled: the levels' contact system B T (times_basis) on T^T K T
    (LEVEL_SCENES[0], LEVELS_2D, ['options.rescale="nodal"'], 1e-10),
    (LEVEL_SCENES[1], LEVELS_3D, ['options.rescale="nodal"'], 1e-10),
    # the iterative path: B T in the phantom basis, GAMG set up once for every level and active set
    (LEVEL_SCENES[0], LEVELS_2D, ['options.solver="iterative"'], 1e-6),
    (LEVEL_SCENES[1], LEVELS_3D, ['options.solver="iterative"'], 1e-6)],
    ids=["2d", "3d", "2d-nodal", "3d-nodal", "2d-iterative", "3d-iterative"])
def test_levels_with_contact_same_on_one_and_two_processes(scene, levels, settings, k_tol, tmp_path):
    """A fatigue life's load levels with frictionless contact
    (analysis.load_path.LevelSolver: one assembly, each level warm-started
    from the last one's active set, parallel MUMPS on the distributed saddle
    point) under mpirun -n 2 equal the serial ones: the same active sets
    and active-set histories at every level (open, partly and wholly closed
    ones, a linear level between), the multipliers to 1e-8 of their
    largest, K to 1e-10 of the K scale. Measured: 2D K to 7e-12, the
    multipliers to 1e-12; 3D K to 4e-11 (the closed penny; 4e-13
    elsewhere), the multipliers to 8e-10 (closed) and 3e-13: the closed 3D
    front's ill-conditioned multipliers (test_run_contact_same_on_one_and_two_processes).
    Nodally rescaled (options.rescale = "nodal"): 2D K to 1.1e-12, the
    multipliers to 1.4e-12; 3D K to 2.9e-11, the multipliers to 4.4e-11.
    On the iterative path (its bar: K to 1e-6, the multipliers to 1e-6 of
    their largest; every solve iterative, the levels after the first
    reusing GAMG): 2D K to 2.9e-12, the multipliers to 2.9e-12; 3D K to
    2.5e-11, the multipliers to 7.6e-11."""
    path = tmp_path / "scene.toml"
    path.write_text(scene)
    one, two = script_on_one_and_two("levels.py", str(path), json.dumps(levels), *settings)
    assert (one["processes"], two["processes"], one["solves"], two["solves"]) == (1, 2, len(levels), len(levels))
    a, b = one["levels"], two["levels"]
    assert [(x["contact"], x["active"], x["history"]) for x in a] == [(x["contact"], x["active"], x["history"])
                                                                       for x in b]
    counts = [sum(x["active"]) for x in a if x["contact"]]
    m = len(a[0]["active"])
    assert 0 in counts and m in counts and any(0 < c < m for c in counts), counts  # open, closed, partly
    lam = max(max(np.abs(x["lambda"]), default=0.0) for x in a)
    assert max(max(np.abs(np.subtract(x["lambda"], y["lambda"])), default=0.0) for x, y in zip(a, b)) <= \
        max(1e-8, k_tol) * lam
    solver = "iterative" if settings == ['options.solver="iterative"'] else "direct"
    for run in (one, two):
        assert [x["solver"] for x in run["levels"]] == [solver] * len(levels), run["levels"]
        assert [x["reused"] for x in run["levels"]] == [solver == "iterative" and k > 0 for k in range(len(levels))]
    scale = max(np.abs(x["sifs"]).max() for x in a)
    print("levels lambda", max(max(np.abs(np.subtract(x["lambda"], y["lambda"])), default=0.0)
                               for x, y in zip(a, b)) / lam,
          "K", max(np.abs(np.subtract(x["sifs"], y["sifs"])).max() for x, y in zip(a, b)) / scale)
    assert max(np.abs(np.subtract(x["sifs"], y["sifs"])).max() for x, y in zip(a, b)) <= k_tol * scale


@pytest.mark.parametrize("scene", [_two_groups(CANTILEVER_2D, "right", "[0.0, -1.0e-5]", "[1.0e-5, 0.0]"),
                                   _two_groups(PENNY_BENT_3D, "xmax", "[0.0, 0.0, -0.01]", "[0.01, 0.0, 0.0]")],
                         ids=["2d", "3d"])
def test_levels_iterative_same_on_one_and_two_processes(scene, tmp_path):
    """A fatigue life's load levels without contact on the iterative path
    (analysis.load_path.LevelSolver, options.solver = "iterative") under
    mpirun -n 2: the distributed matrix put in the phantom-node basis once,
    GAMG set up by the first level's solve and reused by the later ones, as
    serially; K of every level equal to the serial iterative K to 1e-6 of
    the K scale. Measured: 2D 2.1e-12, 3D 5e-12."""
    path = tmp_path / "scene.toml"
    path.write_text(scene)
    levels = [[False, {"shear": 1.0}], [False, {"axial": 1.0}], [False, {"shear": -1.0, "axial": 0.3}]]
    one, two = script_on_one_and_two("levels.py", str(path), json.dumps(levels), "options.contact=none",
                                     'options.solver="iterative"')
    assert (one["processes"], two["processes"], one["solves"], two["solves"]) == (1, 2, 3, 3)
    for run in (one, two):
        assert [(x["solver"], x["reused"], x["contact"]) for x in run["levels"]] == \
            [("iterative", False, False)] + [("iterative", True, False)] * 2, run
    a, b = one["levels"], two["levels"]
    scale = max(np.abs(x["sifs"]).max() for x in a)
    worst = max(np.abs(np.subtract(x["sifs"], y["sifs"])).max() for x, y in zip(a, b)) / scale
    print("levels K", worst)
    assert worst <= 1e-6


def test_3d_crack_in_one_corner_and_outside(tmp_path):
    """A small penny near the top face (most likely on one process's cells
    only; the other's part holds none of it) gives the serial K; a penny
    outside the part is one error, printed once, on every process (exit 2)."""
    small = [*SMALL_3D, "--set", "cracks[0].ellipse.center=[0.0,0.0,3.5]", "--set", "cracks[0].ellipse.a=0.2",
             "--no-estimate"]
    out, serial = tmp_path / "mpi", tmp_path / "serial"
    p = mpirun("run", str(SCENES / "penny_crack.toml"), *small, "--out", str(out))
    assert_clean(p, 0)
    s = _run_serial("run", str(SCENES / "penny_crack.toml"), *small, "--out", str(serial), "-q")
    assert s.returncode == 0, s.stderr
    a, b = (json.loads((d / "results.json").read_text())["sifs"] for d in (serial, out))
    scale = max(abs(r[k]) for r in a for k in ("K_I", "K_II", "K_III"))
    assert len(a) == len(b) > 0
    assert max(_relative(ra[k], rb[k], scale) for ra, rb in zip(a, b) for k in ("K_I", "K_II", "K_III")) <= 1e-10
    p = mpirun("run", str(SCENES / "penny_crack.toml"), *SMALL_3D, "--set", "cracks[0].ellipse.center=[0.0,0.0,30]",
               "--out", str(tmp_path / "outside"))
    assert_clean(p, 2)
    errors = [line for line in p.stderr.splitlines() if line.startswith("cracklip: error:")]
    assert len(errors) == 1 and "no cell of the mesh is cut by the crack" in errors[0], p.stderr


def test_check_3d_open_crack_same_on_one_and_two_processes():
    """`cracklip check` of the penny under mpirun -n 2: the 3D model's summary
    (counts, front, front element sizes, crack area, quadrature) and its
    warnings equal to serial (snapped_nodes, a per-process count, null)."""
    args = ["check", str(SCENES / "penny_crack.toml"), *SMALL_3D]
    p = mpirun(*args, "--json")
    assert_clean(p, 0)
    s = _run_serial(*args, "--json")
    assert s.returncode == 0, s.stderr
    a, b = json.loads(s.stdout), json.loads(p.stdout)
    assert [c.pop("snapped_nodes") for c in b["model"]["cracks"]] == [None]
    a["model"]["cracks"][0].pop("snapped_nodes")
    assert _same(a, b, 1e-12), (a, b)


def test_check_open_crack_same_on_one_and_two_processes():
    """`cracklip check` of an open 2D crack under mpirun -n 2: the model built
    as `run` builds it, its summary (every count over the processes' owned
    cells and nodes), the scene notes and the model warnings printed once by
    rank 0, equal to serial (snapped_nodes, a per-process count, null)."""
    args = ["check", str(SCENES / "interacting_cracks.toml"), "--set", "mesh.h=0.1", "--set", "mesh.tip_h=0.02"]
    p = mpirun(*args, "--json")
    assert_clean(p, 0)
    s = _run_serial(*args, "--json")
    assert s.returncode == 0, s.stderr
    a, b = json.loads(s.stdout), json.loads(p.stdout)
    assert [c.pop("snapped_nodes") for c in b["model"]["cracks"]] == [None, None]
    for c in a["model"]["cracks"]:
        c.pop("snapped_nodes")
    assert _same(a, b, 1e-12), (a, b)  # (lengths and sizes summed in another order: round-off)
    p = mpirun(*args)
    assert_clean(p, 0)
    assert p.stdout.count(": valid") == 1 and p.stdout.count("run writes: ") == 1, p.stdout
    assert p.stderr.count("cracklip: warning:") == 4, p.stderr


@pytest.mark.parametrize("scene, settings", [("block_uniform_pressure.toml", ["--set", "mesh.h=0.1"]),
                                             (PENNY_BENT_3D, [])], ids=["block", "penny-bent-3d"])
def test_check_contact_same_on_one_and_two_processes(scene, settings, tmp_path):
    """`cracklip check --json` of a contact scene under mpirun -n 2: the
    contact summary (multipliers, full and P0 multipliers, segments or lip
    pieces) is the gathered band's, the whole crack's, equal to serial (4
    of 10 full on 8 segments for the block; 4 for the bent penny; 5 and 5
    while the P1- groups followed the node order)."""
    if scene.startswith("title"):
        path = tmp_path / "scene.toml"
        path.write_text(scene)
        scene = str(path)
    args = ["check", str(SCENES / scene), *settings, "--json"]
    p = mpirun(*args)
    assert_clean(p, 0)
    s = _run_serial(*args)
    assert s.returncode == 0, s.stderr
    a, b = json.loads(s.stdout)["model"]["contact"], json.loads(p.stdout)["model"]["contact"]
    assert a == b and a["multipliers"] == 4, (a, b)


def test_no_import_thread_under_a_launcher(monkeypatch):
    """Under mpirun the command line imports PETSc in the main thread: the
    background import beside the first collective (the scene's agreement)
    killed 6 of 8 four-process runs of the pressurised crack at start-up
    (UnpicklingError, 'General MPI error'); 0 of 6 without the thread."""
    from cracklip.cli import prefetch
    from cracklip.scene.processes import LAUNCHER_SIZE, launched_on_several
    for name in LAUNCHER_SIZE:
        monkeypatch.delenv(name, raising=False)
    assert not launched_on_several()
    monkeypatch.setenv("OMPI_COMM_WORLD_SIZE", "1")
    assert not launched_on_several()
    monkeypatch.setenv("OMPI_COMM_WORLD_SIZE", "4")
    assert launched_on_several()
    loading = prefetch.start(("json",))
    assert loading.thread is None
    loading.close()
    monkeypatch.delenv("OMPI_COMM_WORLD_SIZE")
    monkeypatch.setenv("PMI_SIZE", "2")
    assert prefetch.start(("json",)).thread is None
    monkeypatch.delenv("PMI_SIZE")
    loading = prefetch.start(("json",))
    assert loading.thread is not None
    loading.close()
    loading.thread.join(5.0)
    assert not loading.thread.is_alive()


def _grow_both(scene: str, settings: list[str], tmp_path) -> tuple:
    """`cracklip grow` of a shipped scene under mpirun -n 2 (the progress
    lines and the summary printed once) and serially: (the two output
    directories, serial and mpi results.json)."""
    out, serial = tmp_path / "mpi", tmp_path / "serial"
    p = mpirun("grow", str(SCENES / scene), *settings, "--out", str(out))
    assert_clean(p, 0)
    assert p.stdout.count("results in ") == 1, p.stdout
    assert p.stderr.count("cracklip grow: step 1:") == 1, p.stderr
    s = _run_serial("grow", str(SCENES / scene), *settings, "--out", str(serial), "-q")
    assert s.returncode == 0, s.stderr
    a, b = (json.loads((d / "results.json").read_text()) for d in (serial, out))
    assert b["files"] == a["files"] and all((out / f).is_file() for f in a["files"])
    assert (a["steps"], a["stop_reason"], a["stops"]) == (b["steps"], b["stop_reason"], b["stops"])
    assert a["warnings"] == b["warnings"] and a["step_solves"] == b["step_solves"]
    return out, serial, a, b


def _largest_difference(a: list[float], b: list[float]) -> float:
    """max |a - b| over the largest |a|."""
    x, y = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    assert x.shape == y.shape
    return float(np.abs(x - y).max() / max(np.abs(x).max(), 1e-300))


def _life_cycles_same(a: dict, b: dict) -> None:
    """A fatigue life's cycles of a serial and a 2-process grow (results.json
    life): the same load states closed by contact and solved with it at
    every step, each step's largest cycle (K_max, K_min: with contact
    closure the contact's K at the closed levels; Delta K_eff) to 1e-10 of
    the largest K_max."""
    la, lb = a["life"], b["life"]
    assert (la["closure_per_step"], la["level_solves"], la["load_levels_per_step"]) == \
        (lb["closure_per_step"], lb["level_solves"], lb["load_levels_per_step"])
    rows = [[t for st in life["steps"] for t in st["tips"]] for life in (la, lb)]
    assert len(rows[0]) == len(rows[1]) > 0
    scale = max(abs(t["K_max"]) for t in rows[0] if t["K_max"] is not None)
    for key in ("K_max", "K_min", "delta_K_eff"):
        x, y = ([t[key] for t in r] for r in rows)
        assert [v is None for v in x] == [v is None for v in y], key
        assert max(abs(u - v) for u, v in zip(x, y) if u is not None) <= 1e-10 * scale, key


@pytest.mark.parametrize("scene, settings", [
    # fatigue at R = -1: the cycle's two loads on one distributed assembly; the ParaView series and PNGs
    ("hole_fatigue.toml", ["--set", "mesh.refine[0].h=1.0", "--set", "mesh.h=40", "--set", "growth.steps=3"]),
    # fixed increments, point forces, three holes (the path's clipping at the boundary from every process)
    ("drilled_plate.toml", ["--set", "mesh.refine[0].h=0.08", "--set", "mesh.refine[1].h=0.08", "--set", "mesh.h=0.8",
                            "--set", "growth.steps=4", "--set", "growth.da=0.3", "--set", "outputs.vtu=false"]),
    # a flight-spectrum life without contact (Newman closure): the ligament's net-section stress from the
    # processes owning its points (Solution.gradient_anywhere)
    ("hole_crack_spectrum.toml", ["--set", "options.contact=none", "--set", "material.fatigue.closure=newman",
                                  "--set", "mesh.refine[0].h=1.0", "--set", "mesh.h=10", "--set", "growth.steps=2",
                                  "--set", "outputs.vtu=false"]),
    # fatigue at R = -0.5 with unilateral contact: the cycle [max, min] a load path with contact (the lips
    # shut at the minimum load), the active set carried from the maximum to the minimum
    ("fatigue_edge_crack.toml", ["--set", "mesh.h=0.15", "--set", "mesh.refine[0].h=0.03", "--set", "growth.steps=2",
                                 "--set", "outputs.vtu=false"]),
    # fixed increments from a closed crack sliding with Coulomb friction (each step's friction solve)
    ("wing_crack.toml", [*FRICTION_SCENES["wing_crack.toml"], "--set", "growth.steps=2", "--set", "outputs.vtu=false"])])
def test_grow_2d_open_crack_same_on_one_and_two_processes(scene, settings, tmp_path):
    """`cracklip grow` of a shipped open 2D crack under mpirun -n 2: every
    decision (kink, increment, stops, warnings) taken alike on both
    processes from K summed over them, the files written once (rank 0), the
    path equal to the serial one: tip positions to 1e-8 of the part's
    coordinates, K and the kink to 1e-8 of their largest values, the cycles
    to 1e-8 (issue 40 asks 1e-6). Measured (the largest of three runs):
    hole_fatigue (K_I 652.8 -> 692.4 over 3 steps) positions equal to 7e-15
    of the part, K_I to 1e-13, K_II to 1e-11 of its largest, N to 2.4e-13;
    drilled plate K_I to 6e-14, K_II 7e-13; the spectrum life (K_I 308 ->
    351, 2 steps) K_I to 4e-14, N to 9e-14, the residual strength to 4e-14;
    the fatigue edge crack with contact (K_I 1.074 -> 1.264, 2 steps) K_I
    to 1e-15, K_II to 4e-11 of its largest (6e-4), N to 1e-15; the wing
    crack with friction (2 steps, 2 tips) K to 7e-14, the kink to 2e-13. (The hole_fatigue path left the serial one by
    2.3e-4 in K at step 1 in half of the runs until the SIF domain's
    admissible radius stopped short of its bounding node:
    tip_regions.RADIUS_MARGIN.) On the iterative path (options.solver =
    "iterative", run by test_grow_life_closed_by_contact_same_on_one_and_
    two_processes) the bar is issue 40's 1e-6 for growth paths: the
    fatigue edge crack's K_II (3.8e-4 against K_I 1.1) to 7.5e-8 of its
    own largest (2.3e-11 of K_I), the rest to 1e-8."""
    out, serial, a, b = _grow_both(scene, settings, tmp_path)
    tol = 1e-6 if 'options.solver="iterative"' in settings else 1e-8
    tips = [[r for step in res["per_step"] for r in step["tips"]] for res in (a, b)]
    assert [(r["crack"], r["end"], r["status"]) for r in tips[0]] == \
        [(r["crack"], r["end"], r["status"]) for r in tips[1]]
    assert len(tips[0]) >= 3
    size = max(abs(v) for r in tips[0] for v in (r["x"], r["y"]))
    for key in ("x", "y", "length"):
        assert max(abs(ra[key] - rb[key]) for ra, rb in zip(*tips)) <= tol * size, key
    for key in ("K_I", "K_II", "kink_deg", "N"):
        assert _largest_difference([r[key] for r in tips[0]], [r[key] for r in tips[1]]) <= tol, key
    if a["cycles"] is not None:
        assert _relative(a["cycles"], b["cycles"], a["cycles"]) <= tol
    if a["life"] is not None:  # the residual strength per step (from the ligament's net-section stress)
        rs = [[c["multiple"] for c in res["life"]["residual_strength"]] for res in (a, b)]
        assert len(rs[0]) > 0 and _largest_difference(*rs) <= tol
        _life_cycles_same(a, b)
    pa, pb = (np.asarray(res["final"]["cracks"][0]["points"]) for res in (a, b))
    assert pa.shape == pb.shape and np.abs(pa - pb).max() <= tol * size
    rows = [(d / "path.csv").read_text().splitlines() for d in (serial, out)]
    assert rows[0][0] == rows[1][0] and len(rows[0]) == len(rows[1])


@pytest.mark.parametrize("scene, settings", [
    # constant amplitude (Paris), net-section yield watched: the front's ends on the free surface
    ("surface_crack_growth.toml", ["--set", "mesh.h=10", "--set", "mesh.refine[0].h=1.0",
                                   "--set", "mesh.refine[0].radius=12", "--set", "growth.steps=3"]),
    # a flight spectrum, Newman closure, a geometry file: a corner crack at a bore
    ("corner_crack_growth.toml", ["--set", "mesh.h=8", "--set", "mesh.refine[0].h=0.4",
                                  "--set", "mesh.refine[0].radius=10", "--set", "growth.steps=2",
                                  "--set", "outputs.vtu=false"])])
def test_grow_3d_open_crack_same_on_one_and_two_processes(scene, settings, tmp_path):
    """`cracklip grow` of a shipped open 3D crack under mpirun -n 2: the
    crack surface grown alike on both processes (the inside-tests, the
    part's faces, the front's element size and the net-section stress over
    every process), the files written once, equal to the serial run: the
    front points, K along the front and the crack's shape (a, c) to 1e-8,
    the cycles and flights to 1e-8 (issue 40 asks 1e-6). Measured (the
    largest of three runs): surface crack (a 2.0 -> 3.08 in 3 steps, 4-5
    front points) K_I to 4e-12, K_II to 1.5e-10 of its largest, a to
    1.1e-12, the cycles to 5e-12; corner crack (flight spectrum, Newman
    closure, 2 steps) K_I to 3.5e-12, K_III to 1.3e-10 of its largest, the
    cycles to 4e-12."""
    out, serial, a, b = _grow_both(scene, settings, tmp_path)
    assert a["cycles"] > 0 and _relative(a["cycles"], b["cycles"], a["cycles"]) <= 1e-8
    for sa, sb in zip(a["per_step"], b["per_step"]):
        assert _relative(sa["cycles"], sb["cycles"], a["cycles"]) <= 1e-8
        assert _largest_difference(sa["K_I_range"], sb["K_I_range"]) <= 1e-8
        assert sa["shape"].keys() == sb["shape"].keys()
        for c in sa["shape"]:
            ka, kb = sa["shape"][c], sb["shape"][c]
            assert (ka["kind"], ka["points"]) == (kb["kind"], kb["points"])
            for key in ("a", "c", "radius_mean"):
                if ka.get(key) is not None:
                    assert _relative(ka[key], kb[key], ka[key]) <= 1e-8, key
    assert len(a["per_step"]) == a["steps"] + 1 > 2
    rows = [list(csv.DictReader((d / "front_path.csv").open())) for d in (serial, out)]
    assert len(rows[0]) == len(rows[1]) > 4
    assert [(r["step"], r["point"]) for r in rows[0]] == [(r["step"], r["point"]) for r in rows[1]]
    size = max(abs(float(r[k])) for r in rows[0] for k in ("x", "y", "z"))
    for key in ("x", "y", "z"):
        assert max(abs(float(ra[key]) - float(rb[key])) for ra, rb in zip(*rows)) <= 1e-8 * size, key
    for key in ("K_I", "K_II", "K_III", "da", "cycles"):
        assert _largest_difference([float(r[key]) for r in rows[0]], [float(r[key]) for r in rows[1]]) <= 1e-8, key
    if a["life"] is not None:
        _life_cycles_same(a, b)


@pytest.mark.parametrize("grown_same, scene, settings", [
    # a flight spectrum at a hole: the ground levels close the lips (2 of 26 load states, solved with contact)
    (test_grow_2d_open_crack_same_on_one_and_two_processes, "hole_crack_spectrum.toml",
     ["--set", "mesh.refine[0].h=1.0", "--set", "mesh.h=10", "--set", "growth.steps=2", "--set", "outputs.vtu=false"]),
    # ground-air-ground flights: the ground level closes the corner crack (3D contact)
    (test_grow_3d_open_crack_same_on_one_and_two_processes, "corner_crack_gag.toml",
     ["--set", "mesh.refine[0].h=0.2", "--set", "options.radius=0.5", "--set", "growth.steps=2",
      "--set", "outputs.vtu=false"]),
    # the spectrum life at a hole on the iterative path (its levels' contact solves by CG on the saddle point)
    (test_grow_2d_open_crack_same_on_one_and_two_processes, "hole_crack_spectrum.toml",
     ["--set", "mesh.refine[0].h=1.0", "--set", "mesh.h=10", "--set", "growth.steps=2", "--set", "outputs.vtu=false",
      *ITERATIVE]),
    # the fatigue edge crack on the iterative path: its cycle a load path with contact
    (test_grow_2d_open_crack_same_on_one_and_two_processes, "fatigue_edge_crack.toml",
     ["--set", "mesh.h=0.15", "--set", "mesh.refine[0].h=0.03", "--set", "growth.steps=2", "--set", "outputs.vtu=false",
      *ITERATIVE])],
    ids=["hole-spectrum-2d", "corner-gag-3d", "hole-spectrum-2d-iterative", "fatigue-edge-2d-iterative"])
def test_grow_life_closed_by_contact_same_on_one_and_two_processes(grown_same, scene, settings, tmp_path):
    """`cracklip grow` of a shipped fatigue life closed by crack-lip contact
    (material.fatigue.closure = "contact": the closed load levels solved
    with frictionless contact by LevelSolver, each from the last level's
    active set) under mpirun -n 2: the checks of the open cracks' growth
    above (path, K, cycles, files) and the same closed levels, K_max, K_min
    and Delta K_eff per step (_life_cycles_same). Measured (the largest of
    three runs): the spectrum life at a hole K_I to 5e-14, K_II to 1.1e-13
    of K_I's largest, K_min to 5e-14 of K_max, the cycles to 6.4e-14, the
    tip positions to 3e-14 of the part; the corner crack K_max to 6e-13,
    K_min (-0.027 .. 0.005 against K_max 161) to 4e-12 of K_max, the cycles
    to 6e-12, the front points to 1.2e-15 of the part. (The corner crack's
    square section and round crack tie its deepest point and the faces of
    its ends: results.json's deepest and surface_points, indices, may
    differ from serial; in 1 run of 3 the start's front element size came
    out 0.14 % apart, a tie of nearest nodes in
    front_growth.front_element_size. Neither is checked here.) On the
    iterative path (CG on each level's and each cycle's saddle point; the
    bar 1e-6): the spectrum life K_I to 2.5e-11, K_II to 7e-12 of K_I's
    largest, the tip positions to 1.7e-12 of the part, the cycles to
    5e-11; the fatigue edge crack (its cycle a load path with contact) K
    to 8e-12 .. 2.3e-11 of K_I's largest, the positions to 2.2e-12, the
    cycles to 5.5e-12."""
    grown_same(scene, settings, tmp_path)
