"""Output formats, one module per format in this package; adding a format is adding one file.

Each module defines a subclass of :class:`urdf_lint.report.base.BaseFormatter` with a ``name``;
:func:`urdf_lint.report.registry.formats` finds them, and the CLI's ``--output-format``
choices come from there.

JSON schema (``--format json``), version 1::

    {
      "version": 1, "tool": "urdf-lint", "tool_version": "0.1.0",
      "models": [{"entry": str, "args": {str: str}, "name": str, "status": "model"|"failed",
                  "cached": bool (result reused from .urdf_lint_cache),
                  "links": int, "joints": int, "meshes": int}],
      "findings": [{"code": "UL302", "name": "limit-order", "severity": "error"|"warning"|"info",
                    "message": str, "file": str (relative to cwd; ``..`` inside its repository
                    or workspace), "line": int, "col": int,
                    "chain": [[file, line, col], ...]  (macro call sites, outermost first),
                    "models": [str, ...],
                    "fix": {"description": str, "applicability": "safe"|"unsafe",
                            "edits": [{"file": str, "start": int, "end": int, "text": str}]
                                     (byte ranges of the source, replaced by text)
                            | "refused": str (why it is not applied automatically)}
                           (only when the rule has a fix for this finding),
                    "severity_from": [str, ...] (the selected consumer targets that make it
                           this severe, urdf_lint.core.targets; only when one raised it)}],
                    "detail": str (what this instance is about, when the message is a root
                               cause's, e.g. the mesh URI of an unknown package; optional),
                    "value_from": [file, line, col] (where the value came from: a YAML scalar,
                                  a property defined elsewhere; optional),
                    "count": int, "instances": [{finding fields, "target": [kind, name]}, ...]
                             (when several elements, models or places are one finding: one per
                              source location and rule, or per root cause)}],
      "summary": {"models": int, "errors": int, "warnings": int, "info": int}
    }

With ``--statistics``, ``--format json`` prints ``[{"code", "name", "severity", "count"}]``,
then one ``{"model", "entry", "branches", "taken", ...}`` per explored model with branches.

May import: ``core`` (the rooms below it, ``[tool.importlinter]`` in pyproject.toml; never a
room above).
"""

