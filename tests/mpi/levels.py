"""Run under mpirun (or alone) by tests/test_mpi.py: a fatigue life's load
levels (analysis.load_path.LevelSolver) with frictionless crack-lip
contact, one assembly, each level warm-started from the last one's active
set, a linear (contact-free) level between them. Prints one JSON line
(rank 0), per level in the order solved:

  name        the level's name
  contact     solved with contact (else linearly)
  sifs        [K_I, K_II(, K_III)] per tip or front point
  active      the final active set (0/1 per reduced multiplier; [] linear)
  history     active counts per active-set iteration
  lambda      the reduced multipliers ([] linear)
  solver      the solver path of its solves ("direct" or "iterative")
  reused      whether its solves reused the preconditioner (the
              iterative path's AMG hierarchy; false on the direct path)

    python3 tests/mpi/levels.py SCENE STATES_JSON [KEY=VALUE ...]

STATES_JSON: [[contact, {group: factor}], ...].
"""
import json
import sys

import cracklip as cl
from cracklip.analysis.load_path import LevelSolver

sf = cl.load_scene_file(sys.argv[1], sys.argv[3:])
levels = json.loads(sys.argv[2])
solver = LevelSolver(sf.scene)
out = {"levels": []}
try:
    for i, (contact, factors) in enumerate(levels):
        sol, = solver.solve([factors], contact=contact, names=[f"level {i}"])
        comps = ["K_I", "K_II"] + (["K_III"] if sol.model.gdim == 3 else [])
        c = sol.contact
        out["levels"].append({"name": sol.step["name"], "contact": bool(c),
                              "sifs": [[r[k] for k in comps] for r in sol.stress_intensity_factors(None)],
                              "active": [int(a) for a in c["active"]] if c else [],
                              "history": [int(h) for h in c["history"]] if c else [],
                              "lambda": [float(v) for v in c["lambda"]] if c else [],
                              "solver": sol.solver["solver"],
                              "reused": all(s.get("setup_reused", False) for s in sol.solver["solves"])})
    out["solves"] = solver.solves
    out["processes"] = sol.model.V.mesh.comm.size
finally:
    solver.close()
if sol.model.V.mesh.comm.rank == 0:
    print(json.dumps(out), flush=True)
