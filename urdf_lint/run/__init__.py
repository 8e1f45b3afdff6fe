"""run: see ARCHITECTURE.md."""
