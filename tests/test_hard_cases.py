"""Hard cases (issue 6) at small sizes: every case finite, every solve's
relative residual <= 1e-10, the error against the exact answer (or the 4x
finer mesh) falling by >= 2x from the base mesh to the 4x finer one, and what
makes each case hard actually present in the discrete model. The full-size
table is demos/hard_cases.py."""
import dataclasses
import math
import pathlib
import sys
import types

import cracklip as cl
import numpy as np
import pytest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))
import hard_cases as hc  # noqa: E402

RESIDUAL = 1e-10

# Relative energy-norm error allowed on the 4x finer mesh (n = 4 n0_small):
# rate-1 cases land at 2.5e-2 .. 4.3e-2; nu = 0.499 locks (P1), case 14's
# finer mesh has h = 0.25, case 15a (radius below a cell) converges at rate 1/2.
FINE_ERROR = {"1": 0.05, "2": 0.05, "3": 0.05, "4": 0.05, "5": 0.05, "6": 0.05, "9": 0.05, "10": 0.35,
              "13a": 0.05, "13b": 0.05, "14": 0.15, "15a": 0.1, "15b": 0.05}


@pytest.fixture(scope="module")
def rows():
    """Each exact-reference case at n0_small and 4 n0_small (computed once)."""
    return {c.key: hc.run_case(c, c.n0_small) for c in hc.CASES if c.reference == "exact"}


def _base(row):
    return row["levels"][0]


@pytest.mark.parametrize("key", sorted(FINE_ERROR))
def test_exact_reference_cases_converge(rows, key):
    r = rows[key]
    assert r["finite"]
    assert r["relative_residual"] <= RESIDUAL, r["relative_residual"]
    assert r["error_ratio"] >= 2.0, (r["error"], r["error_fine"])
    assert r["error_fine"] <= FINE_ERROR[key], r["error_fine"]
    if r["K_error"] is not None:  # Williams cases: SIFs (radius 0.3; 0.5 for case 14) converge too
        assert r["K_error_fine"] < r["K_error"] or r["K_error_fine"] <= 1e-3, (r["K_error"], r["K_error_fine"])
    assert r["cond_1norm"] > 0 and r["cond_1norm_jacobi"] > 0


def test_geometry_of_the_degenerate_cases(rows):
    """What makes each case hard is really in the model."""
    assert _base(rows["1"])["nodes_on_crack"] >= 3                 # crack through nodes
    assert _base(rows["2"])["edge_cells"] > 0 and _base(rows["2"])["cut_cells"] == 0  # along edges only
    assert _base(rows["3"])["tip_cells"] == 0 and _base(rows["3"])["tip_node_distance"] < 1e-14
    assert _base(rows["4"])["tip_cells"] == 0                      # tip on an edge: no tip cell
    s = _base(rows["5"])
    assert 0.5e-9 <= s["min_subcell_fraction"] <= 2e-9 and s["snapped"] == 0
    assert _base(rows["6"])["mouth_node_phi"] == 0.0 and _base(rows["6"])["tips"] == [[False, True]]
    assert _base(rows["9"])["edge_ratio"] >= 1000.0
    for key in ("13a", "13b"):
        assert _base(rows[key])["tip_cells"] == 1
    assert _base(rows["14"])["crossed_cells"] == 2 and _base(rows["14"])["cells"] == 8
    assert _base(rows["15a"])["radius"] < _base(rows["15a"])["h"]
    assert _base(rows["15b"])["radius"] > 0.5


def test_tip_near_an_edge_is_continuous():
    """The answer is continuous as the tip approaches the edge x = 0 of its
    cell from inside (n = 20, radius 0.2 = 2 h, so the enriched node set does
    not change). Before the enrichment fix a tip within ~1e-3 h of that edge
    stripped the Heaviside dof from a core node of the neighbouring cut
    blending cells: energy error 0.28 instead of 0.087."""
    md = hc.structured_square(20)
    err = {}
    for d in (0.0, 1e-8, 1e-4, 1e-2):
        b = hc.williams_scene(md, (-d, 0.1 / 3.0), 20.0)
        err[d] = cl.solve(b.scene).energy_error(lambda p, s: b.exact.gradient(p, s))[1]
    assert abs(err[1e-8] - err[0.0]) <= 1e-6 * err[0.0], err
    assert abs(err[1e-4] - err[0.0]) <= 1e-3 * err[0.0], err
    assert abs(err[1e-2] - err[0.0]) <= 5e-2 * err[0.0], err
    assert err[0.0] <= 0.09, err


