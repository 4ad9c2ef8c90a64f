"""What the user describes: the part's mesh (generated or imported), the material,
the cracks, boundary conditions and loads (with load paths), growth settings and
numerical options. Nothing here knows about enrichment or solvers.
"""
