"""``urdf-lint server``: the language server (:mod:`.server`), its workspace state
(:mod:`.state`), its worker pool (:mod:`.pool`) and features (:mod:`.actions`,
:mod:`.features`, :mod:`.index`). Needs the ``server`` extra (pygls)."""