@pytest.mark.parametrize("key", ["7", "8"])
def test_finer_mesh_reference_cases_converge(key):
    """Two cracks (4 tips, overlapping enrichment disks) and a 40-segment
    arc: n = 10, 40, 160; |Q(n) - Q(4n)| falls by >= 2x."""
    case = hc.CASE_BY_KEY[key]
    r = hc.run_case(case, case.n0_small)
    assert r["finite"]
    assert r["relative_residual"] <= RESIDUAL
    assert r["error_ratio"] >= 2.0, (r["error"], r["error_fine"])
    assert r["error_fine"] <= 0.05, r["error_fine"]
    lv = r["levels"][0]
    if key == "7":
        assert lv["tip_distance"] < 2 * 0.2 and lv["nodes_with_both_cracks_tip_functions"] > 0
        q = np.asarray(r["levels"][-1]["quantities"])
        assert np.all(q[0::2] > 0)  # tension: K_I > 0 at all four tips


def test_scaling_is_exact():
    """Case 11: loads x 1e6, E x 1e9 (unilateral contact, tip enrichment):
    every output scales by its exact factor to 1e-12, same active set."""
    s = hc.run_scaling(10)
    assert s["finite"] and s["same_active_set"]
    assert s["relative_residual"] <= RESIDUAL
    assert s["max_deviation"] <= 1e-12, s["deviation"]
    assert set(s["deviation"]) == {"u", "stress", "K", "pressure", "gap", "energy", "opening"}


def test_open_closed_open_contact_both_starts():
    """Case 12: both starts reach the same active set and pressure (1e-10),
    closed in the middle, open toward both tips; at n = 20 the SIFs and the
    contact force are within 5 % of the 4x finer mesh (at n = 10, h = 0.2,
    they are 10 % off; the 3-level convergence is in the demo)."""
    r = hc.run_case(hc.CASE_BY_KEY["12"], 20, levels=2)
    assert r["finite"] and r["relative_residual"] <= RESIDUAL
    assert r["starts_agree"], r["pressure_difference_between_starts"]
    assert r["pressure_difference_between_starts"] <= 1e-10
    assert r["error"] <= 0.05
    sol = hc.solve_level(hc.Built(hc.open_closed_open_scene(40)), condition=False)["_solution"]
    cp = sol.contact_pressure(0)
    x, p, gap = cp["x"][:, 0], cp["pressure"], cp["gap"]
    closed = p > 1e-12
    assert closed[np.abs(x) < 0.1].all()                      # closed in the middle
    assert (gap[np.abs(x) > 0.5] > 0).all() and not closed[np.abs(x) > 0.5].any()  # open at both ends
    assert 0 < sol.contact["active"].sum() < sol.contact["active"].size
    # The constraint is weak: the weighted gaps B u - g of the active multipliers vanish.
    cs, active = sol.contact["system"], sol.contact["active"]
    weighted_gap = cs.B @ sol.u - cs.g
    assert np.abs(weighted_gap[active]).max() <= 1e-10 * np.abs(weighted_gap).max()
    assert weighted_gap[~active].min() >= 0.0 and (-sol.contact["lambda"]).min() >= 0.0
    K = hc.sif_vector(sol, 0.15)
    assert K[0] > 0 and K[2] > 0                              # both tips open


def test_demo_quick_writes_table(tmp_path):
    """The demo's JSON and Markdown for a few cases."""
    out = tmp_path / "hc.json"
    res = hc.main(["--quick", "--json", str(out), "--cases", "5", "11", "14"])
    assert out.exists() and out.with_suffix(".md").exists()
    md = out.with_suffix(".md").read_text()
    assert "| case |" in md and "5 1e-9 sliver" in md
    assert res["all_finite"] and res["max_relative_residual"] <= RESIDUAL and res["all_converge"]
    for row in res["rows"]:
        for key in ("case", "hard", "finite", "relative_residual", "cond_1norm", "cond_1norm_jacobi",
                    "error", "wall_time"):
            assert key in row


# -- solids (issue 39) ----------------------------------------------------------------------------

#: The 3D cases run here, at n0_small and 2 n0_small (4 / 8 divisions of the
#: cube for through cracks, 6 / 12 with a front); the full table is the
#: demo's (n = 8 / 16, docs/benchmarks.md).
CASES_3D = ["3D-1", "3D-2", "3D-3", "3D-6", "3D-8", "3D-4"]


