"""Bad input raises typed errors with actionable messages (issue 2)."""
import numpy as np
import pytest
from mpi4py import MPI

import dolfinx.mesh

import cracklip as cl


def _scene(md, cracks=(), dirichlet=None, material=None):
    return cl.Scene(md, material or cl.Material(1.0, 0.3), cracks=list(cracks),
                    dirichlet=dirichlet if dirichlet is not None else [cl.Dirichlet("left")],
                    tractions=[cl.Traction("right", (1.0, 0.0))])


def test_crack_outside_domain(square_h01):
    with pytest.raises(cl.CrackGeometryError, match="does not cross any cell"):
        cl.solve(_scene(square_h01, [cl.Crack([[2.0, 2.0], [3.0, 2.5]])]))


def test_zero_length_segment():
    with pytest.raises(cl.CrackGeometryError, match="segment 1 .* zero length"):
        cl.Crack([[0.0, 0.0], [0.5, 0.0], [0.5, 0.0]])


@pytest.mark.parametrize("E, nu, match", [(1.0, 0.5, "Poisson"), (1.0, 0.7, "Poisson"),
                                          (0.0, 0.3, "Young"), (-2.0, 0.3, "Young"),
                                          (float("nan"), 0.3, "Young")])
def test_bad_material(E, nu, match):
    with pytest.raises(cl.MaterialError, match=match):
        cl.Material(E, nu)


def test_non_triangle_mesh():
    quads = dolfinx.mesh.create_unit_square(MPI.COMM_WORLD, 2, 2, dolfinx.mesh.CellType.quadrilateral)
    md = cl.MeshData(quads, None, {})
    with pytest.raises(cl.MeshError, match="triangles"):
        cl.create_model(cl.Scene(md, cl.Material(1.0, 0.3), dirichlet=[cl.Dirichlet((0.0, 0.0))]))


def test_no_dirichlet(square_h01):
    with pytest.raises(cl.BoundaryConditionError, match="no Dirichlet"):
        _scene(square_h01, dirichlet=[])


def test_rigid_motion_left_free(square_h01):
    with pytest.raises(cl.BoundaryConditionError, match="translation in y"):
        cl.solve(_scene(square_h01, dirichlet=[cl.Dirichlet("left", 0)]))
    # Rollers on one straight edge leave the rotation? No: u_x on a vertical
    # line fixes rotation and x, but y stays free. Two pinned components at one
    # point leave the rotation free:
    x = square_h01.mesh.geometry.x
    with pytest.raises(cl.BoundaryConditionError, match="rotation"):
        cl.solve(_scene(square_h01, dirichlet=[cl.Dirichlet(tuple(x[0, :2]))]))


def test_piece_cut_free_by_crack_is_reported(square_h01):
    """Through crack, u_y fixed only below it: the top piece floats in y."""
    below = np.array(square_h01.nearest_node([-1, -1]))
    scene = _scene(square_h01, [cl.Crack([[-2, 0.013], [2, 0.013]])],
                   dirichlet=[cl.Dirichlet("left", 0), cl.Dirichlet(tuple(below), 1)])
    with pytest.raises(cl.SolverError, match="singular|null pivot"):
        cl.solve(scene)


def test_point_condition_off_node(square_h01):
    with pytest.raises(cl.BoundaryConditionError, match="not a mesh node"):
        cl.solve(_scene(square_h01, dirichlet=[cl.Dirichlet("left"), cl.Dirichlet((0.01234, 0.0), 0)]))


def test_unknown_boundary_tag(square_h01):
    with pytest.raises(cl.MeshError, match="unknown boundary tag 'lft'"):
        cl.solve(_scene(square_h01, dirichlet=[cl.Dirichlet("lft")]))


def test_two_cracks_in_one_cell(square_h01):
    cracks = [cl.Crack([[-2, 0.013], [2, 0.013]]), cl.Crack([[-2, 0.02], [2, 0.02]])]
    with pytest.raises(cl.CrackGeometryError, match="crossed by cracks 0 and 1"):
        cl.solve(_scene(square_h01, cracks))
