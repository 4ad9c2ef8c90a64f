"""cracklip from Python as an engineer in a notebook uses it: a wrong type or value at the public
entry points (cl.Scene, cl.solve, cl.grow, cl.write_vtu, a Solution's crack argument, cl.Material,
cl.Crack, cl.Spectrum) is a cracklip error saying what to give, raised where the mistake is made,
not an AttributeError or a numpy TypeError from deep inside the model; and the results objects say
what they hold in one line (their repr)."""
import pytest

import cracklip as cl


@pytest.fixture(scope="module")
def scene(square_h01):
    return cl.Scene(square_h01, cl.Material(E=1.0, nu=0.3), cracks=[cl.Crack([[-0.3, 0.01], [0.3, 0.01]], name="mid")],
                    dirichlet=[cl.Dirichlet("bottom")], tractions=[cl.Traction("top", (0.0, 0.01))])


@pytest.fixture(scope="module")
def solution(scene):
    return cl.solve(scene)


@pytest.mark.parametrize("kwargs, says", [
    # before: "Poisson's ratio nu must lie in (-1, 0.5) ..., got 0.3": the valid value named as the fault
    ({"E": 1.0, "nu": "0.3"}, "Material.nu must be a number, got '0.3' (str)"),
    # before: "Young's modulus E must be positive, got 200e3"
    ({"E": "200e3", "nu": 0.3}, "Material.E must be a number, got '200e3' (str)"),
    ({"E": None, "nu": 0.3}, "Material.E must be a number"),
])
def test_material_of_the_wrong_type_says_so(kwargs, says):
    with pytest.raises(cl.MaterialError, match="must be a number") as err:
        cl.Material(**kwargs)
    assert says in str(err.value)


def _scene(mesh, **kw):
    args = dict(material=cl.Material(1.0, 0.3), dirichlet=[cl.Dirichlet("bottom")],
                tractions=[cl.Traction("top", (0.0, 0.01))])
    args.update(kw)
    return cl.Scene(mesh, **args)


@pytest.mark.parametrize("field, value, says", [
    # before, each an AttributeError or TypeError from the model or the solve:
    ("material", (1.0, 0.3), "Scene.material must be a cl.Material"),     # 'tuple' has no attribute 'kappa'
    ("options", {"radius": 0.1}, "Scene.options must be a cl.Options"),   # 'dict' has no attribute 'accuracy'
    ("cracks", "crack", "Scene.cracks must be a list"),
    ("dirichlet", ["bottom"], "Scene.dirichlet[0] must be a cl.Dirichlet"),  # 'str' has no attribute 'where'
    ("tractions", "single", "Scene.tractions must be a list"),            # 'Traction' object is not iterable
])
def test_scene_fields_of_the_wrong_type_say_so(square_h01, field, value, says):
    if value == "crack":
        value = cl.Crack([[-0.3, 0.01], [0.3, 0.01]])
    if value == "single":
        value = cl.Traction("top", (0.0, 0.01))
    with pytest.raises(cl.InputError) as err:
        _scene(square_h01, **{field: value})
    assert says in str(err.value)


def test_a_dolfinx_mesh_is_not_a_scene_mesh(square_h01):
    with pytest.raises(cl.InputError, match="Scene.mesh must be a cracklip MeshData .*cl.create_square"):
        _scene(square_h01.mesh)     # before: 'Mesh' object has no attribute 'mesh', from solve


def test_solve_and_grow_name_what_they_take(scene, tmp_path):
    with pytest.raises(cl.InputError, match=r"solve\(\) takes a cl.Scene.*cl.load_scene_file\(path\).scene"):
        cl.solve("demos/scenes/westergaard.toml")      # before: 'str' object has no attribute 'options'

    class SceneFileLike:   # what cl.load_scene_file returns holds the scene (no meshing here)
        pass
    held = SceneFileLike()
    held.scene = scene
    with pytest.raises(cl.InputError, match=r"solve\(scene_file.scene\)"):
        cl.solve(held)
    with pytest.raises(cl.InputError, match=r"grow\(scene_file.scene, scene_file.growth\)"):
        cl.grow(held, cl.Growth(steps=1))              # before: 'SceneFile' object has no attribute 'mesh'
    with pytest.raises(cl.InputError, match=r"cl.Growth\(\*\*settings\)"):
        cl.grow(scene, {"steps": 1})                   # before: 'dict' object has no attribute 'da_fraction'
    with pytest.raises(cl.InputError, match="write_vtu.*solve it first"):
        cl.write_vtu(scene, tmp_path / "x.vtu")        # before: 'Scene' object has no attribute 'subcell_fields'


