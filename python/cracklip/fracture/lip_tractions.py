"""The tractions on a crack's lips that the interaction integral's lip term
takes, in 2D and 3D alike: the contact pressure and friction shear
(cracklip.contact.tractions), the crack's lip pressure, an initial
stress's sigma_0 n.

With the unit-K auxiliary field u_aux and the virtual extension q d, the
lip term of I is - int_lips t . (grad u_aux d) q dA over both lips, t the
traction each lip carries (the - lip the opposite of the + lip's). A crack
pressed shut has a pressure p there, which is what makes K_I = 0 instead of
negative; a sliding one a friction shear, which lowers K_II (and K_III in
3D) to the effective shear's. sif.py (tips) and sif_3d.py (fronts) call
lip_traction at their own lip points.
"""
from __future__ import annotations

import numpy as np

from ..contact.tractions import contact_tractions
from ..model.loads import lip_pressure
from ..scene.stress_field import evaluate_stress


def lip_traction_parts(solution, crack: int, points: dict[str, np.ndarray]) -> list[np.ndarray]:
    """The tractions (n, d) on the + lip of a crack at crack points (cell,
    ref, x, normal as from the crack's lip points), one array per cause:
    the contact tractions (pressure and friction shear), the crack's lip
    pressure, an initial stress's sigma_0 n (the correction field of an
    initial stress sees it on its lips). Each pushes the + lip along n
    (into the + side) when the lips are pressed or pushed apart; the - lip
    carries the opposite."""
    m = solution.model
    n = points["normal"]
    parts = []
    if solution.contact:
        parts.append(contact_tractions(m, solution.contact, crack, points["cell"], points["ref"], n)["traction"])
    crk = m.cracks[crack].crack
    if (callable(crk.pressure) or crk.pressure != 0.0) and solution.factor(crk.pressure_group) != 0.0:
        parts.append(solution.factor(crk.pressure_group) * lip_pressure(crk, points["x"])[:, None] * n)
    if m.scene.initial_stress is not None and solution.factor(m.scene.initial_stress_group) != 0.0:
        sig = evaluate_stress(m.scene.initial_stress, points["x"], "initial stress")
        parts.append(solution.factor(m.scene.initial_stress_group) * np.einsum("nij,nj->ni", sig, n))
    return parts


def lip_traction(solution, crack: int, points: dict[str, np.ndarray]) -> np.ndarray:
    """The total traction (n, d) on the + lip (lip_traction_parts summed)."""
    return sum(lip_traction_parts(solution, crack, points), np.zeros_like(points["normal"]))


def has_lip_traction(solution, crack: int) -> bool:
    """Whether any cause (contact, lip pressure, initial stress) can put a
    traction on the crack's lips in this solution."""
    m = solution.model
    crk = m.cracks[crack].crack
    return (bool(solution.contact)
            or ((callable(crk.pressure) or crk.pressure != 0.0) and solution.factor(crk.pressure_group) != 0.0)
            or (m.scene.initial_stress is not None and solution.factor(m.scene.initial_stress_group) != 0.0))


__all__ = ["lip_traction_parts", "lip_traction", "has_lip_traction"]
