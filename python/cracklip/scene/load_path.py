"""The load path as described: steps of factors per load group, split into increments.

A scene's loads belong to named groups (Traction.group, Dirichlet.group,
...; "default" unless named). Scene.load_path is a list of LoadStep: the
factor of each group at the end of the step; a group not named keeps its
factor from the step before, and every factor is 0 before the first step
(the path starts unloaded). Options.load_steps splits each step into that
many increments (linear in the factors). Without a load path the scene is
one step taking every group from 0 to 1.
"""
from __future__ import annotations

import dataclasses

from ..errors import InputError
from .conditions import LoadStep
from .scene import Scene, load_groups


@dataclasses.dataclass(frozen=True)
class Increment:
    """One increment of the path: step index, increment index within the
    step (1 .. load_steps), and the factor of every group."""
    step: int
    index: int
    factors: dict[str, float]


def steps(scene: Scene) -> list[LoadStep]:
    """The scene's load steps (one step of factor 1 for every group without a path)."""
    groups = load_groups(scene) | {"default"}
    if scene.load_path is None:
        return [LoadStep({g: 1.0 for g in sorted(groups)}, name="load")]
    for st in scene.load_path:
        unknown = sorted(set(st.factors) - groups)
        if unknown:
            raise InputError(f"load step {st.name!r} names load group(s) {unknown} that no load or Dirichlet "
                             f"value belongs to; the scene's groups: {sorted(groups)}")
    return list(scene.load_path)


def increments(scene: Scene) -> list[Increment]:
    """Every increment of the path, in order (the module doc)."""
    groups = sorted(load_groups(scene) | {"default"})
    n = scene.options.load_steps
    prev = {g: 0.0 for g in groups}
    out = []
    for k, st in enumerate(steps(scene)):
        target = {**prev, **st.factors}
        for i in range(1, n + 1):
            out.append(Increment(k, i, {g: prev[g] + (target[g] - prev[g]) * i / n for g in groups}))
        prev = target
    return out
