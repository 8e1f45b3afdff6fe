"""meshes: see ARCHITECTURE.md."""
