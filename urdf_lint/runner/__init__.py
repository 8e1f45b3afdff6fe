"""runner: see ARCHITECTURE.md."""
