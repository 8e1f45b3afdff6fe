"""``urdf_lint.cli``: the command line: one module per command (argparse stays here: parsing the
arguments and printing the result), the pytest plugin and the MCP server; every front end that a
user or a program runs.

May import: ``lsp``, ``preview``, ``review``, ``run``, ``render``, ``formatting``, ``rules``, ``engine``,
``fix``, ``meshes``, ``expansion``, ``runner``, ``discovery``, ``config``, ``report``, ``core``
(the rooms below it, ``[tool.importlinter]`` in pyproject.toml; never a room above).
"""
