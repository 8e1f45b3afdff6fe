"""The language server's methods, one module per LSP method or feature."""
