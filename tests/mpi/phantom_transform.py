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

from split import from_argv

from_argv()  # (before cracklip meshes anything)
import cracklip as cl  # noqa: E402
from cracklip.model.assembly import assemble_distributed_system  # noqa: E402
from cracklip.model.model import create_model  # noqa: E402
from cracklip.solvers.distributed_iterative import DistributedIterativeSolver, transform_in_place  # noqa: E402

sf = cl.load_scene_file(sys.argv[1], [*sys.argv[2:], 'options.solver="iterative"'])
model = create_model(sf.scene)
A, b, _ = assemble_distributed_system(model)
linear = DistributedIterativeSolver(model)
P = A.PtAP(linear.basis.T)
A0 = A.duplicate(copy=True)
norm = A.norm()
A_t = transform_in_place(linear.basis, A)
out = {"processes": model.V.mesh.comm.size, "in_place": A_t is A}
if A_t is A:
    P.axpy(-1.0, A)
    A0.axpy(-1.0, A)
    out.update(difference=P.norm() / norm, changed=A0.norm() / norm)
if model.V.mesh.comm.rank == 0:
    print(json.dumps(out), flush=True)
