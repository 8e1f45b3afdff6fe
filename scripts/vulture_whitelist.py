"""Names vulture (``vulture urdf_lint rules scripts/vulture_whitelist.py``) cannot see used.

Each is reached from outside the call graph vulture reads: a plugin hook or entry point found
by name, a callback an event loop or a parser calls, an attribute set on another library's
module. ``tests/test_dead_names.py`` runs vulture with this file; a name listed here must say
who uses it. This file is read, never imported by the package.
"""
# ruff: noqa
_ = object()

# entry points and plugin hooks, found by name
_.cmd_mcp                     # cli/main.py: getattr(mod, f"cmd_{name}")
_.pytest_addoption            # the pytest plugin (entry point pytest11)
_.pytest_collection_modifyitems
_.pytest_configure
_.runtest                     # pytest.Item subclasses: called by pytest
_.reportinfo
_.__getattr__                 # module __getattr__ (PEP 562): engine/api.py, expansion/__init__.py

# callbacks: signal handlers' and pickling's parameters, expat's handlers
_.signum                      # cli/main.py: a SIGTERM handler's signature
_.protocol                    # core/jobs.py: __reduce_ex__(self, protocol)
_.StartElementHandler         # pyexpat parsers: set, then called by expat
_.EndElementHandler
_.EntityDeclHandler
_.StartDoctypeDeclHandler
_.XmlDeclHandler
_.CharacterDataHandler
_.CommentHandler
_.ProcessingInstructionHandler
_.ordered_attributes          # pyexpat parser settings
_.buffer_text

# attributes set on other modules
_.__spec__                    # core/lazy.py: a deferred module's placeholder
_.__file__
_.dont_write_bytecode         # runner/pool.py: sys.dont_write_bytecode in a worker
_.eval_all                    # expansion/expand.py: xacro's functions replaced by the hooks
_.eval_text
_.handle_macro_call
_.grab_macro
_.grab_property
_.process_include
_.check_attrs
_.reqd_attrs
_.warning
_.print_location
_._eval_find
_._eval
_.verbosity

# expansion/expand.py: xacro's condition check, replaced by the branch-recording hook
_.get_boolean_value
# expansion/clone.py: minidom node fields set on a clone, read by minidom
_.nodeName
# preview/server.py: http.server's hooks and settings, called or read by the standard library
_.daemon_threads
_.allow_reuse_address
_.server_version
_.sys_version
_.log_message
_.do_GET
_.do_HEAD
_.do_POST
_.do_PUT
_.do_PATCH
_.do_DELETE
_.do_OPTIONS
_.send_error                   # preview/server.py: http.server calls it for a bad request
_.close_connection

# the rule API's types, imported under TYPE_CHECKING by every rule module for its check's
# string annotations (``def check(model: "Model", ctx: "Context") -> "Checked"``), which
# vulture does not read
_.Checked
_.Context
_.Model
