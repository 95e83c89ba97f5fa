"""What a sweep says of the rows it cannot answer: an :class:`Issue` per range of driver values.

Kinds: ``assembly`` (no configuration: the links' largest shortfall, or Newton's closure
error), ``singular`` (velocities undefined at a toggle: the group's conditioning),
``no-work``, ``at-rest`` and ``self-locking`` (a load's answer undefined), and ``branch``
(a toggle passed between two samples; the rows are kept).  Ranges are in the driver's
display unit, shortfalls in the display length unit; the message is printed on stderr and
the same fields go to a JSON sweep's ``issues``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field


@dataclass
class Issue:
    """A range of driver values (display units) where something must be said."""

    kind: str            # 'assembly' | 'singular' | 'branch' | 'no-work' | 'at-rest' |
    #                      'self-locking'
    group: str
    lo: float
    hi: float
    count: int
    amount: float        # shortfall (display length; inf: no configuration) or conditioning
    q_unit: str
    l_unit: str
    index: int = field(default=-1, repr=False, compare=False)   # the group's, for sorting
    closure: bool = False   # the amount is Newton's closure error, not links' shortfall

    def text(self) -> str:
        where = (f"at q = {self.lo:.6g} {self.q_unit}" if self.count == 1 or self.lo == self.hi
                 else f"for q in [{self.lo:.6g}, {self.hi:.6g}] {self.q_unit}")
        if self.kind == "assembly":
            why = "no configuration found" if not math.isfinite(self.amount) else \
                f"no convergence, closure error up to {self.amount:.4g} {self.l_unit}" \
                if self.closure else f"links short by up to {self.amount:.4g} {self.l_unit}"
            return f"cannot assemble {where}: {self.group}, {why}"
        if self.kind == "singular":
            return (f"velocities undefined {where}: {self.group} at a toggle (conditioning "
                    f"{self.amount:.2e}); rows left out")
        if self.kind == "no-work":
            return (f"the unknown load {self.group} does no work {where} (a dead centre for "
                    f"it: coefficient {self.amount:.1e} of the largest load's); rows left out")
        if self.kind == "self-locking":
            return (f"the friction locks the mechanism {where} (self-locking, with "
                    f"{self.group}); rows left out")
        if self.kind == "at-rest":
            return (f"{self.group} is undetermined {where}: its pair is at rest (relative "
                    f"rate {self.amount:.1e} of the largest), so the sense of the loss is "
                    "unknown; rows left out")
        return (f"branch point at q = {self.lo:.6g} {self.q_unit}: {self.group} passes a toggle "
                "(its conditioning touches 0); the sweep keeps its branch, the mechanism may "
                "leave on either")

    def as_dict(self) -> dict:
        out = {"kind": self.kind, "group": self.group, "from": self.lo, "to": self.hi,
               "positions": self.count, "message": self.text()}
        if self.kind == "assembly":
            out["shortfall"] = self.amount if math.isfinite(self.amount) else None
            out["unit"] = self.l_unit
        else:
            out["conditioning"] = self.amount
        return out

