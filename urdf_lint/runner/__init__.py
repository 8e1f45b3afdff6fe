"""``urdf_lint.runner``: forked, sandboxed, limited worker processes and their scheduler; handed a
Handler, it knows neither lint nor render; results come back as plain data (:mod:`.wire`), never
pickle.

May import: ``discovery``, ``config``, ``report``, ``core`` (the rooms below it, less the
ones the contract "runner" forbids, ``[tool.importlinter]`` in pyproject.toml; never a room above).
"""

# Set by a command that ends with its run (``urdf-lint check``, ``hook``, ``diff``...; not the
# servers): its parent keeps what it froze at a worker's fork frozen (:meth:`.forked.Process.start`),
# and its own full collection at the end of the run walks only what the run made since
# (0.4 ms, not 12 ms, on the corpus). A long-lived parent collects those objects again.
ONE_SHOT = False
