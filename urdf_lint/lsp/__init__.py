"""``urdf-lint server``: the language server (:mod:`.server`), its workspace state
(:mod:`.state`), its worker pool (:mod:`.pool`) and features (:mod:`.actions`,
:mod:`.features`, :mod:`.index`). Needs the ``server`` extra (pygls).

May import: ``preview``, ``review``, ``run``, ``render``, ``formatting``, ``rules``, ``engine``, ``fix``,
``meshes``, ``expansion``, ``runner``, ``discovery``, ``config``, ``report``, ``core`` (the
rooms below it, ``[tool.importlinter]`` in pyproject.toml; never a room above)."""
