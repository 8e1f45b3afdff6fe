"""``urdf-lint server``: the language server. :mod:`.server` only registers the methods, one
module each in :mod:`.methods` (``handle(services, params)``); :mod:`.core` schedules the lint
(latest wins) and publishes; :mod:`.services` is what every handler reads (the workspace
state of :mod:`.state`, the declarations :mod:`.index`, the expanded models); the workers are
the runner's (``runner.pool.WorkerPool``, persistent). Needs the ``server`` extra (pygls).

May import: every room below it (run, report, engine, fix, runner, discovery, config, core).
"""
