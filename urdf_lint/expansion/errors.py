"""How a failure while expanding becomes one located problem: the table of xacro errors.

Every failure of xacro (or of our hooks and policies) ends as exactly one :class:`Problem`.
:data:`ERROR_TABLE` is read top to bottom; the first row that matches decides the code (by the
rule module, never a literal) and the message. A row looks at the raised exception, at the
exception xacro wrapped in it (``XacroException.exc``, unwrapped to the innermost), or either.
The location is the exception's own when it carries one (XML syntax errors, refused input),
else the innermost element xacro was evaluating; ``(in macro 'inner' < 'outer')`` names the
macros being expanded for rows marked ``macros`` (the innermost three, then the depth).

==================================  ======  =================================================
exception                           code    message
==================================  ======  =================================================
XmlSyntaxError (our parser)         UL001   ``XML syntax error: ...`` at its line and column
RefusedInput (entities, DTD, roots) own     UL007 or UL902, at its own location if known
SyntaxError in an expression        UL002   ``invalid expression: ...``
RecursionError                      UL904   recursion too deep
PackageNotFound (``$(find)``, ...)  UL004   unknown package, with the places searched
OutsideRoots                        UL902   resolves outside the package roots
ArgException (xacro)                UL005   arg without default or value
OSError with a file name            UL003   included file not found
UnsafeExpression (safe_eval)        UL903   refused by the allow-list evaluator
MemoryError                         UL904   ran out of memory
anything else                       UL002   xacro's message
==================================  ======  =================================================
"""
from __future__ import annotations

import errno
import os
import re

from dataclasses import dataclass
from typing import Any, Callable, Iterable

import xacro
import xacro.substitution_args as _subst

from urdf_lint.core import fsbound

from urdf_lint.expansion import safe_eval
from urdf_lint.core.findings import Problem
from urdf_lint.discovery.packages import OutsideRoots, PackageNotFound
from urdf_lint.core.codes import RuleName

# the rules raised here, by name (urdf_lint.core.codes: no rule module is imported)
ul001_xml_syntax = RuleName("ul001_xml_syntax")
ul002_xacro_error = RuleName("ul002_xacro_error")
ul003_missing_include = RuleName("ul003_missing_include")
ul004_unknown_package = RuleName("ul004_unknown_package")
ul005_missing_arg = RuleName("ul005_missing_arg")
ul902_outside_roots = RuleName("ul902_outside_roots")
ul903_unsafe_expression = RuleName("ul903_unsafe_expression")
ul904_resource_limit = RuleName("ul904_resource_limit")


class XmlSyntaxError(xacro.XacroException):  # type: ignore[misc]  # xacro has no stubs
    def __init__(self, msg: str, file: str, line: int, col: int,
                 chain: Iterable[Any] = ()) -> None:
        super().__init__(msg)
        self.loc = (file, line, col, tuple(chain))


class RefusedInput(xacro.XacroException):  # type: ignore[misc]  # xacro has no stubs
    """Input refused for safety (entity declarations, files outside the roots, ...); ``rule``
    names the rule (its code) it is reported as."""
    def __init__(self, msg: str, rule: RuleName, loc: Any = None) -> None:
        super().__init__(msg)
        self.rule = rule
        self.loc = loc


@dataclass(frozen=True)
class ErrorRow:
    """How one kind of xacro failure becomes a finding: what it catches and the rule it names."""
    catches: type | tuple[type, ...]
    rule: RuleName | None                # None: the exception names its rule (RefusedInput)
    message: Callable[..., str]
    looks_at: str = "either"             # "raised" | "wrapped" | "either"
    macros: bool = False                 # append the macro context
    own_location: bool = False           # use the exception's .loc when it has one
    when: Callable[[Any], bool] = lambda e: True
    needs_deps: bool = False             # the message also gets the files read so far


def _arg_declared_later(name: str, deps: Iterable[str]) -> str | None:
    """``file:line`` of an ``<xacro:arg name=... default=...>`` in a file read so far: the
    default exists, but xacro reached a use of the arg first."""
    import re

    from urdf_lint.core.locations import display_path
    q = re.escape(name)
    decl = re.compile(r"<xacro:arg\b[^>]*\bname\s*=\s*[\"']" + q + r"[\"'][^>]*\bdefault\s*=")
    decl2 = re.compile(r"<xacro:arg\b[^>]*\bdefault\s*=[^>]*\bname\s*=\s*[\"']" + q + r"[\"']")
    for f in deps:
        try:
            text = fsbound.read_text(f, errors="replace")
        except OSError:
            continue
        m = decl.search(text) or decl2.search(text)
        if m:
            return f"{display_path(f)}:{text.count(chr(10), 0, m.start()) + 1}"
    return None


def _missing_arg(e: BaseException, deps: Iterable[str] = ()) -> str:
    name = str(e)
    later = _arg_declared_later(name, deps)
    if later:
        return (f"xacro arg '{name}' is used before it is declared: its default ({later}) comes "
                "after its first use here; move the <xacro:arg> above its first use")
    return (f"xacro arg '{name}' has no default and no value was given; pass {name}:=VALUE or "
            "list the model with its args under [tool.urdf-lint] models")


