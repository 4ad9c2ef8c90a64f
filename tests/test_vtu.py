"""cracklip.vtu: the raw-appended VTU writer, read back by an independent
reader (meshio) array for array."""
import meshio
import numpy as np
from cracklip.io.vtu import VtuMesh, write_vtu


def test_written_arrays_read_back_exactly(tmp_path):
    rng = np.random.default_rng(3)
    points = np.zeros((7, 3))
    points[:, :2] = rng.random((7, 2))
    tris = np.array([[0, 1, 2], [2, 3, 4], [4, 5, 6], [6, 0, 3]], dtype=np.int64)
    disp = rng.random((7, 3))
    stress = rng.standard_normal(4)
    side = np.array([1, -1, 1, 0], dtype=np.int32)
    parent = np.array([10, 11, 11, 12], dtype=np.int64)
    write_vtu(tmp_path / "t.vtu", VtuMesh(points, "triangle", tris, {"displacement": disp},
                                          {"stress_xx": stress, "side": side, "parent_cell": parent}))
    m = meshio.read(tmp_path / "t.vtu")
    assert np.array_equal(m.points, points)
    assert np.array_equal(m.cells_dict["triangle"], tris)
    assert np.array_equal(m.point_data["displacement"], disp)
    assert np.array_equal(m.cell_data["stress_xx"][0], stress)
    assert np.array_equal(m.cell_data["side"][0], side) and m.cell_data["side"][0].dtype == np.int32
    assert np.array_equal(m.cell_data["parent_cell"][0], parent)


def test_lines_and_an_empty_mesh(tmp_path):
    pts = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.5, 0.0]])
    write_vtu(tmp_path / "l.vtu", VtuMesh(pts, "line", np.array([[0, 1], [1, 2]]), {"pressure": np.arange(3.0)},
                                          {"lip": np.array([1, -1], dtype=np.int32)}))
    m = meshio.read(tmp_path / "l.vtu")
    assert np.array_equal(m.cells_dict["line"], [[0, 1], [1, 2]])
    assert np.array_equal(m.point_data["pressure"], [0.0, 1.0, 2.0])
    assert np.array_equal(m.cell_data["lip"][0], [1, -1])
    write_vtu(tmp_path / "e.vtu", VtuMesh(np.zeros((0, 3)), "line", np.zeros((0, 2), dtype=np.int64)))
    assert (tmp_path / "e.vtu").read_bytes().startswith(b'<?xml version="1.0"?>')
