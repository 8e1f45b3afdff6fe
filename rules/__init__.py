"""The urdf-lint rule catalogue: one module per rule (see urdf_lint.engine.registry)."""