def test_a_crack_is_given_by_index_or_name(solution):
    by_name = solution.stress_intensity_factors("mid")
    assert by_name[0]["K_I"] == solution.stress_intensity_factors(0)[0]["K_I"]
    assert solution.crack_opening("mid")["normal"].shape == solution.crack_opening(0)["normal"].shape
    # before: TypeError "'<=' not supported between instances of 'int' and 'str'", and for 0.0
    # "list indices must be integers or slices, not float" from the SIF domains
    for bad, says in [("mdi", "no crack named 'mdi': the scene's cracks are 0 'mid'"),
                      (0.0, "crack must be a crack's index (an int) or its name, got 0.0 (float)"),
                      (True, "got True (bool)"),
                      (1, "crack index 1 out of range: the scene has 1 cracks (0 'mid')")]:
        for call in (solution.stress_intensity_factors, solution.crack_opening):
            with pytest.raises(cl.InputError) as err:
                call(bad)
            assert says in str(err.value)


def test_bad_crack_points_and_spectrum_blocks_say_so():
    with pytest.raises(cl.CrackGeometryError, match="points must be numbers"):
        cl.Crack("a")                                  # before: numpy's "could not convert string to float"
    with pytest.raises(cl.InputError, match=r"spectrum.blocks\[0\] must be a cl.SpectrumBlock"):
        cl.Spectrum([[0.0, 1.0]])                      # before: 'list' object has no attribute 'points'
    with pytest.raises(cl.InputError, match=r"spectrum.blocks\[0\].points must be load factors"):
        cl.Spectrum([cl.SpectrumBlock(points=["a", "b"])])


def test_results_say_what_they_hold(scene, solution):
    text = repr(solution)    # before: the dataclass's repr, the whole model and the dof vector (> 10 000 characters)
    assert len(text) < 400, text
    assert text.startswith("Solution(2D; ") and "cracks ['mid']" in text and "contact 'none'" in text
    assert f"{len(solution.u)} dofs" in text and ".stress_intensity_factors(crack)" in text
    result = cl.grow(scene, cl.Growth(steps=1))
    text = repr(result)      # before: every tip record of every step
    assert len(text) < 400, text
    assert text.startswith("GrowthResult(1 steps; 1 cracks; stopped: ") and ".records" in text


def test_one_override_is_one_key_and_a_scene_file_says_what_it_built():
    path = "demos/scenes/westergaard.toml"
    from conftest import ROOT
    # before: InputError "override 'm' must look like KEY=VALUE" (the string iterated by character)
    f = cl.load_scene_file(ROOT / path, overrides="mesh.h=0.2")
    assert f.scene.mesh.h == 0.2
    assert cl.load_scene_file(ROOT / path, overrides=["mesh.h=0.2"]).scene.mesh.h == 0.2
    text = repr(f)           # before: every setting, 4363 characters
    assert len(text) < 400, text
    assert text.startswith("SceneFile('Westergaard mode I check'; ") and "cracks ['edge crack']" in text
    assert ".scene for cl.solve" in text


@pytest.mark.parametrize("call, says", [
    # before: Python's bare "__init__() got an unexpected keyword argument 'contcat'"
    (lambda: cl.Options(contcat="unilateral"), "Options() takes no keyword 'contcat'; did you mean 'contact'?"),
    (lambda: cl.Growth(stesp=2), "Growth() takes no keyword 'stesp'; did you mean 'steps'?"),
    (lambda: cl.Material(E=1.0, Nu=0.3), "Material() takes no keyword 'Nu'; it takes E, nu, plane"),
    (lambda: cl.Crack([[0.0, 0.0], [1.0, 0.0]], nmae="a"), "Crack() takes no keyword 'nmae'; did you mean 'name'?"),
])
def test_a_misspelled_keyword_names_the_nearest(call, says):
    with pytest.raises(cl.KeywordError) as err:
        call()
    assert says in str(err.value)
    assert isinstance(err.value, TypeError) and isinstance(err.value, cl.CracklipError)


