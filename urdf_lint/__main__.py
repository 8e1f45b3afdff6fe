from urdf_lint.cli.main import entry

entry()
