"""Linear solvers of the assembled systems: checked MUMPS solves, the phantom-node
basis, the iterative (GAMG + crack band) path, the saddle point of contact,
nodal rescaling, and the choice between the paths.
"""
