"""One module per LSP method or command: a plain function of (server state, params)."""
