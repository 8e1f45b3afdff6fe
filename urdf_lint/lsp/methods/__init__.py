"""One module per LSP method, each a ``handle(services, params)`` returning the method's
result (ruff's ``server/api/requests``, jedi-language-server's features): thin handlers over
:class:`urdf_lint.lsp.services.Services`. The document lifecycle (``did_open``,
``did_change``, ...) is handed the server itself (it schedules lints and publishes). Adding a
method: a new module here and one line in :mod:`urdf_lint.lsp.server`."""
