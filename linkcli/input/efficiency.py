"""Reading of the efficiency questions of a mechanism with friction (``forces.efficiency``):

    quantities:
      eta:   {efficiency: direct}            # Q0 / Q: output over input power
      eta_r: {efficiency: reverse}           # Q_r / Q0: the load drives, Q holds back
      P0:    {ideal_load: P}                 # the unknown load P without friction
      Pr:    {reverse_load: P}               # P in reverse motion (with friction)
      locks: {self_locking: locks}           # 1 where eta_r <= 0 (it locks itself), else 0
      mu_l:  {self_locking: friction}        # the friction where self-locking starts
      mu_b:  {self_locking: friction, at: block}   # of one loss, when there are several
      eta_s: {efficiency: series, stages: [0.95, 0.9]}                 # product
      eta_p: {efficiency: parallel, stages: [0.9, 0.8], powers: [3, 1]}  # power-weighted

The answers are listed under ``statics`` (they are found with the unknown load).  A series or
parallel efficiency reads only its numbers (expressions of the params); ``powers`` are the
stages' input powers, in any one unit (only their ratios count).

Errors, each an :class:`~linkcli.errors.InputError` at the quantity's YAML path and line
(exit 2): an unknown kind of efficiency or of self-locking answer; a load that is not the
file's unknown one; stages that are not efficiencies in (0, 1]; powers that are not
positive or not one per stage; ``at`` that names no loss.
"""
from __future__ import annotations

import dataclasses

from linkcli.model.mechanism import Quantity

#: the YAML keys of the efficiency questions, each a quantity kind
EFFICIENCY = ("efficiency", "ideal_load", "reverse_load", "self_locking")
KINDS = {"efficiency": ("direct", "reverse", "series", "parallel"),
         "self_locking": ("locks", "friction")}


class EfficiencyQuantities:
    """Efficiency questions (a mixin of the Parser)."""

    def efficiency_quantity(self, name, value, path, loads) -> Quantity:
        return dataclasses.replace(self.efficiency_kind(name, value, path, loads),
                                   line=self.doc.line(path))

    def efficiency_kind(self, name, value, path, loads) -> Quantity:
        kind = next(k for k in EFFICIENCY if k in value)
        allowed = {kind} | ({"stages", "powers"} if kind == "efficiency" else set()) | \
            ({"at"} if kind == "self_locking" else set())
        value = self.mapping(value, path, allowed)
        arg = value[kind]
        where = path + (kind,)
        if kind in ("ideal_load", "reverse_load"):
            load = self.name(arg, where, loads, "load")
            if loads[load].value is not None:
                raise self.error(where, f"'{load}' is a known load: the {kind.replace('_', ' ')}"
                                 " is that of the unknown one", hint="name the load whose "
                                 "value is unknown")
            return Quantity(name, kind, load)
        if arg not in KINDS[kind]:
            raise self.error(where, f"unknown {kind.replace('_', ' ')} answer {arg!r}",
                             hint="one of " + ", ".join(KINDS[kind]))
        if kind == "self_locking":
            at = value.get("at")
            if at is not None and arg != "friction":
                raise self.error(path + ("at",), "'at' names the loss whose friction is asked",
                                 hint="{self_locking: friction, at: SLIDER}")
            return Quantity(name, kind, arg, None if at is None else str(at))
        if arg in ("direct", "reverse"):
            for extra in ("stages", "powers"):
                if extra in value:
                    raise self.error(path + (extra,), f"'{extra}' is for series and parallel "
                                     "efficiencies")
            return Quantity(name, kind, arg)
        return Quantity(name, kind, arg, elements=self.stages(value, path, arg))

    def stages(self, value, path, arg) -> tuple:
        """((eta_i, P_i), ...) of a series (P_i = 1) or parallel efficiency."""
        if "stages" not in value:
            raise self.error(path, f"a {arg} efficiency needs its 'stages'",
                             hint="stages: [0.95, 0.9]")
        etas = self.numbers(value["stages"], path + ("stages",))
        for i, eta in enumerate(etas):
            if not 0 < eta <= 1:
                raise self.error(path + ("stages", i), f"an efficiency is in (0, 1], got {eta:g}")
        if arg == "series":
            if "powers" in value:
                raise self.error(path + ("powers",), "machines in series pass one power: "
                                 "'powers' is for a parallel efficiency")
            return tuple((eta, 1.0) for eta in etas)
        if "powers" not in value:
            raise self.error(path, "a parallel efficiency needs the stages' input 'powers'",
                             hint="powers: [3, 1] (only their ratios count)")
        powers = self.numbers(value["powers"], path + ("powers",))
        if len(powers) != len(etas):
            raise self.error(path + ("powers",), f"{len(powers)} powers for {len(etas)} stages",
                             hint="one input power per stage")
        for i, power in enumerate(powers):
            if not power > 0:
                raise self.error(path + ("powers", i), f"an input power is positive, got {power:g}")
        return tuple(zip(etas, powers))

    def numbers(self, value, path) -> list:
        if not isinstance(value, list) or not value:
            raise self.error(path, "expected a list of numbers")
        return [float(self.number(v, path + (i,))) for i, v in enumerate(value)]