def test_a_misspelled_keyword_of_solve_and_of_a_solution(scene, solution):
    with pytest.raises(cl.KeywordError, match="did you mean 'condition_number'"):
        cl.solve(scene, conditon_number=True)
    with pytest.raises(cl.KeywordError, match=r"Solution.stress_intensity_factors\(\) takes no keyword 'radus'; "
                                              "did you mean 'radius'"):
        solution.stress_intensity_factors(0, radus=0.1)
    with pytest.raises(cl.KeywordError, match=r"Scene\(\) takes no keyword 'crack'; did you mean 'cracks'"):
        cl.Scene(scene.mesh, scene.material, crack=[])
    import inspect   # the signatures help() shows are the functions' own
    assert list(inspect.signature(cl.solve).parameters) == ["scene", "condition_number"]
    assert list(inspect.signature(cl.Material).parameters) == ["E", "nu", "plane"]


def test_cycle_counting_of_a_bad_history_and_its_indices():
    with pytest.raises(cl.InputError, match="the load history must be numbers"):
        cl.count_cycles("abc")                         # before: numpy's "could not convert string to float"
    # ASTM E1049 by hand: reversals 0, 1, 0.5, 2, 0 -> the 1 -> 0.5 range closes one full cycle (0.5),
    # the residue 0 -> 2 -> 0 two half cycles of 2
    v = [0.0, 0.5, 1.0, 0.5, 0.7, 2.0, 0.0]
    c = cl.count_cycles(v, repeated=False)
    assert cl.rainflow(v) == [(0.5, 1.0), (2.0, 1.0)]
    assert (c.lo.tolist(), c.hi.tolist()) == ([3, 0, 6], [2, 5, 5])   # indices into v, as Cycles says now


def test_a_mesh_size_of_the_wrong_type_says_so():
    with pytest.raises(cl.MeshError, match=r"the rectangle's h must be a number, got '0.1' \(str\)"):
        cl.create_square(h="0.1")                      # before: "'<' not supported between 'float' and 'str'"


def test_create_square_says_what_it_takes():
    import inspect
    # before: create_square(h, half_width, **kwargs), a misspelling reported as create_rectangle()'s
    assert list(inspect.signature(cl.create_square).parameters) == [
        "h", "half_width", "refine", "embed_lines", "embed_points", "levels"]
    with pytest.raises(cl.KeywordError, match=r"create_square\(\) takes no keyword 'embed_point'; did you mean "
                                              "'embed_points'"):
        cl.create_square(0.5, embed_point=[(0.0, 0.0)])


@pytest.mark.parametrize("value, says", [
    # before: accepted, and read as 0.01 at the solve (float('0.01'))
    ("0.01", "got '0.01' (a string: write the number itself, value=0.01)"),
    # before: accepted, and a TypeError from float() at the solve
    ((0.0, 0.01), "one Dirichlet per component"),
    (None, "value must be a finite number or a callable f(x), got None"),
    (float("nan"), "got nan"),
])
def test_a_dirichlet_value_of_the_wrong_type_says_so(value, says):
    with pytest.raises(cl.InputError) as err:
        cl.Dirichlet("left", 0, value=value)
    assert says in str(err.value)
    assert cl.Dirichlet("left", 0, value=0.01).value == 0.01 and callable(cl.Dirichlet("left", None, value=abs).value)


def test_a_life_from_python_is_the_command_lines(tmp_path):
    """cl.life(cl.load_life_file(path)) integrates the life `cracklip life`
    does (the same set-up and integration, analysis/table_life.life_of):
    the same cycles to the last bit, its a-N rows; a path instead of the
    read file says how to read it. (Before: no Python entry point.)"""
    import json
    import pathlib
    from cracklip import cli
    path = str(pathlib.Path(__file__).resolve().parents[1] / "demos" / "scenes" / "life_hole_crack.toml")
    life = cl.life(cl.load_life_file(path, ["life.a_final=20.0"]))
    assert cli.main(["life", path, "--set", "life.a_final=20.0", "--out", str(tmp_path), "--quiet", "--no-png"]) == 0
    ref = json.loads((tmp_path / "results.json").read_text())["life"]
    assert life["cycles"] == ref["cycles"] and life["stop"] == ref["stop"] == "a_final"
    assert life["rows"][0]["a"] == 1.5 and life["rows"][-1]["a"] == 20.0 and life["rows"][-1]["cycles"] == ref["cycles"]
    with pytest.raises(cl.InputError, match=r"life\(cl.load_life_file\(path\)\)"):
        cl.life(path)
