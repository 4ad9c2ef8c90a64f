"""Run under mpirun (or alone) by tests/test_mpi.py: the Python API path
(load_scene_file, solve, Solution.stress_intensity_factors) of an open
crack with options.solver = "iterative" (serial: solvers/iterative.py; on
several processes solvers/distributed_iterative.py). Prints one JSON line
(rank 0):

  processes   the number of processes
  sifs        [K_I, K_II(, K_III)] per tip or front point
  solver      the solver path of the solve ("iterative")
  method      its method (Krylov + preconditioner)
  iterations  Krylov iterations
  residual    relative residual of the original (untransformed) system

    python3 tests/mpi/iterative.py SCENE [KEY=VALUE ...]
"""
import json
import sys

from split import from_argv

from_argv()  # (before cracklip meshes anything)
import cracklip as cl  # noqa: E402

sf = cl.load_scene_file(sys.argv[1], [*sys.argv[2:], 'options.solver="iterative"'])
sol = cl.solve(sf.scene)
rows = sol.stress_intensity_factors(None)
comm = sol.model.scene.mesh.mesh.comm
last = sol.solver["solves"][-1]
names = ("K_I", "K_II", "K_III") if sol.model.gdim == 3 else ("K_I", "K_II")
out = {"processes": comm.size, "sifs": [[float(r[k]) for k in names] for r in rows],
       "solver": sol.solver["solver"], "method": last.get("method"), "iterations": last.get("iterations"),
       "residual": last["relative_residual"]}
if comm.rank == 0:
    print(json.dumps(out), flush=True)
