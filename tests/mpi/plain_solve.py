"""Run under mpirun (or alone) by tests/test_mpi.py: a plain P1 solve of a
small 2D or 3D part on the distributed mesh, and the node mesh X-FEM will
use. Prints one JSON line (rank 0):

  energy      strain energy 1/2 u.K u of the solution (K without the
              Dirichlet rows: the true energy), summed over processes
  u_max       the largest displacement component (absolute), over processes
  dofs        global number of dofs
  incomplete  owned nodes whose local cells (owned + ghost) miss part of
              their patch in the whole mesh (0 with vertex patches)
  gmsh_processes  how many processes started gmsh (1: rank 0 meshes)
  node_mesh   extract_node_mesh gives this process's owned then ghost
              nodes, at V's dof coordinates (max distance), all processes

    python3 tests/mpi/plain_solve.py 2|3 [facet]

`facet`: DOLFINx's own partitioner instead (ghosts across facets only), to
show what the vertex patches change.
"""
import json
import sys

import numpy as np
from mpi4py import MPI

import cracklip as cl
from cracklip import _cracklip
from cracklip.analysis.solve import solve_plain
from cracklip.model.assembly import elasticity_form
from cracklip.scene.mesh_3d import create_box
from cracklip.scene.partition import incomplete_patches

dim = int(sys.argv[1])
if sys.argv[2:] == ["facet"]:
    import dolfinx.cpp.mesh
    import cracklip.scene.partition
    cracklip.scene.partition.vertex_patch_partitioner = dolfinx.cpp.mesh.create_cell_partitioner()
if dim == 2:
    md = cl.create_rectangle(0.0, 0.0, 2.0, 1.0, 0.1)
    loads = [cl.Traction("top", (0.2, 1.0)), cl.Traction("right", (0.5, -0.1))]
    clamp = "bottom"
else:
    md = create_box(0.0, 0.0, 0.0, 2.0, 1.0, 1.0, 0.25)
    loads = [cl.Traction("zmax", (0.2, 0.1, 1.0)), cl.Traction("xmax", (0.5, -0.1, 0.0))]
    clamp = "zmin"
scene = cl.Scene(md, cl.Material(E=100.0, nu=0.3), dirichlet=[cl.Dirichlet(clamp)], tractions=loads)
u, _ = solve_plain(scene)

import dolfinx.fem
import dolfinx.fem.petsc
import dolfinx.la

msh = md.mesh
comm = msh.comm
V = dolfinx.fem.VectorFunctionSpace(msh, ("Lagrange", 1))
K = dolfinx.fem.petsc.assemble_matrix(elasticity_form(V, scene.material.E_strain, scene.material.nu_strain))
K.assemble()
x = dolfinx.la.create_petsc_vector(V.dofmap.index_map, V.dofmap.index_map_bs)
x.array[:u.size] = u
y = x.duplicate()
K.mult(x, y)
energy = 0.5 * x.dot(y)
u_max = comm.allreduce(float(np.abs(u).max(initial=0.0)), op=MPI.MAX)

nodes, cells = _cracklip.extract_node_mesh(V._cpp_object)
imap = V.dofmap.index_map
coords = V.tabulate_dof_coordinates()[:, :dim]
ok = (nodes.shape[0] == imap.size_local + imap.num_ghosts and cells.shape[0] == V.dofmap.list.num_nodes
      and np.array_equal(cells, V.dofmap.list.array.reshape(-1, dim + 1)))
far = float(np.abs(nodes - coords).max(initial=0.0))
ok = comm.allreduce(bool(ok), op=MPI.LAND)
far = comm.allreduce(far, op=MPI.MAX)
import cracklip.scene.mesh
gmsh_processes = comm.allreduce(int(cracklip.scene.mesh._GMSH_READY))
out = {"processes": comm.size, "gmsh_processes": gmsh_processes, "energy": energy, "u_max": u_max, "dofs": int(V.dofmap.index_map.size_global * dim),
       "incomplete": incomplete_patches(V), "node_mesh_ok": ok, "node_mesh_distance": far}
if comm.rank == 0:
    print(json.dumps(out), flush=True)