@pytest.fixture(scope="module")
def rows_3d():
    return {k: hc.run_case(hc.CASE_BY_KEY[k], hc.CASE_BY_KEY[k].n0_small) for k in CASES_3D}


@pytest.mark.parametrize("key", CASES_3D)
def test_3d_case_finite_accurate_and_converging_or_warned(rows_3d, key):
    """Every 3D case: finite outputs, every solve's relative residual <=
    1e-10, and the energy error against the exact field falls on the 2x
    finer mesh (rate >= 0.58; fronts at these sizes, radius 0.3 of about one
    element, at least rate 1/2), with no warning of what would stop it. The
    crack along mesh faces (3D-3) converges as the same crack through
    vertices (3D-1): 0.519 -> 0.260 against 0.575 -> 0.288 (it got no
    Heaviside function before, 1.10 -> 1.02, warned crack_on_faces)."""
    r = rows_3d[key]
    assert r["finite"]
    assert r["relative_residual"] <= RESIDUAL, r["relative_residual"]
    assert r["error_ratio"] >= (1.45 if key == "3D-4" else 1.5), (r["error"], r["error_fine"])
    if key == "3D-3":
        assert r["error_fine"] <= rows_3d["3D-1"]["error_fine"], (r["error_fine"], rows_3d["3D-1"]["error_fine"])
    assert not any(w in hc.LIMITING_WARNINGS for lv in r["levels"] for w in lv["warnings"] if w != "enrichment_radius")


def test_3d_cases_have_what_makes_them_hard(rows_3d):
    """The degenerate geometry is really in the discrete model."""
    b = {k: _base(r) for k, r in rows_3d.items()}
    assert b["3D-1"]["nodes_on_crack"] >= 3 and b["3D-1"]["face"] == 0          # vertices, no face
    assert b["3D-2"]["cell_edges_on_crack"] > 0 and b["3D-2"]["face"] == 0       # along edges
    assert b["3D-3"]["face"] == 64 and b["3D-3"]["cut"] == 0 and b["3D-3"]["nodes_on_crack"] == 25  # along faces
    assert b["3D-6"]["bore_nodes_within_h_of_the_plane"] > 0                      # tangent to the bore
    assert b["3D-8"]["distance_over_h"] == 1.5 and min(b["3D-8"]["cut_cells"]) > 0
    assert b["3D-4"]["nodes_on_front"] >= 3 and b["3D-4"]["front"] > 0          # front through nodes
    # K along the front through nodes, interior points with a clear domain (finer mesh): within 2 %.
    assert rows_3d["3D-4"]["K_error_fine"] is not None and rows_3d["3D-4"]["K_error_fine"] < 0.02


def test_3d_crack_along_faces_opens():
    """Case 3D-3 (a through crack on the node layer z = 0, every cell beside
    it a face cell): each of the 5 x 5 nodes on the crack carries a Heaviside
    function (25 pseudo-nodes, 75 enriched dofs), and the lips open as the exact layers do: [[u]] = c_1 - c_0
    + (a_0 - a_1) / E (x^2 - nu y^2) / 2 e_z on z = 0 (LayeredBending3D,
    normal e_z, t = e_x). The P1 interpolation of the quadratic opening
    converges at O(h^2): L2 relative error 0.093 (n = 4) and 0.023 (n = 8).
    Before face cells counted in the 3D Heaviside selection the crack got no
    enriched dof and the lips did not open (error 1.0)."""
    errors = []
    for n, pseudo in ((4, 25), (8, 81)):
        b = hc.case_3d_faces(n)
        lv = hc.solve_level(b, condition=False)
        assert lv["enriched_dofs"] == 3 * pseudo and "crack_on_faces" not in lv["warnings"]
        s = lv["_solution"].lip_samples(0)
        x = s["x"]
        assert np.allclose(x[:, 2], 0.0) and abs(s["weight"].sum() - 4.0) < 1e-12
        ex = b.exact
        nu = ex.material.nu
        jump = np.tile(np.subtract(ex.c[1], ex.c[0]), (len(x), 1))
        jump[:, 2] += (ex.a[0] - ex.a[1]) / ex.material.E * (x[:, 0] ** 2 - nu * x[:, 1] ** 2) / 2.0
        assert np.allclose(jump, ex.displacement(x, 1) - ex.displacement(x, -1), atol=1e-15)
        w = s["weight"][:, None]
        errors.append(math.sqrt((w * (s["jump"] - jump) ** 2).sum() / (w * jump ** 2).sum()))
    assert errors[0] < 0.1 and errors[1] < 0.025 and errors[0] / errors[1] > 3.5, errors


