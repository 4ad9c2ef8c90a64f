"""A solved model and what derives from it: point values, crack opening and
pressure, sub-cell fields, energies, SIFs on demand (cracklip.fracture).
"""
