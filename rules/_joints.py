"""Helpers for the joint-limit rules (not a rule)."""
from urdf_lint.ruleutil import number


def limits(j):
    """(limit element or None, lower, upper, effort, velocity) with URDF defaults (0) applied."""
    lim = j.find("limit")
    if lim is None:
        return None, None, None, None, None
    return (lim, number(lim.get("lower", "0")), number(lim.get("upper", "0")),
            number(lim.get("effort")), number(lim.get("velocity")))


def moving(j):
    return j.get("type") in ("revolute", "prismatic")