def test_crack_on_faces_warns_of_nodes_left_without_a_heaviside_function():
    """The crack_on_faces check (model.checks) on case 3D-3's model (n = 4):
    silent with the layout it got (each of the 25 nodes on the crack has its
    Heaviside function), and naming the nodes when some lack it (the same
    layout without the pseudo-nodes of the 9 interior ones: what the
    selection gave every one of the 25 before face cells counted)."""
    from cracklip.model import checks

    model = hc.solve_level(hc.case_3d_faces(4), condition=False)["_solution"].model
    assert checks._unopened_faces(model, 0) is None
    lay = model.layout
    node = np.asarray(lay.node)
    x = model.x[node]
    keep = (np.abs(x[:, 0]) == 1.0) | (np.abs(x[:, 1]) == 1.0)  # the 16 on the cube's faces
    assert np.count_nonzero(~keep) == 9
    stripped = types.SimpleNamespace(node=node[keep], kind=np.asarray(lay.kind)[keep],
                                     crack=np.asarray(lay.crack)[keep])
    w = checks._unopened_faces(types.SimpleNamespace(geometries=model.geometries, cells=model.cells,
                                                     layout=stripped, cracks=model.cracks), 0)
    assert w is not None and w.code == "crack_on_faces" and "9 of the 25 nodes" in str(w)


@pytest.mark.parametrize("option", [{"blending": "standard"}, {"enrichment": "none"}])
def test_crack_on_faces_spares_the_front_nodes(option):
    """A half-plane crack on the node layer y = 0 whose front runs along the
    z-axis mesh edges (n = 6): with standard blending the core nodes carry
    the jump in their front functions and take no Heaviside function, and
    without front enrichment the front cells' nodes take none (the crack ends
    at those cells, as through cut cells; front_enrichment warns of that).
    Neither is a face the lips cannot open across: crack_on_faces named 7 of
    the 21 nodes on the crack before."""
    w = hc.WilliamsField3D(hc.MAT3, 1.0, -0.4, 0.6, (0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0))
    b = hc.front_scene(hc.structured_cube(6), w, radius=0.3)
    b.scene.options = dataclasses.replace(b.scene.options, **option)
    b.facts = hc._front_facts
    lv = hc.solve_level(b, condition=False)
    assert lv["face"] > 0 and lv["finite"]
    assert "crack_on_faces" not in lv["warnings"], lv["warnings"]


def test_3d_front_on_mesh_edges_crack_along_faces():
    """Case 3D-5's front on the mesh edges of the z axis with its crack
    plane y = 0 on a node layer instead of at 20 degrees (n = 12, radius
    0.3, mixed mode K = (1, -0.4, 0.6)): behind the front the cells beside
    the crack are face cells (240), and the nodes on it beyond the front's
    ramp carry Heaviside functions. K at the interior points within 2 % (1.2 %;
    1.4 % at 20 degrees) and the energy error 0.118 (0.123 at 20 degrees);
    before face cells counted in the 3D selection: K 12 % off, energy error
    2.70, warned crack_on_faces."""
    w = hc.WilliamsField3D(hc.MAT3, 1.0, -0.4, 0.6, (0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0))
    b = hc.front_scene(hc.structured_cube(12), w, radius=0.3)
    b.facts = hc._front_facts
    lv = hc.solve_level(b, condition=False)
    assert lv["face"] > 0 and lv["cut"] == 0 and "crack_on_faces" not in lv["warnings"]
    assert lv["K_points"] >= 1 and lv["K_error"] < 0.02, lv["K_error"]
    assert lv["energy_error"] < 0.15, lv["energy_error"]


def test_3d_shallow_front_base_mesh():
    """Case 3D-7 on its base mesh (the 2x finer one is the demo's): a front
    meeting a loaded face at 10 degrees solves finite with residual <=
    1e-10, and its ends on the face are flagged (free_surface)."""
    lv = hc.solve_level(hc.CASE_BY_KEY["3D-7"].build(6), condition=False)
    assert lv["finite"] and lv["relative_residual"] <= RESIDUAL
    assert lv["free_surface_points"] >= 1 and lv["energy_error"] < 0.3
