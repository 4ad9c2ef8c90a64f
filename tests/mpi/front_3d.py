"""Run under mpirun (or alone) by tests/test_mpi.py: a 3D crack's front as
every process builds it on its part of the mesh (model/cracks/
shared_front.py). Prints one JSON line (rank 0):

  processes   the number of processes
  front       x, s, frame, on_boundary, piece_offsets, closed: the front
              of rank 0
  same        whether every process holds that front (bit for bit)
  local       front segments whose cell is on the process, per process
  owned_front owned front cells per process (the front is split)

    python3 tests/mpi/front_3d.py SCENE [KEY=VALUE ...]
"""
import json
import sys

import numpy as np

import dolfinx.fem

import cracklip as cl
from cracklip import _cracklip
from cracklip.model.cracks.surface import SurfaceCrackModel

sf = cl.load_scene_file(sys.argv[1], sys.argv[2:])
scene = sf.scene
msh = scene.mesh.mesh
comm = msh.comm
V = dolfinx.fem.VectorFunctionSpace(msh, ("Lagrange", 1))
x, cells = _cracklip.extract_node_mesh(V._cpp_object)
crack = SurfaceCrackModel.create(scene, scene.cracks[0], x, cells)
f = crack.geometry.front
keys = ("x", "s", "frame", "on_boundary", "piece_offsets", "closed")
front = {k: np.asarray(f[k]).tolist() for k in keys}
blob = b"".join(np.ascontiguousarray(f[k]).tobytes() for k in keys)
same = all(b == blob for b in comm.allgather(blob))
num_owned = msh.topology.index_map(3).size_local
out = {"processes": comm.size, "front": front, "same": same,
       "local": comm.allgather(int(np.count_nonzero(np.asarray(f["segment_cell"]) >= 0))),
       "segments": len(f["segment_cell"]),
       "owned_front": comm.allgather(int(np.count_nonzero(np.asarray(crack.geometry.cell_class)[:num_owned] == 3)))}
if comm.rank == 0:
    print(json.dumps(out), flush=True)
