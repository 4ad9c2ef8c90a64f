"""Drivers that solve: one scene, a load path, crack growth step by step.
"""
