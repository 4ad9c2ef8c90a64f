"""Crack-lip contact on the multiplier space: frictionless (bilateral or
unilateral by a primal-dual active set), Coulomb friction, the inf-sup test.
"""
