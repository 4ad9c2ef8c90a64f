"""Growth settings as the user gives them (cracklip grow, the [growth] table)."""
from __future__ import annotations

import dataclasses
import math
import typing

from ..errors import InputError, checked_keywords


CRITERIA = ("max_hoop", "max_energy_release")


@checked_keywords
@dataclasses.dataclass
class Growth:
    """Growth settings.

    Attributes:
        criterion: "max_hoop" (maximum hoop stress, Erdogan-Sih; 3D:
            generalised with K_III, code_aster's SITT_MAX_DEVER kink) or
            "max_energy_release" (the kink maximising k1^2 + k2^2 of the
            first-order local stress intensity factors; 2D only).
        da: the increment of a step (of the fastest tip in fatigue), in
            length units; 0 takes 3 element sizes at the first tip. 3D: the
            largest advance along the front in one step (each point
            advances da times its rate over the fastest one's); 0: 2
            element sizes at the front.
        da_fraction: 3D fronts: the step's largest advance as this fraction
            of the fastest point's crack size a (its distance from the
            crack's origin), instead of growth.da: steps that keep pace with
            a crack growing by orders of magnitude on a graded mesh (0: off).
        steps: the number of increments.
        paris_C: C of the Paris law da/dN = C (Delta K)^m; with paris_m the
            growth is fatigue (cycles integrated) and needs a load cycle.
        paris_m: m of the Paris law (> 0).
        threshold: Delta K below which a tip does not grow (fatigue), or
            K_eq below which it does not (fixed increments; 0: always grows).
        walker_gamma: Walker's R-ratio form da/dN = C (Delta K / (1 -
            R)^(1 - gamma))^m with R = K_min / K_max; 1: plain Paris.
        K_Ic: fracture toughness: K_eq at or above it is final failure
            (unset: no check); found inside the step that reaches it (2D
            constant amplitude: K_eq linear over the step; 3D: the fatigue
            life's K_c).
        cycle_max: factors per load group at the maximum of the load cycle
            (unset: every group at 1).
        cycle_min: factors per load group at the minimum of the load cycle
            (unset: R times cycle_max, except an initial stress's own load
            group, which keeps its cycle_max factor: a residual stress does
            not cycle).
        R: load ratio min / max of a proportional cycle of the applied loads
            (when cycle_min is unset): K_min = K_res + R K_applied with a
            residual stress in a load group of its own.
        max_length: stop when a crack's length in the part reaches this
            (3D: a surface or corner crack's depth a, an embedded crack's
            mean radius; unset: no limit); in fatigue the life is the one to
            it, found inside the step that passes it; a crack already at it
            at the start stops at step 0 saying so.
        max_kink_change: stop when a tip's kink turns by more than this
            (degrees) between steps (instability; the first kink, off the
            initial crack, is not compared; 2D only).
        corrections: corrector solves per step (0: the explicit scheme; 2D only):
            each increment is turned about its start until the kink wanted
            at its end is below corrector_tolerance (local symmetry at the
            end of the increment); steadies paths whose explicit kinks
            zig-zag (strong compression along the crack, T << 0).
        corrector_tolerance: the kink (degrees) below which an increment
            is not corrected.
        reference_stress: the remote stress S that factor 1 of each load
            group stands for (beta = K / (S sqrt(pi a)) in beta tables, the
            residual strength in stress); unset: 1 per group (beta per unit
            factor).
        fatigue_material: the fatigue life's growth law and constants
            (cracklip.scene.fatigue.FatigueMaterial; [material.fatigue] in a
            scene file); with it the life is integrated over a spectrum (or
            the cycle of cycle_max / cycle_min / R) instead of paris_C, paris_m.
        spectrum: the load spectrum (cracklip.scene.spectrum.Spectrum; the
            [spectrum] table); needs fatigue_material.
    """
    criterion: str = "max_hoop"
    da: float = 0.0
    steps: int = 10
    da_fraction: float = 0.0
    paris_C: float | None = None
    paris_m: float | None = None
    threshold: float = 0.0
    walker_gamma: float = 1.0
    K_Ic: float | None = None
    cycle_max: dict[str, float] | None = None
    cycle_min: dict[str, float] | None = None
    R: float | None = None
    max_length: float | None = None
    max_kink_change: float = 60.0
    corrections: int = 0
    corrector_tolerance: float = 1.0
    reference_stress: dict[str, float] | None = None
    fatigue_material: typing.Any = None
    spectrum: typing.Any = None

    def __post_init__(self):
        def positive(name, v, allow_none=False, allow_zero=False):
            if v is None and allow_none:
                return
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or \
                    v < 0.0 or (v == 0.0 and not allow_zero):
                raise InputError(f"growth.{name} must be a {'non-negative' if allow_zero else 'positive'} "
                                 f"finite number, got {v!r}")
        if self.criterion not in CRITERIA:
            raise InputError(f"growth.criterion must be one of {CRITERIA}, got {self.criterion!r}")
        positive("da", self.da, allow_zero=True)
        positive("da_fraction", self.da_fraction, allow_zero=True)
        if self.da_fraction >= 1.0:
            raise InputError(f"growth.da_fraction is a fraction of the crack size (below 1, e.g. 0.1), got "
                             f"{self.da_fraction!r}")
        if isinstance(self.steps, bool) or not isinstance(self.steps, int) or self.steps < 1:
            raise InputError(f"growth.steps must be an integer >= 1, got {self.steps!r}")
        if isinstance(self.corrections, bool) or not isinstance(self.corrections, int) or self.corrections < 0:
            raise InputError(f"growth.corrections must be an integer >= 0, got {self.corrections!r}")
        positive("corrector_tolerance", self.corrector_tolerance)
        positive("threshold", self.threshold, allow_zero=True)
        positive("K_Ic", self.K_Ic, allow_none=True)
        positive("max_length", self.max_length, allow_none=True)
        positive("max_kink_change", self.max_kink_change)
        positive("walker_gamma", self.walker_gamma)
        if (self.paris_C is None) != (self.paris_m is None):
            raise InputError("growth.paris_C and growth.paris_m come together (da/dN = C (Delta K)^m)")
        if self.paris_C is not None:
            positive("paris_C", self.paris_C)
            positive("paris_m", self.paris_m)
            if self.cycle_min is None and self.R is None:
                raise InputError("fatigue growth (paris_C, paris_m) needs a load cycle: growth.cycle_min "
                                 "(factors at the minimum load) or growth.R (min = R max)")
        if self.R is not None and not (isinstance(self.R, (int, float)) and math.isfinite(self.R) and self.R < 1.0):
            raise InputError(f"growth.R (the load ratio min / max) must be a finite number below 1, got {self.R!r}")
        for name in ("cycle_max", "cycle_min"):
            v = getattr(self, name)
            if v is not None and (not isinstance(v, dict) or not v or not all(
                    isinstance(f, (int, float)) and not isinstance(f, bool) and math.isfinite(f) for f in v.values())):
                raise InputError(f"growth.{name} must be a table of load group = factor, got {v!r}")
        if self.reference_stress is not None and (not isinstance(self.reference_stress, dict) or not all(
                isinstance(f, (int, float)) and not isinstance(f, bool) and math.isfinite(f) and f > 0
                for f in self.reference_stress.values())):
            raise InputError(f"growth.reference_stress must be a table of load group = positive stress, got "
                             f"{self.reference_stress!r}")
        if self.spectrum is not None and self.fatigue_material is None:
            raise InputError("a load spectrum needs the fatigue constants of the material: give [material.fatigue] "
                             "(law and constants), or Growth(fatigue_material=...)")
        if self.fatigue_material is not None:
            if self.paris_C is not None:
                raise InputError("give the growth law once: growth.paris_C / paris_m or [material.fatigue], not both")
            if self.spectrum is None and self.cycle_min is None and self.R is None:
                raise InputError("the fatigue life needs a load history: a [spectrum] table, or a constant-amplitude "
                                 "cycle (growth.cycle_min or growth.R)")
            if self.spectrum is not None and (self.cycle_min is not None or self.R is not None
                                              or self.cycle_max is not None):
                raise InputError("give the load history once: a [spectrum] or growth.cycle_max / cycle_min / R, "
                                 "not both")
            if self.threshold != 0.0:
                raise InputError("growth.threshold belongs to growth.paris_C; with [material.fatigue] give "
                                 "material.fatigue.threshold (or the law's own, e.g. NASGRO's dK1)")
            if self.walker_gamma != 1.0:
                raise InputError("growth.walker_gamma belongs to growth.paris_C; with [material.fatigue] give "
                                 "law = 'walker' and its gamma there")
            if self.K_Ic is not None:
                # (both were applied: the life's K_c inside the step, growth.K_Ic at the steps' geometries only, so
                # with growth.K_Ic the lower the life ran on to the geometry past it)
                raise InputError("growth.K_Ic belongs to growth.paris_C; with [material.fatigue] give "
                                 "material.fatigue.K_Ic (in the constants' units), which the life finds inside the "
                                 "step that reaches it")
        if self.cycle_max is not None and self.cycle_min is not None:
            bad = [g for g in self.cycle_max if self.cycle_min.get(g, 0.0) > self.cycle_max[g]]
            if bad:
                raise InputError(f"growth.cycle_min is above growth.cycle_max for group(s) {bad}: the load cycle "
                                 "goes from the minimum to the maximum load")

    @property
    def fatigue(self) -> bool:
        """Cycles are counted: growth.paris_C (constant amplitude, Delta K
        linear along each step: analysis.growth_run.increment_cycles) or a
        fatigue life (fatigue_material)."""
        return self.paris_C is not None or self.fatigue_material is not None

    @property
    def life(self) -> bool:
        """The fatigue life of cracklip.analysis.life: a growth law of
        cracklip.fracture.laws over a spectrum or a constant-amplitude cycle."""
        return self.fatigue_material is not None


