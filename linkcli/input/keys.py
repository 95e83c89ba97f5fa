"""Reading of ``keys:``: the answer keys of a course, each checked against the answers.

    keys:
      - k: 3                                  # the digit printed for (default: the file's k)
        source: "exam 2024-06, solution"
        values: {phi3: 27.4, vB: 1.52, C: [120.5, 88.0]}   # as printed; a point is [x, y]
        tolerance: 2%                         # every value's: a percentage or a number
        tolerances: {vB: 0.05}                # one value's own, in its display unit
        wrong: {phi3: "the key's own phi2 gives 29.1"}    # provably wrong: reported, never failed

:class:`KeysSection` (a mixin of the Parser) reads each printed value as printed (its text
and its decimals: it is compared at its printed precision, ``runs.check``), the name it is
of and its tolerance; a value marked ``wrong`` that cannot be read as a number is kept as
printed and never compared.

Errors, each an :class:`~linkcli.errors.InputError` at the key's YAML path and line,
collected (exit 2): keys not a list; k not a digit; a name the file does not define or a
rate its quantity has not; a 'wrong' or 'tolerances' entry without a printed value; a
tolerance that is not a number >= 0 or a percentage; a point's key that is not [x, y]; a
printed value that is not a finite number.
"""
from __future__ import annotations

import dataclasses
import math
import re

from linkcli.model.mechanism import VIBRATION, AnswerKey, KeyEntry, Tolerance, split_rate
from linkcli.input.reader import _Skip

#: a relative tolerance as written: a percentage of at most 6 + 6 digits ('2%', '0.5 %')
TOLERANCE_PERCENT = re.compile(r"^([0-9]{1,6}(\.[0-9]{1,6})?) ?%$")


class KeysSection:
    """``keys`` (a mixin of the Parser)."""

    def keys(self, data, quantities, loads, pool, report) -> tuple:
        spec = data.get("keys")
        if spec is None:
            return ()
        if not isinstance(spec, list):
            raise self.error(("keys",), "expected a list of answer keys")
        keys = []
        for i, item in enumerate(spec):
            key = self.block(self.key, item, ("keys", i), quantities, pool)
            if key is not None:
                keys.append(key)
        return tuple(keys)

    def key(self, item, path, quantities, pool) -> AnswerKey:
        item = self.mapping(item, path, {"k", "values", "wrong", "source", "tolerance",
                                         "tolerances"}, ("values",))
        k = item.get("k")
        if k is not None and (isinstance(k, bool) or not isinstance(k, int) or not 0 <= k <= 9):
            raise self.error(path + ("k",), f"k must be a digit 0-9, got {k!r}")
        values = self.mapping(item["values"], path + ("values",))
        wrong = self.mapping(item.get("wrong") or {}, path + ("wrong",))
        for name in wrong:
            if name not in values:
                self.error(path + ("wrong", name), f"'{name}' has no printed value in this key")
        tolerances = self.key_tolerances(item, path, values)
        entries = []
        for name, printed in values.items():
            vpath = path + ("values", name)
            entry = self.block(self.key_entry, name, printed, vpath, quantities, pool,
                               wrong.get(name))
            if entry is not None:
                entries.append(dataclasses.replace(entry, tolerance=tolerances.get(name)))
        return AnswerKey(k, tuple(entries))

    def key_tolerances(self, item, path, values) -> dict:
        """Each printed value's tolerance: its own under ``tolerances``, else the key's
        ``tolerance`` (for every value of the key), else none."""
        default = None
        if "tolerance" in item:
            default = self.block(self.tolerance, item["tolerance"], path + ("tolerance",))
        own = self.block(self.mapping, item.get("tolerances") or {}, path + ("tolerances",))
        result = {name: default for name in values}
        for name, value in (own or {}).items():
            if name not in values:
                self.error(path + ("tolerances", name),
                           f"'{name}' has no printed value in this key")
                continue
            result[name] = self.block(self.tolerance, value, path + ("tolerances", name))
        return result

    def tolerance(self, value, path) -> Tolerance:
        """A tolerance: a number >= 0 (absolute, in the value's display unit) or a
        percentage of the printed value ('2%', '0.5 %')."""
        match = TOLERANCE_PERCENT.search(value) if isinstance(value, str) else None
        if match:
            return Tolerance(float(match.group(1)) / 100.0, True, match.group(1) + "%")
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise self.error(path, f"a tolerance is a number (absolute, in the value's display "
                             f"unit) or a percentage, got {value!r}",
                             hint="write e.g. 'tolerance: 2%' or 'tolerance: 0.05'")
        number = self.number(value, path)
        if number < 0:
            raise self.error(path, f"a tolerance is at least 0, got {value!r}")
        return Tolerance(number, False, str(self.doc.raw.get(path, value)))

    def key_entry(self, name, printed, path, quantities, pool, wrong) -> KeyEntry:
        line = self.doc.line(path)
        is_point = name in pool and (isinstance(printed, list) or name not in quantities)
        if not is_point:
            base = split_rate(name, quantities)
            if base is not None and base[0] in getattr(self, "failed", ()):
                raise _Skip()           # the quantity's own error is reported already
            if base is None or base[0] not in quantities:
                raise self.error(path, f"the key names '{name}', which the file does not define",
                                 hint="define it under 'quantities' or fix the name")
            if base[1] > quantities[base[0]].rates and quantities[base[0]].kind != "load" \
                    and quantities[base[0]].kind not in VIBRATION:
                raise self.error(path, f"the key names '{name}', which the file does not define: "
                                 f"'{base[0]}' has {quantities[base[0]].rates or 'no'} rate"
                                 f"{'' if quantities[base[0]].rates == 1 else 's'}",
                                 hint=f"compare '{base[0]}' itself")
        if wrong and not _readable(printed, is_point):
            # a garbled printed value: kept as printed, reported, never compared
            return KeyEntry(name, str(self.doc.raw.get(path, printed)), None, 0, wrong, line)
        if is_point:
            if not isinstance(printed, list) or len(printed) != 2:
                raise self.error(path, f"a point's key is [x, y], got {printed!r}")
            texts = [self.doc.raw.get(path + (i,), str(v)) for i, v in enumerate(printed)]
            nums = tuple(self.printed_number(t, path + (i,)) for i, t in enumerate(texts))
            return KeyEntry(name, f"({texts[0]}, {texts[1]})", nums,
                            min(_decimals(t) for t in texts), wrong, line)
        text = self.doc.raw.get(path, str(printed))
        return KeyEntry(name, text, self.printed_number(text, path), _decimals(text), wrong, line)

    def printed_number(self, text, path) -> float:
        try:
            value = float(str(text).replace(",", "."))
        except ValueError:
            raise self.error(path, f"cannot read printed value {text!r} as a number") from None
        if not math.isfinite(value):
            raise self.error(path, f"printed value {text!r} is not finite")
        return value


def _readable(printed, is_point: bool) -> bool:
    """Whether a printed key value can be read as a number (or [x, y] for a point)."""
    values = printed if is_point and isinstance(printed, list) and len(printed) == 2 else (
        None if is_point else [printed])
    if values is None:
        return False
    try:
        return all(math.isfinite(float(str(v).replace(",", "."))) for v in values)
    except ValueError:
        return False


def _decimals(text: str) -> int:
    text = str(text).strip().replace(",", ".")
    return len(text.split(".")[1]) if "." in text else 0
