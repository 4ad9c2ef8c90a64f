"""The discrete X-FEM model of a scene: level sets and cell classes (C++), the
enrichment layout, Dirichlet constraints, the room around each tip, model
checks, and the assembly of the stiffness and the loads.
"""
