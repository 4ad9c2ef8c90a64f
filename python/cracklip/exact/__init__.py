"""Closed-form reference fields (Williams, Griffith, Kirsch) for demos, tests and
scene files' exact boundary conditions; never used by the solver path.
"""
