"""Start-up path of the command line (issue 15): nothing heavy at `import
cracklip`, the short gmsh -> DOLFINx conversion gives gmshio's mesh and
facet tags. No timings here (the CLI's wall time is measured by hand, see
the issue's report)."""
import os
import subprocess
import sys

import numpy as np
import pytest
from conftest import ROOT


def test_import_cracklip_loads_nothing_heavy():
    code = ("import sys, cracklip, cracklip.cli, cracklip.io.scene_file; "
            "print(sorted(m for m in ('dolfinx', 'petsc4py', 'gmsh', 'scipy', 'mpi4py', 'cracklip._cracklip') "
            "if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         env={**os.environ, "PYTHONPATH": str(ROOT / "python")}).stdout.strip()
    assert out == "[]"


def test_lazy_exports():
    import cracklip as cl
    assert set(cl.__all__) <= set(dir(cl))
    for name in cl.__all__:
        assert getattr(cl, name) is not None
    with pytest.raises(AttributeError, match="no attribute 'nonexistent'"):
        cl.nonexistent  # noqa: B018


@pytest.mark.parametrize("h", [0.2, 0.05])
def test_conversion_equals_gmshio(h):
    """Same nodes, same cells (DOLFINx's own ordering of both), same tagged
    facets (boundary and an embedded interior line) as gmshio.model_to_mesh."""
    from mpi4py import MPI
    import dolfinx.cpp.mesh as cm
    from dolfinx.io import gmshio
    from cracklip.scene import mesh
    from cracklip.scene.mesh_import import model_to_mesh
    gm = mesh._gmsh()
    gm.model.add("convert")
    occ = gm.model.occ
    rect = occ.addRectangle(-1, -1, 0, 2, 2)
    occ.fragment([(2, rect)], [(1, occ.addLine(occ.addPoint(-0.5, 0.1, 0), occ.addPoint(0.3, -0.2, 0)))])
    occ.synchronize()
    gm.model.addPhysicalGroup(2, [s for _, s in gm.model.getEntities(2)], 1)
    groups = mesh._box_sides(gm, -1, -1, 1, 1, 1e-9)
    groups["inner"] = groups.pop("other")
    for tag, (name, curves) in enumerate(groups.items(), start=1):
        gm.model.addPhysicalGroup(1, curves, tag)
        gm.model.setPhysicalName(1, tag, name)
    mesh._mesh_2d(gm, h, [])
    try:
        m1, _, f1 = gmshio.model_to_mesh(gm.model, MPI.COMM_WORLD, 0, gdim=2)
        m2, f2, names = model_to_mesh(gm.model, MPI.COMM_WORLD)
    finally:
        gm.model.remove()
    assert names == {"left": 1, "right": 2, "bottom": 3, "top": 4, "inner": 5}
    assert np.array_equal(m1.geometry.x, m2.geometry.x)
    assert np.array_equal(m1.geometry.dofmap.array, m2.geometry.dofmap.array)
    for tag in range(1, 6):
        mids = []
        for m, f in ((m1, f1), (m2, f2)):
            facets = f.indices[f.values == tag]
            mid = m.geometry.x[cm.entities_to_geometry(m._mesh, 1, facets, False)].mean(axis=1)
            mids.append(mid[np.lexsort(mid.T[::-1])])
        assert len(mids[0]) > 0 and np.array_equal(mids[0], mids[1])


def test_solve_stays_the_function_after_its_module_loads():
    """Importing the module that defines solve (cracklip.analysis.solve, as
    the command line and demos do) must leave cracklip.solve the function,
    as the eager __init__ did."""
    code = ("import cracklip, cracklip.analysis.solve, cracklip.model; from cracklip.analysis.solve import solve_plain; "
            "print(callable(cracklip.solve) and not isinstance(cracklip.solve, type(cracklip)), "
            "cracklip.solve.__name__, type(cracklip.model).__name__)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         env={**os.environ, "PYTHONPATH": str(ROOT / "python")}).stdout.strip()
    assert out == "True solve module"