def load_cycle(growth: Growth, groups: typing.Iterable[str],
               initial_stress_group: str | None = None) -> tuple[dict[str, float], dict[str, float], str | None]:
    """The factors per load group at the maximum and the minimum of the load
    cycle of growth.cycle_max / cycle_min / R, and a warning (or None).

    cycle_min unset: R times cycle_max, except the load group of an initial
    (residual) stress when other groups carry the applied load: a residual
    stress does not cycle, so that group (the initial stress and the
    tractions that hold it) keeps its cycle_max factor and K_min = K_res +
    R K_applied. (Scaling it by R too made K_min = R K_max: an edge crack
    with the residual K 0.499 and the applied 1.078 at R = 0.1 had K_min
    0.158 instead of 0.607.) When the initial stress shares its group with every load, nothing
    tells the residual part from the applied one: R scales both, and the
    warning says so."""
    groups = sorted(set(groups)) or ["default"]
    high = dict(growth.cycle_max) if growth.cycle_max is not None else {g: 1.0 for g in groups}
    if growth.cycle_min is not None:
        return high, dict(growth.cycle_min), None
    low = {g: growth.R * f for g, f in high.items()}
    if initial_stress_group is None:
        return high, low, None
    if any(g != initial_stress_group for g in groups):
        if initial_stress_group in high:
            low[initial_stress_group] = high[initial_stress_group]
        return high, low, None
    return high, low, (f"growth.R = {growth.R:g} scales the initial (residual) stress with the applied load: they "
                       f"share the load group {initial_stress_group!r}, so K_min = R K_max, the residual K cycling "
                       f"with the load; give the residual stress (and the tractions holding it) a load group of its "
                       f"own, which R leaves at its cycle_max factor, or set growth.cycle_min")
