"""Fracture mechanics from a solved field: stress intensity factors by the domain
interaction integral, kink criteria, and (pure functions) the laws of growth.
"""
