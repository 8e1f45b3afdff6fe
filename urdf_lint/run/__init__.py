"""``urdf_lint.run``: a check run from request to result (:mod:`.pipeline`: RunRequest ->
CheckResult), its one ending (:mod:`.finish`: policy, run-scope rules, suppression, baseline,
grouping), ``--fix`` (:mod:`.fix`), the formatter's proof (:mod:`.format`), the result cache and
run memo, and the worker's job handler (:mod:`.worker`).

May import: ``render``, ``formatting``, ``rules``, ``engine``, ``fix``, ``meshes``,
``expansion``, ``runner``, ``discovery``, ``config``, ``report``, ``core`` (the rooms below it,
``[tool.importlinter]`` in pyproject.toml; never a room above).
"""
