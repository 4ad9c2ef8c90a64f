"""Newman and Raju's stress intensity factors of surface and corner cracks
under remote tension, and of surface cracks under bending (NASA TM-85793,
1984): a handbook fit to finite element results, stated accurate to +-5 %,
not an exact solution. The
formulas live with the other handbook geometry factors in
cracklip.fracture.handbook (its docstring has them); the 3D checks import
them from here.
"""
from ..fracture.handbook import corner_crack_F, surface_crack_F, surface_crack_k, surface_H

__all__ = ["surface_crack_F", "corner_crack_F", "surface_crack_k", "surface_H"]