def _missing_file(e: OSError, deps: Iterable[str] = ()) -> str:
    # load_yaml records its file before opening it; an include is recorded only once read
    yaml = os.path.abspath(str(e.filename)) in set(deps)
    what = "YAML" if yaml else "included"
    if getattr(e, "errno", None) == errno.EISDIR:
        # ``config/$(arg file)`` with the arg empty: the path ends at the folder
        return f"{what} file path names a folder, not a file: {e.filename}" + \
            _empty_args_hint(str(e.filename), folder=True)
    return f"{what} file not found: {e.filename}" + _empty_args_hint(str(e.filename))


_HOLE = re.compile(r"//|/_|_/|__|_\.|/\.(?!\.?/)|-/|/-")


def _empty_args_hint(path: str, folder: bool = False) -> str:
    """When the path has a hole (``arms//dof/urdf/_macro.xacro``; or it names a ``folder``,
    its file name left empty) and args of the model are empty: which ones, and how to set
    them."""
    empty = sorted(k for k, v in (xacro.substitution_args_context.get("arg") or {}).items()
                   if str(v) == "")
    path = path.replace(os.sep, "/")
    if empty and not (folder or _HOLE.search(path)):
        # no hole, but the name of an empty arg is left in the path (``${dof}dof`` with dof
        # empty gives ``.../dof/...``): that one
        words = set(re.split(r"[/_.\-]+", path))
        empty = [k for k in empty if k in words]
        if not empty:
            return ""
    if not empty:
        return ""
    shown = ", ".join(empty[:6]) + (f" and {len(empty) - 6} more" if len(empty) > 6 else "")
    return (f" (the path was built from args left empty: {shown}; set them with NAME:=VALUE or "
            "[[tool.urdf-lint.models]] args)")


def _generic(e: BaseException) -> str:
    return " ".join((str(e).strip() or repr(e)).split())


ERROR_TABLE: tuple[ErrorRow, ...] = (
    ErrorRow(XmlSyntaxError, ul001_xml_syntax, str, looks_at="raised", own_location=True),
    ErrorRow(RefusedInput, None, str, own_location=True),
    ErrorRow(SyntaxError, ul002_xacro_error, lambda e: f"invalid expression: {e.msg}",
             looks_at="wrapped", macros=True),
    ErrorRow(RecursionError, ul904_resource_limit,
             lambda e: "recursion too deep while expanding (a macro that calls itself without "
                       "end?)", macros=True),
    ErrorRow(PackageNotFound, ul004_unknown_package, str),
    ErrorRow(OutsideRoots, ul902_outside_roots, str),
    ErrorRow(_subst.ArgException, ul005_missing_arg, _missing_arg, looks_at="wrapped",
             needs_deps=True),
    ErrorRow((IOError, OSError), ul003_missing_include, _missing_file, looks_at="wrapped",
             needs_deps=True,
             when=lambda e: bool(getattr(e, "filename", None))),
    ErrorRow(safe_eval.UnsafeExpression, ul903_unsafe_expression, str, macros=True),
    ErrorRow(MemoryError, ul904_resource_limit, lambda e: "expansion ran out of memory",
             macros=True),
    ErrorRow(BaseException, ul002_xacro_error, _generic, looks_at="raised", macros=True),
)


def wrapped(e: BaseException) -> Any:
    """The innermost exception xacro wrapped in ``e`` (lazily evaluated properties wrap errors
    more than once), or None."""
    inner = getattr(e, "exc", None)
    while isinstance(inner, xacro.XacroException) and getattr(inner, "exc", None) is not None:
        inner = inner.exc
    return inner


def problem_for(e: BaseException, here: Any, macros: Iterable[str] = (),
                deps: Iterable[str] = ()) -> Problem:
    """The one located problem for a failed expansion. ``here`` is the origin of the innermost
    element being evaluated, ``macros`` the names of the macros being expanded, innermost
    first."""
    inner = wrapped(e)
    macros = list(macros)
    shown = [f"'{m}'" for m in macros[:3]] + \
        ([f"... ({len(macros)} levels)"] if len(macros) > 3 else [])
    suffix = (" (in macro " + " < ".join(shown) + ")") if macros else ""
    for row in ERROR_TABLE:
        candidates: tuple[Any, ...] = \
            {"raised": (e,), "wrapped": (inner,), "either": (e, inner)}[row.looks_at]
        hit: Any = next((x for x in candidates if isinstance(x, row.catches) and row.when(x)), None)
        if hit is None:
            continue
        rule = row.rule or hit.rule
        loc = (getattr(hit, "loc", None) if row.own_location else None) or here
        text = row.message(hit, deps) if row.needs_deps else row.message(hit)
        return Problem.at(rule.CODE, text + (suffix if row.macros else ""), loc)
    raise AssertionError("the last row catches everything")  # pragma: no cover
