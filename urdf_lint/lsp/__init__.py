"""``urdf-lint server``: the language server. :mod:`.server` only registers the methods, one
module each in :mod:`.methods` (``handle(services, params)``); :mod:`.core` schedules the lint
(latest wins) and publishes; :mod:`.services` is what every handler reads (the workspace
state of :mod:`.state`, the declarations :mod:`.index`, the expanded models); the workers are
the runner's (``runner.pool.WorkerPool``, persistent). Needs the ``server`` extra (pygls).

May import: ``preview``, ``review``, ``run``, ``render``, ``formatting``, ``rules``, ``engine``,
``fix``, ``meshes``, ``expansion``, ``runner``, ``discovery``, ``config``, ``report``, ``core``
(the rooms below it, ``[tool.importlinter]`` in pyproject.toml; never a room above)."""
