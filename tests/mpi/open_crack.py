"""Run under mpirun (or alone) by tests/test_mpi.py: the Python API path
(load_scene_file, solve, Solution.stress_intensity_factors) of an open 2D
crack, the direct solver. Prints one JSON line (rank 0):

  processes   the number of processes
  dofs        global X-FEM dofs (standard + enriched)
  enriched    global enriched dofs
  sifs        [K_I, K_II] per tip
  energy      1/2 u . f: the work of the lip pressure (summed over processes)
  residual    the solve's relative residual
  split       processes owning pseudo-nodes, and ghost pseudo-nodes
              numbered from their owners (the crack crosses the partition)

    python3 tests/mpi/open_crack.py SCENE [KEY=VALUE ...]
"""
import json
import sys

import numpy as np

import cracklip as cl
from cracklip.model.loads import assemble_load

sf = cl.load_scene_file(sys.argv[1], sys.argv[2:])
sol = cl.solve(sf.scene)
rows = sol.stress_intensity_factors(None)
m = sol.model
comm = m.scene.mesh.mesh.comm
f = assemble_load(m)  # this process's owned cells' loads: their work sums over processes
work = comm.allreduce(float(np.dot(f, sol.u)))
if m.distributed:
    dofs, enriched = m.dofs.num_global * m.gdim, None
    own = np.asarray(m.layout.node) < m.V.dofmap.index_map.size_local
    enriched = comm.allreduce(int(np.count_nonzero(own))) * m.gdim
    ghost_numbered = np.count_nonzero(m.dofs.block[m.layout.num_std_nodes:][~own] >= 0)
    split = [comm.allreduce(int(own.any())), comm.allreduce(int(ghost_numbered))]
else:
    dofs, enriched = m.num_dofs, m.gdim * m.layout.num_enriched
    split = [1, 0]
out = {"processes": comm.size, "dofs": int(dofs), "enriched": int(enriched),
       "sifs": [[r["K_I"], r["K_II"]] for r in rows], "work": 0.5 * work,
       "residual": sol.solver["relative_residual"], "split": split}
if comm.rank == 0:
    print(json.dumps(out), flush=True)
