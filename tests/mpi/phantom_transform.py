"""Run under mpirun by tests/test_mpi.py: the distributed phantom transform
T^T A T computed in A's storage (solvers/distributed_iterative.py
transform_in_place) against PETSc's parallel PtAP of the same A. Prints one
JSON line (rank 0):

  processes   the number of processes
  in_place    whether the in-place update applied (A's pattern holds it)
  difference  ||PtAP - in place||_F / ||A||_F
  changed     ||T^T A T - A||_F / ||A||_F (the transform does something)

    python3 tests/mpi/phantom_transform.py SCENE [KEY=VALUE ...]
"""
import json
import sys

import cracklip as cl
from cracklip.model.assembly import assemble_distributed_system
from cracklip.model.model import create_model
from cracklip.solvers.distributed_iterative import DistributedIterativeSolver, transform_in_place
from cracklip.solvers.iterative import crack_band

sf = cl.load_scene_file(sys.argv[1], [*sys.argv[2:], 'options.solver="iterative"'])
model = create_model(sf.scene)
A, b, _ = assemble_distributed_system(model)
linear = DistributedIterativeSolver(model)
P = A.PtAP(linear.basis.T)
A0 = A.duplicate(copy=True)
norm = A.norm()
A_t = transform_in_place(linear.basis, A, linear._owned_rows(crack_band(model, 1)))
out = {"processes": model.V.mesh.comm.size, "in_place": A_t is A}
if A_t is A:
    P.axpy(-1.0, A)
    A0.axpy(-1.0, A)
    out.update(difference=P.norm() / norm, changed=A0.norm() / norm)
if model.V.mesh.comm.rank == 0:
    print(json.dumps(out), flush=True)
