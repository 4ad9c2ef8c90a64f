"""Units of a scene: names, SI factors, K units, Paris C conversion (checked
against a rate computed by hand), and the [units] table of a scene file."""
import math

import pytest

import cracklip as cl
from cracklip.io.scene_file import build_scene, read_document
from cracklip.scene.units import Units, convert, convert_paris_C, label, parse_k_unit
from conftest import ROOT


def test_names_and_factors():
    u = Units("mm", stress="MPa")
    assert u.force_name == "N" and u.name("K") == "MPa sqrt(mm)" and u.name("G") == "N/mm"
    assert u.si_factor("force") == pytest.approx(1.0)  # 1 MPa mm^2 = 1 N
    assert u.si_factor("K") == pytest.approx(1e6 * math.sqrt(1e-3))
    v = Units("in", force="lbf")
    assert v.stress_name == "psi" and v.stress_si == pytest.approx(6894.757293168361)
    assert label(u, "K", "K_I") == "K_I [MPa sqrt(mm)]" and label(None, "K", "K_I") == "K_I"
    # 1 ksi sqrt(in) = 1.0988 MPa sqrt(m) (the handbook factor).
    assert convert(1.0, "K", Units("in", stress="ksi"), Units("m", stress="MPa")) == pytest.approx(1.098843, rel=1e-6)


def test_bad_units_are_typed_errors():
    with pytest.raises(cl.InputError, match="units.length must be one of"):
        Units("furlong", stress="MPa")
    with pytest.raises(cl.InputError, match="give units.force or units.stress"):
        Units("mm")
    with pytest.raises(cl.InputError, match="give only one of force, stress"):
        Units("mm", force="N", stress="Pa")
    with pytest.raises(cl.InputError, match="sqrt"):
        parse_k_unit("MPa m")


@pytest.mark.parametrize("text", ["MPa sqrt(m)", "MPa*sqrt(m)", "MPa √m", "MPa m^0.5"])
def test_k_unit_forms(text):
    assert parse_k_unit(text) == pytest.approx(1e6)


def test_paris_C_conversion_gives_the_same_rate():
    """C = 1e-12 m/cycle (MPa sqrt(m))^-3: at Delta K = 10 MPa sqrt(m) the
    rate is 1e-9 m = 1e-6 mm per cycle; in mm and MPa sqrt(mm) the converted
    C must give the same rate at the same Delta K (316.23 MPa sqrt(mm))."""
    units = Units("mm", stress="MPa")
    C = convert_paris_C(1e-12, 3.0, "m", "MPa sqrt(m)", units)
    dK = 10.0 / math.sqrt(1e-3)
    assert C * dK ** 3 == pytest.approx(1e-6, rel=1e-12)
    # In ksi sqrt(in) and inches: 1e-6 mm = 3.937e-8 in at 9.1005 ksi sqrt(in).
    imperial = Units("in", stress="ksi")
    C2 = convert_paris_C(1e-12, 3.0, "m", "MPa sqrt(m)", imperial)
    assert C2 * (10.0 / 1.098843) ** 3 == pytest.approx(1e-9 / 0.0254, rel=1e-5)


def test_scene_file_units_table():
    doc = read_document(ROOT / "demos" / "scenes" / "block_uniform_pressure.toml")
    doc["units"] = {"length": "mm", "stress": "MPa"}
    doc["mesh"]["h"] = 0.25
    sf = build_scene(doc)
    assert sf.scene.units == Units("mm", stress="MPa")
    doc["units"] = {"length": "mm", "stress": "bar"}
    with pytest.raises(cl.InputError, match="units.stress"):
        build_scene(doc)
